// Compiled with -ffp-contract=off (engine/CMakeLists.txt): the reference must round exactly like
// the GLSL it is compiled from.
#include "render/ring_density.h"

#include <cmath>
#include <cstdint>

namespace planet {
namespace {

using namespace planet::gpu;

// shaders/common/rings.glsl as C++: its functions become members (called on a temporary), the GLSL
// builtins it uses defined in float (no silent promotion to double).
struct RingKernel {
  using real = float;
  using uint = std::uint32_t;
  using vec3 = glm::vec3;
  using vec4 = glm::vec4;

  static float floor(float x) { return std::floor(x); }
  static float sqrt(float x) { return std::sqrt(x); }
  static float pow(float x, float y) { return std::pow(x, y); }
  static float abs(float x) { return std::fabs(x); }
  static float max(float x, float y) { return x < y ? y : x; }  // GLSL 4.50 definitions
  static float min(float x, float y) { return y < x ? y : x; }
  static float clamp(float x, float lo, float hi) { return min(max(x, lo), hi); }

#define RING_CONST static constexpr
#define PRECISE  // C++: compiled with -ffp-contract=off
#define IN(T) const T&
#include "common/rings.glsl"
#undef IN
#undef PRECISE
#undef RING_CONST
};

}  // namespace

uint32_t ringHashCpu(uint32_t x) { return RingKernel().ringHash(x); }

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

}  // namespace planet
