// The clouds' structure and volume (issue 20 point 4) on lavapipe: properties of the cover cube
// map a satellite picture would show (latitude bands, elongated weather, cyclones turning the
// right way) and of rendered frames (darker bases than tops, no specks at distance).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "core/image_file.h"
#include "gpu_fixture.h"
#include "planet/planet_description.h"
#include "planet/terrain_height.h"
#include "render/cloud_cover.h"
#include "render/renderer.h"
#include "vk/commands.h"

namespace planet::test {
namespace {

using CloudShapes = GpuTest;

// The direction through texel (s, t) of a cube face, as shaders/clouds_cover.comp computes it.
glm::dvec3 cubeDirection(int face, double s, double t) {
  const double sc = 2.0 * s - 1.0, tc = 2.0 * t - 1.0;
  glm::dvec3 d;
  switch (face) {
    case 0: d = {1.0, -tc, -sc}; break;
    case 1: d = {-1.0, -tc, sc}; break;
    case 2: d = {sc, 1.0, tc}; break;
    case 3: d = {sc, -1.0, -tc}; break;
    case 4: d = {sc, -tc, 1.0}; break;
    default: d = {-sc, -tc, -1.0}; break;
  }
  return glm::normalize(d);
}

// The built cover of a planet: density cross-faded with equal weights, per texel.
struct Cover {
  uint32_t size = 0;
  std::vector<float> density;  // face after face, row-major
  float at(int face, int x, int y) const { return density[(size_t(face) * size + y) * size + x]; }
  glm::dvec3 direction(int face, int x, int y) const {
    return cubeDirection(face, (x + 0.5) / size, (y + 0.5) / size);
  }
};

Cover buildCover(vk::Context& context, const PlanetDescription& planet) {
  CloudCover cover(context, planet);
  vk::submitAndWait(context, [&](VkCommandBuffer cmd) { cover.recordBuild(cmd); });
  const std::vector<uint8_t> texels = cover.readLevel0();
  Cover result;
  result.size = cover.size();
  result.density.resize(texels.size() / 4);
  for (size_t i = 0; i < result.density.size(); ++i)
    result.density[i] = (texels[i * 4] + texels[i * 4 + 1] + texels[i * 4 + 2]) / (3.0f * 255.0f);
  return result;
}

// The density gradient at an interior texel in a local tangent basis (e1, e2), per radian.
glm::dvec2 gradientIn(const Cover& cover, int face, int x, int y, const glm::dvec3& e1, const glm::dvec3& e2) {
  const glm::dvec3 a = cover.direction(face, x + 1, y) - cover.direction(face, x - 1, y);
  const glm::dvec3 b = cover.direction(face, x, y + 1) - cover.direction(face, x, y - 1);
  const double da = cover.at(face, x + 1, y) - cover.at(face, x - 1, y);
  const double db = cover.at(face, x, y + 1) - cover.at(face, x, y - 1);
  // da = g · a, db = g · b in the basis: solve the 2×2 system.
  const double a1 = glm::dot(a, e1), a2 = glm::dot(a, e2), b1 = glm::dot(b, e1), b2 = glm::dot(b, e2);
  const double det = a1 * b2 - a2 * b1;
  if (std::abs(det) < 1e-12) return glm::dvec2(0.0);
  return {(da * b2 - db * a2) / det, (a1 * db - b1 * da) / det};
}

double latitudeDeg(const glm::dvec3& d) { return std::asin(std::clamp(d.z, -1.0, 1.0)) * 180.0 / std::numbers::pi; }

PlanetDescription earth() { return resolvePreset("earth"); }

TEST_F(CloudShapes, CoverFollowsTheClimateByLatitude) {
  const Cover cover = buildCover(context(), earth());
  // Mean density in bands: the ITCZ (0–10° N), the dry subtropics (20–30°, both hemispheres)
  // and the storm tracks (50–60°).
  double sum[3] = {0, 0, 0}, count[3] = {0, 0, 0};
  for (int face = 0; face < 6; ++face)
    for (uint32_t y = 0; y < cover.size; ++y)
      for (uint32_t x = 0; x < cover.size; ++x) {
        const double lat = latitudeDeg(cover.direction(face, int(x), int(y)));
        const double absLat = std::abs(lat);
        const int band = (lat >= 0.0 && lat < 10.0) ? 0 : (absLat >= 20.0 && absLat < 30.0) ? 1
                                                      : (absLat >= 50.0 && absLat < 60.0) ? 2 : -1;
        if (band < 0) continue;
        sum[band] += cover.at(face, int(x), int(y));
        count[band] += 1.0;
      }
  const double itcz = sum[0] / count[0], subtropics = sum[1] / count[1], stormTracks = sum[2] / count[2];
  std::printf("mean cloud density: ITCZ %.3f, subtropics %.3f, storm tracks %.3f\n", itcz, subtropics, stormTracks);
  EXPECT_GT(itcz, 1.3 * subtropics);
  EXPECT_GT(stormTracks, 1.3 * subtropics);
  EXPECT_GT(subtropics, 0.03);  // dry, not empty: trade cumulus
}

// The zonal winds draw the cover out east–west (fronts, streets): across the latitude bands
// of the trades and the westerlies the density changes faster northward than eastward.
// Isotropic noise gives a ratio of 1.
TEST_F(CloudShapes, CoverIsDrawnOutAlongTheWinds) {
  PlanetDescription planet = earth();
  planet.clouds.cyclones = 0;  // the spirals turn every way: leave them out of this measure
  const Cover cover = buildCover(context(), planet);
  double east = 0.0, north = 0.0;
  for (int face = 0; face < 6; ++face)
    for (uint32_t y = 1; y + 1 < cover.size; ++y)
      for (uint32_t x = 1; x + 1 < cover.size; ++x) {
        const glm::dvec3 d = cover.direction(face, int(x), int(y));
        const double absLat = std::abs(latitudeDeg(d));
        if (absLat < 8.0 || absLat > 60.0) continue;
        const glm::dvec3 e = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), d));
        const glm::dvec3 n = glm::cross(d, e);
        const glm::dvec2 g = gradientIn(cover, face, int(x), int(y), e, n);
        east += g.x * g.x;
        north += g.y * g.y;
      }
  std::printf("gradient energy north / east: %.3f\n", north / east);
  EXPECT_GT(north / east, 1.3);
}

// Cyclones wind into spiral arms counter-clockwise (seen from above) in the north and clockwise
// in the south: going outward along an arm turns against the rotation, so the density gradient
// has radial and azimuthal parts of the same sign in the north (g_r · g_θ > 0 with θ
// counter-clockwise) and of opposite signs in the south.
TEST_F(CloudShapes, CyclonesTurnTheRightWayInEachHemisphere) {
  const PlanetDescription planet = earth();
  const Cover cover = buildCover(context(), planet);
  const std::vector<gpu::CloudVortex> vortices = cloudVortices(planet.clouds, planet.radiusM);
  ASSERT_FALSE(vortices.empty());
  std::vector<double> product(vortices.size(), 0.0), energy(vortices.size(), 0.0);
  for (int face = 0; face < 6; ++face)
    for (uint32_t y = 1; y + 1 < cover.size; ++y)
      for (uint32_t x = 1; x + 1 < cover.size; ++x) {
        const glm::dvec3 d = cover.direction(face, int(x), int(y));
        for (size_t k = 0; k < vortices.size(); ++k) {
          const glm::dvec3 c(vortices[k].centre);
          const double reach = std::acos(std::clamp(glm::dot(c, d), -1.0, 1.0)) / vortices[k].centre.w;
          if (reach < 0.25 || reach > 1.5) continue;
          const glm::dvec3 radial = glm::normalize(d - c * glm::dot(c, d));
          const glm::dvec3 azimuthal = glm::cross(c, radial);
          const glm::dvec2 g = gradientIn(cover, face, int(x), int(y), radial, azimuthal);
          product[k] += g.x * g.y;
          energy[k] += 0.5 * (g.x * g.x + g.y * g.y);
        }
      }
  int right = 0, counted = 0;
  double north = 0.0, south = 0.0;
  for (size_t k = 0; k < vortices.size(); ++k) {
    if (energy[k] <= 0.0) continue;
    const double correlation = product[k] / energy[k];
    const bool isNorth = vortices[k].centre.z > 0.0f;
    (isNorth ? north : south) += correlation;
    right += (isNorth ? correlation > 0.0 : correlation < 0.0) ? 1 : 0;
    ++counted;
  }
  std::printf("cyclones turning the right way: %d of %d; mean correlation north %.3f south %.3f\n", right, counted,
              north / (counted / 2), south / (counted / 2));
  EXPECT_GE(right, int(0.8 * counted));
  EXPECT_GT(north, 0.0);
  EXPECT_LT(south, 0.0);
}

double meanLuminance(const Rgba8Image& image, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) {
  double sum = 0.0;
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = x0; x < x1; ++x) {
      const uint8_t* p = &image.pixels[(size_t(y) * image.width + x) * 4];
      sum += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    }
  return sum / (double(x1 - x0) * double(y1 - y0));
}

RenderSettings smallSettings(uint32_t width, uint32_t height) {
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.terrain.patchSettings.resolution = 128;
  settings.terrain.patchSettings.levelCount = 3;
  return settings;
}

// A thick cloud seen from below is lit only through its column: its base is grey, its sunlit
// top seen from above is bright.
TEST_F(CloudShapes, BaseOfAThickCloudIsDarkerThanItsTop) {
  const PlanetDescription planet = earth();
  const Cover cover = buildCover(context(), planet);
  // The densest texel between 40° S and 40° N whose neighbourhood (±3 texels) is dense too.
  double best = 0.0;
  glm::dvec3 where(1, 0, 0);
  for (int face = 0; face < 4; ++face)
    for (uint32_t y = 3; y + 3 < cover.size; y += 2)
      for (uint32_t x = 3; x + 3 < cover.size; x += 2) {
        double least = 1.0;
        for (int dy = -3; dy <= 3; dy += 3)
          for (int dx = -3; dx <= 3; dx += 3) least = std::min(least, double(cover.at(face, x + dx, y + dy)));
        const glm::dvec3 d = cover.direction(face, int(x), int(y));
        if (least > best && std::abs(latitudeDeg(d)) < 40.0) {
          best = least;
          where = d;
        }
      }
  ASSERT_GT(best, 0.3);
  const glm::dvec2 latLon(latitudeDegOf(where), longitudeDegOf(where));
  Renderer renderer(context(), planet, smallSettings(64, 64));
  const SunPose sun{135, 60};
  const double ground = std::max(terrainHeightM(planet, where), 0.0);
  // Radiance (HDR luminance): the display curve compresses both toward white.
  auto hdrLuminance = [](const RenderResult& result) {
    double sum = 0.0;
    for (uint32_t y = 24; y < 40; ++y)
      for (uint32_t x = 24; x < 40; ++x) {
        const glm::vec4& p = result.hdr[size_t(y) * 64 + x];
        sum += 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
      }
    return sum / 256.0;
  };
  const RenderResult below = renderer.render({latLon.x, latLon.y, ground + 2.0, 0, 90}, sun, 0.0, true);
  const RenderResult above = renderer.render({latLon.x, latLon.y, 12'000.0, 0, -90}, sun, 0.0, true);
  const double base = hdrLuminance(below), top = hdrLuminance(above);
  std::printf("density %.2f at %.2f, %.2f: base %.3f, top %.3f (display %.0f, %.0f)\n", best, latLon.x, latLon.y, base,
              top, meanLuminance(below.image, 24, 24, 40, 40), meanLuminance(above.image, 24, 24, 40, 40));
  EXPECT_LT(base, 0.5 * top);
  EXPECT_GT(meanLuminance(above.image, 24, 24, 40, 40), 150.0);  // a bright white top
}

// Far clouds are filtered to their footprint: no isolated bright pixels near the horizon.
TEST_F(CloudShapes, NoBrightSpecksAtDistance) {
  Renderer renderer(context(), earth(), smallSettings(320, 180));
  int specks = 0;
  // Looking a little up from 1 km: the sky with the layer out to the horizon, little ground.
  for (const CameraPose camera : {CameraPose{20, -30, 1000, 90, 4}, CameraPose{5, 60, 1000, 200, 4},
                                  CameraPose{-52, 120, 1000, 30, 4}}) {
    const Rgba8Image image = renderer.render(camera, {135, 25}).image;
    auto lum = [&](int x, int y) {
      const uint8_t* p = &image.pixels[(size_t(y) * image.width + x) * 4];
      return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    };
    for (int y = 1; y + 1 < int(image.height); ++y)
      for (int x = 1; x + 1 < int(image.width); ++x) {
        double neighbours = 0.0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            if (dx != 0 || dy != 0) neighbours = std::max(neighbours, lum(x + dx, y + dy));
        specks += lum(x, y) > neighbours + 20.0 ? 1 : 0;
      }
  }
  EXPECT_LE(specks, 2);
}

}  // namespace
}  // namespace planet::test
