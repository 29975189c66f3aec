// `planet validate`: the compute shader against the CPU reference for every noise type, both
// hashes and several parameter sets, the value and the value with gradient, with per-case error
// statistics and a device policy.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "noise/noise_settings.h"

namespace planet::vk {
class Context;
}

namespace planet::noise {

struct ParityStats {
  size_t count = 0;
  double maxAbsError = 0.0;
  uint64_t maxUlp = 0;
  size_t identical = 0;      // bit-identical values
  size_t nonFinite = 0;      // GPU or CPU values that are NaN or infinite
  double maxAbsValue = 0.0;  // of the CPU values, for relative tolerances
  double fractionIdentical() const { return count ? double(identical) / double(count) : 0.0; }
};

// Distance in units in the last place between two floats (0 for equal bits; +0/-0 are 1 apart).
uint64_t ulpDistance(float a, float b);
ParityStats compareValues(const std::vector<float>& gpu, const std::vector<float>& cpu);
// Every component of values with gradients (value, d/dx, d/dy, d/dz) compared as above.
ParityStats compareGradients(const std::vector<glm::vec4>& gpu, const std::vector<glm::vec4>& cpu);

// What a device must achieve. Lavapipe runs the same LLVM code paths as the reference, so it
// must agree bit for bit; other drivers may contract multiply-adds, so they get a tolerance.
struct ParityPolicy {
  bool bitIdentical = true;
  double relativeTolerance = 0.0;  // |gpu - cpu| <= tol * max(1, |cpu|max) when !bitIdentical
  std::string description;
  bool accepts(const ParityStats& stats) const;
};
ParityPolicy parityPolicyFor(const vk::Context& context);

struct ValidationCase {
  std::string label;  // e.g. "24 octaves, far (3e4 from origin)"
  NoiseSettings settings;
  bool farPoints = false;
};

// Every type x hash x parameter set that `planet validate` runs.
std::vector<ValidationCase> validationCases();

// Deterministic test points: within ±50 of the origin, or within ±200 of a point 4e4 away.
std::vector<glm::vec3> validationPoints(size_t count, bool far, uint32_t seed);

struct ValidationResult {
  ValidationCase testCase;
  ParityStats stats;          // the value (noise_eval's value variant)
  ParityStats gradientStats;  // every component of the gradient variant: value, d/dx, d/dy, d/dz
  bool pass = false;          // both within the policy
};

struct ValidationReport {
  std::string device;
  std::string driver;
  ParityPolicy policy;
  std::vector<ValidationResult> results;
  bool pass() const;
  nlohmann::json toJson() const;
  std::string table() const;  // the human-readable table printed by `planet validate`
};

// Runs every case on `pointsPerCase` points. `progress(done, total)` is called after each case.
ValidationReport runValidation(vk::Context& context, size_t pointsPerCase,
                               const std::function<void(size_t, size_t)>& progress = {});

}  // namespace planet::noise
