// The CPU reference of the atmosphere (engine/reference/atmosphere_model.h): closed forms where
// they exist, and the physical expectations of a clear Earth sky.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "planet/planet_description.h"
#include "reference/atmosphere_model.h"
#include "render/cloud_cover.h"
#include "shared/exposure_params.h"

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

// --- Multiple scattering (issue 21; Hillaire 2020, §5.5) ----------------------------------------

double skyLuminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// Energy: every order after the first returns less than it received (f_ms < 1), so the series
// converges and Ψ_ms is finite and non-negative everywhere, for both presets with air.
TEST(AtmosphereModel, MultipleScatteringTableIsFiniteAndConservesEnergy) {
  for (const char* preset : {"earth", "mars"}) {
    const gpu::AtmosphereParams params = makeAtmosphereParams(resolvePreset(preset));
    const MultipleScatteringTable table = multipleScatteringTable(params);
    ASSERT_EQ(table.psi.size(), size_t(gpu::kMultiScatteringSize) * gpu::kMultiScatteringSize);
    double mostTransfer = 0.0;
    for (size_t i = 0; i < table.psi.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        ASSERT_TRUE(std::isfinite(table.psi[i][c]) && table.psi[i][c] >= 0.0) << preset << " texel " << i;
        ASSERT_GE(table.transfer[i][c], 0.0) << preset << " texel " << i;
        mostTransfer = std::max(mostTransfer, table.transfer[i][c]);
      }
    // Earth's blue at the ground returns about a third; nothing comes near 1.
    EXPECT_LT(mostTransfer, 0.8) << preset;
    EXPECT_GT(mostTransfer, 0.05) << preset;
  }
  // No air: nothing scatters.
  const MultipleScatteringTable none = multipleScatteringTable(makeAtmosphereParams(resolvePreset("moon")));
  for (const glm::dvec3& psi : none.psi) EXPECT_EQ(psi, glm::dvec3(0.0));
}

// The table reads the sun's transmittance from a table as the GPU does; integrating it directly
// at each sample gives the same Ψ_ms within 1 % where the sun is up.
TEST(AtmosphereModel, MultipleScatteringTableMatchesDirectIntegration) {
  const gpu::AtmosphereParams params = makeAtmosphereParams(resolvePreset("earth"));
  const MultipleScatteringTable table = multipleScatteringTable(params);
  for (uint32_t y : {0u, 5u, 16u, 31u})
    for (uint32_t x : {18u, 24u, 31u}) {
      const glm::dvec2 hMuS = multipleScatteringTexelAltitudeMuS(params, (x + 0.5) / gpu::kMultiScatteringSize,
                                                                 (y + 0.5) / gpu::kMultiScatteringSize);
      const MultipleScatteringPoint direct = multipleScatteringAt(params, hMuS.x, hMuS.y, 1024);
      const size_t i = size_t(y) * gpu::kMultiScatteringSize + x;
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(table.psi[i][c], direct.psi[c], 0.01 * direct.psi[c]) << "texel " << x << ", " << y << " c " << c;
        EXPECT_NEAR(table.transfer[i][c], direct.transfer[c], 1e-9) << "texel " << x << ", " << y;
      }
    }
}

// More air scatters more: doubling Rayleigh and Mie raises Ψ_ms by day (a little near the ground,
// where the sunlit ground, seen through more air, gives much of it) and the share f_ms that one
// more scattering returns much more.
TEST(AtmosphereModel, MultipleScatteringGrowsWithDensity) {
  PlanetDescription earth = resolvePreset("earth");
  const gpu::AtmosphereParams thin = makeAtmosphereParams(earth);
  earth.atmosphere.rayleighScattering *= 2.0;
  earth.atmosphere.mieScattering *= 2.0;
  const gpu::AtmosphereParams dense = makeAtmosphereParams(earth);
  const MultipleScatteringTable thinTable = multipleScatteringTable(thin);
  const MultipleScatteringTable denseTable = multipleScatteringTable(dense);
  for (double altitudeM : {0.0, 5'000.0, 20'000.0})
    for (double muS : {1.0, 0.5}) {
      const glm::dvec3 a = thinTable.sample(thin, altitudeM, muS), b = denseTable.sample(dense, altitudeM, muS);
      EXPECT_GT(skyLuminance(b), 1.03 * skyLuminance(a)) << altitudeM << " m, muS " << muS;
    }
  // And so does the share that one more scattering returns.
  EXPECT_GT(denseTable.transfer[0].g, 1.5 * thinTable.transfer[0].g);
}

// What the sky adds, σ_s · Ψ_ms, is ~0 at the top of the atmosphere (no air there) and ~0 at
// night (the sun far below the horizon lights none of the air a point sees).
TEST(AtmosphereModel, MultipleScatteringVanishesAtTheTopAndAtNight) {
  const gpu::AtmosphereParams params = makeAtmosphereParams(resolvePreset("earth"));
  const MultipleScatteringTable table = multipleScatteringTable(params);
  const double top = params.radii.y;
  const auto source = [&](double h, double muS) {
    const double rayleigh = double(params.rayleigh.g) * std::exp(-h * double(params.rayleigh.w));
    const double mie = double(params.mieScattering.g) * std::exp(-h * double(params.mieScattering.w));
    return (rayleigh + mie) * table.sample(params, h, muS).g;
  };
  EXPECT_LT(source(top, 1.0), 1e-4 * source(0.0, 1.0));
  const double noon = table.sample(params, 0.0, 1.0).b;
  EXPECT_GT(noon, 0.0);
  for (double h : {0.0, 10'000.0, 50'000.0, top}) EXPECT_LT(table.sample(params, h, -1.0).b, 1e-6 * noon) << h;
}

// Twilight (issue 21, point 3): 10 km up with the sun 4° below the horizon, single scattering
// leaves the zenith faint and purple (red above green); the light scattered more than once adds
// half again to its blue.
TEST(AtmosphereModel, MultipleScatteringLightsTheTwilightZenithBlue) {
  const gpu::AtmosphereParams params = makeAtmosphereParams(resolvePreset("earth"));
  const MultipleScatteringTable table = multipleScatteringTable(params);
  const double muS = std::sin(-4.0 * 3.14159265358979 / 180.0);
  const SkySample zenith = skyRadiance(params, 10'000.0, 1.0, muS, muS, 256, 256, &table);
  EXPECT_GT(zenith.total.b, zenith.total.r);
  EXPECT_GT(zenith.total.b, 1.3 * zenith.radiance.b);
  EXPECT_GT(zenith.total.b, zenith.total.g);
  EXPECT_GT(skyLuminance(zenith.total), 1.1 * skyLuminance(zenith.radiance));
  // Without a table the total is the single scattering.
  const SkySample single = skyRadiance(params, 10'000.0, 1.0, muS, muS, 256, 256);
  EXPECT_EQ(single.total, single.radiance);
  EXPECT_EQ(single.radiance, zenith.radiance);
  // By day it adds a part, not the whole: at noon from the ground it is under half the zenith's light.
  const SkySample noon = skyRadiance(params, 0.0, 1.0, 1.0, 1.0, 256, 256, &table);
  EXPECT_GT(skyLuminance(noon.total), skyLuminance(noon.radiance));
  EXPECT_LT(skyLuminance(noon.total), 2.0 * skyLuminance(noon.radiance));
}

// The sky along a view of elevation `viewDeg` and azimuth `azimuthDeg` from the sun's, with the
// sun at `sunDeg`, seen from altitude h: single and multiple scattering (256 steps).
glm::dvec3 skyTotal(const gpu::AtmosphereParams& params, const MultipleScatteringTable& table, double h, double sunDeg,
                    double viewDeg, double azimuthDeg) {
  const double deg = 3.14159265358979 / 180.0;
  const double mu = std::sin(viewDeg * deg), muS = std::sin(sunDeg * deg);
  const double nu = mu * muS + std::cos(viewDeg * deg) * std::cos(sunDeg * deg) * std::cos(azimuthDeg * deg);
  return skyRadiance(params, h, mu, muS, nu, 256, 256, &table).total;
}

// Twilight from the ground too (issue 21, point 3): with the sun 4° below the horizon the zenith
// is blue (blue over red), and the sky 2° above the horizon under the sun (which dips 3.2°
// below the level at 10 km) glows orange (red over blue, red over green).
TEST(AtmosphereModel, TwilightFromTheGroundIsBlueOverheadAndOrangeUnderTheSun) {
  const gpu::AtmosphereParams params = makeAtmosphereParams(resolvePreset("earth"));
  const MultipleScatteringTable table = multipleScatteringTable(params);
  for (double h : {2.0, 10'000.0}) {
    const glm::dvec3 zenith = skyTotal(params, table, h, -4.0, 90.0, 0.0);
    const double dipDeg = std::acos(params.radii.x / (params.radii.x + h)) * 180.0 / 3.14159265358979;
    const glm::dvec3 glow = skyTotal(params, table, h, -4.0, 2.0 - dipDeg, 0.0);
    EXPECT_GT(zenith.b, 1.2 * zenith.r) << h;
    EXPECT_GT(glow.r, 1.5 * glow.b) << h;
    EXPECT_GT(glow.r, glow.g) << h;
  }
}

// Mars (issue 21, point 3): by day, 45° up away from the sun, the sky is butterscotch (red over
// green over blue); at sunset the sky around the sun is blue (blue over red), as the dust scatters
// blue light more forward than red (the preset's mie_g) and its grey extinction takes no more blue
// than red out on the way, and the sky opposite is red-brown.
TEST(AtmosphereModel, MarsSkyIsButterscotchByDayAndBlueAroundTheSettingSun) {
  const gpu::AtmosphereParams params = makeAtmosphereParams(resolvePreset("mars"));
  const MultipleScatteringTable table = multipleScatteringTable(params);
  const glm::dvec3 day = skyTotal(params, table, 2.0, 60.0, 45.0, 180.0);
  EXPECT_GT(day.r, 1.1 * day.g);
  EXPECT_GT(day.g, 1.1 * day.b);
  const glm::dvec3 nearSun = skyTotal(params, table, 2.0, 3.0, 5.0, 3.0);
  const glm::dvec3 away = skyTotal(params, table, 2.0, 3.0, 5.0, 180.0);
  EXPECT_GT(nearSun.b, 1.3 * nearSun.r) << nearSun.b / nearSun.r;
  EXPECT_GT(away.r, 2.0 * away.b) << away.b / away.r;
}

// Airglow (issue 21, point 4; common/atmosphere.glsl, airglowAlong), in double. Earth's shell
// emits evenly between 87 and 97 km, so a ray's light is the zenith radiance times its path
// through the shell over 10 km:
// - straight up from the ground, the zenith radiance, all of it beyond the air (`far`);
// - toward the horizon, (sqrt((R + 97 km)² − R²) − sqrt((R + 87 km)² − R²)) / 10 km, 5.9 times
//   (van Rhijn's brightening, before the air in front dims it);
// - from 400 km straight down, the zenith radiance again, now in front of the air (`near`), and
//   nothing behind the ground;
// - from 400 km grazing the shell at 92 km, its chord through the shell on each side of the
//   lowest point (25 times the zenith's each), over 50 times in all: the band along the night
//   side's limb;
// - a ray that ends below the shell (on a mountain) gets none; a body without airglow none.
TEST(AtmosphereModel, AirglowFollowsThePathThroughItsShell) {
  const PlanetDescription earth = resolvePreset("earth");
  const gpu::AirglowParams airglow = makeAirglowParams(earth);
  const double R = earth.radiusM, bottom = earth.atmosphere.airglowBottomM, top = earth.atmosphere.airglowTopM;
  const double kInfinity = 1e30;
  auto luminance = [](const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
  const double zenith = earth.atmosphere.airglowCdM2 / gpu::kExposureSunCdM2;

  const AirglowLight up = airglowAlong(airglow, R, 2.0, 1.0, kInfinity);
  EXPECT_NEAR(luminance(up.farLight) / zenith, 1.0, 1e-6);
  EXPECT_EQ(up.nearLight, glm::dvec3(0.0));
  EXPECT_GT(up.farLight.g, 1.5 * up.farLight.r);  // green
  EXPECT_GT(up.farLight.r, 2.0 * up.farLight.b);

  const AirglowLight horizon = airglowAlong(airglow, R, 0.0, 0.0, kInfinity);
  const double expected =
      (std::sqrt((R + top) * (R + top) - R * R) - std::sqrt((R + bottom) * (R + bottom) - R * R)) / (top - bottom);
  EXPECT_NEAR(luminance(horizon.farLight) / zenith, expected, 1e-4 * expected);
  EXPECT_GT(expected, 5.5);
  EXPECT_LT(expected, 6.5);

  const double orbit = 400e3;
  const AirglowLight down = airglowAlong(airglow, R, orbit, -1.0, orbit);  // ends on the ground
  EXPECT_NEAR(luminance(down.nearLight) / zenith, 1.0, 1e-6);
  EXPECT_EQ(down.farLight, glm::dvec3(0.0));

  const double tangent = 92e3;
  const double muGraze = -std::sqrt(1.0 - std::pow((R + tangent) / (R + orbit), 2.0));
  const AirglowLight limb = airglowAlong(airglow, R, orbit, muGraze, kInfinity);
  const double chord = std::sqrt((R + top) * (R + top) - (R + tangent) * (R + tangent)) / (top - bottom);
  EXPECT_NEAR(luminance(limb.nearLight) / zenith, chord, 1e-3 * chord);
  EXPECT_NEAR(luminance(limb.farLight) / zenith, chord, 1e-3 * chord);
  EXPECT_GT(2.0 * chord, 50.0);

  EXPECT_EQ(airglowAlong(airglow, R, 2.0, 0.3, 40e3).farLight, glm::dvec3(0.0));
  const AirglowLight none = airglowAlong(makeAirglowParams(resolvePreset("mars")), 3389.5e3, 2.0, 1.0, kInfinity);
  EXPECT_EQ(none.farLight + none.nearLight, glm::dvec3(0.0));
}

}  // namespace
}  // namespace planet
