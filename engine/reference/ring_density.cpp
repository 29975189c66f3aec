// Compiled with -ffp-contract=off (the project-wide rule, top CMakeLists.txt): the reference must round exactly like
// the GLSL it is compiled from.
#include "reference/ring_density.h"

#include <cmath>
#include <cstdint>

#include <fmt/format.h>

#include "common/definitions.h"
#include "core/error.h"

namespace planet {
namespace {

using namespace planet::gpu;

// shaders/common/rings.glsl as C++: its functions become members (called on a temporary), the GLSL
// builtins it uses defined in float (no silent promotion to double).
struct RingKernel {
  PLANET_GLSL_KERNEL(float)
#include "common/rings.glsl"
};

}  // namespace

uint32_t ringHashCpu(uint32_t x) { return RingKernel().lowbias32(x); }

double ringCoordinateCpu(const gpu::RingParams& ring, double radiusM) {
  return (radiusM - double(ring.radii.x)) / (double(ring.radii.y) - double(ring.radii.x));
}

glm::vec4 ringSampleCpu(const gpu::RingParams& ring, float u, float footprint) {
  return RingKernel().ringSample(u, footprint, ring);
}

float ringOpacityCpu(const gpu::RingParams& ring, float u, float footprint) {
  return ringSampleCpu(ring, u, footprint).w;
}

float ringOpacityAtRadiusCpu(const gpu::RingParams& ring, double radiusM) {
  return ringOpacityCpu(ring, float(ringCoordinateCpu(ring, radiusM)));
}

float ringSlantOpacityCpu(float alpha, float cosine) { return RingKernel().ringSlantOpacity(alpha, cosine); }

float ringShadowCpu(const glm::vec3& pointBody, const glm::vec3& sunBody, const gpu::RingParams& ring) {
  return RingKernel().ringShadow(pointBody, sunBody, ring);
}

float ringPlanetShadowCpu(const glm::vec3& pointBody, const glm::vec3& sunBody, const gpu::RingParams& ring) {
  return RingKernel().ringPlanetShadow(pointBody, sunBody, ring);
}

gpu::RingParams ringGpuParams(const RingDescription& ring, double planetRadiusM, double sunAngularRadiusRad) {
  validateRingDescription(ring);
  if (!(std::isfinite(planetRadiusM) && planetRadiusM > 0.0))
    throw Error(fmt::format("ringed body radius must be a positive finite number of metres, got {}",
                            fmt::format("{:g}", planetRadiusM)));
  if (!(std::isfinite(sunAngularRadiusRad) && sunAngularRadiusRad >= 0.0 && sunAngularRadiusRad < 1.0))
    throw Error(fmt::format("sun angular radius must be in [0, 1) rad, got {}", fmt::format("{:g}", sunAngularRadiusRad)));
  gpu::RingParams p{};
  p.radii = glm::vec4(float(ring.innerRadiusM), float(ring.outerRadiusM),
                      float(1.0 / (ring.outerRadiusM - ring.innerRadiusM)), float(planetRadiusM));
  p.colour = glm::vec4(glm::vec3(ring.colour), float(ring.opacity));
  p.variation = glm::vec4(glm::vec3(ring.colourVariation), float(sunAngularRadiusRad));
  p.seedMix = ringHashCpu(ring.seed ^ 0x9e3779b9u);
  p.octaves = ring.octaves;
  p.gapCount = ring.gaps;
  // Gaps at seeded radii inside the middle 60 % of the ring, the first the widest (Cassini:
  // 4,700 km of Saturn's 62,000 km), each clearing 92-98 % of the opacity.
  for (uint32_t g = 0; g < ring.gaps; ++g) {
    const uint32_t h = ringHashCpu(p.seedMix + 0x632be5abu * (g + 1));
    const double a = double(h & 0xffffu) / 65535.0, b = double(h >> 16) / 65535.0;
    const double halfWidth = (g == 0 ? 0.02 + 0.015 * b : 0.004 + 0.008 * b);
    p.gaps[g] = glm::vec4(float(0.2 + 0.6 * a), float(halfWidth), float(0.92 + 0.06 * b), 0.0f);
  }
  return p;
}

}  // namespace planet
