// The colouring schemes of seed 000 (and the altitude ramp they grow from) as terrain.frag reads
// them: a palette and a few shape numbers, filled by planet::schemeGpuParams
// (engine/reference/color_schemes_cpu.h) from a PlanetColors. The model itself is in
// shaders/common/color_schemes.glsl.
#ifndef PLANET_SHARED_SCHEME_PARAMS_H
#define PLANET_SHARED_SCHEME_PARAMS_H

#include "shared/gpu_types.h"

GPU_NAMESPACE_BEGIN

// The scheme numbers: planet::ColorScheme's values (engine/planet/planet_description.h).
GPU_CONST uint kSchemeEarth = 0u;
GPU_CONST uint kSchemeAltitude = 1u;
GPU_CONST uint kSchemeMoon = 2u;
GPU_CONST uint kSchemeMars = 3u;
GPU_CONST uint kSchemeGiant = 4u;
GPU_CONST uint kSchemeAltitudePerturbed = 5u;
GPU_CONST uint kSchemeNoise = 6u;
GPU_CONST uint kSchemeAltitudeNoise = 7u;
GPU_CONST uint kSchemeTurbulence = 8u;
GPU_CONST uint kSchemeEarthLike = 9u;
GPU_CONST uint kSchemeGradient = 10u;
GPU_CONST uint kSchemeMoonLike = 11u;

GPU_CONST uint kSchemePaletteSize = 12u;  // = planet::kMaxPaletteColors
// Octaves of the per-pixel colour noise, each half the wavelength of the one before (seed 000's
// Table 4: lacunarity 2, amplitude 1/2).
GPU_CONST uint kSchemeNoiseOctaves = 8u;

struct SchemeParams {
  // rgb linear. Altitude and altitude_perturbed: lowland, highland, snow (PlanetColors' named
  // colours); the other schemes of seed 000: PlanetColors::palette.
  vec4 palette[kSchemePaletteSize];
  vec4 shape;  // x: scheme number, y: snow line (m, the top of the altitude ramps), z: perturbation,
               // w: slope angle (rad) of gradient's steep colour (the materials' rock slope)
  vec4 noise;  // x: the colour noise's cells per planet radius (radius / noise_wavelength_m),
               // y: 1 with polar caps, z: sin of the caps' latitude, w: the caps' latitude (rad)
};
GPU_ASSERT_SIZE(SchemeParams, 224)

GPU_NAMESPACE_END

#endif
