#version 450
// Single rays through the atmosphere for `planet sky` and the tests (engine/render/sky_tables.h,
// SkyTables::evaluateRays): per ray, (1) the per-pixel march of the reference sky as sky.comp
// (SKY_REFERENCE) does it for a ray that meets no geometry and no cloud: scatteringAlong over the
// ray's stretch inside the atmosphere in `counts.y` equal steps; (2) the same stretch by the
// midpoint rule of the CPU reference: single scattering and σ_s · Ψ_ms from the
// multiple-scattering table in `counts.z` samples.
#extension GL_GOOGLE_include_directive : require

#include "shared/sky_params.h"

layout(local_size_x = kSkyRayWorkgroupSize) in;
layout(push_constant) uniform Push { SkyRayPush push; };
layout(set = 0, binding = 0) uniform sampler2D transmittanceTable;
layout(set = 0, binding = 1) uniform sampler2D multipleScatteringTable;
// In: per ray (altitude above R in m, view zenith cosine, sun zenith cosine, view-sun cosine).
layout(std430, set = 0, binding = 2) readonly buffer Rays { vec4 rays[]; };
// Out: per ray six vec4s (rgb; a unused): the reference march's single scattering, the tables'
// single scattering, their multiple scattering, the transmittance along the stretch by the
// tables' march and by the reference's, and the reference march's total (single and multiple).
layout(std430, set = 0, binding = 3) writeonly buffer Results { vec4 results[]; };

#define MULTIPLE_SCATTERING(a, h, muS) \
  textureLod(multipleScatteringTable, multipleScatteringUv(a, h, muS), 0.0f).rgb
#include "atmosphere_lookup.glsl"

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= uint(push.counts.x)) return;
  AtmosphereParams a = push.atmosphere;
  vec4 ray = rays[index];
  float R = a.radii.x;
  float h = ray.x, mu = ray.y, muS = ray.z, nu = ray.w;
  float r = R + h;
  vec3 reference = vec3(0.0f), referenceTotal = vec3(0.0f), single = vec3(0.0f), multiple = vec3(0.0f);
  vec3 transmittance = vec3(1.0f), referenceTransmittance = vec3(1.0f);
  // The stretch inside the atmosphere, as sky.comp finds it: from the camera (or where the ray
  // enters the top) to where it leaves the top or meets the ground.
  vec2 topHits = raySphere(R, h, mu, a.radii.y);
  bool outside = h >= a.radii.y;
  float tStart = outside ? topHits.x : 0.0f;
  float tExit = outside ? topHits.y : topHits.x;
  vec2 ground = raySphere(R, h, mu, 0.0f);
  float tEnd = mu < 0.0f && ground.x >= 0.0f ? min(ground.x, tExit) : tExit;
  if (a.radii.w > 0.5f && tStart >= 0.0f && tEnd > tStart) {
    float h0 = altitudeAlong(R, h, mu, tStart);
    float r0 = R + h0;
    float mu0 = clamp((r * mu + tStart) / r0, -1.0f, 1.0f);
    float muS0 = clamp((r * muS + tStart * nu) / r0, -1.0f, 1.0f);
    scatteringAlong(a, h0, mu0, muS0, nu, tEnd - tStart, uint(push.counts.y), kStepsEqual, reference, referenceTotal,
                    referenceTransmittance);
    singleScattering(a, h0, mu0, muS0, nu, tEnd - tStart, uint(push.counts.z), single, transmittance);
    multiple = multipleScattering(a, h0, mu0, muS0, nu, tEnd - tStart, uint(push.counts.z));
  }
  results[6u * index + 0u] = vec4(reference, 0.0f);
  results[6u * index + 1u] = vec4(single, 0.0f);
  results[6u * index + 2u] = vec4(multiple, 0.0f);
  results[6u * index + 3u] = vec4(transmittance, 0.0f);
  results[6u * index + 4u] = vec4(referenceTransmittance, 0.0f);
  results[6u * index + 5u] = vec4(referenceTotal, 0.0f);
}
