#include "bench/noise_bench.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include <fmt/format.h>
#include <libnoise/noise.h>

#include "core/error.h"
#include "core/statistics.h"
#include "noise/noise_cpu.h"
#include "noise/noise_gpu.h"
#include "bench/noise_validate.h"
#include "vk/context.h"

namespace planet::noise {
namespace {

double secondsOf(const std::function<void()>& work) {
  auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// One warm-up, then `repeats` timed runs; `run` returns the seconds one run took.
NoiseBenchResult measure(const std::string& method, const NoiseBenchOptions& options,
                         const std::function<double()>& run) {
  run();
  std::vector<double> rates;
  const double evals = double(options.points) * options.octaves;
  for (int i = 0; i < options.repeats; ++i) rates.push_back(evals / run() / 1e6);
  const auto [low, high] = std::minmax_element(rates.begin(), rates.end());
  return {method, "value", options.octaves, percentile(rates, 50.0), *low, *high};
}

// libnoise modules evaluated point by point on one thread, as a library user would.
template <typename Module>
double runLibnoise(Module& module, const std::vector<glm::vec3>& points, std::vector<float>& out) {
  return secondsOf([&] {
    for (size_t i = 0; i < points.size(); ++i) out[i] = float(module.GetValue(points[i].x, points[i].y, points[i].z));
  });
}

}  // namespace

double NoiseBenchReport::rate(const std::string& method, const std::string& output) const {
  for (const NoiseBenchResult& r : results)
    if (r.method == method && r.output == output) return r.medianMevalsPerS;
  return 0.0;
}

nlohmann::json NoiseBenchReport::toJson() const {
  nlohmann::json j;
  j["type"] = type;
  j["device"] = device;
  j["driver"] = driver;
  j["points"] = points;
  j["cpu_threads"] = cpuThreads;
  j["results"] = nlohmann::json::array();
  for (const NoiseBenchResult& r : results)
    j["results"].push_back({{"method", r.method},
                            {"output", r.output},
                            {"octaves", r.octaves},
                            {"mevals_per_s", r.medianMevalsPerS},
                            {"min", r.minMevalsPerS},
                            {"max", r.maxMevalsPerS}});
  return j;
}

std::string NoiseBenchReport::table() const {
  std::string out = fmt::format("device: {} ({})\ntype: {}\npoints: {}, CPU threads: {}\n\n", device, driver, type,
                                points, cpuThreads);
  out +=
      fmt::format("{:<16} {:<9} {:>7} {:>14} {:>22}\n", "method", "output", "octaves", "median M/s", "min - max M/s");
  for (const NoiseBenchResult& r : results)
    out += fmt::format("{:<16} {:<9} {:>7} {:>14.1f} {:>10.1f} - {:<10.1f}\n", r.method, r.output, r.octaves,
                       r.medianMevalsPerS, r.minMevalsPerS, r.maxMevalsPerS);
  double fast = rate("gpu_fast");
  if (fast > 0 && rate("cpu_all") > 0 && rate("libnoise_perlin") > 0)
    out += fmt::format("\ngpu_fast: {:.1f}x cpu_all, {:.1f}x libnoise_perlin, {:.1f}x gpu_reference\n",
                       fast / rate("cpu_all"), fast / rate("libnoise_perlin"), fast / rate("gpu_reference"));
  // What the gradient costs: the value's rate over the value-and-gradient rate, per method.
  std::string costs;
  for (const char* method : {"gpu_fast", "gpu_reference", "cpu_1", "cpu_all"})
    if (rate(method) > 0 && rate(method, "gradient") > 0)
      costs += fmt::format("{}{} {:.2f}x", costs.empty() ? "" : ", ", method, rate(method) / rate(method, "gradient"));
  if (!costs.empty()) out += fmt::format("gradient costs (value rate / value-and-gradient rate): {}\n", costs);
  return out;
}

NoiseBenchReport runNoiseBench(vk::Context& context, const NoiseBenchOptions& options,
                               const std::function<void(const std::string&)>& progress) {
  if (options.repeats < 5) throw Error(fmt::format("repeats must be at least 5, got {}", options.repeats));
  NoiseBenchReport report;
  report.device = context.info.name;
  report.driver = context.info.driver;
  report.points = options.points;
  report.cpuThreads = std::max(1u, std::thread::hardware_concurrency());
  auto note = [&](const std::string& method) {
    if (progress) progress(method);
  };

  // The validation point set near the origin: the same points for every method.
  const std::vector<glm::vec3> points = validationPoints(options.points, false, 1);
  std::vector<float> values(points.size());
  std::vector<glm::vec4> gradients;  // sized when the CPU's gradient runs come
  NoiseSettings settings;
  settings.type = parseNoiseType(options.type);
  settings.octaves = options.octaves;
  settings.faults = options.faults;
  settings.width = options.width;
  validateNoiseSettings(settings);
  report.type = settings.type == NoiseType::Fbm ? std::string("fbm") : describe(settings);
  // A fault sum has no octaves: its rate counts points (one "octave" each).
  NoiseBenchOptions ours = options;
  if (settings.type == NoiseType::Faults) ours.octaves = 1;

  {
    GpuNoise gpu(context);
    gpu.setPoints(points);
    for (bool gradient : {false, true}) {
      for (NoiseHash hash : {NoiseHash::Fast, NoiseHash::Reference}) {
        std::string method = hash == NoiseHash::Fast ? "gpu_fast" : "gpu_reference";
        note(gradient ? method + " gradient" : method);
        settings.hash = hash;
        NoiseBenchResult result = measure(
            method, ours, [&] { return (gradient ? gpu.dispatchGradient(settings) : gpu.dispatch(settings)) * 1e-3; });
        result.output = gradient ? "gradient" : "value";
        report.results.push_back(result);
      }
    }
  }
  settings.hash = NoiseHash::Fast;
  for (unsigned threads : {1u, 0u}) {
    const std::string method = threads == 1 ? "cpu_1" : "cpu_all";
    note(method);
    report.results.push_back(
        measure(method, ours, [&] { return secondsOf([&] { evaluateCpu(settings, points, values, threads); }); }));
  }
  gradients.resize(points.size());
  for (unsigned threads : {1u, 0u}) {
    const std::string method = threads == 1 ? "cpu_1" : "cpu_all";
    note(method + " gradient");
    NoiseBenchResult result = measure(
        method, ours, [&] { return secondsOf([&] { evaluateCpuGradient(settings, points, gradients, threads); }); });
    result.output = "gradient";
    report.results.push_back(result);
  }

  // libnoise's defaults are fBm-like (lacunarity 2, persistence 0.5); only the octave count
  // is set, to match ours. Its octave limit is 30.
  int libnoiseOctaves = std::min(options.octaves, 30);
  NoiseBenchOptions libOptions = options;
  libOptions.octaves = libnoiseOctaves;
  note("libnoise_perlin");
  ::noise::module::Perlin perlin;
  perlin.SetOctaveCount(libnoiseOctaves);
  report.results.push_back(measure("libnoise_perlin", libOptions, [&] { return runLibnoise(perlin, points, values); }));
  note("libnoise_ridged");
  ::noise::module::RidgedMulti ridged;
  ridged.SetOctaveCount(libnoiseOctaves);
  report.results.push_back(measure("libnoise_ridged", libOptions, [&] { return runLibnoise(ridged, points, values); }));
  return report;
}

}  // namespace planet::noise
