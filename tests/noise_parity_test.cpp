// GPU compute against the CPU reference for every case `planet validate` runs.
#include <gtest/gtest.h>

#include "gpu_fixture.h"
#include "noise/noise_cpu.h"
#include "noise/noise_gpu.h"
#include "noise/validate.h"

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

}  // namespace
}  // namespace planet::test
