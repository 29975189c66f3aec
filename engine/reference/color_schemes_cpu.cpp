// Compiled with -ffp-contract=off (the project-wide rule, top CMakeLists.txt): the reference must
// round like the GLSL it is compiled from.
#include "reference/color_schemes_cpu.h"

#include <cmath>
#include <numbers>

#include "noise/noise_kernel.h"

namespace planet {
namespace {

using namespace planet::gpu;

// shaders/common/color_schemes.glsl as C++: its functions become members of a noise kernel (for
// simplexNoise), plus the two builtins it needs that the kernel does not define, in float.
struct SchemeKernel : noise::NoiseKernel<float> {
  static float asin(float x) { return std::asin(x); }
  static float acos(float x) { return std::acos(x); }
#include "common/color_schemes.glsl"
};

}  // namespace

gpu::SchemeParams schemeGpuParams(const PlanetColors& colors, double radiusM, double rockSlopeDeg) {
  static_assert(gpu::kSchemePaletteSize == kMaxPaletteColors);
  gpu::SchemeParams p{};
  const bool ramp = colors.scheme == ColorScheme::Altitude || colors.scheme == ColorScheme::AltitudePerturbed;
  for (size_t i = 0; i < kMaxPaletteColors; ++i) p.palette[i] = glm::vec4(colors.palette[i], 0.0f);
  if (ramp) {
    p.palette[0] = glm::vec4(colors.lowland, 0.0f);
    p.palette[1] = glm::vec4(colors.highland, 0.0f);
    p.palette[2] = glm::vec4(colors.snow, 0.0f);
  }
  const double capRad = colors.iceCapLatitudeDeg * std::numbers::pi / 180.0;
  p.shape = glm::vec4(float(int(colors.scheme)), float(colors.snowLineM), float(colors.perturbation),
                      float(rockSlopeDeg * std::numbers::pi / 180.0));
  p.noise = glm::vec4(float(radiusM / colors.noiseWavelengthM), colors.polarCaps ? 1.0f : 0.0f, float(std::sin(capRad)),
                      float(capRad));
  return p;
}

glm::vec3 schemeColorCpu(const gpu::SchemeParams& params, float altitudeM, float slopeCosine, float sinLatitude,
                         float noise, float edgeM) {
  return SchemeKernel().schemeColor(params, altitudeM, slopeCosine, sinLatitude, noise, edgeM);
}

float schemeNoiseCpu(const glm::vec3& direction, float cellsPerRadius, float footprintRadii) {
  return SchemeKernel().schemeNoise(direction, cellsPerRadius, footprintRadii);
}

float schemePolarCapCpu(const gpu::SchemeParams& params, float sinLatitude, float noise, float edgeLatitude) {
  return SchemeKernel().schemePolarCap(params, sinLatitude, noise, edgeLatitude);
}

}  // namespace planet
