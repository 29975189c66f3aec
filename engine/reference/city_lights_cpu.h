// City lights on the CPU: shaders/common/city_lights.glsl compiled as C++ (the code terrain.frag
// runs), for tests and tools, and the uniform block that carries a planet's lights to the shader.
#pragma once

#include <glm/glm.hpp>

#include "planet/planet_description.h"
#include "shared/lights_params.h"

namespace planet {

// The sun's irradiance in the VIIRS Day/Night Band (500–900 nm) at the top of the atmosphere,
// W m⁻²: the solar spectrum's ~1.9 .. 0.9 W m⁻² nm⁻¹ across the band, integrated (ASTM E-490).
// The renderer's unit of irradiance is the sun's, so a radiance in W m⁻² sr⁻¹ divided by this is
// one in the renderer's units.
inline constexpr double kSunIrradianceDnbWm2 = 570.0;

// The shader's LightsParams for `lights` on a planet of radius radiusM (all zero when disabled):
// the radiance in the renderer's units (gain applied, colour scaled to luminance 1).
gpu::LightsParams lightsGpuParams(const LightsDescription& lights, double radiusM);

// lightsDuskFade: 1 with the sun 6° or more below the horizon .. 0 once it is up.
float lightsDuskFadeCpu(float sinSunElevation);
// lightsHabitability: 0 .. 1, how settled land can be (the arguments as city_lights.glsl's).
float lightsHabitabilityCpu(float altitudeM, float slope, float temperatureC, float moisture, float coast,
                            float valley);
// lightsCover: 0 .. 1, the share of the core radiance a pixel footprintRadii wide shows at
// unit direction `direction` (planet frame) on ground of that habitability.
float lightsCoverCpu(const gpu::LightsParams& params, const glm::vec3& direction, float habitability,
                     float footprintRadii);
// One octave of the lights' noise at a point (its spread is kLightsNoiseSigma).
float lightsNoiseCpu(const gpu::LightsParams& params, const glm::vec3& point, uint32_t octave);

}  // namespace planet
