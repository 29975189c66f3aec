// The CPU double reference of terrain heights: planet-frame conventions, great-circle steps,
// and the height formula of planet_description.h.
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

}  // namespace
}  // namespace planet
