// `planet bench noise`: octave evaluations per second of the GPU compute path (both hashes),
// the CPU reference (one thread, all threads) and libnoise, on the same points in one run; the
// GPU and CPU paths also with the analytic gradient (value and gradient per point).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace planet::vk {
class Context;
}

namespace planet::noise {

struct NoiseBenchOptions {
  size_t points = 1u << 20;
  int octaves = 8;           // fbm octaves; mpd, mpd_ico: levels (faults: counted as 1)
  std::string type = "fbm";  // the type the GPU and CPU methods evaluate (libnoise stays fBm-like)
  int faults = 100;          // faults: great circles per point
  double width = 0.0;        // faults: ramp half-width, radians
  int repeats = 7;           // timed runs after one warm-up run (at least 5)
};

struct NoiseBenchResult {
  std::string method;            // gpu_fast, gpu_reference, cpu_1, cpu_all, libnoise_perlin, libnoise_ridged
  std::string output = "value";  // value, or gradient: value and gradient (libnoise: value only)
  int octaves = 0;
  double medianMevalsPerS = 0.0;  // million point-octave evaluations per second
  double minMevalsPerS = 0.0;
  double maxMevalsPerS = 0.0;
};

struct NoiseBenchReport {
  std::string type;  // e.g. "fbm", "faults count=1000 width=0 seed=0"
  std::string device;
  std::string driver;
  size_t points = 0;
  unsigned cpuThreads = 0;
  std::vector<NoiseBenchResult> results;
  double rate(const std::string& method, const std::string& output = "value") const;  // median, 0 if absent
  nlohmann::json toJson() const;
  std::string table() const;
};

NoiseBenchReport runNoiseBench(vk::Context& context, const NoiseBenchOptions& options,
                               const std::function<void(const std::string&)>& progress = {});

}  // namespace planet::noise
