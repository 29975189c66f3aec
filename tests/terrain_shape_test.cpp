// Shaped layers (planet/terrain_shape.h, shaders/common/terrain_height.glsl): the curves pass
// through their points without overshoot and join their constant ends smoothly, a hypsometry
// gives its area fractions at every seed, a mask multiplies by an earlier layer's value, and bad
// curves in a preset are one-line errors.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "noise/noise_cpu.h"
#include "noise/noise_kernel.h"
#include "planet/planet_description.h"
#include "planet/terrain_height.h"
#include "planet/terrain_shape.h"
#include "test_support.h"

namespace planet {
namespace {

// A kernel whose layer 0 has the curve through `points` as its transfer curve.
struct CurveProbe {
  noise::NoiseKernel<double>::TerrainKernelLayer layer;
  noise::NoiseKernel<double> kernel;
  uint32_t count;

  explicit CurveProbe(const std::vector<CurvePoint>& points) : count(uint32_t(points.size())) {
    curveKnots(points, layer.shape.knots);
    layer.shape.curveKnots = count;
    kernel.terrainLayers = &layer;
    kernel.terrainLayerCount = 1;
  }
  double operator()(double x) { return kernel.terrainCurve(0u, 0u, count, x); }
};

TEST(TerrainShape, CurvesPassThroughTheirPointsMonotoneAndSmooth) {
  const std::vector<CurvePoint> rising{{-1.0, -5000.0}, {-0.2, -4000.0}, {0.0, -100.0}, {0.05, 0.0},
                                       {0.1, 50.0},     {0.6, 400.0},    {0.9, 2500.0}};
  CurveProbe curve(rising);
  for (const CurvePoint& p : rising) EXPECT_NEAR(curve(p.x), p.y, 1e-3 * (1.0 + std::abs(p.y))) << p.x;
  // Constant outside the points.
  EXPECT_EQ(curve(-7.0), -5000.0);
  EXPECT_EQ(curve(3.0), 2500.0);
  // Monotone between them (no overshoot on a rising curve), and continuous in value and slope:
  // one-sided difference quotients agree on both sides of every point, the ends included (the
  // curve meets its constant ends with zero slope).
  double previous = curve(-1.0);
  for (int i = 1; i <= 20000; ++i) {
    double y = curve(-1.0 + 1.9 * i / 20000.0);
    ASSERT_GE(y, previous) << "at step " << i;
    previous = y;
  }
  const double h = 1e-8;
  for (const CurvePoint& p : rising) {
    double left = (curve(p.x) - curve(p.x - h)) / h, right = (curve(p.x + h) - curve(p.x)) / h;
    double scale = 1.0 + std::max(std::abs(left), std::abs(right));
    EXPECT_NEAR(left, right, 0.01 * scale) << "slope jumps at x = " << p.x;
  }
  // A bump (belts): its top is its middle point, and it stays within [0, 1].
  CurveProbe bump({{-0.3, 0.0}, {-0.1, 0.8}, {0.0, 1.0}, {0.1, 0.8}, {0.3, 0.0}});
  for (int i = 0; i <= 1000; ++i) {
    double y = bump(-0.5 + i / 1000.0);
    ASSERT_GE(y, 0.0);
    ASSERT_LE(y, 1.0);
  }
  EXPECT_NEAR(bump(0.0), 1.0, 1e-6);
}

// One fBm layer through a hypsometry that puts 30 % of the area below 0 m and 70 % below 100 m.
PlanetDescription hypsometricPlanet(uint32_t seed) {
  NoiseLayer layer;
  layer.name = "continents";
  layer.noise.type = noise::NoiseType::Fbm;
  layer.noise.octaves = 6;
  layer.noise.H = 0.8;
  layer.noise.seed = seed;
  layer.frequency = 1.0 / 5e6;
  layer.amplitudeM = 1.0;
  layer.hypsometry = {{0.0, -4000.0}, {0.3, 0.0}, {0.7, 100.0}, {1.0, 2000.0}};
  PlanetDescription planet;
  planet.name = "Test";
  planet.radiusM = 6.371e6;
  planet.layers = {layer};
  return planet;
}

TEST(TerrainShape, HypsometryGivesItsAreaFractionsAtEverySeed) {
  // Measured at points independent of the calibration's lattice: uniform random directions.
  std::mt19937_64 random(11);
  std::normal_distribution<double> normal;
  std::vector<glm::dvec3> directions(6000);
  for (glm::dvec3& d : directions) d = glm::normalize(glm::dvec3(normal(random), normal(random), normal(random)));
  for (uint32_t seed = 0; seed < 5; ++seed) {
    const PlanetDescription planet = hypsometricPlanet(seed * 101 + 7);
    size_t belowSea = 0, belowHundred = 0;
    for (const glm::dvec3& d : directions) {
      double h = terrainHeightM(planet, d);
      belowSea += h < 0.0;
      belowHundred += h < 100.0;
    }
    // Binomial spread of 6000 samples: sd 0.006; the bound is 3.3 sd.
    EXPECT_NEAR(double(belowSea) / directions.size(), 0.3, 0.02) << "seed " << seed;
    EXPECT_NEAR(double(belowHundred) / directions.size(), 0.7, 0.02) << "seed " << seed;
  }
  // Without the hypsometry, the same noise's share below its own median differs by seed:
  // the quantiles really are the seed's (the 30 % value is not one fixed number).
  const NoiseLayer a = hypsometricPlanet(7).layers[0], b = hypsometricPlanet(108).layers[0];
  const double fractions[] = {0.3};
  EXPECT_NE(noiseQuantiles(a, 6.371e6, fractions)[0], noiseQuantiles(b, 6.371e6, fractions)[0]);
}

TEST(TerrainShape, AMaskMultipliesByAnEarlierLayersValue) {
  PlanetDescription planet = hypsometricPlanet(3);
  NoiseLayer detail;
  detail.name = "detail";
  detail.noise.type = noise::NoiseType::Fbm;
  detail.noise.octaves = 5;
  detail.noise.seed = 9;
  detail.frequency = 1.0 / 2e5;
  detail.amplitudeM = 300.0;
  detail.mask = "continents";
  planet.layers.push_back(detail);
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  const double noise = noise::evaluateCpuDouble(detail.noise, planet.radiusM * d * detail.frequency);
  PlanetDescription alone = planet;
  alone.layers.pop_back();
  const double base = terrainHeightM(alone, d);
  // Without a mask curve the factor is the continents' value (here its height in metres).
  EXPECT_NEAR(terrainHeightM(planet, d), base + 300.0 * noise * base, 1e-9 * std::abs(300.0 * noise * base) + 1e-9);
  // Through a mask curve that is 2 everywhere, and one that is 0 everywhere.
  planet.layers[1].maskCurve = {{-1e5, 2.0}, {1e5, 2.0}};
  EXPECT_NEAR(terrainHeightM(planet, d), base + 600.0 * noise, 1e-9);
  planet.layers[1].maskCurve = {{-1e5, 0.0}, {1e5, 0.0}};
  EXPECT_EQ(terrainHeightM(planet, d), base);
  // The GPU's struct names the masking layer by index.
  EXPECT_EQ(terrainLayerShape(planet, 1).maskLayer, 0u);
  EXPECT_EQ(terrainLayerShape(planet, 0).maskLayer, gpu::kTerrainNoMask);
}

constexpr std::string_view kShaped = R"([planet]
name = "Test"
radius_m = 1_000_000
has_ocean = false

[colors]
scheme = "altitude"

[[layer]]
name = "base"
type = "fbm"
octaves = 4
frequency = 1e-6
amplitude_m = 1
hypsometry = [[0, -1000], [0.5, 0], [1, 1000]]

[[layer]]
name = "top"
type = "fbm"
octaves = 4
frequency = 1e-5
amplitude_m = 100
mask = "base"
mask_curve = [[-1000, 0], [1000, 1]]
)";

std::string shapedError(std::string_view from, std::string_view to) {
  std::string text(kShaped);
  size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return test::errorOf([&] { parsePlanetDescription(text, "x.toml"); });
}

TEST(TerrainShape, BadCurvesInAPresetAreOneLineErrors) {
  EXPECT_EQ(test::errorOf([] { parsePlanetDescription(kShaped, "x.toml"); }), "");
  EXPECT_EQ(shapedError("mask = \"base\"", "mask = \"top\""), "x.toml:23: mask 'top' must name an earlier layer");
  EXPECT_EQ(shapedError("mask = \"base\"", "mask = \"nowhere\""),
            "x.toml:23: mask 'nowhere' must name an earlier layer");
  EXPECT_EQ(shapedError("mask = \"base\"\n", ""), "x.toml:23: mask_curve needs a mask (the name of an earlier layer)");
  EXPECT_EQ(shapedError("[0.5, 0]", "[0, 0]"), "x.toml:15: hypsometry[1][0] must be above the point before (0), got 0");
  EXPECT_EQ(shapedError("[0.5, 0]", "[0.5, -2000]"),
            "x.toml:15: hypsometry values must not decrease with the area fraction, got -2000 after -1000");
  EXPECT_EQ(shapedError("[1, 1000]]", "[1.5, 1000]]"), "x.toml:15: hypsometry[2][0] must be in [0, 1], got 1.5");
  EXPECT_EQ(shapedError("hypsometry = [[0, -1000], [0.5, 0], [1, 1000]]", "hypsometry = [[0, -1000]]"),
            "x.toml:15: 'hypsometry' must be an array of 2 to 16 points [x, y], got 1 elements");
  EXPECT_EQ(shapedError("[0.5, 0]", "[0.5]"), "x.toml:15: hypsometry[1] must be a point [x, y], got 1 elements");
  EXPECT_EQ(shapedError("amplitude_m = 1\n", "amplitude_m = 1\ntransfer = [[0, 0], [1, 1]]\n"),
            "x.toml:16: give either transfer or hypsometry in [[layer]], not both");
  EXPECT_EQ(shapedError("mask_curve = [[-1000, 0], [1000, 1]]", "mask_curve = [[-1000, 0], [1000, \"one\"]]"),
            "x.toml:24: mask_curve[1][1] must be a number, got string");
}

}  // namespace
}  // namespace planet
