#include "bench/noise_validate.h"

#include <bit>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "core/hash.h"
#include "noise/noise_cpu.h"
#include "noise/noise_gpu.h"
#include "vk/context.h"

namespace planet::noise {
namespace {

constexpr NoiseType kAllTypes[] = {NoiseType::Simplex, NoiseType::Fbm,     NoiseType::Ridged,  NoiseType::Hybrid,
                                   NoiseType::Hetero,  NoiseType::Cascade, NoiseType::Craters, NoiseType::Damped,
                                   NoiseType::Eroded,  NoiseType::Faults,  NoiseType::Mpd,     NoiseType::MpdIco};
constexpr NoiseHash kAllHashes[] = {NoiseHash::Fast, NoiseHash::Reference};

// Monotonic integer image of a float's bits: adjacent floats map to adjacent integers.
int64_t orderedBits(float f) {
  int32_t i = std::bit_cast<int32_t>(f);
  return i < 0 ? int64_t(INT32_MIN) - int64_t(i) : int64_t(i);
}

// A key hashed to a float in [0, 1), for portable deterministic points.
float unitFloat(uint64_t key) { return float(splitMix64Mix(key) >> 40) * (1.0f / 16777216.0f); }

}  // namespace

uint64_t ulpDistance(float a, float b) {
  int64_t d = orderedBits(a) - orderedBits(b);
  return uint64_t(d < 0 ? -d : d);
}

ParityStats compareValues(const std::vector<float>& gpu, const std::vector<float>& cpu) {
  ParityStats s;
  s.count = std::min(gpu.size(), cpu.size());
  for (size_t i = 0; i < s.count; ++i) {
    float g = gpu[i], c = cpu[i];
    if (!std::isfinite(g) || !std::isfinite(c)) {
      ++s.nonFinite;
      continue;
    }
    if (std::bit_cast<uint32_t>(g) == std::bit_cast<uint32_t>(c)) ++s.identical;
    s.maxAbsError = std::max(s.maxAbsError, std::fabs(double(g) - double(c)));
    s.maxUlp = std::max(s.maxUlp, ulpDistance(g, c));
    s.maxAbsValue = std::max(s.maxAbsValue, std::fabs(double(c)));
  }
  return s;
}

ParityStats compareGradients(const std::vector<glm::vec4>& gpu, const std::vector<glm::vec4>& cpu) {
  auto flatten = [](const std::vector<glm::vec4>& v) {
    std::vector<float> out;
    out.reserve(4 * v.size());
    for (const glm::vec4& g : v) out.insert(out.end(), {g.x, g.y, g.z, g.w});
    return out;
  };
  return compareValues(flatten(gpu), flatten(cpu));
}

bool ParityPolicy::accepts(const ParityStats& stats) const {
  if (stats.count == 0 || stats.nonFinite != 0) return false;
  if (bitIdentical) return stats.identical == stats.count;
  return stats.maxAbsError <= relativeTolerance * std::max(1.0, stats.maxAbsValue);
}

ParityPolicy parityPolicyFor(const vk::Context& context) {
  ParityPolicy policy;
  if (context.info.driverId == VK_DRIVER_ID_MESA_LLVMPIPE) {
    policy.bitIdentical = true;
    policy.description = "lavapipe: every value bit-identical to the CPU reference";
  } else {
    // Hardware drivers may fuse a*b+c into one rounding and reorder nothing else; over 24
    // octaves that stays far below 1e-4 of the value range.
    policy.bitIdentical = false;
    policy.relativeTolerance = 1e-4;
    policy.description = "hardware driver: max |gpu - cpu| <= 1e-4 * max(1, max |cpu|)";
  }
  return policy;
}

std::vector<ValidationCase> validationCases() {
  std::vector<ValidationCase> cases;
  for (NoiseType type : kAllTypes) {
    for (NoiseHash hash : kAllHashes) {
      NoiseSettings base;
      base.type = type;
      base.hash = hash;
      if (type == NoiseType::Faults) {
        // The hash setting does not apply (one integer hash per fault): the fast one only.
        if (hash != NoiseHash::Fast) continue;
        cases.push_back({"100 sharp faults, seed 0, near origin", base, false});
        NoiseSettings smooth = base;
        smooth.faults = 2000;
        smooth.width = 0.02;
        smooth.seed = 12345;
        cases.push_back({"2000 faults, width 0.02, seed 12345, far (4e4 from origin)", smooth, true});
        continue;
      }
      if (isMpd(type)) {
        if (hash != NoiseHash::Fast) continue;
        cases.push_back({"8 levels, H 1, seed 0, near origin", base, false});
        NoiseSettings deep = base;
        deep.octaves = 24;
        deep.H = 0.9;
        deep.seed = 12345;
        cases.push_back({"24 levels, H 0.9, seed 12345, far (4e4 from origin)", deep, true});
        NoiseSettings multi = base;
        multi.octaves = 12;
        multi.H = 0.7;
        multi.multifractal = true;
        multi.gain = 1.5;
        multi.seed = 42;
        cases.push_back({"12 levels, H 0.7, multifractal gain 1.5, seed 42", multi, false});
        continue;
      }
      cases.push_back({"defaults (8 oct, L 2, H 1, seed 0), near origin", base, false});
      if (type == NoiseType::Simplex) {
        // Octaves, lacunarity, H, offset and gain do not apply: vary only seed and distance.
        NoiseSettings far = base;
        far.seed = 777;
        cases.push_back({"seed 777, far (4e4 from origin)", far, true});
        continue;
      }
      NoiseSettings deep = base;
      deep.octaves = 24;
      deep.H = 0.9;
      deep.seed = 12345;
      cases.push_back({"24 oct, H 0.9, seed 12345, far (4e4 from origin)", deep, true});

      NoiseSettings odd = base;
      odd.octaves = 5;
      odd.lacunarity = 2.7;
      odd.H = 0.5;
      odd.seed = 42;
      odd.offset = defaultOffset(type) + 0.1;
      odd.gain = 1.5;
      cases.push_back({"5 oct, L 2.7, H 0.5, offset +0.1, gain 1.5, seed 42", odd, false});
    }
  }
  return cases;
}

std::vector<glm::vec3> validationPoints(size_t count, bool far, uint32_t seed) {
  const glm::vec3 centre = far ? glm::vec3(31000.0f, -17000.0f, 22000.0f) : glm::vec3(0.0f);
  const float halfSize = far ? 200.0f : 50.0f;
  std::vector<glm::vec3> points(count);
  for (size_t i = 0; i < count; ++i) {
    uint64_t key = (uint64_t(seed) << 40) ^ (uint64_t(i) * 3);
    points[i] = centre + halfSize * (2.0f * glm::vec3(unitFloat(key), unitFloat(key + 1), unitFloat(key + 2)) - 1.0f);
  }
  return points;
}

bool ValidationReport::pass() const {
  if (results.empty()) return false;
  for (const ValidationResult& r : results)
    if (!r.pass) return false;
  return true;
}

nlohmann::json ValidationReport::toJson() const {
  nlohmann::json j;
  j["device"] = device;
  j["driver"] = driver;
  j["policy"] = policy.description;
  j["pass"] = pass();
  j["cases"] = nlohmann::json::array();
  for (const ValidationResult& r : results) {
    j["cases"].push_back({{"type", noiseTypeName(r.testCase.settings.type)},
                          {"hash", noiseHashName(r.testCase.settings.hash)},
                          {"params", r.testCase.label},
                          {"settings", describe(r.testCase.settings)},
                          {"points", r.stats.count},
                          {"max_abs_error", r.stats.maxAbsError},
                          {"max_ulp", r.stats.maxUlp},
                          {"fraction_identical", r.stats.fractionIdentical()},
                          {"non_finite", r.stats.nonFinite},
                          {"gradient_max_abs_error", r.gradientStats.maxAbsError},
                          {"gradient_max_ulp", r.gradientStats.maxUlp},
                          {"gradient_fraction_identical", r.gradientStats.fractionIdentical()},
                          {"gradient_non_finite", r.gradientStats.nonFinite},
                          {"pass", r.pass}});
  }
  return j;
}

std::string ValidationReport::table() const {
  std::string out = fmt::format("device: {} ({})\npolicy: {}\n\n", device, driver, policy.description);
  // The grad columns: the value with gradient variant, its four components together.
  out += fmt::format("{:<8} {:<9} {:<52} {:>8} {:>11} {:>8} {:>10} {:>11} {:>8} {:>10}  {}\n", "type", "hash",
                     "parameters", "points", "max|err|", "max ULP", "identical", "grad|err|", "grad ULP", "grad ident",
                     "result");
  for (const ValidationResult& r : results) {
    out += fmt::format("{:<8} {:<9} {:<52} {:>8} {:>11.3g} {:>8} {:>9.3f}% {:>11.3g} {:>8} {:>9.3f}%  {}\n",
                       noiseTypeName(r.testCase.settings.type), noiseHashName(r.testCase.settings.hash),
                       r.testCase.label, r.stats.count, r.stats.maxAbsError, r.stats.maxUlp,
                       100.0 * r.stats.fractionIdentical(), r.gradientStats.maxAbsError, r.gradientStats.maxUlp,
                       100.0 * r.gradientStats.fractionIdentical(), r.pass ? "ok" : "FAIL");
  }
  size_t passed = 0;
  for (const ValidationResult& r : results) passed += r.pass;
  out += fmt::format("\n{} of {} cases within tolerance: {}\n", passed, results.size(), pass() ? "PASS" : "FAIL");
  return out;
}

ValidationReport runValidation(vk::Context& context, size_t pointsPerCase,
                               const std::function<void(size_t, size_t)>& progress) {
  ValidationReport report;
  report.device = context.info.name;
  report.driver = context.info.driver;
  report.policy = parityPolicyFor(context);

  GpuNoise gpuNoise(context);
  const std::vector<glm::vec3> nearPoints = validationPoints(pointsPerCase, false, 1);
  const std::vector<glm::vec3> farPoints = validationPoints(pointsPerCase, true, 2);
  std::vector<float> gpuValues(pointsPerCase), cpuValues(pointsPerCase);
  std::vector<glm::vec4> gpuGradients(pointsPerCase), cpuGradients(pointsPerCase);
  const std::vector<ValidationCase> cases = validationCases();
  bool farLoaded = false;
  gpuNoise.setPoints(nearPoints);
  for (size_t c = 0; c < cases.size(); ++c) {
    const ValidationCase& testCase = cases[c];
    const std::vector<glm::vec3>& points = testCase.farPoints ? farPoints : nearPoints;
    if (testCase.farPoints != farLoaded) {
      gpuNoise.setPoints(points);
      farLoaded = testCase.farPoints;
    }
    gpuNoise.dispatch(testCase.settings);
    gpuNoise.readValues(gpuValues);
    evaluateCpu(testCase.settings, points, cpuValues, 0);
    gpuNoise.dispatchGradient(testCase.settings);
    gpuNoise.readGradients(gpuGradients);
    evaluateCpuGradient(testCase.settings, points, cpuGradients, 0);
    ValidationResult result{testCase, compareValues(gpuValues, cpuValues), compareGradients(gpuGradients, cpuGradients),
                            false};
    result.pass = report.policy.accepts(result.stats) && report.policy.accepts(result.gradientStats);
    report.results.push_back(result);
    if (progress) progress(c + 1, cases.size());
  }
  return report;
}

}  // namespace planet::noise
