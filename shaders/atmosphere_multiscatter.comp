#version 450
// The multiple-scattering table (Hillaire 2020, §5.5; shaders/common/atmosphere.glsl): for each
// texel, the altitude and sun zenith cosine it stands for, and Ψ_ms there from 64 directions,
// the sun's transmittance read from the transmittance table built just before. One invocation
// per texel: the table has only 32 × 32 of them, each a few thousand samples.
#extension GL_GOOGLE_include_directive : require

#include "shared/sky_params.h"

layout(local_size_x = kSkyWorkgroupSize, local_size_y = kSkyWorkgroupSize) in;
layout(push_constant) uniform Push { AtmosphereParams atmosphere; };
layout(set = 0, binding = 0) uniform sampler2D transmittanceTable;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D table;

#include "atmosphere_lookup.glsl"

void main() {
  uvec2 texel = gl_GlobalInvocationID.xy;
  if (texel.x >= kMultiScatteringSize || texel.y >= kMultiScatteringSize) return;
  vec2 uv = (vec2(texel) + 0.5f) / float(kMultiScatteringSize);
  vec2 hMuS = multipleScatteringAltitudeMuS(atmosphere, uv.x, uv.y);
  vec3 psi, transfer;
  multipleScatteringTexel(atmosphere, hMuS.x, hMuS.y, psi, transfer);
  imageStore(table, ivec2(texel), vec4(psi, transfer.y));
}
