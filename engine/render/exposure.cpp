#include "render/exposure.h"

#include <cmath>

#include "common/definitions.h"

namespace planet {
namespace {

using namespace planet::gpu;

// shaders/common/exposure.glsl compiled as C++ in float, as the GPU runs it.
struct ExposureKernel {
  PLANET_GLSL_KERNEL(float)
  static real log2(real x) { return std::log2(x); }
  static real exp2(real x) { return std::exp2(x); }
#include "common/exposure.glsl"
};

}  // namespace

ExposureHistogram exposureHistogram(std::span<const glm::vec4> hdr) {
  ExposureKernel kernel;
  ExposureHistogram histogram{};
  for (const glm::vec4& c : hdr) ++histogram[kernel.exposureBin(kernel.exposureLuminance(c.r, c.g, c.b))];
  return histogram;
}

ExposureReport exposureFromHistogram(const ExposureHistogram& histogram) {
  ExposureKernel kernel;
  // The same float arithmetic, in the same order, as shaders/luminance_exposure.comp.
  float total = 0.0f;
  for (uint32_t bin = 1; bin < kExposureBins; ++bin) total += float(histogram[bin]);  // bin 0: black
  const float low = total * kExposureLowFraction;
  const float high = total * kExposureHighFraction;
  float below = 0.0f, weight = 0.0f, weightedLog2 = 0.0f;
  for (uint32_t bin = 1; bin < kExposureBins; ++bin)
    kernel.exposureAccumulate(bin, float(histogram[bin]), low, high, below, weight, weightedLog2);
  ExposureReport report;
  report.log2Luminance = weight > 0.0f ? weightedLog2 / weight : kExposureMinLog2;
  report.target = report.exposure = kernel.exposureForLuminance(float(report.log2Luminance));
  report.pixels = weight;
  return report;
}

double adaptExposure(double current, double target, double stepS) {
  ExposureKernel kernel;
  return kernel.adaptExposure(float(current), float(target), float(stepS));
}

}  // namespace planet
