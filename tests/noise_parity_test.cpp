// GPU compute against the CPU reference for every case `planet validate` runs.
#include <gtest/gtest.h>

#include "gpu_fixture.h"
#include "noise/noise_cpu.h"
#include "noise/noise_gpu.h"
#include "bench/noise_validate.h"

namespace planet::test {
namespace {

using NoiseParity = GpuTest;

TEST_F(NoiseParity, GpuMatchesCpuReferenceForEveryTypeHashAndParameterSet) {
  noise::ParityPolicy policy = noise::parityPolicyFor(context());
  noise::GpuNoise gpu(context());
  for (const noise::ValidationCase& c : noise::validationCases()) {
    std::vector<glm::vec3> points = noise::validationPoints(3000, c.farPoints, 9);
    std::vector<float> gpuValues(points.size()), cpuValues(points.size());
    gpu.evaluate(c.settings, points, gpuValues);
    noise::evaluateCpu(c.settings, points, cpuValues, 0);
    noise::ParityStats stats = noise::compareValues(gpuValues, cpuValues);
    EXPECT_TRUE(policy.accepts(stats)) << noise::describe(c.settings) << " (" << c.label << "): max|err| "
                                       << stats.maxAbsError << ", max ULP " << stats.maxUlp << ", identical "
                                       << stats.identical << "/" << stats.count << "; policy: " << policy.description;
  }
}

TEST_F(NoiseParity, ChangingParametersNeedsNoNewPipeline) {
  // The same GpuNoise object evaluates different types, seeds and hashes one after another:
  // parameters are push constants, and the results still match the reference.
  noise::GpuNoise gpu(context());
  std::vector<glm::vec3> points = noise::validationPoints(512, false, 10);
  gpu.setPoints(points);
  for (uint32_t seed : {0u, 1u, 77u}) {
    noise::NoiseSettings s;
    s.type = noise::NoiseType::Hybrid;
    s.hash = seed % 2 ? noise::NoiseHash::Reference : noise::NoiseHash::Fast;
    s.seed = seed;
    gpu.dispatch(s);
    std::vector<float> gpuValues(points.size()), cpuValues(points.size());
    gpu.readValues(gpuValues);
    noise::evaluateCpu(s, points, cpuValues);
    EXPECT_TRUE(noise::parityPolicyFor(context()).accepts(noise::compareValues(gpuValues, cpuValues))) << seed;
  }
}

TEST_F(NoiseParity, PointSetsSplitOverSeveralDispatchesMatchTheReference) {
  // Large point sets are split into dispatches that each start at params.firstIndex; a small
  // cap exercises that path (10,000 points in dispatches of 1,024) without 17 M points.
  noise::GpuNoise gpu(context());
  gpu.setMaxPointsPerDispatch(1024);
  std::vector<glm::vec3> points = noise::validationPoints(10000, false, 11);
  noise::NoiseSettings s;
  s.type = noise::NoiseType::Ridged;
  std::vector<float> gpuValues(points.size()), cpuValues(points.size());
  gpu.evaluate(s, points, gpuValues);
  noise::evaluateCpu(s, points, cpuValues);
  noise::ParityStats stats = noise::compareValues(gpuValues, cpuValues);
  EXPECT_TRUE(noise::parityPolicyFor(context()).accepts(stats))
      << "identical " << stats.identical << "/" << stats.count << ", max|err| " << stats.maxAbsError;
}

}  // namespace
}  // namespace planet::test
