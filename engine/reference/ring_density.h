// The CPU reference of the planetary rings: shaders/common/rings.glsl compiled as C++ (in
// float, with -ffp-contract=off like the GLSL's `precise`), so that tests can hold ring.frag,
// ring_eval.comp and any shader that uses ringShadow against it. The meaning of every function
// is at its GLSL definition. The parameters come from ringGpuParams below.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "planet/ring_description.h"
#include "shared/ring_params.h"

namespace planet {

// The shaders' block for `ring` around a body of radius planetRadiusM (which casts the shadow
// on it), lit by a sun of angular radius sunAngularRadiusRad (the penumbrae). Validates `ring`.
gpu::RingParams ringGpuParams(const RingDescription& ring, double planetRadiusM, double sunAngularRadiusRad);


// The shaders' integer hash (lowbias32, shaders/common/hash.glsl), for seeding on the CPU.
uint32_t ringHashCpu(uint32_t x);

// The ring coordinate of body-frame radius radiusM: 0 at the inner radius, 1 at the outer.
// In double (the GPU computes it in float from a camera-relative position).
double ringCoordinateCpu(const gpu::RingParams& ring, double radiusM);

// The ring at coordinate u, seen perpendicularly: rgb the particles' albedo, a the opacity in
// [0, 1] (0 for u outside (0, 1) and for NaN). `footprint`: how much u changes across a pixel
// (0: every octave).
glm::vec4 ringSampleCpu(const gpu::RingParams& ring, float u, float footprint = 0.0f);
// Its opacity only.
float ringOpacityCpu(const gpu::RingParams& ring, float u, float footprint = 0.0f);
// ringSampleCpu(ring, u(radiusM)).a: 0 outside [inner, outer].
float ringOpacityAtRadiusCpu(const gpu::RingParams& ring, double radiusM);

// Opacity along a path at `cosine` to the ring's normal, for perpendicular opacity alpha.
float ringSlantOpacityCpu(float alpha, float cosine);

// The fraction of sunlight reaching a body-frame point after passing the ring (1: no ring in
// the way). sunBody: unit vector toward the sun.
float ringShadowCpu(const glm::vec3& pointBody, const glm::vec3& sunBody, const gpu::RingParams& ring);

// The visible fraction of the sun's disc at a body-frame point, with the ringed body (radius
// ring.radii.w) in the way: the body's shadow on the ring.
float ringPlanetShadowCpu(const glm::vec3& pointBody, const glm::vec3& sunBody, const gpu::RingParams& ring);

}  // namespace planet
