#version 450
// The transmittance table (Bruneton & Neyret 2008, §4): for each texel, the altitude and
// zenith cosine it stands for, and the transmittance from there to the top of the atmosphere
// (shaders/common/atmosphere.glsl; the CPU reference is the same source in double).
#extension GL_GOOGLE_include_directive : require

#include "shared/sky_params.h"

layout(local_size_x = kSkyWorkgroupSize, local_size_y = kSkyWorkgroupSize) in;
layout(push_constant) uniform Push { AtmosphereParams atmosphere; };
layout(set = 0, binding = 0, rgba32f) uniform writeonly image2D table;

#define SUN_TRANSMITTANCE(a, h, muS) vec3(1.0f)  // unused here: no scattering integral
#include "common/atmosphere.glsl"

void main() {
  uvec2 texel = gl_GlobalInvocationID.xy;
  if (texel.x >= kTransmittanceWidth || texel.y >= kTransmittanceHeight) return;
  vec2 uv = (vec2(texel) + 0.5f) / vec2(kTransmittanceWidth, kTransmittanceHeight);
  vec2 hMu = transmittanceAltitudeMu(atmosphere, uv.x, uv.y);
  vec3 depth = opticalDepthToTop(atmosphere, hMu.x, hMu.y, kTransmittanceSteps);
  imageStore(table, ivec2(texel), vec4(exp(-depth), 1.0f));
}
