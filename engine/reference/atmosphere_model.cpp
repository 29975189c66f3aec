// Compiled without fused multiply-adds (the project-wide rule), so that the double evaluation
// follows the shared source step by step.
#include "reference/atmosphere_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/definitions.h"
#include "core/parallel_for.h"
#include "shared/exposure_params.h"

namespace planet {
namespace {

using gpu::AirglowParams;
using gpu::AtmosphereParams;
using gpu::kMultiScatteringDirections;
using gpu::kMultiScatteringGroundAlbedo;
using gpu::kMultiScatteringSize;
using gpu::kMultiScatteringSteps;
using gpu::kSkyViewHeight;
using gpu::kSkyViewSteps;
using gpu::kSkyViewWidth;
using gpu::kStepsEqual;
using gpu::kStepsTowardEnd;
using gpu::kStepsTowardStart;
using gpu::kTransmittanceHeight;
using gpu::kTransmittanceSteps;
using gpu::kTransmittanceWidth;

}  // namespace

glm::dvec3 sampleBilinear(const std::vector<glm::dvec3>& table, uint32_t width, uint32_t height, double u, double v) {
  const double x = u * width - 0.5, y = v * height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const double fx = x - x0, fy = y - y0;
  const auto at = [&](double i, double j) {
    const int ix = std::clamp(int(i), 0, int(width) - 1), iy = std::clamp(int(j), 0, int(height) - 1);
    return table[size_t(iy) * width + size_t(ix)];
  };
  return glm::mix(glm::mix(at(x0, y0), at(x0 + 1.0, y0), fx), glm::mix(at(x0, y0 + 1.0), at(x0 + 1.0, y0 + 1.0), fx),
                  fy);
}

namespace {

// shaders/common/atmosphere.glsl compiled as C++: its functions become members, so that one
// source gives the GPU code and this reference.
template <typename Real>
struct AtmosphereKernel {
  PLANET_GLSL_KERNEL(Real)

  uint32_t sunSteps = 512;  // midpoint steps of each sun transmittance
  // When set, the sun's transmittance is read from this double transmittance table as the GPU
  // reads its own (atmosphere_lookup.glsl), instead of integrated.
  const std::vector<glm::dvec3>* transmittanceTable = nullptr;
  // MULTIPLE_SCATTERING's table.
  const MultipleScatteringTable* multipleScatteringTable = nullptr;

  static real cos(real x) { return std::cos(x); }
  static real acos(real x) { return std::acos(x); }
  static real atan(real y, real x) { return std::atan2(y, x); }

  // The sun's transmittance with the planet's shadow: zero once the sun is below the horizon
  // of altitude h (the GPU softens this edge over the sun's disc; the reference is sharp, except
  // when it reads a table as the GPU does).
  vec3 sunTransmittance(const AtmosphereParams& a, real h, real muS) {
    if (transmittanceTable) {
      const real R = a.radii.x, hc = max(h, real(0));
      const real horizon = -sqrt(hc * (real(2) * R + hc)) / (R + hc);
      const real visible = glm::smoothstep(-real(a.radii.z), real(a.radii.z), muS - horizon);
      if (visible <= real(0)) return vec3(0);
      const vec2 uv = transmittanceUv(a, hc, muS);
      return sampleBilinear(*transmittanceTable, kTransmittanceWidth, kTransmittanceHeight, uv.x, uv.y) * visible;
    }
    if (rayHitsGround(real(a.radii.x), h, muS)) return vec3(0);
    vec3 depth = opticalDepthToTop(a, h, muS, sunSteps);
    return vec3(exp(-depth.x), exp(-depth.y), exp(-depth.z));
  }

  vec3 multipleScatteringLookup(const AtmosphereParams& a, real h, real muS) {
    return multipleScatteringTable->sample(a, h, muS);
  }

#define SUN_TRANSMITTANCE(a, h, muS) sunTransmittance(a, h, muS)
#define MULTIPLE_SCATTERING(a, h, muS) multipleScatteringLookup(a, h, muS)
#include "common/atmosphere.glsl"
#undef MULTIPLE_SCATTERING
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
  p.mieExtinction = glm::vec4(glm::vec3(a.mieScattering * a.mieExtinctionRatio + a.mieAbsorption), 0.0f);
  p.mieG = glm::vec4(glm::vec3(a.mieG), 0.0f);
  p.ozone = glm::vec4(glm::vec3(a.ozoneAbsorption), float(a.ozoneCenterM));
  return p;
}

AirglowParams makeAirglowParams(const PlanetDescription& planet) {
  const AtmosphereDescription& a = planet.atmosphere;
  AirglowParams p{};
  if (!a.enabled || !(a.airglowCdM2 > 0.0)) return p;
  // The colour scaled to the luminance asked for, in the frame's unit.
  const glm::dvec3 color(a.airglowColor);
  const double luminance = glm::dot(color, glm::dvec3(0.2126, 0.7152, 0.0722));
  const glm::dvec3 radiance = color * (a.airglowCdM2 / gpu::kExposureSunCdM2 / luminance);
  p.radiance = glm::vec4(glm::vec3(radiance), 1.0f);
  p.layer = glm::vec4(float(a.airglowBottomM), float(a.airglowTopM), 0.0f, 0.0f);
  return p;
}

AirglowLight airglowAlong(const AirglowParams& airglow, double radiusM, double altitudeM, double mu, double tEndM) {
  Kernel kernel;
  AirglowLight light;
  kernel.airglowAlong(airglow, radiusM, altitudeM, mu, tEndM, light.nearLight, light.farLight);
  return light;
}

glm::dvec3 transmittanceToTop(const AtmosphereParams& atmosphere, double altitudeM, double mu, uint32_t steps) {
  Kernel kernel;
  glm::dvec3 depth = kernel.opticalDepthToTop(atmosphere, altitudeM, mu, steps);
  return glm::exp(-depth);
}

glm::dvec3 transmittanceAlong(const AtmosphereParams& atmosphere, double altitudeM, double mu, double distanceM,
                              uint32_t steps) {
  Kernel kernel;
  return glm::exp(-kernel.opticalDepthAlong(atmosphere, altitudeM, mu, distanceM, steps));
}

glm::dvec2 cameraTransmittanceUnit(double mu, double distanceM, double muHorizon, double farthestM) {
  Kernel kernel;
  return kernel.cameraTransmittanceUnit(mu, distanceM, muHorizon, farthestM);
}

glm::dvec2 transmittanceTexelAltitudeMu(const AtmosphereParams& atmosphere, double u, double v) {
  Kernel kernel;
  return kernel.transmittanceAltitudeMu(atmosphere, u, v);
}

SkySample skyRadiance(const AtmosphereParams& atmosphere, double altitudeM, double mu, double muS, double nu,
                      uint32_t steps, uint32_t sunSteps, const MultipleScatteringTable* multipleScattering) {
  Kernel kernel;
  kernel.sunSteps = sunSteps;
  const double R = atmosphere.radii.x;
  const double top = atmosphere.radii.y;
  double start = 0.0;
  double h = altitudeM, m = mu, ms = muS;
  double length = 0.0;
  if (altitudeM >= top) {  // outside (or on the top sphere): start where the ray enters the atmosphere
    const glm::dvec2 hits = kernel.raySphere(R, altitudeM, mu, top);
    if (hits.x < 0.0 || hits.y <= hits.x) return {glm::dvec3(0.0), glm::dvec3(1.0), glm::dvec3(0.0)};
    start = hits.x;
    h = top;
    const double r = R + altitudeM;
    m = (r * mu + start) / (R + h);
    ms = (r * muS + start * nu) / (R + h);
    // The end from the viewpoint: from the entry point itself, on the top sphere, a ray going down
    // would meet that sphere at distance 0 and read it as where it leaves.
    const double end = kernel.rayHitsGround(R, altitudeM, mu) ? kernel.raySphere(R, altitudeM, mu, 0.0).x : hits.y;
    length = end - start;
  } else {
    length = kernel.rayHitsGround(R, h, m) ? kernel.raySphere(R, h, m, 0.0).x : kernel.distanceToTop(atmosphere, h, m);
  }
  SkySample sample;
  kernel.singleScattering(atmosphere, h, m, ms, nu, length, steps, sample.radiance, sample.transmittance);
  sample.total = sample.radiance;
  if (multipleScattering && atmosphere.radii.w != 0.0f) {
    kernel.multipleScatteringTable = multipleScattering;
    sample.total += kernel.multipleScattering(atmosphere, h, m, ms, nu, length, steps);
  }
  return sample;
}

glm::dvec3 MultipleScatteringTable::sample(const AtmosphereParams& atmosphere, double altitudeM, double muS) const {
  Kernel kernel;
  const glm::dvec2 uv = kernel.multipleScatteringUv(atmosphere, altitudeM, muS);
  return sampleBilinear(psi, kMultiScatteringSize, kMultiScatteringSize, uv.x, uv.y);
}

glm::dvec2 multipleScatteringTexelAltitudeMuS(const AtmosphereParams& atmosphere, double u, double v) {
  Kernel kernel;
  return kernel.multipleScatteringAltitudeMuS(atmosphere, u, v);
}

MultipleScatteringTable multipleScatteringTable(const AtmosphereParams& atmosphere) {
  MultipleScatteringTable table;
  const size_t texels = size_t(kMultiScatteringSize) * kMultiScatteringSize;
  table.psi.assign(texels, glm::dvec3(0.0));
  table.transfer.assign(texels, glm::dvec3(0.0));
  if (atmosphere.radii.w == 0.0f) return table;  // no air: nothing scatters
  // The transmittance table as atmosphere_transmittance.comp builds it, in double.
  std::vector<glm::dvec3>& transmittance = table.transmittance;
  transmittance.resize(size_t(kTransmittanceWidth) * kTransmittanceHeight);
  parallelFor(transmittance.size(), 256, 0, [&](size_t begin, size_t end) {
    Kernel kernel;
    for (size_t i = begin; i < end; ++i) {
      const double u = (double(i % kTransmittanceWidth) + 0.5) / kTransmittanceWidth;
      const double v = (double(i / kTransmittanceWidth) + 0.5) / kTransmittanceHeight;
      const glm::dvec2 hMu = kernel.transmittanceAltitudeMu(atmosphere, u, v);
      transmittance[i] = glm::exp(-kernel.opticalDepthToTop(atmosphere, hMu.x, hMu.y, kTransmittanceSteps));
    }
  });
  parallelFor(texels, 16, 0, [&](size_t begin, size_t end) {
    Kernel kernel;
    kernel.transmittanceTable = &transmittance;
    for (size_t i = begin; i < end; ++i) {
      const double u = (double(i % kMultiScatteringSize) + 0.5) / kMultiScatteringSize;
      const double v = (double(i / kMultiScatteringSize) + 0.5) / kMultiScatteringSize;
      const glm::dvec2 hMuS = kernel.multipleScatteringAltitudeMuS(atmosphere, u, v);
      kernel.multipleScatteringTexel(atmosphere, hMuS.x, hMuS.y, table.psi[i], table.transfer[i]);
    }
  });
  return table;
}

MultipleScatteringPoint multipleScatteringAt(const AtmosphereParams& atmosphere, double altitudeM, double muS,
                                             uint32_t sunSteps) {
  Kernel kernel;
  kernel.sunSteps = sunSteps;
  MultipleScatteringPoint point{glm::dvec3(0.0), glm::dvec3(0.0)};
  if (atmosphere.radii.w == 0.0f) return point;
  kernel.multipleScatteringTexel(atmosphere, altitudeM, muS, point.psi, point.transfer);
  return point;
}

std::vector<glm::dvec3> skyViewTable(const AtmosphereParams& atmosphere, double altitudeM, double groundM, double muS,
                                     const MultipleScatteringTable& multipleScattering) {
  std::vector<glm::dvec3> table(size_t(gpu::kSkyViewWidth) * gpu::kSkyViewHeight, glm::dvec3(0.0));
  if (atmosphere.radii.w == 0.0f) return table;
  parallelFor(table.size(), 64, 0, [&](size_t begin, size_t end) {
    Kernel kernel;
    kernel.transmittanceTable = &multipleScattering.transmittance;
    kernel.multipleScatteringTable = &multipleScattering;
    for (size_t i = begin; i < end; ++i) {
      const double u = (double(i % gpu::kSkyViewWidth) + 0.5) / gpu::kSkyViewWidth;
      const double v = (double(i / gpu::kSkyViewWidth) + 0.5) / gpu::kSkyViewHeight;
      table[i] = kernel.skyViewTexel(atmosphere, altitudeM, groundM, muS, u, v);
    }
  });
  return table;
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
