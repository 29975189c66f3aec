#include "planet/octave_budget.h"

#include <algorithm>
#include <cmath>

#include "noise/noise_kernel.h"

namespace planet {
namespace {

constexpr double kOctahedronEdgeArc = 1.5707963267948966;   // 90 degrees
constexpr double kIcosahedronEdgeArc = 1.1071487177940904;  // atan(2), 63.4 degrees

}  // namespace

OctaveBudget octaveBudget(const NoiseLayer& layer, double spacingM, double wavelengthsPerSpacing) {
  const uint32_t maxOctaves = uint32_t(layer.noise.octaves);
  if (!(spacingM > 0.0) || !std::isfinite(spacingM)) return {maxOctaves, 1.0f};
  // The shaders scale octaves by L rounded to float; use the same L here (mpd: 2, each level
  // halves the edges).
  const bool mpd = noise::isMpd(layer.noise.type);
  const double lacunarity = mpd ? 2.0 : double(float(layer.noise.lacunarity));
  // A crater octave's features are its craters, at most 2 kCraterRadiusMax cells across: its
  // wavelength for this purpose is that diameter, not the cell (else sliding vertices swim).
  // damped and eroded keep fBm's rule: a damped octave is a simplex octave scaled down, and an
  // eroded gully octave's stripes are at least one of its lattice units apart (noise_erosion.glsl).
  // An MPD "octave" i is level i + 1, whose edges are a base edge's arc (in units of the unit
  // sphere the layer samples: frequency = 1 / radius) over 2^(i + 1).
  double feature =
      layer.noise.type == noise::NoiseType::Craters ? 2.0 * double(noise::NoiseKernel<float>::kCraterRadiusMax) : 1.0;
  if (layer.noise.type == noise::NoiseType::Mpd) feature = 0.5 * kOctahedronEdgeArc;
  if (layer.noise.type == noise::NoiseType::MpdIco) feature = 0.5 * kIcosahedronEdgeArc;
  const double count =
      1.0 + std::log(feature / (layer.frequency * wavelengthsPerSpacing * spacingM)) / std::log(lacunarity);
  if (!(count < double(maxOctaves))) return {maxOctaves, 1.0f};
  if (!(count > 1.0)) return {1, 1.0f};
  const double whole = std::floor(count);
  const double fraction = count - whole;
  if (fraction <= 0.0) return {uint32_t(whole), 1.0f};
  // A weight that rounds to 0 in float still counts as a (nearly free) extra octave: harmless.
  return {uint32_t(whole) + 1, std::max(float(fraction), 1e-7f)};
}

}  // namespace planet
