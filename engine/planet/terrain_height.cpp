// Compiled without fused multiply-adds like every C++ build of shared GLSL (the top CMakeLists.txt).
#include "planet/terrain_height.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <optional>

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

namespace {

struct HeightRange {
  double lo = 0.0, hi = 0.0;
};

HeightRange times(HeightRange a, HeightRange b) {
  const double p[] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return {*std::min_element(std::begin(p), std::end(p)), *std::max_element(std::begin(p), std::end(p))};
}

HeightRange curveRange(const std::vector<CurvePoint>& points) {
  HeightRange r{points.front().y, points.front().y};
  for (const CurvePoint& point : points) r = {std::min(r.lo, point.y), std::max(r.hi, point.y)};
  return r;
}

// The largest |N| of one simplex octave: a search found 0.976 (shaders/common/noise.glsl,
// kNoiseScale); 5 % more.
constexpr double kSimplexBound = 1.025;

}  // namespace

std::optional<TerrainHeightBounds> exactTerrainHeightBounds(const PlanetDescription& planet) {
  std::vector<HeightRange> values;
  HeightRange sum{planet.baseHeightM, planet.baseHeightM};
  for (size_t l = 0; l < planet.layers.size(); ++l) {
    const NoiseLayer& layer = planet.layers[l];
    // The noise through its curve: clamped to its end values outside its knots and monotone
    // between them (Fritsch–Carlson, terrain_shape.cpp), so within its values' range whatever
    // the noise; without a curve only the fractals whose sum of octaves is bounded.
    HeightRange noise;
    if (!layer.hypsometry.empty()) {
      noise = curveRange(layer.hypsometry);
    } else if (!layer.transfer.empty()) {
      noise = curveRange(layer.transfer);
    } else if (layer.noise.type == noise::NoiseType::Simplex || layer.noise.type == noise::NoiseType::Fbm) {
      // fBm: Σ N_i w^i over its octaves (the last faded toward the sum before it).
      const double w = double(noise::toNoiseParams(layer.noise).octaveWeight);
      double weights = 0.0;
      const int octaves = layer.noise.type == noise::NoiseType::Simplex ? 1 : layer.noise.octaves;
      for (int i = 0; i < octaves; ++i) weights += std::pow(std::abs(w), i);
      noise = {-kSimplexBound * weights, kSimplexBound * weights};
    } else {
      return std::nullopt;
    }
    HeightRange mask{1.0, 1.0};
    if (!layer.mask.empty())
      mask = layer.maskCurve.empty() ? values[maskIndex(planet, l)] : curveRange(layer.maskCurve);
    values.push_back(times(noise, mask));
    const HeightRange term = times(values.back(), {layer.amplitudeM, layer.amplitudeM});
    sum = {sum.lo + term.lo, sum.hi + term.hi};
  }
  const HeightRange height = times(sum, {planet.heightScale, planet.heightScale});
  // The shaders evaluate in float: a thousandth and a metre for their rounding.
  const double slack = 1e-3 * std::max(std::abs(height.lo), std::abs(height.hi)) + 1.0;
  return TerrainHeightBounds{std::min(0.0, height.lo - slack), std::max(0.0, height.hi + slack)};
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
    double layerMargin = 2.0 * tail * steepest * layerMaskBound(planet, l);
    // A curve keeps the layer within its value bound either side of 0 whatever the octaves add,
    // so no two points differ by more than twice that (its steepest slope is unbounded where two
    // knots nearly meet, as at a hypsometry's cliff).
    if (!layer.hypsometry.empty() || !layer.transfer.empty())
      layerMargin = std::min(layerMargin, 2.0 * layerValueBound(planet, l));
    margin += std::abs(layer.amplitudeM) * layerMargin;
  }
  margin *= std::abs(planet.heightScale);
  TerrainHeightBounds bounds{std::min(0.0, (lowest - margin) * 1.1), std::max(0.0, (highest + margin) * 1.1)};
  // Where every layer's range is known, the sum of the ranges is a bound too, and often far
  // tighter (the margin above scales the finer octaves by a curve's steepest slope anywhere).
  if (const std::optional<TerrainHeightBounds> exact = exactTerrainHeightBounds(planet)) {
    bounds.minM = std::max(bounds.minM, exact->minM);
    bounds.maxM = std::min(bounds.maxM, exact->maxM);
  }
  return bounds;
}

std::vector<double> terrainHeightsAlong(const PlanetDescription& planet, const glm::dvec3& start, double bearingDeg,
                                        double stepM, size_t count) {
  std::vector<double> heights(count);
  for (size_t i = 0; i < count; ++i)
    heights[i] = terrainHeightM(planet, travelGreatCircle(start, bearingDeg, double(i) * stepM, planet.radiusM));
  return heights;
}

}  // namespace planet
