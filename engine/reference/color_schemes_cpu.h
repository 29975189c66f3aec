// Seed 000's colouring schemes and seed 004's polar caps on the CPU: shaders/common/color_schemes.glsl
// compiled as C++ (the code terrain.frag runs), for tests and tools, and the uniform block that
// carries a planet's scheme to the shader.
#pragma once

#include <glm/glm.hpp>

#include "planet/planet_description.h"
#include "shared/scheme_params.h"

namespace planet {

// The shader's SchemeParams for `colors` on a planet of radius radiusM whose materials put bare
// rock at rockSlopeDeg (gradient's steep colour).
gpu::SchemeParams schemeGpuParams(const PlanetColors& colors, double radiusM, double rockSlopeDeg);

// schemeColor: the ground's colour above sea level (linear RGB). altitudeM above sea level,
// slopeCosine = normal · vertical, noise in [-1, 1] (schemeNoiseCpu), edgeM: the mare shore's width.
glm::vec3 schemeColorCpu(const gpu::SchemeParams& params, float altitudeM, float slopeCosine, float sinLatitude,
                         float noise, float edgeM);

// schemeNoise: the colour noise at unit direction `direction` (planet frame), its largest octave
// cellsPerRadius cells per radius, for a pixel footprintRadii radii wide.
float schemeNoiseCpu(const glm::vec3& direction, float cellsPerRadius, float footprintRadii);

// schemePolarCap: 0 .. 1, how much of the point is seed 004's polar ice.
float schemePolarCapCpu(const gpu::SchemeParams& params, float sinLatitude, float noise, float edgeLatitude);

}  // namespace planet
