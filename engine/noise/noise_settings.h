// User-facing description of one noise function (type, octaves, lacunarity, H, offset, gain,
// seed, hash), its validation, and its conversion to the GPU parameter block.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "shared/noise_params.h"

namespace planet::noise {

enum class NoiseType : uint32_t {
  Simplex = gpu::kNoiseSimplex,
  Fbm = gpu::kNoiseFbm,
  Ridged = gpu::kNoiseRidged,
  Hybrid = gpu::kNoiseHybrid,
  Hetero = gpu::kNoiseHetero,
  Cascade = gpu::kNoiseCascade,
  Craters = gpu::kNoiseCraters,
  Damped = gpu::kNoiseDamped,
  Eroded = gpu::kNoiseEroded,
  Faults = gpu::kNoiseFaults,
  Mpd = gpu::kNoiseMpd,
  MpdIco = gpu::kNoiseMpdIco,
};

enum class NoiseHash : uint32_t {
  Fast = gpu::kNoiseHashFast,
  Reference = gpu::kNoiseHashReference,
};

inline constexpr int kMinOctaves = 1;
inline constexpr int kMaxOctaves = int(gpu::kNoiseMaxOctaves);
// Bounds that keep every fractal finite in float over 32 octaves (a negative H would let the
// octave weights, and hetero's running product, overflow).
inline constexpr double kMinH = 0.0;
inline constexpr double kMaxH = 4.0;
inline constexpr double kMaxOffset = 10.0;
inline constexpr double kMaxGain = 16.0;
// Craters: offset is the rim perturbation, a fraction of the radius (noise.glsl, cratersNoise).
inline constexpr double kMaxCraterPerturbation = 0.5;
// Faults (noise_generators.glsl): how many great circles, and the transition's half-width in
// radians (a step wider than a quarter turn would no longer be a fault).
inline constexpr int kMinFaults = 1;
inline constexpr int kMaxFaults = 10000;
inline constexpr double kMaxFaultWidth = 1.5;
// Midpoint displacement: subdivision levels (octaves holds them). Level 24 cells are 6e-8 of the
// radius, the float resolution of a direction.
inline constexpr int kMinMpdLevels = 1;
inline constexpr int kMaxMpdLevels = 24;

struct NoiseSettings {
  NoiseType type = NoiseType::Fbm;
  int octaves = 8;  // mpd, mpd_ico: subdivision levels (1..24); faults: 1 (ignored otherwise)
  double lacunarity = 2.0;
  double H = 1.0;
  std::optional<double> offset;  // empty: the type's default (defaultOffset)
  std::optional<double> gain;    // empty: 2 (ridged: crest feedback; damped: slope damping; eroded: gully depth)
  uint32_t seed = 0;
  NoiseHash hash = NoiseHash::Fast;
  int faults = 100;           // faults: number of great circles, 1..10,000
  double width = 0.0;         // faults: transition half-width in radians, [0, 1.5] (0: sharp steps)
  bool multifractal = false;  // mpd, mpd_ico: offsets scaled by gain · mean(parents) (seed 000 Table 3)
};

// True for the generators of issue 22 (faults, mpd, mpd_ico): functions of the direction only,
// sampled on the unit sphere (a layer's frequency is 1 / radius), and not fractals of octaves.
bool isGenerator(NoiseType type);
bool isMpd(NoiseType type);

// Offset used when none is given: ridged 1, hybrid 0.7, hetero 0.7, cascade 0.8, craters 0.25
// (rim perturbation), eroded 3 (base octaves: floor(offset), at least 1), others 0.
double defaultOffset(NoiseType type);
inline constexpr double kDefaultGain = 2.0;

const char* noiseTypeName(NoiseType type);
const char* noiseHashName(NoiseHash hash);
// Parse "fbm", "ridged", ... / "fast", "reference"; throw planet::Error naming the bad value.
NoiseType parseNoiseType(std::string_view name);
NoiseHash parseNoiseHash(std::string_view name);

// Throws planet::Error naming the first out-of-range value: octaves outside 1..32 (mpd: levels
// outside 1..24), faults outside 1..10,000, width outside [0, 1.5],
// lacunarity outside (1, 8], H outside [0, 4], |offset| > 10 (craters: outside [0, 0.5]),
// gain outside [0, 16], NaN/Inf.
void validateNoiseSettings(const NoiseSettings& settings);

// Validates, then fills the parameter block shared with the shaders (count = 0).
gpu::NoiseParams toNoiseParams(const NoiseSettings& settings);

// A one-line summary, e.g. "ridged octaves=8 L=2 H=1 offset=1 gain=2 seed=0 hash=fast".
std::string describe(const NoiseSettings& settings);

}  // namespace planet::noise
