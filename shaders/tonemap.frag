#version 450
// HDR → display (issue 4, point 2): exposure, then Narkowicz's fit of the ACES filmic curve
// (2015); the sRGB target encodes the result. The exposure is the fixed one (params.x), or with
// eye adaptation (issue 21, point 4; params.y = 1) the one the luminance pass wrote this frame,
// and then the stars' and the city lights' shares of each pixel (from its alpha: shared/
// exposure_params.h) take exposures of their own (exposureDisplayScale).
#extension GL_GOOGLE_include_directive : require

#include "common/definitions.glsl"
#include "shared/exposure_params.h"
#include "common/exposure.glsl"

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D hdr;
layout(set = 0, binding = 1, std430) readonly buffer Exposure { ExposureState exposure; };
layout(push_constant) uniform Push { vec4 params; };  // x: fixed exposure (1 with adaptation), y: 1 to adapt

layout(location = 0) out vec4 outColor;

vec3 filmic(vec3 x) { return clamp(x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f); }

void main() {
  vec4 c = imageLoad(hdr, ivec2(gl_FragCoord.xy));
  float scale = params.x;
  if (params.y > 0.5f) {
    scale = exposureDisplayScale(exposure.values.x, c.a);
  }
  outColor = vec4(filmic(c.rgb * scale), 1.0f);
}
