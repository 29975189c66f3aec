// The sky on lavapipe (issue 4, point 6): the transmittance table against the CPU reference of
// the same source, and pixel checks of physical expectations on rendered frames.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/image_file.h"
#include "gpu_fixture.h"
#include "planet/terrain_height.h"
#include "reference/atmosphere_model.h"
#include "render/renderer.h"
#include "render/sky_tables.h"
#include "vk/commands.h"

namespace planet::test {
namespace {

using SkyRender = GpuTest;

struct Rgb {
  double r = 0, g = 0, b = 0;
  double luminance() const { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }
};

// Mean display colour (0..255) of the rectangle [x0, x1) × [y0, y1).
Rgb meanColor(const Rgba8Image& image, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) {
  Rgb sum;
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = x0; x < x1; ++x) {
      const uint8_t* p = &image.pixels[(size_t(y) * image.width + x) * 4];
      sum.r += p[0];
      sum.g += p[1];
      sum.b += p[2];
    }
  const double n = double(x1 - x0) * double(y1 - y0);
  return {sum.r / n, sum.g / n, sum.b / n};
}

// Median luminance of an area, and how many of its pixels are brighter than `bright`.
struct Spread {
  double median = 0.0;
  int brightPixels = 0;
};
Spread luminanceSpread(const Rgba8Image& image, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, double bright) {
  std::vector<double> values;
  Spread spread;
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = x0; x < x1; ++x) {
      const uint8_t* p = &image.pixels[(size_t(y) * image.width + x) * 4];
      values.push_back(0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]);
      spread.brightPixels += values.back() > bright ? 1 : 0;
    }
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  spread.median = values[values.size() / 2];
  return spread;
}

RenderSettings skySettings() {
  RenderSettings settings;
  settings.width = 96;
  settings.height = 64;
  settings.terrain.patchSettings.resolution = 128;
  settings.terrain.patchSettings.levelCount = 3;
  return settings;
}

// Earth without clouds, so that the sky checks see the clear sky.
PlanetDescription clearEarth() {
  PlanetDescription earth = resolvePreset("earth");
  earth.clouds.enabled = false;
  return earth;
}

TEST_F(SkyRender, TransmittanceTableMatchesCpuReference) {
  for (const char* preset : {"earth", "mars"}) {
    const PlanetDescription planet = resolvePreset(preset);
    SkyTables tables(context(), planet);
    vk::submitAndWait(context(), [&](VkCommandBuffer cmd) { tables.recordBuild(cmd, nullptr); });
    const std::vector<glm::vec4> table = tables.readTransmittance();
    ASSERT_EQ(table.size(), size_t(gpu::kTransmittanceWidth) * gpu::kTransmittanceHeight);
    double worst = 0.0;
    for (uint32_t y = 0; y < gpu::kTransmittanceHeight; y += 3)
      for (uint32_t x = 0; x < gpu::kTransmittanceWidth; x += 5) {
        const glm::dvec2 hMu = transmittanceTexelAltitudeMu(tables.atmosphere(), (x + 0.5) / gpu::kTransmittanceWidth,
                                                            (y + 0.5) / gpu::kTransmittanceHeight);
        const glm::dvec3 expected = transmittanceToTop(tables.atmosphere(), hMu.x, hMu.y);
        const glm::vec4 actual = table[size_t(y) * gpu::kTransmittanceWidth + x];
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(actual[c]) - expected[c]));
      }
    // The table integrates with 500 float steps, the reference with 4096 double ones.
    EXPECT_LT(worst, 2e-3) << preset;
    // The first texel is the ground looking straight up: the closed form of an exponential
    // atmosphere, exp(−Σ β·H·(1 − e^(−top/H))).
    const AtmosphereDescription& a = planet.atmosphere;
    glm::dvec3 depth(0.0);
    const gpu::AtmosphereParams& p = tables.atmosphere();
    for (int c = 0; c < 3; ++c)
      depth[c] = p.rayleigh[c] * a.rayleighScaleHeightM * (1.0 - std::exp(-a.heightM / a.rayleighScaleHeightM)) +
                 p.mieExtinction[c] * a.mieScaleHeightM * (1.0 - std::exp(-a.heightM / a.mieScaleHeightM));
    if (a.ozoneAbsorption == glm::dvec3(0.0)) {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(table[0][c], std::exp(-depth[c]), 2e-3) << preset << " channel " << c;
    }
  }
}

TEST_F(SkyRender, HdrFrameIsFiniteEverywhere) {
  Renderer renderer(context(), resolvePreset("earth"), skySettings());
  const CameraPose views[] = {
      {20, -30, 2.0e7, 0, -90}, {20, -30, 1.0e5, 90, -10}, {20, -30, 2, 90, 10}, {0, 0, 2, 0, 90}};
  for (const CameraPose& camera : views)
    for (double elevation : {60.0, 1.0, -30.0}) {
      const RenderResult result = renderer.render(camera, {135.0, elevation}, 1234.5, true);
      ASSERT_EQ(result.hdr.size(), size_t(96 * 64));
      for (const glm::vec4& texel : result.hdr)
        for (int c = 0; c < 3; ++c)
          ASSERT_TRUE(std::isfinite(texel[c]) && texel[c] >= 0.0f)
              << "altitude " << camera.altitudeM << " sun " << elevation << ": " << texel[c];
    }
}

TEST_F(SkyRender, SpaceIsBlackWithStars) {
  // From 20,000 km looking up (away from the planet): black space with stars in it.
  RenderSettings settings = skySettings();
  settings.width = 320;
  settings.height = 180;
  PlanetDescription earth = resolvePreset("earth");
  {
    Renderer renderer(context(), earth, settings);
    const Spread sky = luminanceSpread(renderer.render({20, -30, 2.0e7, 0, 80}, {135, 35}).image, 0, 0, 320, 180, 60.0);
    EXPECT_LT(sky.median, 4.0);
    EXPECT_GE(sky.brightPixels, 5);
  }
  earth.stars.enabled = false;
  Renderer renderer(context(), earth, settings);
  const Spread empty = luminanceSpread(renderer.render({20, -30, 2.0e7, 0, 80}, {135, 35}).image, 0, 0, 320, 180, 60.0);
  EXPECT_EQ(empty.brightPixels, 0);
  EXPECT_LT(empty.median, 1.0);
}

// Stars fade out where the sky in front of them is bright: none in the daytime sky from the
// ground, plenty at night from the same place.
TEST_F(SkyRender, NoStarsInTheDaytimeSky) {
  RenderSettings settings = skySettings();
  settings.width = 320;
  settings.height = 180;
  Renderer renderer(context(), clearEarth(), settings);
  const CameraPose up{20, -30, 2, 0, 60};
  const Rgba8Image day = renderer.render(up, {135, 50}).image;
  const Rgba8Image night = renderer.render(up, {135, -30}).image;
  const Spread nightSky = luminanceSpread(night, 0, 0, 320, 180, 60.0);
  EXPECT_GE(nightSky.brightPixels, 5);
  EXPECT_LT(nightSky.median, 6.0);
  // By day no pixel stands out from its neighbours three pixels away on either side (the sky
  // itself changes smoothly).
  auto lum = [&](uint32_t x, uint32_t y) {
    const uint8_t* p = &day.pixels[(size_t(y) * 320 + x) * 4];
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
  };
  int outliers = 0;
  for (uint32_t y = 0; y < 180; ++y)
    for (uint32_t x = 3; x + 3 < 320; ++x) outliers += lum(x, y) > std::max(lum(x - 3, y), lum(x + 3, y)) + 8.0 ? 1 : 0;
  EXPECT_EQ(outliers, 0);
}

TEST_F(SkyRender, NoonSkyIsBlueAtZenithAndBrighterTowardHorizon) {
  Renderer renderer(context(), clearEarth(), skySettings());
  // Standing at 2 m, looking north and 45° up, the sun high in the south-east.
  const RenderResult result = renderer.render({20, -30, 2, 0, 45}, {135, 60});
  const Rgb top = meanColor(result.image, 32, 0, 64, 6);    // ~75° above the horizon
  const Rgb low = meanColor(result.image, 32, 52, 64, 58);  // ~18° above the horizon
  EXPECT_GT(top.b, top.r + 40) << top.r << " " << top.g << " " << top.b;
  EXPECT_GT(top.b, top.g);
  EXPECT_GT(low.luminance(), top.luminance() + 10) << low.luminance() << " vs " << top.luminance();
}

TEST_F(SkyRender, SunsetSkyIsRedShifted) {
  Renderer renderer(context(), clearEarth(), skySettings());
  // Looking toward the sun just above the horizon, at noon and at sunset.
  const Rgb noon = meanColor(renderer.render({20, -30, 2, 135, 8}, {135, 60}).image, 0, 20, 96, 30);
  const Rgb sunset = meanColor(renderer.render({20, -30, 2, 135, 8}, {135, 2}).image, 0, 20, 96, 30);
  EXPECT_GT(sunset.r / std::max(sunset.b, 1.0), 2.0 * noon.r / std::max(noon.b, 1.0))
      << "noon " << noon.r << "," << noon.g << "," << noon.b << " sunset " << sunset.r << "," << sunset.g << ","
      << sunset.b;
  EXPECT_GT(sunset.r, sunset.b);
}

// A sea point and a beach point found with the CPU reference, seen straight down from 300 m.
TEST_F(SkyRender, OceanIsDarkerThanBeach) {
  const PlanetDescription earth = clearEarth();
  glm::dvec2 sea(1000.0), beach(1000.0);
  for (double lat = -50.0; lat <= 50.0 && (sea.x > 999.0 || beach.x > 999.0); lat += 0.37)
    for (double lon = -180.0; lon < 180.0; lon += 0.53) {
      const double h = terrainHeightM(earth, directionFromLatLon(lat, lon));
      if (h < -300.0 && sea.x > 999.0) sea = {lat, lon};
      if (h > 2.0 && h < earth.colors.beachHeightM * 0.5 && beach.x > 999.0) beach = {lat, lon};
    }
  ASSERT_LT(sea.x, 999.0);
  ASSERT_LT(beach.x, 999.0);
  Renderer renderer(context(), earth, skySettings());
  const double h = terrainHeightM(earth, directionFromLatLon(beach.x, beach.y));
  const Rgb water = meanColor(renderer.render({sea.x, sea.y, 300, 0, -90}, {135, 50}).image, 40, 24, 56, 40);
  const Rgb sand = meanColor(renderer.render({beach.x, beach.y, h + 300, 0, -90}, {135, 50}).image, 44, 28, 52, 36);
  EXPECT_LT(water.luminance() * 1.5, sand.luminance()) << water.luminance() << " vs " << sand.luminance();
  EXPECT_GT(water.b, water.r);  // the sea is blue
}

// Without patch textures (the viewer's low quality) the sea has no face frame for its waves: it
// once became NaN there and was drawn pale grey-blue. Open sea seen from 1000 km must look the
// same with and without them.
TEST_F(SkyRender, SeaLooksTheSameWithoutPatchTextures) {
  const PlanetDescription earth = clearEarth();
  const CameraPose camera{20, -30, 1.0e6, 0, -90};
  ASSERT_LT(terrainHeightM(earth, directionFromLatLon(camera.latitudeDeg, camera.longitudeDeg)), -1000.0);
  RenderSettings withPatches = skySettings();
  RenderSettings withoutPatches = skySettings();
  withoutPatches.terrain.patches = false;
  const RenderResult a = Renderer(context(), earth, withPatches).render(camera, {135, 35});
  const RenderResult b = Renderer(context(), earth, withoutPatches).render(camera, {135, 35});
  for (const glm::vec4& texel : b.hdr)
    for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(texel[c]) && texel[c] >= 0.0f) << texel[c];
  const Rgb sea = meanColor(a.image, 40, 24, 56, 40);
  const Rgb plain = meanColor(b.image, 40, 24, 56, 40);
  EXPECT_GT(sea.b, sea.r + 40.0);  // deep blue
  EXPECT_NEAR(plain.r, sea.r, 4.0);
  EXPECT_NEAR(plain.g, sea.g, 4.0);
  EXPECT_NEAR(plain.b, sea.b, 4.0);
}

// White, unsaturated pixels: clouds (the clear sky is blue, the ground darker).
double cloudyFraction(const Rgba8Image& image) {
  size_t white = 0;
  for (size_t i = 0; i < image.pixels.size(); i += 4) {
    const int r = image.pixels[i], g = image.pixels[i + 1], b = image.pixels[i + 2];
    white += (std::min({r, g, b}) > 170 && std::max({r, g, b}) - std::min({r, g, b}) < 40) ? 1 : 0;
  }
  return double(white) / double(image.pixels.size() / 4);
}

TEST_F(SkyRender, CloudsAreSeenFromAboveAndBelowAndDriftWithTime) {
  RenderSettings settings = skySettings();
  settings.width = 160;
  settings.height = 90;
  const PlanetDescription earth = resolvePreset("earth");
  Renderer cloudy(context(), earth, settings);
  Renderer clear(context(), clearEarth(), settings);
  const CameraPose below{20, -30, 2, 315, 55};     // from the sea, looking up, away from the sun
  const CameraPose above{20, -30, 1.5e4, 0, -60};  // from 15 km, looking down
  const SunPose sun{135, 50};
  EXPECT_GT(cloudyFraction(cloudy.render(below, sun).image), 0.05);
  EXPECT_LT(cloudyFraction(clear.render(below, sun).image), 0.005);
  EXPECT_GT(cloudyFraction(cloudy.render(above, sun).image), 0.05);
  EXPECT_LT(cloudyFraction(clear.render(above, sun).image), 0.005);
  // Half an hour later the layer has moved (looking up, nothing else depends on the time).
  const Rgba8Image now = cloudy.render(below, sun, 0.0).image;
  const Rgba8Image later = cloudy.render(below, sun, 1800.0).image;
  EXPECT_GT(psnrRgb(now, later), 0.0);
  EXPECT_LT(psnrRgb(now, later), 30.0);
  EXPECT_EQ(clear.render(below, sun, 0.0).image.pixels, clear.render(below, sun, 1800.0).image.pixels);
}

// The airless Moon: a black sky over a sunlit ground, even by day.
TEST_F(SkyRender, AirlessSkyStaysBlackByDay) {
  Renderer renderer(context(), resolvePreset("moon"), skySettings());
  const RenderResult result = renderer.render({-20, 40, 2, 0, 20}, {100, 40});
  EXPECT_LT(luminanceSpread(result.image, 0, 0, 96, 10, 60.0).median, 3.0);
  const Rgb ground = meanColor(result.image, 0, 54, 96, 64);
  EXPECT_GT(ground.luminance(), 20.0);
}

}  // namespace
}  // namespace planet::test
