// The star catalogue (issue 4, point 4): settings, their validation, and the CPU reference of
// what stars.comp generates. The model (sphere point picking, the magnitude law, temperature and
// colour) is in shaders/common/stars.glsl, compiled here as C++ (reference/star_kernel.h).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "shared/star_params.h"

namespace planet {

// Stars a real sky has brighter than `faintestMagnitude`, by the law of stars.glsl:
// 9,000 · 10^(0.5 (faintest − 6.5)), rounded (16,005 for magnitude 7).
uint32_t realisticStarCount(float faintestMagnitude);

struct StarSettings {
  uint32_t seed = 1;  // same seed, same catalogue (on every device and on the CPU)
  // Stars in the catalogue, all of them between magnitude −1.5 (the clamp) and
  // faintestMagnitude. realisticStarCount(7) ≈ 16,000 gives the real sky's density.
  uint32_t count = 16000;
  float faintestMagnitude = 7.0f;  // the law's faint end; 6.5 is the naked-eye limit
  // HDR value of a magnitude-0 star's total flux: its sprite's pixels sum to this (luminance,
  // before any exposure), and a star of magnitude m gives brightness · 10^(−0.4 m).
  float brightness = 1.0f;
  bool cullTiles = true;  // draw only the sky tiles the view can see (off: every star, for comparisons)
};

inline constexpr float kStarMinFaintestMagnitude = 0.0f;
inline constexpr float kStarMaxFaintestMagnitude = 12.0f;
inline constexpr float kStarMaxBrightness = 1000.0f;  // keeps the brightest sprite far below half-float's 65,504

// Throws planet::Error naming the first bad value: count 0 or above gpu::kStarMaxCount,
// faintestMagnitude outside [0, 12] or not finite, brightness not in (0, 1000].
void validateStarSettings(const StarSettings& settings);

// The catalogue computed on the CPU from the same source as the GPU's (validates first).
std::vector<gpu::StarRecord> starCatalogueCpu(const StarSettings& settings);

// Sky tiles (shared/star_params.h): the catalogue of `count` stars holds the stars of tile t at
// indices starTileFirstIndex(t, count) .. starTileFirstIndex(t + 1, count) − 1 (t ≤ kStarTileCount).
uint32_t starTileFirstIndex(uint32_t tile, uint32_t count);

// A spherical cap around a tile: every direction of the tile is within radiusRad of axis.
struct StarTileCap {
  glm::dvec3 axis{0.0, 0.0, 1.0};  // unit
  double radiusRad = 0.0;
};
StarTileCap starTileCap(uint32_t tile);

}  // namespace planet
