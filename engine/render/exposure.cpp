#include "render/exposure.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

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

float exposureLightsPhysical(double lightsGain) { return lightsGain > 0.0 ? float(1.0 / lightsGain) : 1.0f; }

ExposureHistogram exposureHistogram(std::span<const glm::vec4> hdr, uint32_t width, uint32_t height,
                                    double lightsGain) {
  if (hdr.size() != size_t(width) * height)
    throw Error(fmt::format("an HDR frame of {}x{} has {} pixels, not {}", width, height, size_t(width) * height,
                            hdr.size()));
  const float lightsPhysical = exposureLightsPhysical(lightsGain);
  ExposureKernel kernel;
  ExposureHistogram histogram{};
  for (uint32_t by = 0; by < height; by += 2)
    for (uint32_t bx = 0; bx < width; bx += 2) {
      // As shaders/luminance_histogram.comp adds them: row by row within the block.
      float sum = 0.0f, count = 0.0f;
      for (uint32_t y = by; y < std::min(by + 2, height); ++y)
        for (uint32_t x = bx; x < std::min(bx + 2, width); ++x) {
          const glm::vec4& c = hdr[size_t(y) * width + x];
          sum += kernel.exposureSceneLuminance(c.r, c.g, c.b, c.a, lightsPhysical);
          count += 1.0f;
        }
      ++histogram[kernel.exposureBin(sum / count)];
    }
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

double exposureDisplayScale(double exposure, float alpha) {
  ExposureKernel kernel;
  return kernel.exposureDisplayScale(float(exposure), alpha);
}

double adaptExposure(double current, double target, double stepS) {
  ExposureKernel kernel;
  return kernel.adaptExposure(float(current), float(target), float(stepS));
}

}  // namespace planet
