// Compiled with -ffp-contract=off (the project-wide rule, top CMakeLists.txt): the reference must round exactly like
// the GLSL it is compiled from.
#include "reference/eclipse.h"

#include <cmath>

#include <fmt/format.h>

#include "common/definitions.h"
#include "core/error.h"
#include "reference/atmosphere_model.h"
#include "reference/sunlight.h"

namespace planet {
namespace {

// shaders/common/eclipse.glsl as C++ (its functions become members), with the builtins it needs
// beyond the common kernel's in precision Real.
template <typename Real>
struct EclipseKernel {
  PLANET_GLSL_KERNEL(Real)
  struct EclipseParams {  // the GLSL struct in this precision
    vec4 occluders[gpu::kEclipseMaxOccluders];
    vec4 refracted[gpu::kEclipseMaxOccluders];
    vec4 sun;
  };
  static real acos(real x) { return std::acos(x); }
  static real asin(real x) { return std::asin(x); }
  static real atan(real y, real x) { return std::atan2(y, x); }
#include "common/eclipse.glsl"
};
using FloatKernel = EclipseKernel<float>;
using DoubleKernel = EclipseKernel<double>;

}  // namespace

gpu::EclipseParams eclipseGpuParams(std::span<const Occluder> occluders, const glm::dmat3& toFrame,
                                    double sunAngularRadiusRad) {
  if (occluders.size() > gpu::kEclipseMaxOccluders)
    throw Error(
        fmt::format("{} bodies can hide the sun, at most {} are drawn", occluders.size(), gpu::kEclipseMaxOccluders));
  gpu::EclipseParams e{};
  for (size_t i = 0; i < occluders.size(); ++i) {
    const Occluder& o = occluders[i];
    if (!(std::isfinite(o.radiusM) && o.radiusM >= 0.0))
      throw Error(fmt::format("occluder radius {} m must be a finite number >= 0", o.radiusM));
    for (int c = 0; c < 3; ++c)
      if (!(o.refracted[c] >= 0.0 && o.refracted[c] <= 1.0))
        throw Error(fmt::format("occluder's refracted share {} is outside [0, 1]", o.refracted[c]));
    e.occluders[i] = glm::vec4(glm::vec3(toFrame * o.centreM), float(o.radiusM));
    e.refracted[i] = glm::vec4(glm::vec3(o.refracted), 0.0f);
  }
  e.sun = glm::vec4(float(sunAngularRadiusRad), float(occluders.size()), 0.0f, 0.0f);
  return e;
}

float sunDiscCoveredCpu(float k, float s) { return FloatKernel().sunDiscCovered(k, s); }

float occluderSunVisibleCpu(const glm::vec3& toOccluder, float radius, const glm::vec3& sun, float sunRadius) {
  return FloatKernel().occluderSunVisible(toOccluder, radius, sun, sunRadius);
}

float eclipseSunVisibleRefractedCpu(const glm::vec3& fromCamera, const glm::vec3& sun,
                                    const gpu::EclipseParams& eclipse, glm::vec3& refracted) {
  FloatKernel::EclipseParams e;
  for (uint32_t i = 0; i < gpu::kEclipseMaxOccluders; ++i) {
    e.occluders[i] = eclipse.occluders[i];
    e.refracted[i] = eclipse.refracted[i];
  }
  e.sun = eclipse.sun;
  return FloatKernel().eclipseSunVisibleRefracted(fromCamera, sun, e, refracted);
}

float eclipseSunVisibleCpu(const glm::vec3& fromCamera, const glm::vec3& sun, const gpu::EclipseParams& eclipse) {
  glm::vec3 refracted;
  return eclipseSunVisibleRefractedCpu(fromCamera, sun, eclipse, refracted);
}

glm::dvec3 refractedIntoShadow(const PlanetDescription& planet) {
  if (!planet.atmosphere.enabled) return glm::dvec3(0.0);
  const gpu::AtmosphereParams atmosphere = makeAtmosphereParams(planet);
  const double scaleHeight = planet.atmosphere.rayleighScaleHeightM;
  const glm::dvec3 half = transmittanceToTop(atmosphere, scaleHeight, 0.0);  // the limb to the top, one way
  return (2.0 * scaleHeight / planet.radiusM) * half * half;
}

double sunDiscCovered(double k, double s) { return DoubleKernel().sunDiscCovered(k, s); }

double occluderSunVisible(const glm::dvec3& toOccluder, double radius, const glm::dvec3& sun, double sunRadius) {
  return DoubleKernel().occluderSunVisible(toOccluder, radius, sun, sunRadius);
}

double sceneSunVisible(const SceneDescription& scene, const std::vector<BodyState>& states, size_t receiver,
                       const glm::dvec3& pointSceneM) {
  if (states.size() != scene.bodies.size())
    throw Error(fmt::format("scene state has {} bodies, the scene {}", states.size(), scene.bodies.size()));
  const double distance = glm::length(pointSceneM);
  const glm::dvec3 sun = -pointSceneM / distance;
  const double sunRadius = sunlightAtDistance(distance).angularRadiusRad;
  double visible = 1.0;
  for (size_t j = 0; j < states.size(); ++j) {
    if (j == receiver) continue;
    visible *= occluderSunVisible(states[j].positionM - pointSceneM, scene.bodies[j].planet.radiusM, sun, sunRadius);
  }
  return visible;
}

}  // namespace planet
