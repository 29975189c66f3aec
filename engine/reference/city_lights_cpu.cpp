// Compiled with -ffp-contract=off (the project-wide rule, top CMakeLists.txt): the reference must
// round like the GLSL it is compiled from.
#include "reference/city_lights_cpu.h"

#include <cmath>

#include "noise/noise_kernel.h"

namespace planet {
namespace {

using namespace planet::gpu;

// shaders/common/city_lights.glsl as C++: its functions become members of a noise kernel (for
// simplexNoise), plus the builtin it needs that the kernel does not define, in float.
struct LightsKernel : noise::NoiseKernel<float> {
  static float log(float x) { return std::log(x); }
#include "common/city_lights.glsl"
};

}  // namespace

gpu::LightsParams lightsGpuParams(const LightsDescription& lights, double radiusM) {
  gpu::LightsParams p{};
  if (!lights.enabled) return p;
  // nW cm⁻² sr⁻¹ → W m⁻² sr⁻¹ (1e-9 · 1e4), then in units of the sun's irradiance in the band.
  const double radiance = lights.radianceNw * 1e-5 / kSunIrradianceDnbWm2 * lights.gain;
  const glm::dvec3 c(lights.color);
  const double luminance = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;  // Rec. 709
  p.radiance = glm::vec4(glm::vec3(c * (radiance / luminance)), float(lights.coverage));
  p.shape = glm::vec4(float(radiusM / lights.citySizeM), float(radiusM / double(LightsKernel::kLightsRegionWavelengthM)), 0.0f, 0.0f);
  p.seedMix = LightsKernel().lowbias32(lights.seed ^ 0x85ebca6bu);
  return p;
}

float lightsDuskFadeCpu(float sinSunElevation) { return LightsKernel().lightsDuskFade(sinSunElevation); }

float lightsHabitabilityCpu(float altitudeM, float slope, float temperatureC, float moisture, float coast,
                            float valley) {
  return LightsKernel().lightsHabitability(altitudeM, slope, temperatureC, moisture, coast, valley);
}

float lightsCoverCpu(const gpu::LightsParams& params, const glm::vec3& direction, float habitability,
                     float footprintRadii) {
  return LightsKernel().lightsCover(params, direction, habitability, footprintRadii);
}

float lightsNoiseCpu(const gpu::LightsParams& params, const glm::vec3& point, uint32_t octave) {
  return LightsKernel().simplexNoise(point, glm::uvec3(0u), kNoiseHashFast, params.seedMix + 1u + octave);
}

}  // namespace planet
