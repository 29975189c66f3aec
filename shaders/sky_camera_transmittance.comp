#version 450
// The camera's transmittance table (issue 21, point 7; shared/sky_params.h,
// kCameraTransmittanceDistances), built from inside the air before the cloud pass and the
// compose, again only when the camera's altitude or the air moved (SkyPass keeps it as it keeps
// the sky-view table, with its mapping, SkyUniforms::camera.z and aerial.w): the air's optical
// depth from the camera to each distance along rays of each zenith cosine (common/atmosphere.glsl, cameraTransmittanceUnit, maps both). The compose reads
// a pixel's transmittance to what it shows from it in one filtered read. Each invocation marches
// one row outward from the camera, kCameraTransmittanceSteps midpoint steps between neighbouring
// texels, and adds up as it goes.
// Why a table of the camera's own: the ratio of two reads of the transmittance table to the top
// (Bruneton & Neyret 2008) cost lavapipe two reads per pixel and does not hold near the
// horizon, where both values are tiny (from the ground toward mountains 200 km away it gave
// 0.013 where the march gives 0.027); there the compose fell back on the aerial volume's,
// filtered across columns 17 pixels apart.
#extension GL_GOOGLE_include_directive : require

#include "shared/sky_params.h"

layout(local_size_x = kCameraTransmittanceWorkgroup) in;

#include "sky_uniforms.glsl"
layout(set = 0, binding = kSkyTableBindingTransmittance) uniform sampler2D transmittanceTable;
layout(set = 0, binding = kSkyTableBindingMultipleScattering) uniform sampler2D multipleScatteringTable;
layout(set = 0, binding = kSkyTableBindingCameraTransmittance, rgba32f) uniform writeonly image2D cameraTransmittance;

#define MULTIPLE_SCATTERING(a, h, muS) \
  textureLod(multipleScatteringTable, multipleScatteringUv(a, h, muS), 0.0f).rgb
#include "atmosphere_lookup.glsl"
#include "sky_aerial.glsl"

void main() {
  uint row = gl_GlobalInvocationID.x;
  if (row >= kCameraTransmittanceDirections) return;
  AtmosphereParams a = sky.atmosphere;
  float R = a.radii.x;
  float h = sky.camera.x;
  float mu = cameraTransmittanceTexel(0u, row).y;
  vec3 depth = vec3(0.0f);
  float done = 0.0f;
  imageStore(cameraTransmittance, ivec2(0, row), vec4(0.0f));
  for (uint i = 1u; i < kCameraTransmittanceDistances; ++i) {
    float target = cameraTransmittanceTexel(i, row).x;
    float dt = (target - done) / float(kCameraTransmittanceSteps);
    for (uint k = 0u; k < kCameraTransmittanceSteps; ++k)
      depth += extinctionAt(a, altitudeAlong(R, h, mu, done + (float(k) + 0.5f) * dt)) * dt;
    done = target;
    imageStore(cameraTransmittance, ivec2(i, row), vec4(depth, 0.0f));
  }
}
