// The CPU double reference of terrain heights: planet-frame conventions, great-circle steps,
// and the height formula of planet_description.h.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/error.h"
#include "noise/noise_cpu.h"
#include "planet/terrain_height.h"

namespace planet {
namespace {

TEST(TerrainHeight, LatitudeAndLongitudeFollowThePlanetFrame) {
  EXPECT_LT(glm::length(directionFromLatLon(0, 0) - glm::dvec3(1, 0, 0)), 1e-15);
  EXPECT_LT(glm::length(directionFromLatLon(0, 90) - glm::dvec3(0, 1, 0)), 1e-15);
  EXPECT_LT(glm::length(directionFromLatLon(90, 123) - glm::dvec3(0, 0, 1)), 1e-15);
  EXPECT_LT(glm::length(directionFromLatLon(-90, 0) - glm::dvec3(0, 0, -1)), 1e-15);
  EXPECT_THROW(directionFromLatLon(90.5, 0), Error);
  EXPECT_THROW(directionFromLatLon(std::nan(""), 0), Error);
}

// Angle between unit vectors, well conditioned for small angles (acos of the dot is not).
double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

TEST(TerrainHeight, GreatCircleStepsCoverTheirDistanceInTheirBearing) {
  const double r = 6'371'000.0;
  const glm::dvec3 start = directionFromLatLon(10, 20);
  for (double bearing : {0.0, 45.0, 90.0, 200.0}) {
    glm::dvec3 end = travelGreatCircle(start, bearing, 1000.0, r);
    EXPECT_NEAR(angleBetween(start, end) * r, 1000.0, 1e-6) << bearing;
  }
  EXPECT_GT(travelGreatCircle(start, 0.0, 1000.0, r).z, start.z);    // north
  EXPECT_LT(travelGreatCircle(start, 180.0, 1000.0, r).z, start.z);  // south
  // From a pole the direction is still well defined.
  glm::dvec3 fromPole = travelGreatCircle(glm::dvec3(0, 0, 1), 0.0, 1000.0, r);
  EXPECT_NEAR(angleBetween(glm::dvec3(0, 0, 1), fromPole) * r, 1000.0, 1e-6);
}

TEST(TerrainHeight, HeightIsScaledBasePlusTheLayerSum) {
  PlanetDescription earth = resolvePreset("earth");
  earth.heightScale = 1.5;
  earth.baseHeightM = -2400.0;
  for (NoiseLayer& layer : earth.layers) {  // unshaped: each term is amplitude times noise
    layer.transfer.clear();
    layer.hypsometry.clear();
    layer.mask.clear();
    layer.maskCurve.clear();
    if (layer.amplitudeM == 0.0) layer.amplitudeM = 700.0;
  }
  const glm::dvec3 d = directionFromLatLon(12.3, -45.6);
  double sum = earth.baseHeightM;
  for (const NoiseLayer& layer : earth.layers)
    sum += layer.amplitudeM * noise::evaluateCpuDouble(layer.noise, earth.radiusM * d * layer.frequency);
  EXPECT_DOUBLE_EQ(terrainHeightM(earth, d), 1.5 * sum);
  EXPECT_EQ(terrainHeightM(earth, d), terrainHeightM(earth, d));  // deterministic
}

TEST(TerrainHeight, EarthHeightsArePlausibleAndVaryAlongALine) {
  const PlanetDescription earth = resolvePreset("earth");
  std::vector<double> h = terrainHeightsAlong(earth, directionFromLatLon(30, 40), 90.0, 50'000.0, 200);
  auto [lo, hi] = std::minmax_element(h.begin(), h.end());
  EXPECT_GT(*lo, -15'000.0);
  EXPECT_LT(*hi, 12'000.0);
  EXPECT_GT(*hi - *lo, 1'000.0) << "a 10,000 km line should cross real relief";
}

// The terrain's height bounds (estimateTerrainHeightBounds: the horizon cut, the culling hulls,
// the frame's shading bounds) hold at 6,000 points of every built-in preset, a lattice other than
// the estimate's own; Earth's come from its layers' ranges (exactTerrainHeightBounds) and are
// within a few km of its highest and lowest ground, where the sampled estimate alone gave 144 km.
TEST(TerrainHeight, BoundsHoldEverywhereAndFollowTheLayersRanges) {
  for (const char* name : {"earth", "mars", "moon", "giant", "faults", "mpd"}) {
    SCOPED_TRACE(name);
    const PlanetDescription planet = resolvePreset(name);
    const TerrainHeightBounds bounds = estimateTerrainHeightBounds(planet);
    constexpr int kPoints = 6000;
    double lowest = 1e300, highest = -1e300;
    for (int i = 0; i < kPoints; ++i) {
      const double z = 1.0 - (2.0 * i + 1.0) / kPoints;
      const double r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.3999632297286533 * i + 0.7;
      const double h = terrainHeightM(planet, {r * std::cos(phi), z, r * std::sin(phi)});
      lowest = std::min(lowest, h);
      highest = std::max(highest, h);
    }
    std::printf("%s: heights %.0f .. %.0f m at %d points, bounds %.0f .. %.0f m\n", name, lowest, highest, kPoints,
                bounds.minM, bounds.maxM);
    EXPECT_LE(bounds.minM, lowest);
    EXPECT_GE(bounds.maxM, highest);
  }
  const PlanetDescription earth = resolvePreset("earth");
  const std::optional<TerrainHeightBounds> exact = exactTerrainHeightBounds(earth);
  ASSERT_TRUE(exact.has_value());
  // Continents' hypsometry -6300 .. 1200 m, mountains 0 .. 5000, hills 0 .. 900, ground ±30 m
  // times its octaves' weights (~2.2) and the simplex bound.
  EXPECT_NEAR(exact->minM, -6300.0 - 30.0 * 2.23 * 1.025, 20.0);
  EXPECT_NEAR(exact->maxM, 1200.0 + 5000.0 + 900.0 + 30.0 * 2.23 * 1.025, 20.0);
  EXPECT_EQ(estimateTerrainHeightBounds(earth).maxM, exact->maxM);

  // A plain fBm layer: its octaves' weights times the simplex bound, scaled and shifted.
  PlanetDescription plain = earth;
  plain.layers.resize(1);
  plain.layers[0].hypsometry.clear();
  plain.layers[0].amplitudeM = -100.0;
  plain.heightScale = 2.0;
  plain.baseHeightM = 50.0;
  const double w = std::pow(plain.layers[0].noise.lacunarity, -plain.layers[0].noise.H);
  double weights = 0.0;
  for (int i = 0; i < plain.layers[0].noise.octaves; ++i) weights += std::pow(w, i);
  const std::optional<TerrainHeightBounds> fbm = exactTerrainHeightBounds(plain);
  ASSERT_TRUE(fbm.has_value());
  EXPECT_NEAR(fbm->maxM, 2.0 * (50.0 + 100.0 * 1.025 * weights), 2.0);
  EXPECT_NEAR(fbm->minM, 2.0 * (50.0 - 100.0 * 1.025 * weights), 2.0);
  // A fractal without a curve whose range is not derived (ridged): no exact bounds.
  plain.layers[0].noise.type = noise::NoiseType::Ridged;
  EXPECT_FALSE(exactTerrainHeightBounds(plain).has_value());
}

// Where the noise's planes x = y, y = z, x = z (simplex faces at every octave) cut the surface,
// and where the axes do, two points 1 mm apart on either side differ by no more than the ground's
// slope allows. With Gustavson's 0.6 kernel they differed by 2-7 m at the poles and by 17 cm
// across longitude 45°.
TEST(TerrainHeight, NoSeamAtThePolesAxesOrAlongTheNoisePlanes) {
  const PlanetDescription earth = resolvePreset("earth");
  const struct {
    double lat, lon, bearing;
  } crossings[] = {{90.0, 0.0, 0.0},  {0.0, 0.0, 45.0},  {0.0, 90.0, 45.0}, {0.0, 180.0, 45.0},
                   {-90.0, 0.0, 0.0}, {35.0, 45.0, 90.0}, {-60.0, 45.0, 90.0}, {0.0, 45.0, 0.0}};
  for (const auto& c : crossings) {
    // Start 0.5 mm before the crossing point and step over it.
    const glm::dvec3 at = directionFromLatLon(c.lat, c.lon);
    const glm::dvec3 before = travelGreatCircle(at, c.bearing + 180.0, 0.0005, earth.radiusM);
    const std::vector<double> h = terrainHeightsAlong(earth, before, c.bearing, 0.001, 2);
    EXPECT_LT(std::abs(h[1] - h[0]), 0.005) << "across " << c.lat << ", " << c.lon << " bearing " << c.bearing;
  }
}

// Seen from 1 to 10 km up, the land must not be a plain: the median slope between points 300 m
// and 3 km apart on land, over 40 lines spread across the planet. The earlier stack (H = 1
// mountains, hybrid hills) had 2.7 % and 1.5 % and rendered as a featureless plain; this one
// has about 10 % and 4.5 % (Earth's land: a median slope of several percent at 100 m).
TEST(TerrainHeight, EarthLandHasRelief) {
  const PlanetDescription earth = resolvePreset("earth");
  for (double lagM : {300.0, 3000.0}) {
    std::vector<double> slopes;
    for (int i = 0; i < 40; ++i) {
      const glm::dvec3 start = directionFromLatLon((i * 37) % 120 - 60, (i * 71) % 360 - 180);
      const std::vector<double> h = terrainHeightsAlong(earth, start, (i * 53) % 360, lagM, 60);
      if (*std::min_element(h.begin(), h.end()) <= 0.0) continue;  // land lines only
      for (size_t k = 1; k < h.size(); ++k) slopes.push_back(std::abs(h[k] - h[k - 1]) / lagM);
    }
    ASSERT_GE(slopes.size(), 5u * 59u) << "too few lines on land at a lag of " << lagM << " m";
    std::nth_element(slopes.begin(), slopes.begin() + slopes.size() / 2, slopes.end());
    EXPECT_GT(slopes[slopes.size() / 2], lagM < 1000.0 ? 0.06 : 0.03) << "median slope at a lag of " << lagM << " m";
  }
}

}  // namespace
}  // namespace planet
