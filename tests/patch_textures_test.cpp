// The patch textures on the GPU (engine/render/patch_textures.h) at Earth scale, thousands of km
// from the noise origin: heights against the CPU double reference, normals against its finite
// differences, and the incremental updates (nothing to do, one recentre step, one level finer).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "gpu_fixture.h"
#include "planet/clipmap_orientation.h"
#include "planet/planet_gpu_data.h"
#include "planet/terrain_height.h"
#include "render/patch_layout.h"
#include "render/patch_textures.h"
#include "test_support.h"
#include "vk/commands.h"
#include "vk/image.h"

namespace planet::test {
namespace {

using PatchTexturesGpu = GpuTest;

// Heights: the GPU evaluates the same octaves at the same point as the double reference, in
// float. The layers of largest amplitude (kilometres per unit of noise) see their noise inputs
// rounded to ~1e-7 noise units: millimetres of height. Measured on lavapipe with the earth
// preset: at most 2.2 mm over the 6 × 520 texels checked (3.3 mm with its earlier 7.5 km
// continents).
constexpr double kHeightToleranceM = 0.01;
// Normals: central differences over 2 texels of heights each within kHeightToleranceM tilt the
// normal by at most kHeightToleranceM / spacing (0.019 rad at the finest level's 0.53 m).
// Measured on lavapipe: 0.0038 rad at the finest level, 0.0001 rad at the coarsest (17 m): the
// float rounding above changes in steps as the position moves, by ~2 mm between neighbours.
// The texels a level keeps after a recentre step are evaluated from the same tile anchors and
// offsets; only the octave budget moves with the level's centre (by ~1e-6 of an octave), which
// can change a height by about an ulp (0.24 mm at 2-4 km, 0.49 mm at 4-8 km), and a normal by
// that over the texel spacing. Measured on lavapipe: at most one ulp (0.24 mm, 3e-4 rad) or
// bit-identical, depending on the preset's numbers.
constexpr double kMovedToleranceM = 0.001;

// Camera: above the Sierra Nevada, ~11,000 km from the noise origin's axis crossing, 300 m up,
// looking through a 60° × 1080 px view.
constexpr double kLatitudeDeg = 37.2;
constexpr double kLongitudeDeg = -118.6;
constexpr double kAltitudeM = 300.0;

double nadirPixelM(double radiusM) {
  return radiusM * pixelFootprintTheta(radiusM, kAltitudeM, std::numbers::pi / 3.0, 1080);
}

// The camera direction moved to the centre of its finest texel, so that moving it by whole
// texels moves its texel index by exactly that many.
glm::dvec3 cameraDirection(const PatchSettings& settings, double radiusM) {
  const glm::dvec3 start = directionFromLatLon(kLatitudeDeg, kLongitudeDeg);
  const PatchLayout layout = choosePatchLayout(settings, radiusM, start, nadirPixelM(radiusM));
  const double texel = std::ldexp(1.0, layout.levels[0].exponent);
  const glm::dvec2 ab = cubeFaceCoordinates(layout.face, start);
  return cubeFaceDirection(layout.face, (std::floor(ab.x / texel) + 0.5) * texel,
                           (std::floor(ab.y / texel) + 0.5) * texel);
}

// Every texel of every layer (layer after layer, rows of x), as floats (4 per texel). The readback
// leaves the image in TRANSFER_SRC_OPTIMAL; it is transitioned back to GENERAL, the layout
// PatchTextures keeps it in, so the same object can be updated again.
std::vector<float> readBack(vk::Context& context, const PatchTextures& patches) {
  vk::Image image = patches.image();  // a copy of the handles, whose layout field the helpers track
  const std::vector<uint8_t> bytes = vk::readbackImage(context, image);
  vk::submitAndWait(context, [&](VkCommandBuffer cmd) {
    // The copy's reads finish before later compute writes and fragment reads.
    vk::transitionImage(cmd, image, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  });
  std::vector<float> texels(bytes.size() / sizeof(float));
  std::memcpy(texels.data(), bytes.data(), bytes.size());
  return texels;
}

// Level texel (x, y) of `level`, where toroidal storage keeps it (its face index mod resolution).
glm::vec4 texelOf(const std::vector<float>& texels, uint32_t resolution, const PatchLevel& level, int64_t x,
                  int64_t y) {
  const glm::uvec2 stored = PatchTextures::storedTexel(level, resolution, x, y);
  const size_t i = ((size_t(level.layer) * resolution + stored.y) * resolution + stored.x) * 4;
  return {texels[i], texels[i + 1], texels[i + 2], texels[i + 3]};
}

uint32_t runUpdate(vk::Context& context, PatchTextures& patches, const PatchLayout& layout) {
  uint32_t rebuilt = 0;
  vk::submitAndWait(context, [&](VkCommandBuffer cmd) { rebuilt = patches.update(cmd, layout); });
  return rebuilt;
}

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// The CPU reference of a texel: direction, double height at the level's octave budget, and the
// normal from central differences of the double surface points (R + h)·p.
struct ReferenceTexel {
  double heightM;
  glm::dvec3 normal;
};
ReferenceTexel referenceTexel(const PlanetDescription& planet, const PatchLayout& layout, const PatchLevel& level,
                              double x, double y) {
  const double spacingM = patchTexelSpacingM(layout, level, planet.radiusM);
  auto point = [&](double px, double py, double* height = nullptr) {
    const glm::dvec2 ab = patchTexelCoordinates(level, px, py);
    const glm::dvec3 d = cubeFaceDirection(layout.face, ab.x, ab.y);
    const double h = terrainHeightM(planet, d, spacingM);
    if (height) *height = h;
    return (planet.radiusM + h) * d;
  };
  ReferenceTexel result;
  point(x, y, &result.heightM);
  const glm::dvec3 alongA = point(x + 1, y) - point(x - 1, y);
  const glm::dvec3 alongB = point(x, y + 1) - point(x, y - 1);
  result.normal = glm::normalize(glm::cross(alongA, alongB));
  return result;
}

TEST_F(PatchTexturesGpu, HeightsAndNormalsMatchTheDoubleReferenceOnEveryLevel) {
  const PlanetDescription planet = resolvePreset("earth");
  PlanetGpuData data(context(), planet);
  const PatchSettings settings;
  PatchTextures patches(context(), data, settings);
  const glm::dvec3 camera = cameraDirection(settings, planet.radiusM);
  const PatchLayout layout = choosePatchLayout(settings, planet.radiusM, camera, nadirPixelM(planet.radiusM));

  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(runUpdate(context(), patches, layout), settings.levelCount);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ timing ] full update, %u levels of %u^2 on %s: %.0f ms (with validation)\n", settings.levelCount,
              settings.resolution, context().info.name.c_str(), seconds * 1e3);
  const std::vector<float> texels = readBack(context(), patches);

  // Corners, edges, the centre, tile borders and deterministic pseudo-random texels of every level.
  const int64_t last = settings.resolution - 1;
  std::mt19937 random(5);
  double maxHeightError = 0.0, maxNormLength = 0.0;
  for (const PatchLevel& level : layout.levels) {
    const double spacingM = patchTexelSpacingM(layout, level, planet.radiusM);
    std::vector<std::pair<int64_t, int64_t>> samples = {{0, 0},
                                                        {last, 0},
                                                        {0, last},
                                                        {last, last},
                                                        {last / 2, last / 2},
                                                        {settings.resolution / 2, settings.resolution / 2},
                                                        {0, last / 3},
                                                        {last, 2 * last / 3}};
    for (int64_t x = 60; x < 70; ++x) samples.push_back({x, x + 3});  // across tile borders
    for (int i = 0; i < 500; ++i) samples.push_back({random() % settings.resolution, random() % settings.resolution});
    double maxAngle = 0.0;
    for (const auto& [x, y] : samples) {
      const glm::vec4 gpu = texelOf(texels, settings.resolution, level, x, y);
      const ReferenceTexel ref = referenceTexel(planet, layout, level, double(x), double(y));
      const double heightError = std::abs(double(gpu.w) - ref.heightM);
      const double angle = angleBetween(glm::dvec3(gpu), ref.normal);
      EXPECT_LE(heightError, kHeightToleranceM)
          << "exponent " << level.exponent << " texel " << x << "," << y << ": " << gpu.w << " vs " << ref.heightM;
      // The normal is the central differences of four neighbours, each within the height
      // tolerance: per axis a slope error of up to 2 tol / 2 spacing, and the two axes add (the
      // eroded ranges' steep walls turn the float path's position rounding into such errors).
      EXPECT_LE(angle, 2.0 * kHeightToleranceM / spacingM) << "exponent " << level.exponent << " texel " << x << "," << y;
      maxHeightError = std::max(maxHeightError, heightError);
      maxAngle = std::max(maxAngle, angle);
      maxNormLength = std::max(maxNormLength, std::abs(glm::length(glm::dvec3(gpu)) - 1.0));
    }
    std::printf("[ measured ] exponent %d, spacing %.3f m: max normal angle %.3g rad (%.3g deg)\n", level.exponent,
                spacingM, maxAngle, maxAngle * 180.0 / std::numbers::pi);
  }
  EXPECT_LE(maxNormLength, 1e-6);
  std::printf("[ measured ] max |height - reference| %.3g m\n", maxHeightError);
}

// The moon's crater layer: the patch heights come from the shader variant with the crater
// fractal (planet_gpu_data.h, hasCraterLayer); the crater-free variant would draw the layer as
// simplex and miss the reference by hundreds of metres. Every level against the double reference.
TEST_F(PatchTexturesGpu, MoonCraterHeightsMatchTheDoubleReferenceOnEveryLevel) {
  const PlanetDescription planet = resolvePreset("moon");
  ASSERT_TRUE(hasCraterLayer(planet));
  PlanetGpuData data(context(), planet);
  const PatchSettings settings;
  PatchTextures patches(context(), data, settings);
  const glm::dvec3 camera = cameraDirection(settings, planet.radiusM);
  const PatchLayout layout = choosePatchLayout(settings, planet.radiusM, camera, nadirPixelM(planet.radiusM));
  ASSERT_EQ(runUpdate(context(), patches, layout), settings.levelCount);
  const std::vector<float> texels = readBack(context(), patches);
  std::mt19937 random(6);
  double maxHeightError = 0.0;
  for (const PatchLevel& level : layout.levels) {
    for (int i = 0; i < 200; ++i) {
      const int64_t x = random() % settings.resolution, y = random() % settings.resolution;
      const glm::dvec2 ab = patchTexelCoordinates(level, double(x), double(y));
      const double reference = terrainHeightM(planet, cubeFaceDirection(layout.face, ab.x, ab.y),
                                              patchTexelSpacingM(layout, level, planet.radiusM));
      const double error = std::abs(double(texelOf(texels, settings.resolution, level, x, y).w) - reference);
      EXPECT_LE(error, kHeightToleranceM) << "exponent " << level.exponent << " texel " << x << "," << y;
      maxHeightError = std::max(maxHeightError, error);
    }
  }
  std::printf("[ measured ] moon: max |height - reference| %.3g m\n", maxHeightError);
}

TEST_F(PatchTexturesGpu, UpdatesRebuildOnlyWhatMoved) {
  const PlanetDescription planet = resolvePreset("earth");
  PlanetGpuData data(context(), planet);
  const PatchSettings settings;
  PatchTextures patches(context(), data, settings);
  const double radius = planet.radiusM;
  const double pixel = nadirPixelM(radius);
  const glm::dvec3 camera = cameraDirection(settings, radius);
  const PatchLayout layout = choosePatchLayout(settings, radius, camera, pixel);
  ASSERT_EQ(runUpdate(context(), patches, layout), settings.levelCount);
  const std::vector<float> first = readBack(context(), patches);
  const uint32_t res = settings.resolution;
  const size_t layerFloats = size_t(res) * res * 4;
  auto sameLayer = [&](const std::vector<float>& a, const std::vector<float>& b, uint32_t layer) {
    return std::memcmp(a.data() + layer * layerFloats, b.data() + layer * layerFloats, layerFloats * sizeof(float)) ==
           0;
  };

  // (3) The same layout: nothing to do, and the texels stay bit for bit.
  EXPECT_EQ(runUpdate(context(), patches, layout), 0u);
  const std::vector<float> unchanged = readBack(context(), patches);
  EXPECT_EQ(std::memcmp(first.data(), unchanged.data(), first.size() * sizeof(float)), 0);

  // (4) One recentre step of the finest level along +a and -b (diagonally): the levels that
  // moved keep the texels they still cover where they are stored (bit for bit) and compute only
  // the two strips they newly cover; the result matches a level built whole at the new place.
  const int64_t step = res / settings.recentreDivisor;
  const PatchLevel& finest = layout.levels[0];
  const glm::dvec2 ab = cubeFaceCoordinates(layout.face, camera);
  const double finestTexel = std::ldexp(1.0, finest.exponent);
  const glm::dvec3 movedCamera =
      cubeFaceDirection(layout.face, ab.x + double(step) * finestTexel, ab.y - double(step) * finestTexel);
  const PatchLayout moved = choosePatchLayout(settings, radius, movedCamera, pixel);
  ASSERT_EQ(moved.face, layout.face);
  ASSERT_EQ(moved.levels[0].exponent, finest.exponent);
  ASSERT_EQ(moved.levels[0].originA, finest.originA + step);
  ASSERT_EQ(moved.levels[0].originB, finest.originB - step);
  uint32_t movedLevels = 0;
  uint64_t newTexels = 0;
  for (size_t j = 0; j < layout.levels.size(); ++j) {
    const int64_t dA = std::abs(moved.levels[j].originA - layout.levels[j].originA);
    const int64_t dB = std::abs(moved.levels[j].originB - layout.levels[j].originB);
    movedLevels += dA != 0 || dB != 0 ? 1 : 0;
    newTexels += uint64_t(res * res - (res - dA) * (res - dB));
  }
  EXPECT_EQ(runUpdate(context(), patches, moved), movedLevels);
  EXPECT_EQ(patches.lastUpdateTexels(), newTexels) << "only the new strips are computed";
  // One diagonal step of a level's own recentre size or of the finest's: under a quarter of it.
  EXPECT_LE(newTexels, uint64_t(movedLevels) * res * res / 4);
  const std::vector<float> after = readBack(context(), patches);
  // The texels both windows cover were not written again.
  const PatchLevel& movedFinest = moved.levels[0];
  for (int64_t y = 0; y < res; ++y)
    for (int64_t x = 0; x < res; ++x) {
      const int64_t oldX = x + step, oldY = y - step;  // the same face index in the old window
      if (oldX >= res || oldY < 0) continue;
      ASSERT_EQ(texelOf(after, res, movedFinest, x, y), texelOf(first, res, finest, oldX, oldY))
          << "texel " << x << "," << y;
    }
  // Against the same layout built whole by a second set of patch textures.
  PatchTextures whole(context(), data, settings);
  ASSERT_EQ(runUpdate(context(), whole, moved), settings.levelCount);
  const std::vector<float> wholeTexels = readBack(context(), whole);
  double maxHeightDifference = 0.0, maxAngle = 0.0;
  size_t identical = 0;
  for (int64_t y = 0; y < res; ++y) {
    for (int64_t x = 0; x < res; ++x) {
      const glm::vec4 incremental = texelOf(after, res, movedFinest, x, y);
      const glm::vec4 built = texelOf(wholeTexels, res, movedFinest, x, y);
      identical += incremental == built ? 1 : 0;
      maxHeightDifference = std::max(maxHeightDifference, std::abs(double(incremental.w) - double(built.w)));
      maxAngle = std::max(maxAngle, angleBetween(glm::dvec3(incremental), glm::dvec3(built)));
    }
  }
  // The kept texels carry the octave budget of the old centre (an ulp at most, see above).
  EXPECT_LE(maxHeightDifference, kMovedToleranceM);
  EXPECT_LE(maxAngle, kMovedToleranceM / patchTexelSpacingM(moved, moved.levels[0], radius));
  std::printf("[ measured ] after one diagonal recentre step: %zu of %lld texels bit-identical to a whole build, "
              "max height difference %.3g m, max normal angle %.3g rad\n",
              identical, (long long)(res * res), maxHeightDifference, maxAngle);
  for (size_t j = 0; j < layout.levels.size(); ++j) {
    if (moved.levels[j].originA == layout.levels[j].originA && moved.levels[j].originB == layout.levels[j].originB) {
      EXPECT_TRUE(sameLayer(first, after, moved.levels[j].layer)) << "level " << j << " should not change";
    }
  }

  // (5) A finer pixel (exactly half): the finest exponent drops by one, the other levels keep
  // their exponent, origin and layer, so only the new finest level is rebuilt (into the layer
  // of the old coarsest one).
  const PatchLayout finer = choosePatchLayout(settings, radius, movedCamera, 0.5 * pixel);
  ASSERT_EQ(finer.levels[0].exponent, moved.levels[0].exponent - 1);
  EXPECT_EQ(runUpdate(context(), patches, finer), 1u);
  const std::vector<float> afterFiner = readBack(context(), patches);
  for (size_t j = 1; j < finer.levels.size(); ++j)
    EXPECT_TRUE(sameLayer(after, afterFiner, finer.levels[j].layer)) << "level " << j << " should not change";
  EXPECT_FALSE(sameLayer(after, afterFiner, finer.levels[0].layer));

  // invalidate(): everything again.
  patches.invalidate();
  EXPECT_EQ(runUpdate(context(), patches, finer), settings.levelCount);
  EXPECT_EQ(runUpdate(context(), patches, finer), 0u);
}

// Under the real-time budget (PatchTextures::plan): the first plan is a load (every level whole);
// after a jump that makes every level new, each frame writes at most the budget (or one
// minimum strip), coarsest level first, each level from a square at its centre grown by strips
// (what its layer holds only grows, and holds its centre from the first strip); when nothing
// is left, every level is what a whole build writes, bit for bit.
TEST_F(PatchTexturesGpu, ABudgetGrowsEachLevelFromItsCentreToWhatAWholeBuildWrites) {
  const PlanetDescription planet = resolvePreset("earth");
  PlanetGpuData data(context(), planet);
  const PatchSettings settings{128, 4, 0.5, 8};
  PatchTextures patches(context(), data, settings);
  const double radius = planet.radiusM;
  const double pixel = nadirPixelM(radius);
  const glm::dvec3 camera = cameraDirection(settings, radius);
  const uint64_t budget = realTimePatchBudget(settings);
  const uint64_t res = settings.resolution;
  EXPECT_EQ(budget, res * res / 8);

  const PatchTextures::Plan load = patches.plan(choosePatchLayout(settings, radius, camera, pixel), budget);
  EXPECT_EQ(load.deferred, 0u) << "nothing held: the first frame is a load";
  for (size_t j = 0; j < load.work.size(); ++j) {
    ASSERT_EQ(load.work[j].size(), 1u);
    EXPECT_EQ(load.work[j][0].texels(), res * res);
  }
  vk::submitAndWait(context(), [&](VkCommandBuffer cmd) { patches.update(cmd, load); });

  // A pixel 16 times finer: every exponent changes (by the level count, so the layers stay).
  const PatchLayout jumped = choosePatchLayout(settings, radius, camera, pixel / 16.0);
  for (size_t j = 0; j < jumped.levels.size(); ++j) ASSERT_EQ(jumped.levels[j].exponent, load.layout.levels[j].exponent - 4);
  std::vector<PatchTextures::Region> before(jumped.levels.size());
  uint32_t frames = 0;
  uint64_t written = 0;
  bool coarsestWhole = false;
  for (;; ++frames) {
    ASSERT_LT(frames, 100u);
    const PatchTextures::Plan plan = patches.plan(jumped, budget);
    uint64_t texels = 0;
    for (size_t j = 0; j < plan.work.size(); ++j) {
      for (const PatchTextures::Region& r : plan.work[j]) texels += r.texels();
      const PatchTextures::Region& held = plan.held[j];
      EXPECT_EQ(plan.usable[j], !held.empty());
      if (held.empty()) continue;
      // It holds the window's centre and everything it held before.
      const PatchLevel& level = jumped.levels[j];
      const int64_t centreA = level.originA + int64_t(res / 2), centreB = level.originB + int64_t(res / 2);
      EXPECT_TRUE(held.originA <= centreA && centreA < held.originA + held.width && held.originB <= centreB &&
                  centreB < held.originB + held.height)
          << "frame " << frames << " level " << j;
      const PatchTextures::Region& old = before[j];
      if (!old.empty()) {
        EXPECT_TRUE(held.originA <= old.originA && held.originB <= old.originB &&
                    held.originA + held.width >= old.originA + old.width &&
                    held.originB + held.height >= old.originB + old.height)
            << "frame " << frames << " level " << j;
      }
      before[j] = held;
    }
    if (texels == 0) {
      EXPECT_EQ(plan.deferred, 0u);
      break;
    }
    EXPECT_LE(texels, std::max<uint64_t>(budget, PatchTextures::kMinStripTexels * res)) << "frame " << frames;
    // Coarsest first: while the coarsest level is not whole, every frame works on it.
    if (!coarsestWhole) {
      EXPECT_FALSE(plan.work.back().empty()) << "frame " << frames;
    }
    coarsestWhole = plan.held.back().texels() == res * res;
    written += texels;
    const auto levelsWorked = uint32_t(std::count_if(plan.work.begin(), plan.work.end(),
                                                     [](const std::vector<PatchTextures::Region>& w) { return !w.empty(); }));
    vk::submitAndWait(context(), [&](VkCommandBuffer cmd) { EXPECT_EQ(patches.update(cmd, plan), levelsWorked); });
    EXPECT_EQ(patches.lastUpdateTexels(), texels);
  }
  std::printf("[ measured ] %u frames of at most %llu texels to build %zu new levels\n", frames,
              (unsigned long long)budget, jumped.levels.size());
  EXPECT_EQ(written, uint64_t(jumped.levels.size()) * res * res) << "each texel written once";
  EXPECT_GE(frames, uint32_t(written / budget));

  PatchTextures whole(context(), data, settings);
  ASSERT_EQ(runUpdate(context(), whole, jumped), settings.levelCount);
  const std::vector<float> grown = readBack(context(), patches);
  const std::vector<float> built = readBack(context(), whole);
  EXPECT_EQ(std::memcmp(grown.data(), built.data(), grown.size() * sizeof(float)), 0);
}

TEST_F(PatchTexturesGpu, RejectsLayoutsThatDoNotFitTheSettings) {
  const PlanetDescription planet = resolvePreset("moon");
  PlanetGpuData data(context(), planet);
  const PatchSettings settings{64, 3, 1.0, 8};
  EXPECT_NE(errorOf([&] {
              PatchTextures p(context(), data, PatchSettings{64, 3, 1.0, 5});
            }).find("got 64"),
            std::string::npos);
  PatchTextures patches(context(), data, settings);
  EXPECT_EQ(patches.image().layers, 3u);
  EXPECT_EQ(patches.image().extent.width, 64u);
  EXPECT_EQ(patches.image().format, VK_FORMAT_R32G32B32A32_SFLOAT);
  EXPECT_NE(patches.sampler(), VkSampler(VK_NULL_HANDLE));
  const PatchLayout layout = choosePatchLayout(settings, planet.radiusM, {1, 2, 3}, 10.0);
  auto updateError = [&](const PatchLayout& bad) {
    return errorOf([&] { vk::submitAndWait(context(), [&](VkCommandBuffer cmd) { patches.update(cmd, bad); }); });
  };
  PatchLayout bad = layout;
  bad.resolution = 128;
  EXPECT_NE(updateError(bad).find("128"), std::string::npos);
  bad = layout;
  bad.levels.pop_back();
  EXPECT_NE(updateError(bad).find("2 levels"), std::string::npos);
  bad = layout;
  bad.levels[1].layer = bad.levels[0].layer;
  EXPECT_NE(updateError(bad).find("used twice"), std::string::npos);
  bad = layout;
  bad.face = 9;
  EXPECT_NE(updateError(bad).find("9"), std::string::npos);
  // A rejected layout recorded nothing and marked nothing up to date.
  EXPECT_EQ(runUpdate(context(), patches, layout), 3u);
}

}  // namespace
}  // namespace planet::test
