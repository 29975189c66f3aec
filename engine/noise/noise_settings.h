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

struct NoiseSettings {
  NoiseType type = NoiseType::Fbm;
  int octaves = 8;
  double lacunarity = 2.0;
  double H = 1.0;
  std::optional<double> offset;  // empty: the type's default (defaultOffset)
  std::optional<double> gain;    // empty: 2 (ridged: crest feedback; damped: slope damping; eroded: gully depth)
  uint32_t seed = 0;
  NoiseHash hash = NoiseHash::Fast;
};

// Offset used when none is given: ridged 1, hybrid 0.7, hetero 0.7, cascade 0.8, craters 0.25
// (rim perturbation), eroded 3 (base octaves: floor(offset), at least 1), others 0.
double defaultOffset(NoiseType type);
inline constexpr double kDefaultGain = 2.0;

const char* noiseTypeName(NoiseType type);
const char* noiseHashName(NoiseHash hash);
// Parse "fbm", "ridged", ... / "fast", "reference"; throw planet::Error naming the bad value.
NoiseType parseNoiseType(std::string_view name);
NoiseHash parseNoiseHash(std::string_view name);

// Throws planet::Error naming the first out-of-range value: octaves outside 1..32,
// lacunarity outside (1, 8], H outside [0, 4], |offset| > 10 (craters: outside [0, 0.5]),
// gain outside [0, 16], NaN/Inf.
void validateNoiseSettings(const NoiseSettings& settings);

// Validates, then fills the parameter block shared with the shaders (count = 0).
gpu::NoiseParams toNoiseParams(const NoiseSettings& settings);

// A one-line summary, e.g. "ridged octaves=8 L=2 H=1 offset=1 gain=2 seed=0 hash=fast".
std::string describe(const NoiseSettings& settings);

}  // namespace planet::noise
