// City lights on a planet's night side (issue 14, point 2) as terrain.frag reads them: filled by
// planet::lightsGpuParams (engine/reference/city_lights_cpu.h) from a LightsDescription. The
// model itself is in shaders/common/city_lights.glsl.
#ifndef PLANET_SHARED_LIGHTS_PARAMS_H
#define PLANET_SHARED_LIGHTS_PARAMS_H

#include "shared/gpu_types.h"

GPU_NAMESPACE_BEGIN

// Octaves of the cities' noise, each half the wavelength of the one before: from the largest
// (a metropolitan area) down to blocks of streets 1/128 of its size.
GPU_CONST uint kLightsCityOctaves = 8u;
GPU_CONST uint kLightsCityShapeOctaves = 4u;  // the first ones: where the cities are; the rest: their streets

struct LightsParams {
  vec4 radiance;  // rgb: radiance of a fully lit city core (the renderer's units: the sun's irradiance is 1,
                  // the preset's gain applied), w: coverage (0 .. 1, the lit share of the most habitable land)
  vec4 shape;     // x: cells per radius of the cities' largest octave (radius / city_size_m),
                  // y: cells per radius of the settled regions (radius / kLightsRegionWavelengthM),
                  // z, w: unused
  uint seedMix;   // the preset's seed, its bits spread (lowbias32)
  uint pad0;
  uint pad1;
  uint pad2;
};
GPU_ASSERT_SIZE(LightsParams, 48)

GPU_NAMESPACE_END

#endif
