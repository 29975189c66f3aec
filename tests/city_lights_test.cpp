// City lights on lavapipe (issue 14, point 2): Earth's night side from 12,000 km with the sun 60°
// below the horizon at the nadir. Without lights it is dark (nothing lights a night side any
// more); with them the lit pixels lie on land, none over the deep sea or the polar ice, and the
// clouds dim them; by day the lights add nothing. Each pixel's ground point comes from the
// camera's ray in double precision, its land or sea from the CPU reference heights.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include <gtest/gtest.h>

#include "core/image_file.h"
#include "gpu_fixture.h"
#include "planet/terrain_height.h"
#include "render/renderer.h"

namespace planet::test {
namespace {

using CityLightsGpu = GpuTest;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr uint32_t kWidth = 320, kHeight = 180;
const CameraPose kOrbit{20.0, -30.0, 1.2e7, 0.0, -90.0};
const SunPose kNight{135.0, -60.0};

RenderSettings settings(bool lights, bool clouds = true) {
  RenderSettings s;
  s.width = kWidth;
  s.height = kHeight;
  s.terrain.lights = lights;
  s.sky.clouds = clouds;
  return s;
}

int channelMax(const Rgba8Image& image, uint32_t x, uint32_t y) {
  const uint8_t* p = &image.pixels[(size_t(y) * image.width + x) * 4];
  return std::max({p[0], p[1], p[2]});
}

// The unit direction (planet frame) of the ground a point of a pixel sees, if its ray meets the
// sphere of the sea level (the terrain differs from it by under 0.1 % of the distance).
// (u, v): where in the pixel, 0 .. 1 from its top left corner.
std::optional<glm::dvec3> groundOf(const CameraPose& pose, double radiusM, uint32_t x, uint32_t y, double u,
                                   double v) {
  const CameraBasis b = cameraBasis(pose, radiusM);
  const glm::dvec3 right = glm::normalize(glm::cross(b.forward, b.up));
  const double tanHalf = std::tan(0.5 * RenderSettings{}.fovYDeg * kDeg);
  const double sx = ((x + u) / kWidth * 2.0 - 1.0) * tanHalf * double(kWidth) / kHeight;
  const double sy = (1.0 - (y + v) / kHeight * 2.0) * tanHalf;
  const glm::dvec3 ray = glm::normalize(b.forward + sx * right + sy * b.up);
  const double along = -glm::dot(b.position, ray);
  const double missSquared = glm::dot(b.position, b.position) - along * along;
  if (missSquared > radiusM * radiusM) return std::nullopt;
  const double t = along - std::sqrt(radiusM * radiusM - missSquared);
  return glm::normalize(b.position + t * ray);
}

// No lights: every pixel whose ground has the sun more than 18° below its horizon (no twilight
// left) is black but for at most 3 of 255 (it was up to 16 from the fill light before the fill
// set with the sun). The 3 is twilight's inscatter, which the aerial-perspective volume's froxels
// (about 10 pixels wide here) carry a little past the twilight zone: the reference march
// (--sky reference) gives 0 at that pixel. With lights: at least 100 lit pixels (more than 8 of 255 above
// the unlit image; about 500 today), every one of them on land (the CPU height above −300 m at
// the pixel's centre: a 70 km pixel near a coast may be drawn from its land) and equatorward of
// 66° (the ice and tundra have none); none over the deep sea (below −2,000 m, 100 km and more
// from a coast). The clouds dim the lights: less light in total with them than without.
TEST_F(CityLightsGpu, NightSideLightsAreOnLandAndNoneOverSeaOrIce) {
  const PlanetDescription earth = resolvePreset("earth");
  Renderer renderer(context(), earth, settings(true));
  const Rgba8Image lit = renderer.render(kOrbit, kNight).image;
  renderer.terrain().setLightsEnabled(false);
  const Rgba8Image dark = renderer.render(kOrbit, kNight).image;
  renderer.terrain().setLightsEnabled(true);
  SkySettings noClouds = renderer.settings().sky;
  noClouds.clouds = false;
  renderer.setSkySettings(noClouds);
  const Rgba8Image clear = renderer.render(kOrbit, kNight).image;
  writePng((testOutputDir() / "lights_night.png").string(), lit);
  writePng((testOutputDir() / "lights_night_off.png").string(), dark);
  const glm::dvec3 sun = sunDirection(kNight, kOrbit);
  const double radius = earth.radiusM + earth.seaLevelM;
  int night = 0, darkMax = 0, litPixels = 0, deepSea = 0;
  uint32_t darkX = 0, darkY = 0;
  long litSum = 0, clearSum = 0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const std::optional<glm::dvec3> ground = groundOf(kOrbit, radius, x, y, 0.5, 0.5);
      if (!ground) continue;
      // The CPU heights at the pixel's centre and corners: the drawn pixel is one of them.
      double highest = terrainHeightM(earth, *ground), lowest = highest;
      for (const auto& [u, v] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}})
        if (const std::optional<glm::dvec3> corner = groundOf(kOrbit, radius, x, y, u, v)) {
          const double h = terrainHeightM(earth, *corner);
          highest = std::max(highest, h);
          lowest = std::min(lowest, h);
        }
      const double latitude = latitudeDegOf(*ground);
      const int added = channelMax(lit, x, y) - channelMax(dark, x, y);
      litSum += channelMax(lit, x, y);
      clearSum += channelMax(clear, x, y);
      if (glm::dot(*ground, sun) < -0.31) {
        ++night;
        if (channelMax(dark, x, y) > darkMax) {
          darkMax = channelMax(dark, x, y);
          darkX = x;
          darkY = y;
        }
      }
      if (added > 8) {
        ++litPixels;
        EXPECT_GT(highest, -300.0) << "light over the sea at pixel " << x << "," << y;
        EXPECT_LT(std::abs(latitude), 66.0) << "light on polar ground at pixel " << x << "," << y;
      }
      if (highest < -2000.0) {
        ++deepSea;
        EXPECT_LE(added, 2) << "light over the deep sea at pixel " << x << "," << y;
      }
    }
  EXPECT_GT(night, 5000);  // the test sees the night side
  EXPECT_GT(deepSea, 3000);
  EXPECT_LE(darkMax, 3) << "at pixel " << darkX << "," << darkY;
  EXPECT_GE(litPixels, 100);
  EXPECT_LT(litSum, clearSum);
}

// By day the lights add nothing: from 1,000 km with the sun 60° up at the nadir (every point in
// view has it at least 30° up) the image with lights is the image without. The lights' code is
// kept in every frame (shadingPerFrame off): by default a frame with no night in view leaves it out.
TEST_F(CityLightsGpu, DaySideIsTheSameWithAndWithoutLights) {
  const PlanetDescription earth = resolvePreset("earth");
  const CameraPose low{20.0, -30.0, 1.0e6, 0.0, -90.0};
  const SunPose day{135.0, 60.0};
  RenderSettings small = settings(true);
  small.width = 160;
  small.height = 90;
  small.terrain.shadingPerFrame = false;
  Renderer renderer(context(), earth, small);
  const Rgba8Image with = renderer.render(low, day).image;
  EXPECT_TRUE(renderer.terrain().frame().shading.lights);
  renderer.terrain().setLightsEnabled(false);  // the same as a renderer made without (the toggle's test)
  EXPECT_EQ(with.pixels, renderer.render(low, day).image.pixels);
  EXPECT_FALSE(renderer.terrain().frame().shading.lights);
}

// The viewer's toggle: turning the lights off and on again in one renderer switches between the
// specialised pipelines and gives the images of renderers made so.
TEST_F(CityLightsGpu, ToggleSwitchesThePipelineAndMatchesFreshRenderers) {
  const PlanetDescription earth = resolvePreset("earth");
  RenderSettings small = settings(true);
  small.width = 160;
  small.height = 90;
  Renderer renderer(context(), earth, small);
  const Rgba8Image on = renderer.render(kOrbit, kNight).image;
  renderer.terrain().setLightsEnabled(false);
  EXPECT_FALSE(renderer.terrain().lightsDrawn());
  const Rgba8Image off = renderer.render(kOrbit, kNight).image;
  small.terrain.lights = false;
  EXPECT_EQ(off.pixels, Renderer(context(), earth, small).render(kOrbit, kNight).image.pixels);
  EXPECT_NE(off.pixels, on.pixels);
  renderer.terrain().setLightsEnabled(true);
  EXPECT_EQ(renderer.render(kOrbit, kNight).image.pixels, on.pixels);
}

}  // namespace
}  // namespace planet::test
