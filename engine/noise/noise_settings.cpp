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
    {NoiseType::Faults, "faults"},   {NoiseType::Mpd, "mpd"},       {NoiseType::MpdIco, "mpd_ico"},
};

void requireFinite(double value, const char* name) {
  if (!std::isfinite(value)) throw Error(fmt::format("{} must be a finite number, got {}", name, value));
}

}  // namespace

bool isGenerator(NoiseType type) { return type == NoiseType::Faults || isMpd(type); }

bool isMpd(NoiseType type) { return type == NoiseType::Mpd || type == NoiseType::MpdIco; }

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
      "unknown noise type '{}' (expected simplex, fbm, ridged, hybrid, hetero, cascade, craters, damped, eroded, "
      "faults, mpd or mpd_ico)",
      name));
}

NoiseHash parseNoiseHash(std::string_view name) {
  if (name == "fast") return NoiseHash::Fast;
  if (name == "reference") return NoiseHash::Reference;
  throw Error(fmt::format("unknown noise hash '{}' (expected fast or reference)", name));
}

void validateNoiseSettings(const NoiseSettings& s) {
  if (isMpd(s.type)) {
    if (s.octaves < kMinMpdLevels || s.octaves > kMaxMpdLevels)
      throw Error(fmt::format("levels of {} must be in {}..{}, got {}", noiseTypeName(s.type), kMinMpdLevels,
                              kMaxMpdLevels, s.octaves));
  } else if (s.type != NoiseType::Faults && (s.octaves < kMinOctaves || s.octaves > kMaxOctaves)) {
    throw Error(fmt::format("octaves must be in {}..{}, got {}", kMinOctaves, kMaxOctaves, s.octaves));
  }
  if (s.type == NoiseType::Faults) {
    if (s.faults < kMinFaults || s.faults > kMaxFaults)
      throw Error(fmt::format("faults (the number of great circles) must be in {}..{}, got {}", kMinFaults, kMaxFaults,
                              s.faults));
    requireFinite(s.width, "width");
    if (!(s.width >= 0.0 && s.width <= kMaxFaultWidth))
      throw Error(fmt::format("width of faults must be in [0, {}] radians, got {}", kMaxFaultWidth, s.width));
  }
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
  // Faults have no octaves: one "octave" that a renderer's budget may only switch off (0).
  p.octaves = s.type == NoiseType::Faults ? 1u : uint32_t(s.octaves);
  p.hash = uint32_t(s.hash);
  p.seedMix = NoiseKernel<float>{}.noiseSeedMix(s.seed);
  p.lacunarity = float(s.lacunarity);
  p.octaveWeight = float(std::pow(s.lacunarity, -s.H));
  p.offset = float(s.offset.value_or(defaultOffset(s.type)));
  p.gain = float(s.gain.value_or(kDefaultGain));
  p.lastOctaveWeight = 1.0f;
  if (s.type == NoiseType::Faults) {
    p.offset = float(s.width);
    p.elements = uint32_t(s.faults);
  } else if (isMpd(s.type)) {
    // Each level halves the edges: lacunarity 2 whatever was given, so offsets fall by 2^-H.
    p.lacunarity = 2.0f;
    p.octaveWeight = float(std::pow(2.0, -s.H));
    p.elements = s.multifractal ? 1u : 0u;
  }
  return p;
}

std::string describe(const NoiseSettings& s) {
  if (s.type == NoiseType::Faults) return fmt::format("faults count={} width={} seed={}", s.faults, s.width, s.seed);
  if (isMpd(s.type))
    return fmt::format("{} levels={} H={} multifractal={} gain={} seed={}", noiseTypeName(s.type), s.octaves, s.H,
                       s.multifractal, s.gain.value_or(kDefaultGain), s.seed);
  return fmt::format("{} octaves={} L={} H={} offset={} gain={} seed={} hash={}", noiseTypeName(s.type), s.octaves,
                     s.lacunarity, s.H, s.offset.value_or(defaultOffset(s.type)), s.gain.value_or(kDefaultGain), s.seed,
                     noiseHashName(s.hash));
}

}  // namespace planet::noise
