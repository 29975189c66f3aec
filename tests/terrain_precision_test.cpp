// Earth-scale precision: heights sampled 5 cm apart on an Earth-radius planet, 6,371 km from
// the noise origin, through the float rebased path the GPU runs (terrain_rebase.h), are smooth
// and equal the double-precision reference within 1 cm. A plain float evaluation of the same
// points is shown to miss it, so the test can fail.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "noise/noise_kernel.h"
#include "noise/permutation.h"
#include "planet/terrain_height.h"
#include "planet/terrain_rebase.h"

namespace planet {
namespace {

constexpr double kSpacingM = 0.05;
constexpr int kSamples = 400;  // 20 m of line
constexpr double kToleranceM = 0.01;

struct Line {
  glm::dvec3 anchor;               // on the radius sphere
  std::vector<glm::dvec3> points;  // on the radius sphere, kSpacingM apart
};

Line sampleLine(const PlanetDescription& planet, double latDeg, double lonDeg) {
  Line line;
  const glm::dvec3 start = directionFromLatLon(latDeg, lonDeg);
  line.anchor = planet.radiusM * start;
  // Start 3.7 m from the anchor so that offsets are neither zero nor round numbers.
  for (int i = 0; i < kSamples; ++i)
    line.points.push_back(planet.radiusM * travelGreatCircle(start, 60.0, 3.7 + kSpacingM * i, planet.radiusM));
  return line;
}

// Largest difference between the sample-to-sample steps of `h` and of the reference: a
// stair-step (a run of equal inputs, then a jump) shows as the height change it swallowed.
double maxStepError(const std::vector<double>& h, const std::vector<double>& reference) {
  double worst = 0;
  for (size_t i = 1; i < h.size(); ++i)
    worst = std::max(worst, std::abs((h[i] - h[i - 1]) - (reference[i] - reference[i - 1])));
  return worst;
}

TEST(TerrainPrecision, RebasedFloatHeightsMatchDoubleWithinOneCentimetreAndAreSmooth) {
  const PlanetDescription earth = resolvePreset("earth");
  for (auto [lat, lon] : {std::pair{37.1, -122.3}, std::pair{-33.9, 151.2}, std::pair{89.99, 10.0}}) {
    const Line line = sampleLine(earth, lat, lon);
    const OctaveTables tables = buildOctaveTables(earth, line.anchor);
    std::vector<double> rebased, reference;
    double worst = 0;
    for (const glm::dvec3& p : line.points) {
      rebased.push_back(terrainHeightRebased(earth, tables, glm::vec3(p - line.anchor)));
      reference.push_back(terrainHeightM(earth, p / earth.radiusM));
      worst = std::max(worst, std::abs(rebased.back() - reference.back()));
    }
    EXPECT_LT(worst, kToleranceM) << "at " << lat << ", " << lon;
    // Float heights of kilometres carry a few millimetres of rounding, so steps between 5 cm
    // samples follow the reference to within 7.5 mm: no stair-steps (measured: at most 5.2 mm,
    // under twice the largest error, so rounding noise; the plain float path below is off by metres).
    const double stepError = maxStepError(rebased, reference);
    std::printf("%.2f, %.2f: worst %.2f mm, step error %.2f mm\n", lat, lon, worst * 1e3, stepError * 1e3);
    EXPECT_LT(stepError, 0.0075) << lat << ", " << lon;
  }
}

TEST(TerrainPrecision, RebasedMoonCratersMatchDoubleWithinOneCentimetre) {
  // The crater layer's rebased walk turns each octave's simplex lattice shift into the cubic cell
  // shift (noise.glsl, craterCellShift): a wrong cell there moves every crater by whole cells,
  // metres to kilometres of height, while the other layers would still agree.
  const PlanetDescription moon = resolvePreset("moon");
  for (auto [lat, lon] : {std::pair{12.0, -48.0}, std::pair{-71.5, 133.3}}) {
    const Line line = sampleLine(moon, lat, lon);
    const OctaveTables tables = buildOctaveTables(moon, line.anchor);
    std::vector<double> rebased, reference;
    double worst = 0;
    for (const glm::dvec3& p : line.points) {
      rebased.push_back(terrainHeightRebased(moon, tables, glm::vec3(p - line.anchor)));
      reference.push_back(terrainHeightM(moon, p / moon.radiusM));
      worst = std::max(worst, std::abs(rebased.back() - reference.back()));
    }
    std::printf("moon %.2f, %.2f: worst %.2f mm, step error %.2f mm\n", lat, lon, worst * 1e3,
                maxStepError(rebased, reference) * 1e3);
    EXPECT_LT(worst, kToleranceM) << "at " << lat << ", " << lon;
    EXPECT_LT(maxStepError(rebased, reference), 0.0075) << lat << ", " << lon;
  }
}

TEST(TerrainPrecision, PlainFloatEvaluationFailsAtEarthScale) {
  // Without rebasing, the float noise input of the hills layer (318 units of 20 km from the
  // origin) moves in steps of 0.6 m, so the metre-scale octaves are evaluated at the wrong
  // places and the heights miss the reference by far more than the tolerance (measured: up to
  // 1.3 m on these lines).
  const PlanetDescription earth = resolvePreset("earth");
  double worst = 0;
  for (auto [lat, lon] :
       {std::pair{37.1, -122.3}, std::pair{33.8, -90.0}, std::pair{17.8, 0.0}, std::pair{-21.1, -30.0}}) {
    const Line line = sampleLine(earth, lat, lon);
    for (const glm::dvec3& p : line.points) {
      double h = earth.baseHeightM;
      for (const NoiseLayer& layer : earth.layers) {
        noise::NoiseKernel<float> kernel;
        kernel.permutation = noise::permutationTable(layer.noise.seed).data();
        h += layer.amplitudeM * kernel.evaluateNoise(noise::toNoiseParams(layer.noise), glm::vec3(p * layer.frequency));
      }
      worst = std::max(worst, std::abs(h - terrainHeightM(earth, p / earth.radiusM)));
    }
  }
  std::printf("plain float evaluation misses the double reference by up to %.4f m\n", worst);
  EXPECT_GT(worst, kToleranceM);
}

}  // namespace
}  // namespace planet
