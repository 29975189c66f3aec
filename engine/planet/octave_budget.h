// Octave limiting (DESIGN.md, "Aliasing and cost"): a sample whose neighbours are s metres away
// cannot show an octave whose wavelength is shorter than a few s; evaluating it only aliases
// and costs time. Octave i of a layer has wavelength 1 / (frequency · L^i) (craters: the
// largest crater's diameter, 0.6 of that; mpd, mpd_ico: octave i is subdivision level i + 1, its
// edge length the wavelength; faults have one octave). The budget keeps
// every octave whose wavelength is at least kOctaveWavelengthsPerSpacing · s and fades the
// next one in over one octave, so the count is continuous in s:
//   count(s) = clamp(1 + log_L(1 / (frequency · k · s)), 1, octaves)
//   octaves evaluated = ceil(count), the last one weighted by count − floor(count) (1 if whole).
// Budgets are computed on the CPU in double (per ring, per patch level) and handed to the
// shaders, so the CPU reference and the GPU use the same octave counts bit for bit.
#pragma once

#include <cstdint>

#include "planet/planet_description.h"

namespace planet {

// Wavelengths of the finest full octave per sample spacing (2 is Nyquist; 4 leaves the linear
// interpolation between vertices an error of about (π/4)²/2 ≈ 30 % of the faded octave's
// amplitude at worst, and keeps sliding vertices from shimmering).
inline constexpr double kOctaveWavelengthsPerSpacing = 4.0;

struct OctaveBudget {
  uint32_t octaves = 1;           // 1..layer octaves: how many to evaluate
  float lastOctaveWeight = 1.0f;  // (0, 1]: weight of the last one (NoiseParams::lastOctaveWeight)
};

// The budget of `layer` for samples `spacingM` apart. spacingM <= 0 (or not finite) means
// unlimited: every octave at full weight.
OctaveBudget octaveBudget(const NoiseLayer& layer, double spacingM,
                          double wavelengthsPerSpacing = kOctaveWavelengthsPerSpacing);

}  // namespace planet
