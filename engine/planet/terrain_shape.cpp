#include "planet/terrain_shape.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <tuple>

#include <fmt/format.h>

#include "core/error.h"
#include "core/parallel_for.h"
#include "noise/noise_cpu.h"
#include "noise/noise_settings.h"

namespace planet {
namespace {

// What a layer's quantiles depend on, compared exactly: the noise settings as evaluated, the
// sphere the noise is sampled on and the fractions asked for.
using QuantileKey = std::tuple<int, int, double, double, double, double, uint32_t, int, double, std::vector<double>>;

QuantileKey quantileKey(const NoiseLayer& layer, double radiusM, std::span<const double> fractions) {
  const noise::NoiseSettings& n = layer.noise;
  return {int(n.type),
          n.octaves,
          n.lacunarity,
          n.H,
          n.offset.value_or(noise::defaultOffset(n.type)),
          n.gain.value_or(noise::kDefaultGain),
          n.seed,
          int(n.hash),
          radiusM * layer.frequency,
          std::vector<double>(fractions.begin(), fractions.end())};
}

std::vector<double> computeQuantiles(const NoiseLayer& layer, double radiusM, std::span<const double> fractions) {
  // Points of equal area: the Fibonacci lattice on the sphere, z uniform in (-1, 1).
  const size_t n = kHypsometrySamples;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  const double scale = radiusM * layer.frequency;
  std::vector<double> values(n);
  parallelFor(n, 1024, 0, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const double z = 1.0 - (2.0 * double(i) + 1.0) / double(n);
      const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
      const double phi = golden * double(i);
      values[i] = noise::evaluateCpuDouble(layer.noise, scale * glm::dvec3(r * std::cos(phi), r * std::sin(phi), z));
    }
  });
  std::sort(values.begin(), values.end());
  std::vector<double> quantiles;
  for (double fraction : fractions) {
    const double at = std::clamp(fraction, 0.0, 1.0) * double(n - 1);
    const size_t below = std::min(size_t(at), n - 2);
    const double t = at - double(below);
    quantiles.push_back(values[below] + (values[below + 1] - values[below]) * t);
  }
  return quantiles;
}

}  // namespace

std::vector<double> noiseQuantiles(const NoiseLayer& layer, double radiusM, std::span<const double> fractions) {
  static std::mutex mutex;
  static std::map<QuantileKey, std::vector<double>> cache;
  QuantileKey key = quantileKey(layer, radiusM, fractions);
  {
    std::lock_guard lock(mutex);
    if (auto found = cache.find(key); found != cache.end()) return found->second;
  }
  // Computed outside the lock (it runs on every core); two threads that race compute the same values.
  std::vector<double> quantiles = computeQuantiles(layer, radiusM, fractions);
  std::lock_guard lock(mutex);
  return cache.emplace(std::move(key), std::move(quantiles)).first->second;
}

void curveKnots(std::span<const CurvePoint> points, gpu::vec4* knots) {
  const size_t n = points.size();
  // x as the GPU reads it: floats, at least a millionth of the curve's span apart. Points closer
  // than that (a hypsometry's quantiles where the noise has an atom, as craters have at 0) are
  // moved apart: the curve is then a steep but finite step, not a division by a denormal.
  const double span = std::max(points[n - 1].x - points[0].x, 1e-30);
  std::vector<float> x(n);
  for (size_t k = 0; k < n; ++k) {
    x[k] = float(points[k].x);
    if (k > 0) {
      const float least = float(double(x[k - 1]) + 1e-6 * span);
      x[k] = std::max(x[k], std::max(least, std::nextafter(x[k - 1], INFINITY)));
    }
  }
  std::vector<double> secant(n - 1), slope(n, 0.0);
  for (size_t k = 0; k + 1 < n; ++k) secant[k] = (points[k + 1].y - points[k].y) / (double(x[k + 1]) - double(x[k]));
  for (size_t k = 1; k + 1 < n; ++k)
    slope[k] = secant[k - 1] * secant[k] <= 0.0 ? 0.0 : 0.5 * (secant[k - 1] + secant[k]);
  // Fritsch–Carlson: slopes limited so that each segment stays monotone (no overshoot).
  for (size_t k = 0; k + 1 < n; ++k) {
    if (secant[k] == 0.0) {
      slope[k] = slope[k + 1] = 0.0;
      continue;
    }
    const double a = slope[k] / secant[k], b = slope[k + 1] / secant[k];
    const double length = std::hypot(a, b);
    if (length > 3.0) {
      slope[k] = 3.0 / length * a * secant[k];
      slope[k + 1] = 3.0 / length * b * secant[k];
    }
  }
  for (size_t k = 0; k < n; ++k) knots[k] = gpu::vec4(x[k], float(points[k].y), float(slope[k]), 0.0f);
}

size_t maskIndex(const PlanetDescription& planet, size_t l) {
  const std::string& mask = planet.layers[l].mask;
  for (size_t i = 0; i < l; ++i)
    if (planet.layers[i].name == mask) return i;
  throw Error(fmt::format("layer '{}': mask '{}' names no earlier layer", planet.layers[l].name, mask));
}

gpu::TerrainLayer terrainLayerShape(const PlanetDescription& planet, size_t l) {
  const NoiseLayer& layer = planet.layers[l];
  gpu::TerrainLayer shape{};
  shape.noise = noise::toNoiseParams(layer.noise);
  shape.amplitudeM = float(layer.amplitudeM);
  shape.maskLayer = gpu::kTerrainNoMask;
  if (!layer.hypsometry.empty()) {
    std::vector<double> fractions;
    for (const CurvePoint& point : layer.hypsometry) fractions.push_back(point.x);
    const std::vector<double> quantiles = noiseQuantiles(layer, planet.radiusM, fractions);
    std::vector<CurvePoint> points;
    for (size_t k = 0; k < quantiles.size(); ++k) points.push_back({quantiles[k], layer.hypsometry[k].y});
    curveKnots(points, shape.knots);
    shape.curveKnots = uint32_t(points.size());
  } else if (!layer.transfer.empty()) {
    curveKnots(layer.transfer, shape.knots);
    shape.curveKnots = uint32_t(layer.transfer.size());
  }
  if (!layer.mask.empty()) {
    shape.maskLayer = uint32_t(maskIndex(planet, l));
    if (!layer.maskCurve.empty()) {
      curveKnots(layer.maskCurve, shape.knots + gpu::kTerrainCurveKnots);
      shape.maskKnots = uint32_t(layer.maskCurve.size());
    }
  }
  return shape;
}

namespace {

double largestValue(const std::vector<CurvePoint>& points) {
  double bound = 0.0;
  for (const CurvePoint& point : points) bound = std::max(bound, std::abs(point.y));
  return bound;
}

}  // namespace

double layerMaskBound(const PlanetDescription& planet, size_t l) {
  const NoiseLayer& layer = planet.layers[l];
  if (layer.mask.empty()) return 1.0;
  if (!layer.maskCurve.empty()) return largestValue(layer.maskCurve);
  return layerValueBound(planet, maskIndex(planet, l));
}

double layerValueBound(const PlanetDescription& planet, size_t l) {
  const NoiseLayer& layer = planet.layers[l];
  double bound = 2.0;  // fractals of the presets' parameters stay within about ±2
  if (!layer.hypsometry.empty()) bound = largestValue(layer.hypsometry);
  if (!layer.transfer.empty()) bound = largestValue(layer.transfer);
  return bound * layerMaskBound(planet, l);
}

}  // namespace planet
