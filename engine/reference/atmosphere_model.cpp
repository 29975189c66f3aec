// Compiled without fused multiply-adds (the project-wide rule), so that the double evaluation
// follows the shared source step by step.
#include "reference/atmosphere_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/definitions.h"

namespace planet {
namespace {

using gpu::AtmosphereParams;
using gpu::kTransmittanceHeight;
using gpu::kTransmittanceWidth;

// shaders/common/atmosphere.glsl compiled as C++: its functions become members, so that one
// source gives the GPU code and this reference.
template <typename Real>
struct AtmosphereKernel {
  PLANET_GLSL_KERNEL(Real)

  uint32_t sunSteps = 512;  // midpoint steps of each sun transmittance

  // The sun's transmittance with the planet's shadow: zero once the sun is below the horizon
  // of altitude h (the GPU softens this edge over the sun's disc; the reference is sharp).
  vec3 sunTransmittance(const AtmosphereParams& a, real h, real muS) {
    if (rayHitsGround(real(a.radii.x), h, muS)) return vec3(0);
    vec3 depth = opticalDepthToTop(a, h, muS, sunSteps);
    return vec3(exp(-depth.x), exp(-depth.y), exp(-depth.z));
  }

#define SUN_TRANSMITTANCE(a, h, muS) sunTransmittance(a, h, muS)
#include "common/atmosphere.glsl"
#undef SUN_TRANSMITTANCE
};

using Kernel = AtmosphereKernel<double>;

}  // namespace

AtmosphereParams makeAtmosphereParams(const PlanetDescription& planet) {
  const AtmosphereDescription& a = planet.atmosphere;
  AtmosphereParams p{};
  p.radii = glm::vec4(float(planet.radiusM), float(a.heightM), float(kSunAngularRadiusRad), a.enabled ? 1.0f : 0.0f);
  p.ozoneSun = glm::vec4(float(0.5 * a.ozoneWidthM), gpu::kSunIrradiance, 0.0f, 0.0f);
  if (!a.enabled) {
    p.rayleigh.w = float(1.0 / a.rayleighScaleHeightM);
    p.mieScattering.w = float(1.0 / a.mieScaleHeightM);
    return p;  // no air: every coefficient 0, every transmittance 1
  }
  p.rayleigh = glm::vec4(glm::vec3(a.rayleighScattering), float(1.0 / a.rayleighScaleHeightM));
  p.mieScattering = glm::vec4(glm::vec3(a.mieScattering), float(1.0 / a.mieScaleHeightM));
  p.mieExtinction = glm::vec4(glm::vec3(a.mieScattering * a.mieExtinctionRatio + a.mieAbsorption), float(a.mieG));
  p.ozone = glm::vec4(glm::vec3(a.ozoneAbsorption), float(a.ozoneCenterM));
  return p;
}

glm::dvec3 transmittanceToTop(const AtmosphereParams& atmosphere, double altitudeM, double mu, uint32_t steps) {
  Kernel kernel;
  glm::dvec3 depth = kernel.opticalDepthToTop(atmosphere, altitudeM, mu, steps);
  return glm::exp(-depth);
}

glm::dvec2 transmittanceTexelAltitudeMu(const AtmosphereParams& atmosphere, double u, double v) {
  Kernel kernel;
  return kernel.transmittanceAltitudeMu(atmosphere, u, v);
}

SkySample skyRadiance(const AtmosphereParams& atmosphere, double altitudeM, double mu, double muS, double nu,
                      uint32_t steps, uint32_t sunSteps) {
  Kernel kernel;
  kernel.sunSteps = sunSteps;
  const double R = atmosphere.radii.x;
  const double top = atmosphere.radii.y;
  double start = 0.0;
  double h = altitudeM, m = mu, ms = muS;
  if (altitudeM > top) {  // outside: start where the ray enters the atmosphere
    glm::dvec2 enter = kernel.raySphere(R, altitudeM, mu, top);
    if (enter.x < 0.0) return {glm::dvec3(0.0), glm::dvec3(1.0)};
    start = enter.x;
    h = top;
    const double r = R + altitudeM;
    m = (r * mu + start) / (R + h);
    ms = (r * muS + start * nu) / (R + h);
  }
  const double length =
      kernel.rayHitsGround(R, h, m) ? kernel.raySphere(R, h, m, 0.0).x : kernel.distanceToTop(atmosphere, h, m);
  SkySample sample;
  kernel.singleScattering(atmosphere, h, m, ms, nu, length, steps, sample.radiance, sample.transmittance);
  return sample;
}

glm::dvec3 skyIrradiance(const AtmosphereParams& atmosphere, double muS) {
  // E = ∫ L(ω) cos θ dω over the upper hemisphere, by the midpoint rule in (cos θ, φ): with
  // dω = d(cos θ) dφ the weight of each cell is cos θ · Δ(cos θ) · Δφ.
  constexpr int kZenith = 12, kAzimuth = 16;
  const double sinS = std::sqrt(std::max(0.0, 1.0 - muS * muS));
  glm::dvec3 sum(0.0);
  for (int i = 0; i < kZenith; ++i) {
    const double mu = (i + 0.5) / kZenith;
    const double sinV = std::sqrt(1.0 - mu * mu);
    for (int j = 0; j < kAzimuth; ++j) {
      const double phi = (j + 0.5) / kAzimuth * 2.0 * std::numbers::pi;
      const double nu = mu * muS + sinV * sinS * std::cos(phi);
      sum += skyRadiance(atmosphere, 0.0, mu, muS, nu, 32, 48).radiance * mu;
    }
  }
  return sum * (1.0 / kZenith) * (2.0 * std::numbers::pi / kAzimuth);
}

std::array<glm::vec4, kSkyIrradianceSamples> skyIrradianceTable(const AtmosphereParams& atmosphere) {
  std::array<glm::vec4, kSkyIrradianceSamples> table{};
  if (atmosphere.radii.w == 0.0f) return table;
  for (int i = 0; i < kSkyIrradianceSamples; ++i) {
    const double muS = kSkyIrradianceMinMuS + (1.0 - kSkyIrradianceMinMuS) * i / (kSkyIrradianceSamples - 1);
    table[size_t(i)] = glm::vec4(glm::vec3(skyIrradiance(atmosphere, muS)), 0.0f);
  }
  return table;
}

}  // namespace planet
