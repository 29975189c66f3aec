// Compiled without fused multiply-adds like every C++ build of shared GLSL (the top CMakeLists.txt).
#include "planet/terrain_height.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/error.h"
#include "planet/octave_budget.h"
#include "planet/terrain_kernel.h"
#include "planet/terrain_shape.h"

namespace planet {

glm::dvec3 directionFromLatLon(double latitudeDeg, double longitudeDeg) {
  if (!std::isfinite(latitudeDeg) || latitudeDeg < -90.0 || latitudeDeg > 90.0)
    throw Error(fmt::format("latitude must be in [-90, 90] degrees, got {}", latitudeDeg));
  if (!std::isfinite(longitudeDeg)) throw Error(fmt::format("longitude must be finite, got {}", longitudeDeg));
  const double lat = latitudeDeg * std::numbers::pi / 180.0;
  const double lon = longitudeDeg * std::numbers::pi / 180.0;
  return {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)};
}

double latitudeDegOf(const glm::dvec3& d) {
  return std::atan2(d.z, std::hypot(d.x, d.y)) / (std::numbers::pi / 180.0);
}
double longitudeDegOf(const glm::dvec3& d) { return std::atan2(d.y, d.x) / (std::numbers::pi / 180.0); }

glm::dvec3 travelGreatCircle(const glm::dvec3& start, double bearingDeg, double distanceM, double radiusM) {
  // Local east and north at `start`; at a pole, "north" is taken along longitude 0 (+x).
  const glm::dvec3 up = glm::normalize(start);
  glm::dvec3 east = glm::cross(glm::dvec3(0.0, 0.0, 1.0), up);
  east = glm::length(east) < 1e-12 ? glm::dvec3(0.0, 1.0, 0.0) : glm::normalize(east);
  const glm::dvec3 north = glm::cross(up, east);
  const double bearing = bearingDeg * std::numbers::pi / 180.0;
  const glm::dvec3 heading = std::cos(bearing) * north + std::sin(bearing) * east;
  const double angle = distanceM / radiusM;
  return glm::normalize(std::cos(angle) * up + std::sin(angle) * heading);
}

double terrainHeightM(const PlanetDescription& planet, const glm::dvec3& direction, double spacingM) {
  // The layer sum of shaders/common/terrain_height.glsl, each layer walked plainly from the
  // point on the radius sphere times its frequency.
  const TerrainKernelLayers<double> layers = terrainKernelLayers<double>(planet, spacingM);
  noise::NoiseKernel<double> kernel;
  layers.attach(kernel, false);
  return kernel.terrainHeightSum(planet.baseHeightM, planet.heightScale, planet.radiusM * glm::normalize(direction), 0u);
}

double surfaceHeightM(const PlanetDescription& planet, const glm::dvec3& direction) {
  const double ground = terrainHeightM(planet, direction);
  return planet.hasOcean ? std::max(ground, planet.seaLevelM) : ground;
}

TerrainHeightBounds estimateTerrainHeightBounds(const PlanetDescription& planet) {
  constexpr int kSamples = 4096;
  const double spacing = planet.radiusM * std::sqrt(4.0 * std::numbers::pi / kSamples);
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  double highest = -1e300, lowest = 1e300;
  for (int i = 0; i < kSamples; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / kSamples;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden * i;
    const double h = terrainHeightM(planet, {r * std::cos(phi), r * std::sin(phi), z}, spacing);
    highest = std::max(highest, h);
    lowest = std::min(lowest, h);
  }
  // What the omitted octaves can add: each weighs octaveWeight^i; bound a fractal's finer part
  // by twice its geometric tail (the multifractals multiply by signals of about 1..2).
  // A curve scales that by at most its steepest slope (a monotone cubic stays within three times
  // its steepest secant), a mask by its largest factor.
  double margin = 0.0;
  for (size_t l = 0; l < planet.layers.size(); ++l) {
    const NoiseLayer& layer = planet.layers[l];
    const OctaveBudget budget = octaveBudget(layer, spacing);
    const double weight = std::pow(layer.noise.lacunarity, -layer.noise.H);
    double tail = 0.0;
    for (int i = int(budget.octaves) - 1; i < layer.noise.octaves; ++i) tail += std::pow(weight, i);
    const gpu::TerrainLayer shape = terrainLayerShape(planet, l);
    double steepest = shape.curveKnots > 0 ? 0.0 : 1.0;
    for (uint32_t k = 0; k + 1 < shape.curveKnots; ++k)
      steepest = std::max(steepest, 3.0 * std::abs(double(shape.knots[k + 1].y) - double(shape.knots[k].y)) /
                                        (double(shape.knots[k + 1].x) - double(shape.knots[k].x)));
    margin += std::abs(layer.amplitudeM) * 2.0 * tail * steepest * layerMaskBound(planet, l);
  }
  margin *= std::abs(planet.heightScale);
  return {std::min(0.0, (lowest - margin) * 1.1), std::max(0.0, (highest + margin) * 1.1)};
}

std::vector<double> terrainHeightsAlong(const PlanetDescription& planet, const glm::dvec3& start, double bearingDeg,
                                        double stepM, size_t count) {
  std::vector<double> heights(count);
  for (size_t i = 0; i < count; ++i)
    heights[i] = terrainHeightM(planet, travelGreatCircle(start, bearingDeg, double(i) * stepM, planet.radiusM));
  return heights;
}

}  // namespace planet
