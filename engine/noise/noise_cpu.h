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

}  // namespace planet::noise
