// Mars and the Moon have the large-scale structure of the real bodies (issue 19, point 5),
// measured on coarse equirect grids of the CPU reference (heightmap_export.h, filtered to the
// pixel spacing, as `planet export heightmap --filtered`): Mars's dichotomy, volcanoes and
// canyon, the Moon's maria. Each figure is checked at several seeds, as `--seed` gives them.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "export/heightmap_export.h"
#include "export/terrain_statistics.h"
#include "planet/planet_description.h"
#include "planet/terrain_height.h"

namespace planet {
namespace {

constexpr double kPi = std::numbers::pi;

// A built-in preset with `seedOffset` added to every layer's seed (what `--seed` does).
PlanetDescription presetWithSeed(const std::string& name, uint32_t seedOffset) {
  PlanetDescription planet = resolvePreset(name);
  for (NoiseLayer& layer : planet.layers) layer.noise.seed += seedOffset;
  return planet;
}

struct Grid {
  uint32_t width = 0, height = 0;
  double spacingM = 0.0;       // the octave limit the heights were evaluated with
  std::vector<float> heightsM;  // row-major, top row first
  float at(uint32_t x, uint32_t y) const { return heightsM[size_t(y) * width + x]; }
};

Grid coarseGrid(const PlanetDescription& planet, uint32_t width, uint32_t height) {
  Heightmap map = computeHeightmap(planet, equirectSpec(width, height, true));
  return {width, height, map.spacingM, std::move(map.heightsM)};
}

double rowLatitudeRad(uint32_t y, uint32_t height) { return kPi / 2.0 * (double(height) - 2.0 * y - 1.0) / height; }

// The regions of 8-connected pixels above `thresholdM`, joined across 180 degrees of longitude.
int regionsAbove(const Grid& grid, float thresholdM) {
  std::vector<uint8_t> seen(grid.heightsM.size(), 0);
  int regions = 0;
  std::vector<size_t> stack;
  for (size_t start = 0; start < grid.heightsM.size(); ++start) {
    if (seen[start] || grid.heightsM[start] <= thresholdM) continue;
    ++regions;
    seen[start] = 1;
    stack.push_back(start);
    while (!stack.empty()) {
      const size_t i = stack.back();
      stack.pop_back();
      const int x = int(i % grid.width), y = int(i / grid.width);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int ny = y + dy;
          if (ny < 0 || ny >= int(grid.height)) continue;
          const int nx = (x + dx + int(grid.width)) % int(grid.width);
          const size_t j = size_t(ny) * grid.width + size_t(nx);
          if (!seen[j] && grid.heightsM[j] > thresholdM) {
            seen[j] = 1;
            stack.push_back(j);
          }
        }
    }
  }
  return regions;
}

// Mars at seeds 0-2 on a 1-degree grid (~59 km pixels: the dichotomy, volcanoes and canyon,
// not the hills).
class MarsStructure : public testing::TestWithParam<uint32_t> {
 protected:
  static constexpr uint32_t kWidth = 360, kHeight = 180;
};

// MOLA's hypsometry is bimodal: northern lowlands near -4 km over about a third of the planet,
// southern highlands near +1.5 km (Aharonson et al. 2001). A single broad fBm peak, as before
// issue 19, fails the trough and both peak positions.
TEST_P(MarsStructure, HypsometryIsBimodalWithLowlandsNearMinus4AndHighlandsNearPlus1point5Km) {
  const PlanetDescription mars = presetWithSeed("mars", GetParam());
  const Grid grid = coarseGrid(mars, kWidth, kHeight);
  const TerrainStatistics s = computeTerrainStatistics(grid.heightsM, kWidth, kHeight, mars.radiusM);
  EXPECT_TRUE(s.bimodal);
  EXPECT_GE(s.lowerPeakM, -5000.0);
  EXPECT_LE(s.lowerPeakM, -3000.0);
  EXPECT_GE(s.upperPeakM, 500.0);
  EXPECT_LE(s.upperPeakM, 2500.0);
  const double lowerPeakShare = s.hypsometry[size_t((s.lowerPeakM - kHypsometryMinM) / kHypsometryBinM)];
  EXPECT_LE(s.troughShare, 0.5 * lowerPeakShare);
  double lowland = 0.0;  // the area below -2 km: the lowland plains
  for (int bin = 0; bin < kHypsometryBins; ++bin)
    if (kHypsometryMinM + (bin + 1) * kHypsometryBinM <= -2000.0) lowland += s.hypsometry[size_t(bin)];
  EXPECT_GT(lowland, 0.25);
  EXPECT_LT(lowland, 0.45);
  std::printf("[ measured ] mars seed %u: peaks %.0f and %.0f m, trough %.3f of %.3f, lowlands %.3f of the area\n",
              GetParam(), s.lowerPeakM, s.upperPeakM, s.troughShare, lowerPeakShare, lowland);
}

// A few shield volcanoes: the highest point is a volcano above 10 km (Olympus Mons: 21.9 km), and
// 2 to 6 separate regions rise above 8 km (MOLA: Olympus, the three Tharsis Montes, Elysium Mons).
// Nothing else reaches 8 km: the dichotomy and the massifs top out near 6 km.
TEST_P(MarsStructure, AFewShieldVolcanoesRiseAbove8Km) {
  const PlanetDescription mars = presetWithSeed("mars", GetParam());
  const Grid grid = coarseGrid(mars, kWidth, kHeight);
  const float highest = *std::max_element(grid.heightsM.begin(), grid.heightsM.end());
  EXPECT_GT(highest, 10'000.0f);
  EXPECT_LT(highest, 25'000.0f);
  const int volcanoes = regionsAbove(grid, 8'000.0f);
  EXPECT_GE(volcanoes, 2);
  EXPECT_LE(volcanoes, 6);
  // Without the volcano layer no region reaches 8 km: the count above is the volcanoes'.
  PlanetDescription flat = mars;
  for (NoiseLayer& layer : flat.layers)
    if (layer.name == "volcanoes") layer.amplitudeM = 0.0;
  EXPECT_EQ(regionsAbove(coarseGrid(flat, kWidth, kHeight), 8'000.0f), 0);
  std::printf("[ measured ] mars seed %u: highest %.0f m, %d regions above 8 km\n", GetParam(), highest, volcanoes);
}

// The canyon system cuts the deepest ground: the lowest point lies below -6 km, and it is the
// canyon's doing (the terrain there without the canyon layer is at least 3 km higher).
TEST_P(MarsStructure, TheLowestGroundIsTheCanyonsFloorBelowMinus6Km) {
  const PlanetDescription mars = presetWithSeed("mars", GetParam());
  const Grid grid = coarseGrid(mars, kWidth, kHeight);
  const size_t lowest = size_t(std::min_element(grid.heightsM.begin(), grid.heightsM.end()) - grid.heightsM.begin());
  EXPECT_LT(grid.heightsM[lowest], -6'000.0f);
  EXPECT_GT(grid.heightsM[lowest], -9'000.0f);  // MOLA's lowest: -8.2 km in Hellas
  const glm::dvec2 latLon = equirectPixelCentreDeg(uint32_t(lowest % kWidth), uint32_t(lowest / kWidth), kWidth, kHeight);
  PlanetDescription noCanyon = mars;
  for (NoiseLayer& layer : noCanyon.layers)
    if (layer.name == "canyon") layer.amplitudeM = 0.0;
  const double without = terrainHeightM(noCanyon, directionFromLatLon(latLon.x, latLon.y), grid.spacingM);
  EXPECT_GT(without - grid.heightsM[lowest], 3'000.0);
  std::printf("[ measured ] mars seed %u: lowest %.0f m at %.1f, %.1f (%.0f m without the canyon)\n", GetParam(),
              grid.heightsM[lowest], latLon.x, latLon.y, without);
}

INSTANTIATE_TEST_SUITE_P(Seeds, MarsStructure, testing::Values(0u, 1u, 2u));

// The Moon at seeds 0-2 on a grid of ~21 km pixels.
class MoonMaria : public testing::TestWithParam<uint32_t> {};

// One pixel of the grid: its height, area weight (cos latitude) and slope to its east and south
// neighbours (as terrain_statistics.h measures land slopes).
struct Sample {
  double heightM, weight, slope;
};

// Area-weighted value of `key` below which the fraction `p` of the samples' area lies.
template <typename Key>
double weightedQuantile(std::vector<Sample> samples, double p, Key key) {
  std::sort(samples.begin(), samples.end(), [&](const Sample& a, const Sample& b) { return key(a) < key(b); });
  double total = 0.0;
  for (const Sample& s : samples) total += s.weight;
  double below = 0.0;
  for (const Sample& s : samples) {
    below += s.weight;
    if (below >= p * total) return key(s);
  }
  return key(samples.back());
}

double weightedSpread(const std::vector<Sample>& samples) {
  double w = 0.0, mean = 0.0, square = 0.0;
  for (const Sample& s : samples) {
    w += s.weight;
    mean += s.weight * s.heightM;
  }
  mean /= w;
  for (const Sample& s : samples) square += s.weight * (s.heightM - mean) * (s.heightM - mean);
  return std::sqrt(square / w);
}

// The maria, the lowest ~16 % of the surface (Head 1976), are lava plains: far flatter than the
// cratered highlands, 1-3 km below them (LOLA), and low enough that the moon scheme paints them
// its dark lowland colour (it blends to the highland colour between -1.5 and +1.5 km).
TEST_P(MoonMaria, TheLowestSixthIsFlatterAndLowerThanTheHighlands) {
  const PlanetDescription moon = presetWithSeed("moon", GetParam());
  const uint32_t width = 512, height = 256;
  const Grid grid = coarseGrid(moon, width, height);
  std::vector<Sample> samples;
  for (uint32_t y = 0; y < height; ++y) {
    const double lat = rowLatitudeRad(y, height);
    const double eastM = moon.radiusM * std::cos(lat) * 2.0 * kPi / width;
    const double southM = moon.radiusM * kPi / height;
    for (uint32_t x = 0; x < width; ++x) {
      const double h = grid.at(x, y);
      const double east = (grid.at((x + 1) % width, y) - h) / eastM;
      const double south = y + 1 < height ? (grid.at(x, y + 1) - h) / southM : (grid.at(x, y - 1) - h) / southM;
      samples.push_back({h, std::cos(lat), std::hypot(east, south)});
    }
  }
  const double cutM = weightedQuantile(samples, 0.16, [](const Sample& s) { return s.heightM; });
  std::vector<Sample> maria, highlands;
  for (const Sample& s : samples) (s.heightM <= cutM ? maria : highlands).push_back(s);
  const auto height50 = [](const Sample& s) { return s.heightM; };
  const auto slope50 = [](const Sample& s) { return s.slope; };
  const double mariaSpread = weightedSpread(maria), highlandSpread = weightedSpread(highlands);
  const double mariaSlope = weightedQuantile(maria, 0.5, slope50), highlandSlope = weightedQuantile(highlands, 0.5, slope50);
  const double depthM = weightedQuantile(highlands, 0.5, height50) - weightedQuantile(maria, 0.5, height50);
  EXPECT_LT(mariaSpread, 0.5 * highlandSpread);
  EXPECT_LT(mariaSlope, 0.5 * highlandSlope);
  EXPECT_GT(depthM, 1'000.0);
  EXPECT_LT(depthM, 3'000.0);
  double dark = 0.0, total = 0.0;  // the share of the surface below -1.5 km: the maria's dark area
  for (const Sample& s : samples) {
    total += s.weight;
    dark += s.heightM < -1'500.0 ? s.weight : 0.0;
  }
  EXPECT_GT(dark / total, 0.12);
  EXPECT_LT(dark / total, 0.25);
  std::printf(
      "[ measured ] moon seed %u: maria below %.0f m, height spread %.0f vs %.0f m, median slope %.4f vs %.4f, "
      "%.0f m below the highlands; %.3f of the area below -1.5 km\n",
      GetParam(), cutM, mariaSpread, highlandSpread, mariaSlope, highlandSlope, depthM, dark / total);
}

INSTANTIATE_TEST_SUITE_P(Seeds, MoonMaria, testing::Values(0u, 1u, 2u));

}  // namespace
}  // namespace planet
