#version 450
// The sky-view table (Hillaire 2020, §5.3), built before the compose pass whenever the altitude or
// the sun has moved beyond a small tolerance since its last build (SkyPass::skyViewBuilt): the
// sky's radiance around the camera for the frame's altitude and sun, single and multiple
// scattering, by view azimuth from the sun and view zenith angle (common/atmosphere.glsl,
// skyViewTexel; the CPU reference computes the same texels from the same source).
#extension GL_GOOGLE_include_directive : require

#include "shared/sky_params.h"

layout(local_size_x = kSkyWorkgroupSize, local_size_y = kSkyWorkgroupSize) in;

#include "sky_uniforms.glsl"
layout(set = 0, binding = kSkyTableBindingTransmittance) uniform sampler2D transmittanceTable;
layout(set = 0, binding = kSkyTableBindingMultipleScattering) uniform sampler2D multipleScatteringTable;
layout(set = 0, binding = kSkyTableBindingSkyView, rgba32f) uniform writeonly image2D skyView;

#define MULTIPLE_SCATTERING(a, h, muS) \
  textureLod(multipleScatteringTable, multipleScatteringUv(a, h, muS), 0.0f).rgb
#include "atmosphere_lookup.glsl"

void main() {
  uvec2 texel = gl_GlobalInvocationID.xy;
  if (texel.x >= kSkyViewWidth || texel.y >= kSkyViewHeight) return;
  vec2 uv = (vec2(texel) + 0.5f) / vec2(kSkyViewWidth, kSkyViewHeight);
  vec3 transmittance;
  vec3 radiance =
      skyViewTexelAndTransmittance(sky.atmosphere, sky.camera.x, sky.surface.z, sky.sunLocal.z, uv.x, uv.y, transmittance);
  imageStore(skyView, ivec2(texel), vec4(radiance, 1.0f - transmittance.y));
}
