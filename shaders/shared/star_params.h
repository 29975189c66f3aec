// The starfield (engine/render/star_pass.h): the star record that stars.comp writes and
// stars.vert reads, the push constants of both, and the constants of the star model in
// shaders/common/stars.glsl.
#ifndef PLANET_SHARED_STAR_PARAMS_H
#define PLANET_SHARED_STAR_PARAMS_H

#include "shared/gpu_types.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kStarBindingCatalogue = 0u;  // StarRecord[count] (set 0, compute writes, vertex reads)
GPU_CONST uint kStarWorkgroupSize = 64u;
GPU_CONST uint kStarMaxCount = 1048576u;  // 2^20 stars, 32 MiB: a real sky to magnitude ~11.7

// Sky tiles: kStarTileBands bands of equal height in z (equal area, by the hat-box theorem)
// times kStarTileSectors azimuth sectors. The catalogue is ordered by tile, each holding an
// equal share of the stars, so a draw can skip the tiles outside the view (lavapipe shades
// vertices at ~0.5 µs each, on one thread).
GPU_CONST uint kStarTileBands = 16u;
GPU_CONST uint kStarTileSectors = 32u;  // a multiple of 4: whole sectors per quadrant
GPU_CONST uint kStarTileCount = kStarTileBands * kStarTileSectors;

// The star model (shaders/common/stars.glsl has the reasons).
GPU_CONST float kStarBrightestMagnitude = -1.5f;  // brighter magnitudes drawn are clamped to this (Sirius: −1.46)
GPU_CONST float kStarMinTemperatureK = 3000.0f;
GPU_CONST float kStarMaxTemperatureK = 25000.0f;  // upper end of Kang et al.'s Planckian-locus fit
// A star's image is a Gaussian of standard deviation kStarSpriteSigma · diameter (so ±2σ spans
// the diameter), and each pixel gets the part of it that falls on its square. The point sprite
// is the diameter plus kStarSpriteMargin pixels: its pixels then cover the Gaussian to at least
// ±(diameter/2 + 0.5) px (2.67σ), so a star's pixels add up to its flux (≥ 98.5 %) wherever it
// falls between pixel centres: no twinkling as the view turns.
GPU_CONST float kStarSpriteSigma = 0.25f;
GPU_CONST float kStarSpriteMargin = 2.0f;

// Whether the eye sees a star against the sky in front of it (common/star_visibility.glsl).
GPU_CONST float kStarSunLux = 1.28e5f;  // the sun's illuminance above the air: HDR radiance 1 is 1.28e5 cd/m²
GPU_CONST float kStarMagnitudeZeroLux = 2.54e-6f;  // the illuminance of a magnitude-0 star
GPU_CONST float kStarNanolambertCdM2 = 3.183e-6f;  // 1 nL in cd/m² (a lambert is 10⁴/π cd/m²)
GPU_CONST float kStarLuxPerFootCandle = 10.764f;
GPU_CONST float kStarFadeStops = 0.66f;  // a star fades in over ±0.66 stops (±0.5 magnitude) about the threshold

// One star. 32 bytes, so the vertex shader reads it with two aligned vec4 loads.
struct StarRecord {
  vec4 direction;  // xyz: unit direction (planet frame), w: apparent visual magnitude
  vec4 color;      // rgb: linear sRGB × relative flux 10^(−0.4 m) (luminance 1 at m = 0), w: temperature K
};
GPU_ASSERT_SIZE(StarRecord, 32)

// Push constants of stars.comp.
struct StarGeneratePush {
  uint count;               // stars to generate (indices 0..count−1)
  uint seed;                // StarSettings::seed, unmixed
  float faintestMagnitude;  // the law's faint end: N(< m) = count · 10^(0.5 (m − faintest))
  uint pad0;
};
GPU_ASSERT_SIZE(StarGeneratePush, 16)

// Push constants of stars.vert.
struct StarDrawPush {
  mat4 directionToClip;  // planet-frame direction (w = 0) → clip space
  float brightness;      // HDR flux (summed over the sprite, luminance) of a magnitude-0 star
  float pixelScale;      // sprite diameters are multiplied by this (≥ 1, from the viewport height)
  float maxPointSize;    // device limit; below 1 + kStarSpriteMargin every star is one plain pixel
  float pad0;
};
GPU_ASSERT_SIZE(StarDrawPush, 80)

GPU_NAMESPACE_END

#endif
