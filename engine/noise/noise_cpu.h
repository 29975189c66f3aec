// CPU reference evaluation of the noise (the shared GLSL source compiled as C++).
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "noise/noise_settings.h"

namespace planet::noise {

// Float reference: bit-identical to the compute shader on lavapipe. `threads` 0 means one
// per hardware thread. `out` must hold one value per point.
void evaluateCpu(const NoiseSettings& settings, std::span<const glm::vec3> points, std::span<float> out,
                 unsigned threads = 1);

float evaluateCpu(const NoiseSettings& settings, const glm::vec3& point);

// Double-precision reference of the same source, for accuracy tests far from the origin.
double evaluateCpuDouble(const NoiseSettings& settings, const glm::dvec3& point);

// The noise with its analytic gradient, (value, d/dx, d/dy, d/dz) per point
// (common/noise_gradient.glsl): the value is bit-identical to evaluateCpu's, the whole vec4 to
// the compute shader's gradient variant on lavapipe. `out` must hold one vec4 per point.
void evaluateCpuGradient(const NoiseSettings& settings, std::span<const glm::vec3> points, std::span<glm::vec4> out,
                         unsigned threads = 1);

glm::vec4 evaluateCpuGradient(const NoiseSettings& settings, const glm::vec3& point);

// Double-precision reference of the value with gradient.
glm::dvec4 evaluateCpuGradientDouble(const NoiseSettings& settings, const glm::dvec3& point);

}  // namespace planet::noise
