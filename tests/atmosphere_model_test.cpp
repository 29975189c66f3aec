// The CPU reference of the atmosphere (engine/reference/atmosphere_model.h): closed forms where
// they exist, and the physical expectations of a clear Earth sky.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "planet/planet_description.h"
#include "reference/atmosphere_model.h"
#include "render/cloud_cover.h"

namespace planet {
namespace {

gpu::AtmosphereParams earthWithoutOzone() {
  PlanetDescription earth = resolvePreset("earth");
  earth.atmosphere.ozoneAbsorption = glm::dvec3(0.0);
  return makeAtmosphereParams(earth);
}

// Straight up from the ground the optical depth of an exponential layer of scale height H up
// to height Z is β·H·(1 − e^(−Z/H)) exactly.
TEST(AtmosphereModel, VerticalTransmittanceMatchesClosedForm) {
  const PlanetDescription earth = resolvePreset("earth");
  const gpu::AtmosphereParams params = earthWithoutOzone();
  const AtmosphereDescription& a = earth.atmosphere;
  const glm::dvec3 t = transmittanceToTop(params, 0.0, 1.0, 20000);
  for (int c = 0; c < 3; ++c) {
    const double rayleigh =
        double(params.rayleigh[c]) * a.rayleighScaleHeightM * (1.0 - std::exp(-a.heightM / a.rayleighScaleHeightM));
    const double mie =
        double(params.mieExtinction[c]) * a.mieScaleHeightM * (1.0 - std::exp(-a.heightM / a.mieScaleHeightM));
    const double expected = std::exp(-(rayleigh + mie));
    EXPECT_NEAR(t[c], expected, 1e-6 * expected) << "channel " << c;
  }
  // Earth's zenith transmittance is about 0.75 in red... 0.3 in blue (with haze).
  EXPECT_GT(t.r, t.g);
  EXPECT_GT(t.g, t.b);
}

TEST(AtmosphereModel, HorizonTransmittanceIsFarBelowZenith) {
  const gpu::AtmosphereParams params = makeAtmosphereParams(resolvePreset("earth"));
  const glm::dvec3 zenith = transmittanceToTop(params, 0.0, 1.0);
  const glm::dvec3 horizon = transmittanceToTop(params, 0.0, 0.0);
  for (int c = 0; c < 3; ++c) EXPECT_LT(horizon[c], 0.2 * zenith[c]);
  // A horizontal ray from 50 km sees much less air than one from the ground.
  EXPECT_GT(transmittanceToTop(params, 50'000.0, 0.0).b, 10.0 * horizon.b);
}

TEST(AtmosphereModel, NoAirMeansFullTransmittanceAndBlackSky) {
  const gpu::AtmosphereParams params = makeAtmosphereParams(resolvePreset("moon"));
  EXPECT_EQ(transmittanceToTop(params, 0.0, 0.1), glm::dvec3(1.0));
  EXPECT_EQ(skyRadiance(params, 0.0, 0.5, 0.5, 0.3).radiance, glm::dvec3(0.0));
}

// Noon: the zenith is blue; the sky toward the horizon is brighter than the zenith.
TEST(AtmosphereModel, NoonSkyIsBlueAtZenithAndBrighterTowardHorizon) {
  const gpu::AtmosphereParams params = makeAtmosphereParams(resolvePreset("earth"));
  const double muS = std::cos(30.0 * 3.14159265358979 / 180.0);
  const glm::dvec3 zenith = skyRadiance(params, 2.0, 1.0, muS, muS).radiance;
  EXPECT_GT(zenith.b, 1.5 * zenith.r);
  // 5° above the horizon, 90° in azimuth from the sun.
  const double mu = std::sin(5.0 * 3.14159265358979 / 180.0);
  const double nu = mu * muS;
  const glm::dvec3 horizon = skyRadiance(params, 2.0, mu, muS, nu).radiance;
  const auto luminance = [](const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
  EXPECT_GT(luminance(horizon), 1.3 * luminance(zenith));
}

// Sunset: the sky toward the sun near the horizon is red-shifted compared with noon's.
TEST(AtmosphereModel, SunsetSkyTowardTheSunIsRedShifted) {
  const gpu::AtmosphereParams params = makeAtmosphereParams(resolvePreset("earth"));
  const double mu = std::sin(3.0 * 3.14159265358979 / 180.0);
  const double sunsetMuS = std::sin(2.0 * 3.14159265358979 / 180.0);
  const glm::dvec3 sunset =
      skyRadiance(params, 2.0, mu, sunsetMuS, std::cos(std::asin(mu) - std::asin(sunsetMuS))).radiance;
  const double noonMuS = std::sin(60.0 * 3.14159265358979 / 180.0);
  const glm::dvec3 noon = skyRadiance(params, 2.0, mu, noonMuS, std::cos(std::asin(mu) - std::asin(noonMuS))).radiance;
  EXPECT_GT(sunset.r / sunset.b, 2.0 * (noon.r / noon.b));
  EXPECT_GT(sunset.r, sunset.b);
}

TEST(AtmosphereModel, SkyIrradianceGrowsWithSunElevationAndVanishesAtNight) {
  const gpu::AtmosphereParams params = makeAtmosphereParams(resolvePreset("earth"));
  const auto table = skyIrradianceTable(params);
  EXPECT_LT(table.front().b, 1e-3 * table.back().b);  // sun 11° below the horizon
  for (int i = 1; i < kSkyIrradianceSamples; ++i) EXPECT_GE(table[size_t(i)].b, table[size_t(i - 1)].b) << i;
  // Clear-sky diffuse light at high sun is roughly a tenth of the direct sun (blue-heavy).
  const glm::vec4 high = table.back();
  EXPECT_GT(high.b, 0.03f);
  EXPECT_LT(high.b, 0.4f);
  EXPECT_GT(high.b, high.r);
}

// Seed 001 eq. 4.2: the three cover images' weights always sum to 1, and the layer drifts at
// the wind speed.
TEST(CloudMotion, WeightsSumToOneAndTheLayerDriftsWithTheWind) {
  CloudDescription clouds;
  clouds.windMps = 10.0;
  clouds.evolvePeriodS = 1000.0;
  for (double t : {0.0, 123.0, 500.0, 999.0, 1e6}) {
    const CloudMotion m = cloudMotion(clouds, 6.371e6, t);
    EXPECT_NEAR(m.weights.x + m.weights.y + m.weights.z, 1.0, 1e-6) << t;
    EXPECT_GE(std::min({m.weights.x, m.weights.y, m.weights.z}), 0.0f);
  }
  EXPECT_FLOAT_EQ(cloudMotion(clouds, 6.371e6, 0.0).weights.x, 2.0f / 3.0f);
  const double layerRadius = 6.371e6 + 0.5 * (clouds.bottomM + clouds.topM);
  EXPECT_NEAR(cloudMotion(clouds, 6.371e6, 3600.0).driftRad, 10.0 * 3600.0 / layerRadius, 1e-6);
}

}  // namespace
}  // namespace planet
