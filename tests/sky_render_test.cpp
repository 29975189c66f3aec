// The sky on lavapipe (issue 4, point 6): the transmittance table against the CPU reference of
// the same source, and pixel checks of physical expectations on rendered frames.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
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

// Earth without clouds from the tables and from the reference march at 320x180: the display
// images' PSNR, and the largest difference between their rows' mean luminances (of 255).
struct MarchComparison {
  Rgba8Image tables;
  double psnr = 0.0;
  double worstRow = 0.0;
};
MarchComparison compareWithMarch(vk::Context& context, const CameraPose& camera, const SunPose& sun) {
  RenderSettings settings;
  settings.width = 320;
  settings.height = 180;
  RenderSettings reference = settings;
  reference.sky.mode = SkyMode::Reference;
  const PlanetDescription earth = clearEarth();
  MarchComparison c;
  c.tables = Renderer(context, earth, settings).render(camera, sun).image;
  const Rgba8Image marched = Renderer(context, earth, reference).render(camera, sun).image;
  for (uint32_t y = 0; y < 180; ++y)
    c.worstRow = std::max(c.worstRow, std::abs(meanColor(c.tables, 0, y, 320, y + 1).luminance() -
                                               meanColor(marched, 0, y, 320, y + 1).luminance()));
  c.psnr = psnrRgb(c.tables, marched);
  return c;
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
  // (1.7 × with multiple scattering, which brings blue light into the sunset sky too; it was 2 ×
  // with single scattering alone.)
  EXPECT_GT(sunset.r / std::max(sunset.b, 1.0), 1.5 * noon.r / std::max(noon.b, 1.0))
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

// Mean luminance (HDR, linear) of the rows [y0, y1) of a frame `width` wide.
double hdrRowsLuminance(const std::vector<glm::vec4>& hdr, uint32_t width, uint32_t y0, uint32_t y1) {
  double sum = 0.0;
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const glm::vec4& c = hdr[size_t(y) * width + x];
      sum += 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    }
  return sum / (double(y1 - y0) * width);
}

// Under an overcast the sea mirrors the cloud base (water.frag): grey, and toward the horizon a
// good part of the sky's light (0.29 just below it), where it was the clear sky's blue darkened
// by the clouds' shadow (navy under a white sky: 0.07). The clouds hide the sun's glint, which the
// shadow's factor of a quarter left blazing. Under the clear sky the rough sea reflects at the
// horizon Fresnel averaged over its waves' facets (about 0.4), not a mirror's (0.9).
TEST_F(SkyRender, TheSeaUnderAnOvercastMirrorsTheCloudBase) {
  RenderSettings settings = skySettings();
  settings.width = 160;
  settings.height = 90;
  PlanetDescription overcast = resolvePreset("earth");
  overcast.clouds.coverage = 0.95;
  ASSERT_LT(terrainHeightM(overcast, directionFromLatLon(20, -30)), -1000.0);
  Renderer renderer(context(), overcast, settings);
  // From a deck, 3 degrees below the horizon: the horizon at row ~40 of 90.
  const CameraPose deck{20, -30, 10, 0, -3};
  const SunPose sun{135, 35};
  const RenderResult cloudy = renderer.render(deck, sun, 0.0, true);
  const double sky = hdrRowsLuminance(cloudy.hdr, 160, 30, 37);
  const double sea = hdrRowsLuminance(cloudy.hdr, 160, 44, 50);
  EXPECT_GT(sea, 0.2 * sky) << "sea " << sea << " sky " << sky;
  EXPECT_LT(sea, 0.45 * sky) << "sea " << sea << " sky " << sky;  // the horizon still shows
  const Rgb grey = meanColor(cloudy.image, 0, 44, 160, 50);
  EXPECT_LT(std::abs(grey.b - grey.r), 12.0) << grey.r << " " << grey.g << " " << grey.b;
  // The same sea without the clouds is blue.
  SkySettings noClouds = renderer.settings().sky;
  noClouds.clouds = false;
  renderer.setSkySettings(noClouds);
  const RenderResult clear = renderer.render(deck, sun, 0.0, true);
  const Rgb blue = meanColor(clear.image, 0, 44, 160, 50);
  EXPECT_GT(blue.b, blue.r + 30.0) << blue.r << " " << blue.g << " " << blue.b;
  const double clearSky = hdrRowsLuminance(clear.hdr, 160, 30, 37);
  const double clearSea = hdrRowsLuminance(clear.hdr, 160, 44, 50);
  // The clear sky mirrored 2-6 degrees below the horizon: the rough sea's Fresnel there (0.3-0.45;
  // a mirror's would be 0.55-0.7) of the sky as bright as 2-6 degrees above it (0.41 measured).
  EXPECT_GT(clearSea, 0.3 * clearSky) << "sea " << clearSea << " sky " << clearSky;
  EXPECT_LT(clearSea, 0.55 * clearSky) << "sea " << clearSea << " sky " << clearSky;

  // Toward a low sun: a glint under the clear sky, none under the overcast.
  const CameraPose towardSun{20, -30, 10, 135, -8};
  const SunPose low{135, 12};
  EXPECT_GT(luminanceSpread(renderer.render(towardSun, low).image, 0, 50, 160, 90, 250.0).brightPixels, 10);
  renderer.setSkySettings(settings.sky);
  const Spread under = luminanceSpread(renderer.render(towardSun, low).image, 0, 50, 160, 90, 120.0);
  EXPECT_EQ(under.brightPixels, 0) << "median " << under.median;
}

// At sunset the sea mirrors the sky around it (water.frag, skyViewReflection): toward the sun,
// away from its glint, the sea just below the horizon takes the orange of the glow above it and
// a good part of its light. Before the sea read the sky-view table it mirrored an estimate from
// the sky's irradiance, which a sun 3 degrees up leaves dim and grey: that sea was near black
// (0.1 of the sky's luminance, red/blue 1.1 on the display). High above the ground, where the
// camera's table is not the sky the sea sees, the estimate takes over.
TEST_F(SkyRender, TheSeaMirrorsTheSunsetGlow) {
  RenderSettings settings = skySettings();
  settings.width = 160;
  settings.height = 90;
  const PlanetDescription earth = clearEarth();
  ASSERT_LT(terrainHeightM(earth, directionFromLatLon(20, -30)), -1000.0);
  Renderer renderer(context(), earth, settings);
  // From 10 m toward the sun 3 degrees up, 3 degrees below the horizon: the horizon at row ~40 of
  // 90, the glint in the middle columns (~64-96); the sky 2-7 degrees up and the sea 2-6 down at
  // the sides.
  const RenderResult sunset = renderer.render(CameraPose{20, -30, 10, 90, -3}, SunPose{90, 3}, 0.0, true);
  double sky = 0.0, sea = 0.0;
  Rgb seaColor;
  for (const uint32_t x0 : {0u, 120u}) {
    for (uint32_t y = 30; y < 37; ++y)
      for (uint32_t x = x0; x < x0 + 40; ++x) {
        const glm::vec4& c = sunset.hdr[size_t(y) * 160 + x];
        sky += 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
      }
    for (uint32_t y = 44; y < 50; ++y)
      for (uint32_t x = x0; x < x0 + 40; ++x) {
        const glm::vec4& c = sunset.hdr[size_t(y) * 160 + x];
        sea += 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
      }
    const Rgb side = meanColor(sunset.image, x0, 44, x0 + 40, 50);
    seaColor = {seaColor.r + 0.5 * side.r, seaColor.g + 0.5 * side.g, seaColor.b + 0.5 * side.b};
  }
  sky /= 7.0 * 80.0;
  sea /= 6.0 * 80.0;
  EXPECT_GT(sea, 0.3 * sky) << "sea " << sea << " sky " << sky;
  EXPECT_LT(sea, 0.8 * sky) << "sea " << sea << " sky " << sky;
  EXPECT_GT(seaColor.r, 2.0 * seaColor.b) << seaColor.r << " " << seaColor.g << " " << seaColor.b;
  EXPECT_GT(seaColor.r, 60.0) << seaColor.r << " " << seaColor.g << " " << seaColor.b;

  // The table's weight: whole near the ground, none from 30 km up.
  const TerrainPass& terrain = renderer.terrain();
  EXPECT_EQ(terrain.skyViewWeight(0.0), 1.0);
  EXPECT_EQ(terrain.skyViewWeight(TerrainPass::kSkyViewFadeStartM), 1.0);
  EXPECT_GT(terrain.skyViewWeight(15'000.0), 0.2);
  EXPECT_LT(terrain.skyViewWeight(15'000.0), 0.9);
  EXPECT_EQ(terrain.skyViewWeight(TerrainPass::kSkyViewFadeEndM), 0.0);
  EXPECT_EQ(terrain.skyViewWeight(4e5), 0.0);
}

// The airless Moon: a black sky over a sunlit ground, even by day.
TEST_F(SkyRender, AirlessSkyStaysBlackByDay) {
  Renderer renderer(context(), resolvePreset("moon"), skySettings());
  const RenderResult result = renderer.render({-20, 40, 2, 0, 20}, {100, 40});
  EXPECT_LT(luminanceSpread(result.image, 0, 0, 96, 10, 60.0).median, 3.0);
  const Rgb ground = meanColor(result.image, 0, 54, 96, 64);
  EXPECT_GT(ground.luminance(), 20.0);
}

// The sky from the per-frame tables (issue 21, point 1) against the reference march of every
// pixel's ray (`--sky reference`, 64 samples, point 2): the display images (tonemapped 8-bit,
// sRGB, as written to PNG) within 30 dB PSNR over the whole 320x180 image, at the ground at noon
// and at sunset, from 10 km, 100 km and from orbit across the limb, with Earth's clouds and
// terrain (the aerial-perspective volume covers both) and on Mars.
// The sky-view table and the camera's transmittance table are built again only when their inputs
// moved beyond SkyPass's tolerances: a frame a little higher than the last build (half the
// altitude tolerance, 8 m at 2 km) reads the tables built for the first and draws what a fresh
// renderer draws there within 50 dB (the ground's haze from the kept camera's table, the sky
// from the kept sky-view table); 1.5 times the tolerance higher builds both again; the sun 0.1°
// lower builds the sky-view table but not the camera's (which holds no sunlight); a fresh renderer
// always builds both.
TEST_F(SkyRender, TheAltitudesTablesAreBuiltAgainOnlyWhenTheirInputsMove) {
  const PlanetDescription planet = resolvePreset("earth");
  RenderSettings settings = skySettings();
  settings.sky.clouds = false;
  Renderer renderer(context(), planet, settings);
  const SunPose sun{200.0, 8.0};
  const CameraPose first{33.8, -90.0, 2000.0, 200.0, 5.0};
  renderer.render(first, sun);
  EXPECT_TRUE(renderer.sky().skyViewBuilt());
  EXPECT_TRUE(renderer.sky().cameraTransmittanceBuilt());
  renderer.render(first, sun);
  EXPECT_FALSE(renderer.sky().skyViewBuilt()) << "the same frame again";
  EXPECT_FALSE(renderer.sky().cameraTransmittanceBuilt()) << "the same frame again";

  const double tolerance = SkyPass::skyViewAltitudeToleranceM(planet.radiusM, first.altitudeM);
  EXPECT_NEAR(tolerance, 16.0, 0.5);
  CameraPose near = first;
  near.altitudeM += 0.5 * tolerance;
  const Rgba8Image reused = renderer.render(near, sun).image;
  EXPECT_FALSE(renderer.sky().skyViewBuilt());
  EXPECT_FALSE(renderer.sky().cameraTransmittanceBuilt());
  Renderer fresh(context(), planet, settings);
  const Rgba8Image built = fresh.render(near, sun).image;
  EXPECT_TRUE(fresh.sky().skyViewBuilt());
  EXPECT_TRUE(fresh.sky().cameraTransmittanceBuilt());
  const double psnr = psnrRgb(reused, built);
  // The ground (the lower half) alone, where the camera's table gives the haze's transmittance.
  const auto lowerHalf = [](const Rgba8Image& image) {
    Rgba8Image half{image.width, image.height - image.height / 2, {}};
    half.pixels.assign(image.pixels.begin() + ptrdiff_t(4u * image.width * (image.height / 2)), image.pixels.end());
    return half;
  };
  const double groundPsnr = psnrRgb(lowerHalf(reused), lowerHalf(built));
  std::printf("[ measured ] with the tables built 8 m lower: %.1f dB against a fresh build, the ground %.1f dB\n", psnr,
              groundPsnr);
  EXPECT_GE(psnr, 50.0);
  EXPECT_GE(groundPsnr, 50.0);

  CameraPose higher = first;
  higher.altitudeM += 1.5 * tolerance;
  renderer.render(higher, sun);
  EXPECT_TRUE(renderer.sky().skyViewBuilt()) << "1.5 tolerances higher";
  EXPECT_TRUE(renderer.sky().cameraTransmittanceBuilt()) << "1.5 tolerances higher";
  renderer.render(higher, SunPose{sun.azimuthDeg, sun.elevationDeg - 0.1});
  EXPECT_TRUE(renderer.sky().skyViewBuilt()) << "the sun 0.1 degrees lower";
  EXPECT_FALSE(renderer.sky().cameraTransmittanceBuilt()) << "the sun 0.1 degrees lower";
}

TEST_F(SkyRender, TablesSkyMatchesTheReferenceMarch) {
  struct View {
    const char* name;
    const char* preset;
    CameraPose camera;
    SunPose sun;
  };
  const View views[] = {
      {"ground, noon", "earth", {20, -30, 2, 0, 10}, {135, 60}},
      {"ground, sunset", "earth", {20, -30, 2, 135, 5}, {135, 2}},
      {"10 km", "earth", {20, -30, 1.0e4, 90, -5}, {135, 30}},
      {"100 km", "earth", {20, -30, 1.0e5, 90, -12}, {135, 20}},
      {"orbit, limb", "earth", {20, -30, 4.0e5, 90, -18}, {135, 20}},
      {"mars, ground", "mars", {20, -30, 2, 135, 10}, {135, 20}},
  };
  RenderSettings settings = skySettings();
  settings.width = 320;
  settings.height = 180;
  RenderSettings reference = settings;
  reference.sky.mode = SkyMode::Reference;
  for (const char* preset : {"earth", "mars"}) {
    const PlanetDescription planet = resolvePreset(preset);
    Renderer tables(context(), planet, settings);
    Renderer marched(context(), planet, reference);
    for (const View& view : views) {
      if (std::string(view.preset) != preset) continue;
      const Rgba8Image a = tables.render(view.camera, view.sun).image;
      const Rgba8Image b = marched.render(view.camera, view.sun).image;
      const double psnr = psnrRgb(a, b);
      std::printf("tables vs reference sky, %s: %.1f dB\n", view.name, psnr);
      EXPECT_GE(psnr, 30.0) << view.name;
      // Not one black image against another: the view shows sky or lit ground.
      EXPECT_GT(meanColor(a, 0, 0, 320, 180).luminance(), 10.0) << view.name;
    }
  }
}

// The terminator seen from orbit at the exposure the night side takes (12,000 km, the sun 30°
// below the camera's horizon, exposure 500: what auto exposure measures there) follows the
// per-pixel march. From above the air each column of the aerial-perspective volume splits its own
// ray, and across the terminator neighbouring columns' light differs by orders of magnitude;
// blended linearly, the lit side's light reached a column's width into the night, and lifted by
// the exposure each column's edge showed as a step, a staircase along the terminator (25.0 dB).
// Held to twice the blend of the logarithms, the light falls geometrically between such columns
// as the march's does (37.4 dB measured).
TEST_F(SkyRender, TheTerminatorFromOrbitHasNoStepsAtTheNightSidesExposure) {
  RenderSettings settings;
  settings.width = 320;
  settings.height = 180;
  settings.sky.exposure = 500.0;
  RenderSettings reference = settings;
  reference.sky.mode = SkyMode::Reference;
  const PlanetDescription earth = clearEarth();
  const CameraPose orbit{20, -30, 1.2e7};
  const SunPose sun{30, -30};
  const Rgba8Image a = Renderer(context(), earth, settings).render(orbit, sun).image;
  const Rgba8Image b = Renderer(context(), earth, reference).render(orbit, sun).image;
  const double psnr = psnrRgb(a, b);
  std::printf("the terminator from 12,000 km at exposure 500: %.1f dB against the march\n", psnr);
  EXPECT_GE(psnr, 30.0);
  // The lit crescent is in view, saturated: not one black image against another.
  EXPECT_GT(meanColor(a, 0, 0, 320, 180).luminance(), 10.0);
}

// The haze over the sea from an airliner's height at sunset (the aerial-perspective volume, issue
// 21, point 1) follows the per-pixel march without bands: from 10 km looking 5° down, the mean of
// each row within 3 of 255 of the march's. The volume held its light by distance, filtered
// between slices that near the camera are long next to the haze's scale height, and the rows
// fell up to 6.5 short of the march, in bands a slice wide (35.2 dB); held by opacity, with the
// transmittance from the table along each pixel's own ray, 49.3 dB, the worst row 2.1 off, at
// the horizon. The sea now takes its light from the sky-view table along its own direction
// (sky_compose.glsl, aerialPerspective): measured 61.2 dB, the worst row 0.2 off.
TEST_F(SkyRender, TheHazeOverTheSeaFollowsTheMarchWithoutBandsAtTheSlices) {
  const MarchComparison c = compareWithMarch(context(), {35, -20, 1.0e4, 90, -5}, {90, 2});
  const double psnr = c.psnr, worstRow = c.worstRow;
  std::printf("haze over the sea from 10 km at sunset: %.1f dB against the march, worst row %.2f of 255\n", psnr,
              worstRow);
  EXPECT_GE(psnr, 55.0);
  EXPECT_LT(worstRow, 1.0);
}

// The horizon seen from 60 km at twilight (the sun 7° below the camera's horizontal, just above
// the ground's horizon) follows the per-pixel march: the aerial-perspective volume's columns are
// 6 rows apart at 180 lines, and a column over the horizon ends short of the ground's opacity
// with the light of the sunlit air beyond it; its light lifted the ground under the horizon to
// the sky's brightness, a band up to 6 rows tall (the worst row 15.0 of 255 too bright, 36.9 dB).
// The ground that ends near the ground sphere takes its light from the sky-view table, whose rows
// gather at the horizon (measured 49.2 dB, the worst row 0.7 off).
TEST_F(SkyRender, TheGroundUnderTheHorizonFrom60KmIsNotLitLikeTheSkyAboveIt) {
  const MarchComparison c = compareWithMarch(context(), {20, -30, 6.0e4, 135, -10}, {135, -7});
  const double psnr = c.psnr, worstRow = c.worstRow;
  std::printf("the horizon from 60 km at twilight: %.1f dB against the march, worst row %.2f of 255\n", psnr, worstRow);
  EXPECT_GE(psnr, 45.0);
  EXPECT_LT(worstRow, 3.0);
  // The twilight arch is in view (its brightest row 90 of 255): not one black image against another.
  double brightestRow = 0.0;
  for (uint32_t y = 0; y < 180; ++y)
    brightestRow = std::max(brightestRow, meanColor(c.tables, 0, y, 320, y + 1).luminance());
  EXPECT_GT(brightestRow, 50.0);
}

// The cloud pass at half resolution (issue 21, point 7), upsampled by the compose, against the
// same pass at every pixel (SkySettings::cloudScale 1), on views with clouds and silhouettes:
// mountains standing in the layer with cloud between and behind their ridges (the camera 200 m
// into its base), the sea's horizon under an overcast sky, and clouds over the sea from 400 km.
// The display images within 40 dB PSNR (measured 46.3, 52.6 and 46.6 dB), and at most 0.1 % of
// the pixels (57 of 57,600) off by more than 32 of 255 (measured 3, 0 and 24: single pixels where
// a ridge is thinner than a sample's block, the edges of small clouds from 400 km). Clouds smeared
// across the ridges (the upsampling without its weights for the agreement of the rays' ends)
// fail both: 39.7 dB and 94 such pixels in the mountains.
TEST_F(SkyRender, HalfResolutionCloudsMatchFullResolutionAndStayOffSilhouettes) {
  struct View {
    const char* name;
    CameraPose camera;
    SunPose sun;
    double timeS;
  };
  const View views[] = {
      {"mountains in the clouds", {-9.9993, 86.1849, 2200, 90, 15}, {90, 40}, 7000},
      {"sea horizon, overcast", {20, -30, 2, 315, 4}, {135, 50}, 0},
      {"400 km", {20, -30, 4.0e5, 90, -60}, {135, 35}, 0},
  };
  RenderSettings settings = skySettings();
  settings.width = 320;
  settings.height = 180;
  settings.sky.cloudScale = 2;
  RenderSettings fullSettings = settings;
  fullSettings.sky.cloudScale = 1;
  const PlanetDescription earth = resolvePreset("earth");
  Renderer half(context(), earth, settings);
  Renderer full(context(), earth, fullSettings);
  const std::string out = testOutputDir().string();
  for (const View& view : views) {
    const Rgba8Image a = half.render(view.camera, view.sun, view.timeS).image;
    const Rgba8Image b = full.render(view.camera, view.sun, view.timeS).image;
    const double psnr = psnrRgb(a, b);
    size_t off = 0;
    for (size_t i = 0; i < a.pixels.size(); i += 4) {
      int worst = 0;
      for (size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(a.pixels[i + c]) - int(b.pixels[i + c])));
      off += worst > 32 ? 1 : 0;
    }
    std::printf("half vs full resolution clouds, %s: %.1f dB, %zu pixels off by more than 32\n", view.name, psnr, off);
    // Each view shows clouds (white, unsaturated pixels).
    EXPECT_GT(cloudyFraction(b), 0.05) << view.name;
    EXPECT_GE(psnr, 40.0) << view.name;
    const size_t allowed = a.pixels.size() / 4 / 1000;
    EXPECT_LE(off, allowed) << view.name;
    if (psnr < 40.0 || off > allowed) {
      const std::string name = out + "/half_resolution_clouds_" + std::to_string(&view - views);
      writePng(name + ".half.png", a);
      writePng(name + ".full.png", b);
      writePng(name + ".diff.png", diffImage(a, b));
    }
  }
}

// The cloud pass and the compose run only where the air or the sun's disc can show
// (SkySettings::regions): the pictures are those of passes over the whole image, bit for bit,
// and from orbit the regions leave most of the image out. Earth from 20,000 km, from 6,300 km
// with the limb and the sun in view, from the ground (everything); the airless Moon with the sun
// in view (its disc only).
TEST_F(SkyRender, ThePassesRunOnlyWhereTheAirOrTheSunCanShow) {
  struct View {
    const char* preset;
    CameraPose camera;
    SunPose sun;
    double mostShare;  // of the image the compose may cover
    double leastShare;
  };
  const View views[] = {
      {"earth", {20, -30, 2.0e7, 0, -90}, {135, 35}, 0.3, 0.05},
      {"earth", {20, -30, 6.3e6, 135, -45}, {135, 35}, 0.9, 0.2},
      {"earth", {20, -30, 2.0, 135, 10}, {135, 35}, 1.0, 1.0},
      {"moon", {10, 20, 3.0e6, 135, 20}, {135, 35}, 0.02, 0.0001},
  };
  RenderSettings settings = skySettings();
  settings.width = 192;
  settings.height = 108;
  RenderSettings wholeSettings = settings;
  wholeSettings.sky.regions = false;
  for (const View& view : views) {
    SCOPED_TRACE(std::string(view.preset) + " from " + std::to_string(view.camera.altitudeM) + " m");
    const PlanetDescription planet = resolvePreset(view.preset);
    Renderer regions(context(), planet, settings);
    Renderer whole(context(), planet, wholeSettings);
    const Rgba8Image a = regions.render(view.camera, view.sun).image;
    const Rgba8Image b = whole.render(view.camera, view.sun).image;
    EXPECT_EQ(a.pixels, b.pixels);
    const PixelRect& compose = regions.sky().composeRegion();
    const double share = double(compose.width()) * compose.height() / (double(settings.width) * settings.height);
    std::printf("sky regions, %s from %.0f m: the compose covers %.1f %% of the image\n", view.preset,
                view.camera.altitudeM, 100.0 * share);
    EXPECT_LE(share, view.mostShare);
    EXPECT_GE(share, view.leastShare);
    EXPECT_EQ(whole.sky().composeRegion().width(), settings.width);
    if (a.pixels != b.pixels) {
      const std::string name = testOutputDir().string() + "/sky_regions_" + std::to_string(&view - views);
      writePng(name + ".regions.png", a);
      writePng(name + ".whole.png", b);
    }
  }
}

// The tables' compose runs the tiles whose pixels all show the sky, or all show the ground, by
// pipelines without the other side's code (SkySettings::tileClasses, sky_classify.comp), and the
// cloud pass its tiles whose rays all end before the cloud layer by one without the march
// (sky_cloud_classify.comp), which also gives the ground's compose tiles clear of the layer one
// that reads only its shadow (from the clouds' shadow table: no cloud tile whose samples only
// such tiles read is run at all), and the ground's tiles whose rays end well short of the ground
// sphere one without the sky-view table's light and the volume's transmittance (kSkyTileNear):
// the pictures are those of the pipelines with everything, bit for bit where no tile is clear of
// the clouds (elsewhere the shadow table's filter and the samples' upsampling differ by a level
// of 255 at most); from a plane most compose tiles are of one kind, below the layer most of the
// ground's cloud and compose tiles are clear of it, and from low down most of the ground's tiles
// are near. From 50 m and 1.5 km (below
// Earth's clouds at 2 km), from 10 km looking down, 30 m over the sea, Mars from 100 m, Earth's
// limb from 6,300 km, and the airless Moon looking at the sun (its compose runs only around the
// disc).
TEST_F(SkyRender, TilesOfOneKindAreComposedWithoutTheOtherSidesCode) {
  struct View {
    const char* preset;
    CameraPose camera;
    double leastOfOneKind;  // share of the compose tiles that are all sky or all ground
    double leastClear;      // share of the cloud tiles that take no march
    double leastGroundClear;  // share of the ground's compose tiles clear of the clouds
    double leastNear;         // share of the ground's compose tiles near (kSkyTileNear)
  };
  const View views[] = {
      // Measured: 61 and 36 of 84 cloud tiles take no march; 225 of 254 and 120 of 144 ground tiles
      // are clear of the clouds, 192 and 118 near; over the sea 48 of 84 and 168 of 192 clear; on
      // Mars 282 of 336 tiles ground, 168 of them near.
      {"earth", {33.81, -89.95, 50, 60, -8}, 0.7, 0.5, 0.8, 0.6},
      {"earth", {36.5, -118.3, 1500, 90, 2}, 0.7, 0.3, 0.7, 0.7},
      {"earth", {36.5, -118.3, 10000, 90, -60}, 0.9, 0.0, 0.0, 0.0},
      // Over the sea every ray that meets it ends on the ground sphere: no tile is near.
      {"earth", {35, -20, 30, 90, -5}, 0.8, 0.4, 0.7, 0.0},
      // Mars's terrain bound reaches above its air, so its ground's tiles are the ground's only
      // where the classify passes show that their rays end inside the air.
      {"mars", {-4.6, 137.4, 100, 45, -5}, 0.85, 0.0, 0.0, 0.5},
      {"earth", {20, -30, 6.3e6, 135, -45}, 0.5, 0.0, 0.0, 0.0},
      {"moon", {10, 20, 3000, 135, 30}, 0.5, 0.0, 0.0, 0.0},
  };
  const SunPose sun{135, 35};
  RenderSettings settings = skySettings();
  settings.width = 192;
  settings.height = 108;
  RenderSettings mixedSettings = settings;
  mixedSettings.sky.tileClasses = false;
  const uint32_t group = gpu::kSkyWorkgroupSize;
  const auto tilesOf = [group](const PixelRect& region) {
    return ((region.width() + group - 1) / group) * ((region.height() + group - 1) / group);
  };
  for (const View& view : views) {
    SCOPED_TRACE(std::string(view.preset) + " from " + std::to_string(view.camera.altitudeM) + " m");
    const PlanetDescription planet = resolvePreset(view.preset);
    Renderer classes(context(), planet, settings);
    Renderer mixed(context(), planet, mixedSettings);
    const Rgba8Image a = classes.render(view.camera, sun).image;
    const Rgba8Image b = mixed.render(view.camera, sun).image;
    const auto counts = classes.sky().readTileCounts();
    const auto mixedCounts = mixed.sky().readTileCounts();
    const uint32_t groundClear = counts[gpu::kSkyTileAerialClear] + counts[gpu::kSkyTileAerialClearNear];
    const uint32_t near = counts[gpu::kSkyTileAerialNear] + counts[gpu::kSkyTileAerialClearNear];
    const uint32_t ground = SkyPass::groundTiles(counts);
    const uint32_t tiles = counts[gpu::kSkyTileMixed] + counts[gpu::kSkyTileSky] + ground;
    // Every tile of each pass's region is run once, in either setting.
    EXPECT_EQ(tiles, tilesOf(classes.sky().composeRegion()));
    EXPECT_EQ(mixedCounts[gpu::kSkyTileMixed], tiles);
    // The cloud tiles listed; the rest of the region's are those no compose tile reads.
    const uint32_t listedCloudTiles = counts[gpu::kSkyCloudTileMarch] + counts[gpu::kSkyCloudTileClear];
    const bool clouds = planet.clouds.enabled;
    const uint32_t cloudTiles = clouds ? tilesOf(classes.sky().cloudRegion()) : 0u;
    EXPECT_EQ(mixedCounts[gpu::kSkyCloudTileMarch], cloudTiles);
    EXPECT_EQ(mixedCounts[gpu::kSkyCloudTileClear], 0u);
    if (groundClear == 0) {
      EXPECT_EQ(listedCloudTiles, cloudTiles);
      EXPECT_EQ(a.pixels, b.pixels);
    } else {
      EXPECT_LE(listedCloudTiles, cloudTiles);
      EXPECT_LT(counts[gpu::kSkyCloudTileClear], cloudTiles - counts[gpu::kSkyCloudTileMarch]);
      int largest = 0;
      for (size_t i = 0; i < a.pixels.size(); ++i)
        largest = std::max(largest, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
      const double psnr = psnrRgb(a, b);
      std::printf("  against the mixed pipelines: %.1f dB, at most %d of 255\n", psnr, largest);
      EXPECT_LE(largest, 1);
      EXPECT_GE(psnr, 60.0);
    }
    const double oneKind = double(counts[gpu::kSkyTileSky] + ground) / std::max(tiles, 1u);
    const double clear = double(cloudTiles - counts[gpu::kSkyCloudTileMarch]) / std::max(cloudTiles, 1u);
    std::printf(
        "sky tiles, %s from %.0f m: %u tiles, %u sky, %u ground (%u clear of the clouds, %u near), %u mixed; %u "
        "cloud tiles, %u without the march (%u not run)\n",
        view.preset, view.camera.altitudeM, tiles, counts[gpu::kSkyTileSky], ground, groundClear, near,
        counts[gpu::kSkyTileMixed], cloudTiles, cloudTiles - counts[gpu::kSkyCloudTileMarch],
        cloudTiles - listedCloudTiles);
    EXPECT_GE(oneKind, view.leastOfOneKind);
    EXPECT_GE(clear, view.leastClear);
    EXPECT_GE(double(groundClear) / std::max(ground, 1u), view.leastGroundClear);
    EXPECT_GE(double(near) / std::max(ground, 1u), view.leastNear);
    // Above the layer's base every ray may meet it.
    if (view.camera.altitudeM >= planet.clouds.bottomM) {
      EXPECT_EQ(counts[gpu::kSkyCloudTileClear], 0u);
      EXPECT_EQ(groundClear, 0u);
    }
    // From above the air the ground takes the volume's transmittance.
    if (view.camera.altitudeM >= planet.atmosphere.heightM) {
      EXPECT_EQ(near, 0u);
    }
    if (a.pixels != b.pixels) {
      const std::string name = testOutputDir().string() + "/sky_tiles_" + std::to_string(&view - views);
      writePng(name + ".classes.png", a);
      writePng(name + ".mixed.png", b);
    }
  }
}

// The clouds' shadow on the ground's tiles clear of the layer comes from the clouds' shadow table
// (sky_cloud_shadow.comp), one read per pixel, where the mixed pipelines upsample the cloud pass's
// samples, each of which read the cover's cube: from a low sun the shadow is there (the ground
// differs from the same view without clouds), the picture is that of the mixed pipelines within
// 3 levels of 255 (measured: 1 and 2), and it follows the reference march (which reads the cube at every pixel) as
// closely as they do. The shadow's steep dependence on density from a low sun is where a coarse
// table would show (sky_compose.glsl, cloudShadowTableUv: a uniform one lost 4.6 dB here).
// From 50 m at a sun of 8°, and from 1.9 km, just under the layer's base, at 3°.
TEST_F(SkyRender, CloudShadowOnTheGroundClearOfTheCloudsFollowsTheCover) {
  struct View {
    CameraPose camera;
    SunPose sun;
  };
  const View views[] = {{{33.82, -89.95, 50, 60, -8}, {60, 8}}, {{36.5, -118.3, 1900, 200, -10}, {30, 3}}};
  RenderSettings settings = skySettings();
  settings.width = 192;
  settings.height = 108;
  RenderSettings mixedSettings = settings;
  mixedSettings.sky.tileClasses = false;
  RenderSettings referenceSettings = settings;
  referenceSettings.sky.mode = SkyMode::Reference;
  const PlanetDescription earth = resolvePreset("earth");
  PlanetDescription cloudless = earth;
  cloudless.clouds.enabled = false;
  Renderer classes(context(), earth, settings);
  Renderer mixed(context(), earth, mixedSettings);
  Renderer reference(context(), earth, referenceSettings);
  Renderer withoutClouds(context(), cloudless, settings);
  for (const View& view : views) {
    SCOPED_TRACE("from " + std::to_string(view.camera.altitudeM) + " m");
    const Rgba8Image a = classes.render(view.camera, view.sun).image;
    const auto counts = classes.sky().readTileCounts();
    const Rgba8Image b = mixed.render(view.camera, view.sun).image;
    const Rgba8Image marched = reference.render(view.camera, view.sun).image;
    const Rgba8Image clear = withoutClouds.render(view.camera, view.sun).image;
    // The view is mostly the ground's tiles clear of the clouds.
    const uint32_t groundClear = counts[gpu::kSkyTileAerialClear] + counts[gpu::kSkyTileAerialClearNear];
    const uint32_t group = gpu::kSkyWorkgroupSize;
    const uint32_t tiles = ((settings.width + group - 1) / group) * ((settings.height + group - 1) / group);
    EXPECT_GE(double(groundClear) / tiles, 0.5);
    // The shadow: pixels darker than without clouds by a tenth or more, in the lower half.
    int shadowed = 0, lowerHalf = 0;
    for (uint32_t y = settings.height / 2; y < settings.height; ++y)
      for (uint32_t x = 0; x < settings.width; ++x) {
        const size_t i = (size_t(y) * settings.width + x) * 4;
        shadowed += int(a.pixels[i + 1]) < 0.9 * int(clear.pixels[i + 1]) ? 1 : 0;
        ++lowerHalf;
      }
    int largest = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
      largest = std::max(largest, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
    const double againstMixed = psnrRgb(a, b), tableMarch = psnrRgb(a, marched), mixedMarch = psnrRgb(b, marched);
    std::printf(
        "clouds' shadow from %.0f m, sun %.0f deg: %.0f %% of the lower half shadowed; against the mixed "
        "pipelines %.1f dB, at most %d of 255; against the march %.1f dB (the mixed pipelines %.1f)\n",
        view.camera.altitudeM, view.sun.elevationDeg, 100.0 * shadowed / lowerHalf, againstMixed, largest, tableMarch,
        mixedMarch);
    EXPECT_GE(double(shadowed) / lowerHalf, 0.2);
    EXPECT_LE(largest, 3);
    EXPECT_GE(tableMarch, mixedMarch - 1.0);
  }
}

// The sky-view table the GPU builds each frame against the double CPU reference of the same
// source (skyViewTable): from the ground, from 10 km at twilight and from 400 km. Half the
// texels within 0.1 % of the brightest (half floats hold 3 digits; the GPU marches in float), 99 %
// within 2 %, every texel within 6 %: the worst are the rows beside the horizon from orbit, rays
// that graze the ground through 2,000 km of air, where the sky changes several times over from
// one row to the next (measured: 1.4 % and 5.6 % there, under 0.1 % from inside the air).
TEST_F(SkyRender, SkyViewTableMatchesCpuReference) {
  struct Case {
    CameraPose camera;
    SunPose sun;
  };
  const Case cases[] = {
      {{20, -30, 2, 0, 10}, {135, 30}}, {{20, -30, 1.0e4, 0, 10}, {135, -4}}, {{20, -30, 4.0e5, 0, -18}, {135, 20}}};
  RenderSettings settings = skySettings();
  const PlanetDescription earth = clearEarth();
  Renderer renderer(context(), earth, settings);
  const gpu::AtmosphereParams params = makeAtmosphereParams(earth);
  const MultipleScatteringTable table = multipleScatteringTable(params);
  for (const Case& c : cases) {
    renderer.render(c.camera, c.sun);
    const std::vector<glm::vec4> gpuTable = renderer.sky().readSkyView();
    // The sun's zenith cosine at the camera's ground point, as the frame placed it.
    const double muS = std::sin(c.sun.elevationDeg * 3.14159265358979 / 180.0);
    const std::vector<glm::dvec3> cpuTable = skyViewTable(params, c.camera.altitudeM, 0.0, muS, table);
    ASSERT_EQ(gpuTable.size(), cpuTable.size());
    double brightest = 0.0;
    for (const glm::dvec3& texel : cpuTable) brightest = std::max({brightest, texel.r, texel.g, texel.b});
    std::vector<double> errors;
    for (size_t i = 0; i < cpuTable.size(); ++i)
      for (int ch = 0; ch < 3; ++ch) errors.push_back(std::abs(double(gpuTable[i][ch]) - cpuTable[i][ch]));
    std::sort(errors.begin(), errors.end());
    const double median = errors[errors.size() / 2], p99 = errors[errors.size() * 99 / 100], worst = errors.back();
    std::printf("sky view, altitude %g m, sun %g°: median %.2e, 99th percentile %.2e, worst %.2e of brightest %.2e\n",
                c.camera.altitudeM, c.sun.elevationDeg, median, p99, worst, brightest);
    EXPECT_GT(brightest, 0.0);
    EXPECT_LT(median, 0.001 * brightest) << "altitude " << c.camera.altitudeM;
    EXPECT_LT(p99, 0.02 * brightest) << "altitude " << c.camera.altitudeM;
    EXPECT_LT(worst, 0.06 * brightest) << "altitude " << c.camera.altitudeM;
  }
}

// The camera's transmittance table the GPU builds each frame from inside the air
// (sky_camera_transmittance.comp), read as the compose reads it (bilinear, clamped), against the
// double integral along each ray: 2,000 rays from each viewpoint, most near the horizon, each
// ending before the ground sphere and within the table's reach, as what a pixel shows does.
// The worst error of the transmittance comes from the filter between texels on rays that end
// near the ground far below (measured on lavapipe: 0.14, 1.1 and 2.1 of 255 from 2 m, 10 km and
// 30 km; a model of the same table found 5.4 from 30 km on its worst of many more rays).
TEST_F(SkyRender, CameraTransmittanceTableMatchesTheIntegralAlongEachRay) {
  struct Case {
    double altitudeM;
    double worst;  // of 255
  };
  const Case cases[] = {{2.0, 1.0}, {1.0e4, 3.0}, {3.0e4, 6.0}};
  const PlanetDescription earth = clearEarth();
  const gpu::AtmosphereParams params = makeAtmosphereParams(earth);
  Renderer renderer(context(), earth, skySettings());
  constexpr uint32_t kWidth = gpu::kCameraTransmittanceDistances, kHeight = gpu::kCameraTransmittanceDirections;
  for (const Case& c : cases) {
    renderer.render({20, -30, c.altitudeM, 0, -10}, {135, 30});
    const std::vector<glm::vec4> texels = renderer.sky().readCameraTransmittance();
    ASSERT_EQ(texels.size(), size_t(kWidth) * kHeight);
    const std::vector<glm::dvec3> table(texels.begin(), texels.end());
    const gpu::SkyUniforms& u = renderer.sky().uniforms();
    const double R = params.radii.x, h = u.camera.x, hGround = u.surface.z;
    const double farthest = u.camera.z, muHorizon = u.aerial.w;
    // As the compose reads it: unit coordinates 0 and 1 fall on the first and last texels' centres.
    const auto read = [&](glm::dvec2 unit) {
      return sampleBilinear(table, kWidth, kHeight, (0.5 + unit.x * (kWidth - 1)) / kWidth,
                            (0.5 + unit.y * (kHeight - 1)) / kHeight);
    };
    std::mt19937 random(7);
    std::normal_distribution<double> nearHorizon(0.0, 0.05);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst = 0.0;
    for (int k = 0; k < 2000; ++k) {
      const double mu = std::clamp(k % 4 == 0 ? 2.0 * unit(random) - 1.0 : muHorizon + nearHorizon(random), -1.0, 1.0);
      // Before the ground sphere where the ray meets it (the nearer root of the ray-sphere quadratic).
      const double r = R + h, b = r * mu, cc = (h - hGround) * (2.0 * R + h + hGround);
      const double disc = b * b - cc;
      double reach = farthest;
      if (mu < 0.0 && disc >= 0.0) reach = std::min(reach, cc / (-b + std::sqrt(disc)));
      const double t = reach * unit(random) * unit(random);
      const glm::dvec3 exact = transmittanceAlong(params, h, mu, t, 4096);
      const glm::dvec3 tabled = glm::exp(-read(cameraTransmittanceUnit(mu, t, muHorizon, farthest)));
      for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, 255.0 * std::abs(tabled[ch] - exact[ch]));
    }
    std::printf("camera transmittance table from %g m: worst %.2f of 255 against the integral\n", c.altitudeM, worst);
    EXPECT_LT(worst, c.worst) << "altitude " << c.altitudeM;
  }
}

// Twilight with multiple scattering (issue 21, point 3): from 10 km with the sun 4° below the
// horizon, looking toward it, the sky high up is blue and the band just above the horizon under
// the sun glows orange. (Exposure 100: the twilight sky is ~1 % of the day's.)
TEST_F(SkyRender, TwilightIsBlueOverheadWithAnOrangeGlowUnderTheSun) {
  RenderSettings settings = skySettings();
  settings.width = 320;
  settings.height = 180;
  settings.sky.exposure = 100.0;
  Renderer renderer(context(), clearEarth(), settings);
  // Pitch 20°: the top row is 50° above the level; the horizon of 10 km, 3.2° below the level, is
  // at row ~157, and rows 150–155 are 0.7–2.2° above it.
  const Rgba8Image image = renderer.render({20, -30, 1.0e4, 135, 20}, {135, -4}).image;
  const Rgb high = meanColor(image, 0, 0, 320, 30);
  const Rgb glow = meanColor(image, 120, 150, 200, 155);
  std::printf("twilight from 10 km: high sky %.0f,%.0f,%.0f; glow under the sun %.0f,%.0f,%.0f\n", high.r, high.g,
              high.b, glow.r, glow.g, glow.b);
  EXPECT_GT(high.b, high.r + 10) << high.r << " " << high.b;
  EXPECT_GT(glow.r, glow.b + 20) << glow.r << " " << glow.b;
  EXPECT_GT(glow.r, glow.g) << glow.r << " " << glow.g;
}

// Stars in the upper `rows` of an image: pixels brighter than their eight neighbours and than
// the pixels three away on either side by more than 20 of 255 (the sky's gradient is not a star).
int countStars(const Rgba8Image& image, uint32_t rows) {
  auto lum = [&](uint32_t x, uint32_t y) {
    const uint8_t* p = &image.pixels[(size_t(y) * image.width + x) * 4];
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
  };
  int stars = 0;
  for (uint32_t y = 3; y + 3 < rows; ++y)
    for (uint32_t x = 3; x + 3 < image.width; ++x) {
      const double l = lum(x, y);
      bool peak = l > lum(x - 3, y) + 20.0 && l > lum(x + 3, y) + 20.0;
      for (int dy = -1; dy <= 1 && peak; ++dy)
        for (int dx = -1; dx <= 1 && peak; ++dx)
          if ((dx != 0 || dy != 0) && lum(x + dx, y + dy) >= l) peak = false;
      stars += peak ? 1 : 0;
    }
  return stars;
}

// The stars come out one by one at dusk (issue 21, point 4): each shows once the sky in front of
// it is dark enough for its magnitude (common/star_visibility.glsl), as the eye sees them, not all
// at once: with the sun 4° down a few of the brightest, more at 8°, the whole catalogue at night.
// The same exposure (a night's) for all three, so that only the fade differs.
TEST_F(SkyRender, TheStarsComeOutOneByOneAtDusk) {
  RenderSettings settings = skySettings();
  settings.width = 320;
  settings.height = 180;
  settings.sky.exposure = 64.0;
  Renderer renderer(context(), clearEarth(), settings);
  const CameraPose east{35, -20, 2, 90, 35};  // the sky from 5° to 65° up, toward the sun's side
  const uint32_t rows = 150;                  // above the sea
  const int civil = countStars(renderer.render(east, {90, -4}).image, rows);
  const int nautical = countStars(renderer.render(east, {90, -8}).image, rows);
  const int night = countStars(renderer.render(east, {90, -30}).image, rows);
  std::printf("stars seen with the sun 4 degrees down: %d, 8 degrees: %d, at night: %d\n", civil, nautical, night);
  EXPECT_GE(civil, 1);
  EXPECT_GT(nautical, civil);
  EXPECT_LT(4 * civil, nautical);
  EXPECT_LT(4 * nautical, night);
  EXPECT_GE(night, 100);
}

// Mars (issue 21, point 3): a butterscotch daytime sky (red over green over blue) away from the
// sun, and at sunset, as in Curiosity's photographs, a blue glow around the sun (its dust scatters
// blue light more forward than red) in a brown sky.
TEST_F(SkyRender, MarsSkyIsButterscotchByDayAndBlueAroundTheSettingSun) {
  RenderSettings settings = skySettings();
  settings.width = 160;
  settings.height = 90;
  Renderer renderer(context(), resolvePreset("mars"), settings);
  const Rgb day = meanColor(renderer.render({20, -30, 2, 315, 45}, {135, 60}).image, 0, 0, 160, 45);
  std::printf("mars noon, away from the sun: %.0f,%.0f,%.0f\n", day.r, day.g, day.b);
  EXPECT_GT(day.r, day.g + 5);
  EXPECT_GT(day.g, day.b + 5);
  // The sun 3° up, straight ahead in the middle of the picture (on the plains at 0° N 0° E, where
  // no mountain hides it), at the exposure a camera would take for a sunset (the daylight
  // default's 10 turns the glow white); the sky up to 7° above the sun and 10° to either side of
  // it (0.67° a pixel), and the sky opposite.
  settings.sky.exposure = 2.0;
  Renderer sunset(context(), resolvePreset("mars"), settings);
  const Rgb nearSun = meanColor(sunset.render({0, 0, 2, 135, 3}, {135, 3}).image, 65, 35, 95, 45);
  const Rgb away = meanColor(sunset.render({0, 0, 2, 315, 3}, {135, 3}).image, 50, 25, 110, 45);
  std::printf("mars sunset: around the sun %.0f,%.0f,%.0f; away %.0f,%.0f,%.0f\n", nearSun.r, nearSun.g, nearSun.b,
              away.r, away.g, away.b);
  EXPECT_GT(nearSun.b, nearSun.r + 8);  // blue, not the white or yellow-green of an Earth-like haze
  EXPECT_GT(away.r, 1.5 * away.b);      // brown
}

}  // namespace
}  // namespace planet::test
