// Compiled with -ffp-contract=off (the project-wide rule, top CMakeLists.txt): the reference must round exactly
// like the GLSL it is compiled from.
#include "noise/noise_cpu.h"

#include <algorithm>
#include <string>
#include <thread>
#include <vector>

#include "core/error.h"
#include "noise/noise_kernel.h"
#include "noise/permutation.h"

namespace planet::noise {
namespace {

template <typename Real>
NoiseKernel<Real> makeKernel(const NoiseSettings& settings) {
  NoiseKernel<Real> kernel;
  kernel.permutation = permutationTable(settings.seed).data();
  return kernel;
}

// Evaluates `point(kernel, params, p)` at every point into out, on `threads` threads (0: one per
// hardware thread; at least 1,024 points a thread).
template <typename Out, typename PointFn>
void evaluatePoints(const char* what, const NoiseSettings& settings, std::span<const glm::vec3> points,
                    std::span<Out> out, unsigned threads, PointFn point) {
  if (out.size() < points.size()) throw Error(std::string(what) + ": output span smaller than the point count");
  const gpu::NoiseParams params = toNoiseParams(settings);
  const NoiseKernel<float> kernel = makeKernel<float>(settings);
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = unsigned(std::min<size_t>(threads, std::max<size_t>(1, points.size() / 1024)));

  auto run = [&](size_t begin, size_t end) {
    NoiseKernel<float> local = kernel;
    for (size_t i = begin; i < end; ++i) out[i] = point(local, params, points[i]);
  };
  if (threads <= 1) {
    run(0, points.size());
    return;
  }
  std::vector<std::thread> workers;
  size_t chunk = (points.size() + threads - 1) / threads;
  for (unsigned t = 0; t < threads; ++t) {
    size_t begin = std::min(points.size(), t * chunk);
    size_t end = std::min(points.size(), begin + chunk);
    workers.emplace_back(run, begin, end);
  }
  for (std::thread& w : workers) w.join();
}

}  // namespace

void evaluateCpu(const NoiseSettings& settings, std::span<const glm::vec3> points, std::span<float> out,
                 unsigned threads) {
  evaluatePoints("evaluateCpu", settings, points, out, threads,
                 [](NoiseKernel<float>& k, const gpu::NoiseParams& params, const glm::vec3& p) {
                   return k.evaluateNoise(params, p);
                 });
}

float evaluateCpu(const NoiseSettings& settings, const glm::vec3& point) {
  NoiseKernel<float> kernel = makeKernel<float>(settings);
  return kernel.evaluateNoise(toNoiseParams(settings), point);
}

double evaluateCpuDouble(const NoiseSettings& settings, const glm::dvec3& point) {
  NoiseKernel<double> kernel = makeKernel<double>(settings);
  return kernel.evaluateNoise(toNoiseParams(settings), point);
}

void evaluateCpuGradient(const NoiseSettings& settings, std::span<const glm::vec3> points, std::span<glm::vec4> out,
                         unsigned threads) {
  evaluatePoints("evaluateCpuGradient", settings, points, out, threads,
                 [](NoiseKernel<float>& k, const gpu::NoiseParams& params, const glm::vec3& p) {
                   return k.evaluateNoiseGradient(params, p);
                 });
}

glm::vec4 evaluateCpuGradient(const NoiseSettings& settings, const glm::vec3& point) {
  NoiseKernel<float> kernel = makeKernel<float>(settings);
  return kernel.evaluateNoiseGradient(toNoiseParams(settings), point);
}

glm::dvec4 evaluateCpuGradientDouble(const NoiseSettings& settings, const glm::dvec3& point) {
  NoiseKernel<double> kernel = makeKernel<double>(settings);
  return kernel.evaluateNoiseGradient(toNoiseParams(settings), point);
}

}  // namespace planet::noise
