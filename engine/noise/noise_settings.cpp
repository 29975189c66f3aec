#include "noise/noise_settings.h"

#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "noise/noise_kernel.h"

namespace planet::noise {
namespace {

struct TypeName {
  NoiseType type;
  const char* name;
};
constexpr TypeName kTypeNames[] = {
    {NoiseType::Simplex, "simplex"}, {NoiseType::Fbm, "fbm"},       {NoiseType::Ridged, "ridged"},
    {NoiseType::Hybrid, "hybrid"},   {NoiseType::Hetero, "hetero"}, {NoiseType::Cascade, "cascade"},
    {NoiseType::Craters, "craters"}, {NoiseType::Damped, "damped"}, {NoiseType::Eroded, "eroded"},
};

void requireFinite(double value, const char* name) {
  if (!std::isfinite(value)) throw Error(fmt::format("{} must be a finite number, got {}", name, value));
}

}  // namespace

double defaultOffset(NoiseType type) {
  switch (type) {
    case NoiseType::Ridged: return 1.0;
    case NoiseType::Hybrid:
    case NoiseType::Hetero: return 0.7;
    case NoiseType::Cascade: return 0.8;
    case NoiseType::Craters: return 0.25;
    case NoiseType::Eroded: return 3.0;
    default: return 0.0;
  }
}

const char* noiseTypeName(NoiseType type) {
  for (const TypeName& t : kTypeNames)
    if (t.type == type) return t.name;
  return "unknown";
}

const char* noiseHashName(NoiseHash hash) { return hash == NoiseHash::Reference ? "reference" : "fast"; }

NoiseType parseNoiseType(std::string_view name) {
  for (const TypeName& t : kTypeNames)
    if (name == t.name) return t.type;
  throw Error(fmt::format(
      "unknown noise type '{}' (expected simplex, fbm, ridged, hybrid, hetero, cascade, craters, damped or eroded)",
      name));
}

NoiseHash parseNoiseHash(std::string_view name) {
  if (name == "fast") return NoiseHash::Fast;
  if (name == "reference") return NoiseHash::Reference;
  throw Error(fmt::format("unknown noise hash '{}' (expected fast or reference)", name));
}

void validateNoiseSettings(const NoiseSettings& s) {
  if (s.octaves < kMinOctaves || s.octaves > kMaxOctaves)
    throw Error(fmt::format("octaves must be in {}..{}, got {}", kMinOctaves, kMaxOctaves, s.octaves));
  requireFinite(s.lacunarity, "lacunarity");
  if (!(s.lacunarity > 1.0 && s.lacunarity <= 8.0))
    throw Error(fmt::format("lacunarity must be in (1, 8], got {}", s.lacunarity));
  requireFinite(s.H, "H");
  if (!(s.H >= kMinH && s.H <= kMaxH)) throw Error(fmt::format("H must be in [{}, {}], got {}", kMinH, kMaxH, s.H));
  if (s.offset) {
    requireFinite(*s.offset, "offset");
    if (std::abs(*s.offset) > kMaxOffset)
      throw Error(fmt::format("offset must be in [-{}, {}], got {}", kMaxOffset, kMaxOffset, *s.offset));
    // The crater shader's bound on the cells a crater can reach assumes at most this much.
    if (s.type == NoiseType::Craters && !(*s.offset >= 0.0 && *s.offset <= kMaxCraterPerturbation))
      throw Error(fmt::format("offset of craters (the rim perturbation) must be in [0, {}], got {}",
                              kMaxCraterPerturbation, *s.offset));
  }
  if (s.gain) {
    requireFinite(*s.gain, "gain");
    if (!(*s.gain >= 0.0 && *s.gain <= kMaxGain))
      throw Error(fmt::format("gain must be in [0, {}], got {}", kMaxGain, *s.gain));
  }
}

gpu::NoiseParams toNoiseParams(const NoiseSettings& s) {
  validateNoiseSettings(s);
  gpu::NoiseParams p{};
  p.type = uint32_t(s.type);
  p.octaves = uint32_t(s.octaves);
  p.hash = uint32_t(s.hash);
  p.seedMix = NoiseKernel<float>{}.noiseSeedMix(s.seed);
  p.lacunarity = float(s.lacunarity);
  p.octaveWeight = float(std::pow(s.lacunarity, -s.H));
  p.offset = float(s.offset.value_or(defaultOffset(s.type)));
  p.gain = float(s.gain.value_or(kDefaultGain));
  p.lastOctaveWeight = 1.0f;
  return p;
}

std::string describe(const NoiseSettings& s) {
  return fmt::format("{} octaves={} L={} H={} offset={} gain={} seed={} hash={}", noiseTypeName(s.type), s.octaves,
                     s.lacunarity, s.H, s.offset.value_or(defaultOffset(s.type)), s.gain.value_or(kDefaultGain), s.seed,
                     noiseHashName(s.hash));
}

}  // namespace planet::noise
