#version 450
// HDR → display (issue 4, point 2): exposure, then Narkowicz's fit of the ACES filmic curve
// (2015); the sRGB target encodes the result.
#extension GL_GOOGLE_include_directive : require

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D hdr;
layout(push_constant) uniform Push { vec4 params; };  // x: exposure

layout(location = 0) out vec4 outColor;

vec3 filmic(vec3 x) { return clamp(x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f); }

void main() {
  vec3 c = imageLoad(hdr, ivec2(gl_FragCoord.xy)).rgb;
  outColor = vec4(filmic(c * params.x), 1.0f);
}
