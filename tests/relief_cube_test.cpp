// The relief cube (engine/render/relief_cube.h, issue 20 point 2): its texels against the CPU
// double reference, and what it is for: from orbit, where the camera's patch textures end and
// at quality `low` (no patches), coastlines that follow the terrain instead of the mesh.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <fmt/format.h>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/image_file.h"
#include "gpu_fixture.h"
#include "planet/planet_gpu_data.h"
#include "planet/terrain_height.h"
#include "render/relief_cube.h"
#include "render/renderer.h"
#include "render/view_quality.h"
#include "test_support.h"
#include "vk/image.h"

namespace planet::test {
namespace {

using ReliefCubeGpu = GpuTest;

// The direction through texel coordinates st of cube face `face` (Vulkan's face order and
// orientation), as relief_cube.comp computes it.
glm::dvec3 cubeDirection(uint32_t face, glm::dvec2 st) {
  const double sc = 2.0 * st.x - 1.0, tc = 2.0 * st.y - 1.0;
  const glm::dvec3 faces[6] = {{1.0, -tc, -sc}, {-1.0, -tc, sc}, {sc, 1.0, tc},
                               {sc, -1.0, -tc}, {sc, -tc, 1.0},  {-sc, -tc, -1.0}};
  return glm::normalize(faces[face]);
}

// Heights: the GPU evaluates the octaves the texel spacing keeps, in float from the point on the
// radius sphere, and stores them as half floats (11 significant bits: 2 m at 4 km, 4 m at 8 km).
// Normals: the same surface's, unit length to half-float rounding, and never facing down.
TEST_F(ReliefCubeGpu, TexelsHoldTheDoubleReferencesHeightsAtTheirSpacing) {
  const PlanetDescription planet = resolvePreset("earth");
  PlanetGpuData data(context(), planet);
  const uint32_t size = 64;
  ReliefCube relief(context(), data, size);
  ASSERT_NEAR(relief.texelAngleRad(), 2.0 / size, 1e-12);
  const std::vector<uint8_t> bytes = vk::readbackImage(context(), relief.image());
  ASSERT_EQ(bytes.size(), size_t(6) * size * size * 8);
  const double spacingM = planet.radiusM * relief.texelAngleRad();
  double worstHeight = 0.0, worstLength = 0.0, lowestUp = 1.0;
  int land = 0, checked = 0;
  for (uint32_t face = 0; face < 6; ++face)
    for (uint32_t y = 0; y < size; y += 3)
      for (uint32_t x = 0; x < size; x += 5) {
        uint16_t half[4];
        std::memcpy(half, bytes.data() + ((size_t(face) * size + y) * size + x) * 8, sizeof(half));
        const glm::dvec3 n(glm::unpackHalf1x16(half[0]), glm::unpackHalf1x16(half[1]), glm::unpackHalf1x16(half[2]));
        const double h = glm::unpackHalf1x16(half[3]);
        const glm::dvec3 up = cubeDirection(face, (glm::dvec2(x, y) + 0.5) / double(size));
        const double reference = terrainHeightM(planet, up, spacingM);
        const double tolerance = 1.0 + 1e-3 * std::abs(reference);
        worstHeight = std::max(worstHeight, std::abs(h - reference) / tolerance);
        EXPECT_NEAR(h, reference, tolerance) << fmt::format("face {} texel ({}, {})", face, x, y);
        worstLength = std::max(worstLength, std::abs(glm::length(n) - 1.0));
        lowestUp = std::min(lowestUp, glm::dot(n, up) / glm::length(n));
        land += reference > 0.0;
        ++checked;
      }
  EXPECT_LT(worstLength, 2e-3);
  EXPECT_GT(lowestUp, 0.5);
  // Both land and sea were checked (the preset's 29 % land).
  EXPECT_GT(land, checked / 10);
  EXPECT_LT(land, checked / 2);
  std::printf("relief texels: worst height error %.2f of its tolerance, normal length off by %.1e, lowest up %.3f\n",
              worstHeight, worstLength, lowestUp);
}

TEST_F(ReliefCubeGpu, BadSizesAreOneLineErrors) {
  const PlanetDescription planet = resolvePreset("earth");
  PlanetGpuData data(context(), planet);
  for (uint32_t size : {0u, 12u, 20u, 8192u}) {
    try {
      ReliefCube relief(context(), data, size);
      ADD_FAILURE() << "size " << size << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), fmt::format("relief cube size {} is not a multiple of 8 in 16..4096", size));
    }
  }
}

// Sea pixels of a render without clouds (looksLikeSea).
std::vector<uint8_t> seaMask(const Rgba8Image& image) {
  std::vector<uint8_t> sea(size_t(image.width) * image.height);
  for (size_t i = 0; i < sea.size(); ++i) sea[i] = looksLikeSea(&image.pixels[i * 4]);
  return sea;
}

// From 8,000 km over 40° N with the patches off (quality `low`), the coast with the relief cube
// against the coast with full patch textures (the reference: texels finer than the pixels on
// the camera's face): the share of the reference's coastal pixels (a sea pixel beside a land
// pixel, or the reverse) whose land or sea differs. Without the relief the coast follows the
// mesh's triangles, hundreds of km wide near the limb.
TEST_F(ReliefCubeGpu, FromOrbitWithoutPatchesTheCoastFollowsTheTerrainNotTheMesh) {
  PlanetDescription planet = resolvePreset("earth");
  planet.clouds.enabled = false;
  auto render = [&](bool patches, bool relief) {
    RenderSettings settings;
    settings.width = 320;
    settings.height = 180;
    settings.terrain.patches = patches;
    settings.terrain.relief = relief;
    Renderer renderer(context(), planet, settings);
    return renderer.render({40.0, 80.0, 8.0e6, 0.0, -90.0}, {150.0, 45.0}).image;
  };
  const Rgba8Image reference = render(true, true);
  const Rgba8Image withRelief = render(false, true);
  const Rgba8Image vertexOnly = render(false, false);
  writePng((testOutputDir() / "relief_orbit_no_patches.png").string(), withRelief);
  writePng((testOutputDir() / "relief_orbit_vertex_only.png").string(), vertexOnly);
  const std::vector<uint8_t> sea = seaMask(reference);
  const std::vector<uint8_t> relief = seaMask(withRelief);
  const std::vector<uint8_t> vertex = seaMask(vertexOnly);
  const int w = int(reference.width), h = int(reference.height);
  int coast = 0, reliefWrong = 0, vertexWrong = 0;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const bool edge = sea[i] != sea[i - 1] || sea[i] != sea[i + 1] || sea[i] != sea[i - w] || sea[i] != sea[i + w];
      if (!edge) continue;
      ++coast;
      reliefWrong += relief[i] != sea[i];
      vertexWrong += vertex[i] != sea[i];
    }
  ASSERT_GT(coast, 300) << "the view should hold coastlines";
  const double reliefShare = double(reliefWrong) / coast, vertexShare = double(vertexWrong) / coast;
  std::printf("coastal pixels %d: land or sea differs from the patches' at %.3f with the relief, %.3f from vertices\n",
              coast, reliefShare, vertexShare);
  // Measured on lavapipe: see the printout; the relief's texels (~20 km) against pixels of
  // 15-100 km leave a pixel's worth of disagreement along the coast, the mesh several.
  EXPECT_LT(reliefShare, 0.35);
  EXPECT_GT(vertexShare, 1.5 * reliefShare);
}

// The land-sea transition's width in pixels across the coast: for each pair of neighbouring
// pixels on either side of the coast (seaMask), the share of the full land-to-sea contrast (blue
// minus red, medians of sea and of land) crossed in that one step. A coast drawn as sharp as the
// pixels allow crosses most of the contrast in one or two steps; one blurred over w pixels
// crosses 1/w per step. The width is 1 / the median share.
double coastWidthPx(const Rgba8Image& image) {
  const std::vector<uint8_t> sea = seaMask(image);
  const int w = int(image.width), h = int(image.height);
  auto contrast = [&](size_t i) { return double(image.pixels[i * 4 + 2]) - double(image.pixels[i * 4]); };
  std::vector<double> seaValues, landValues;
  for (size_t i = 0; i < sea.size(); ++i) (sea[i] ? seaValues : landValues).push_back(contrast(i));
  if (seaValues.size() < 100 || landValues.size() < 100) return 0.0;
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  const double full = median(seaValues) - median(landValues);
  std::vector<double> shares;
  for (int y = 0; y + 1 < h; ++y)
    for (int x = 0; x + 1 < w; ++x) {
      const size_t i = size_t(y) * w + x;
      for (size_t j : {i + 1, i + size_t(w)})
        if (sea[i] != sea[j]) shares.push_back(std::abs(contrast(i) - contrast(j)) / full);
    }
  if (shares.size() < 100) return 0.0;
  return 1.0 / median(shares);
}

// Issue 11 point 2: from 8,000 km the coast is as sharp as the pixels allow at every viewer
// quality, and follows the terrain rather than texel blocks or triangles (low and medium may be
// softer). Low and medium render the viewer's 480x270 window at their render scale (240x135 and
// 360x203), and so does high, as the reference. Sharpness: the transition's width in pixels (the water
// sphere cuts the terrain, so this stays near two pixels unless the colours blur the coast).
// Shape: the share of coastal pixels whose land or sea differs from quality `high` drawn at the
// same size (a coast shifted by a whole pixel differs at about half of them).
TEST_F(ReliefCubeGpu, FromOrbitTheCoastIsSharpAtEveryQuality) {
  PlanetDescription planet = resolvePreset("earth");
  planet.clouds.enabled = false;
  RenderSettings base;
  auto render = [&](ViewQuality quality, ViewQuality size, bool relief) {
    RenderSettings settings = viewRenderSettings(base, quality, 480, 270);
    const RenderSettings sized = viewRenderSettings(base, size, 480, 270);
    settings.width = sized.width;
    settings.height = sized.height;
    settings.terrain.relief = relief;
    Renderer renderer(context(), viewPlanet(planet, quality), settings);
    return renderer.render({40.0, 80.0, 8.0e6, 0.0, -90.0}, {150.0, 45.0}).image;
  };
  auto disagreement = [](const Rgba8Image& image, const Rgba8Image& reference) {
    const std::vector<uint8_t> sea = seaMask(reference), other = seaMask(image);
    const int w = int(reference.width), h = int(reference.height);
    int coast = 0, wrong = 0;
    for (int y = 1; y + 1 < h; ++y)
      for (int x = 1; x + 1 < w; ++x) {
        const size_t i = size_t(y) * w + x;
        if (sea[i] == sea[i - 1] && sea[i] == sea[i + 1] && sea[i] == sea[i - w] && sea[i] == sea[i + w]) continue;
        ++coast;
        wrong += other[i] != sea[i];
      }
    return coast > 100 ? double(wrong) / coast : 1.0;
  };
  for (ViewQuality quality : {ViewQuality::Low, ViewQuality::Medium}) {
    const Rgba8Image image = render(quality, quality, true);
    const Rgba8Image high = render(ViewQuality::High, quality, true);
    writePng((testOutputDir() / fmt::format("coast_orbit_{}.png", viewQualityName(quality))).string(), image);
    writePng((testOutputDir() / fmt::format("coast_orbit_high_at_{}_size.png", viewQualityName(quality))).string(), high);
    const double width = coastWidthPx(image), highWidth = coastWidthPx(high), share = disagreement(image, high);
    std::printf("quality %s (%ux%u): land-sea transition %.2f px (high's %.2f), %.3f of the coast differs from high's\n",
                viewQualityName(quality), image.width, image.height, width, highWidth, share);
    EXPECT_GT(width, 0.0) << "the view should hold coastlines";
    EXPECT_LT(width, 3.5) << viewQualityName(quality);
    EXPECT_LT(highWidth, 3.5) << "high at " << viewQualityName(quality) << "'s size";
    EXPECT_LT(share, 0.3) << viewQualityName(quality);
  }
}

}  // namespace
}  // namespace planet::test
