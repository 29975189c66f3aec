// Where the patch textures lie on the planet (issue 3, "Patch textures by compute"): a stack of
// square height/normal textures around the camera, finer than the mesh, whose texels are fixed
// points of the planet so that the shading they carry never slides as the camera moves.
//
// Texels live on a cube face (gnomonic projection). Face f has planet-frame unit axes A, B and
// N with A × B = N; face coordinates (a, b) name the direction normalize(N + a·A + b·B). Level j
// of a layout has texel size Δ_j = 2^exponent_j in face units and its texel (x, y) (x, y =
// 0..resolution−1) is centred on
//   a = (originA_j + x + 0.5)·Δ_j,   b = (originB_j + y + 0.5)·Δ_j,
// with integer origins. So a texel is a function of (face, exponent, origin, x, y) only: a
// level that moves by whole texels samples the same planet points at shifted indices, and a
// level whose (face, exponent, origin) is unchanged need not be recomputed.
//
// Levels are ordered finest first and exponent_(j+1) = exponent_j + 1. Each level is stored in
// layer `layer_j` = exponent_j mod levelCount of the texture array, so when the camera
// descends by a factor of two only one layer (the new finest) holds stale texels.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "planet/cube_face.h"

namespace planet {

// Bounds of the patch texture settings.
inline constexpr uint32_t kPatchMinResolution = 16;
inline constexpr uint32_t kPatchMaxResolution = 4096;
inline constexpr uint32_t kPatchMaxLevels = 16;

struct PatchLevel {
  int exponent = 0;     // texel size Δ = 2^exponent face units (negative: finer than a face)
  int64_t originA = 0;  // texel (0, 0) is centred on ((originA + 0.5)·Δ, (originB + 0.5)·Δ)
  int64_t originB = 0;
  uint32_t layer = 0;   // texture array layer that holds this level: exponent mod levelCount
};

struct PatchLayout {
  int face = 0;              // every level lies on this face
  uint32_t resolution = 0;   // texels per side of every level
  std::vector<PatchLevel> levels;  // finest first, exponents consecutive
};

struct PatchSettings {
  uint32_t resolution = 512;  // texels per side of each level
  uint32_t levelCount = 6;    // levels (texture array layers)
  // Texels per pixel of the finest level at the nadir. 0.5 (a texel spans up to two pixels)
  // lets a 512² level cover a 960-pixel-wide view looking straight down, so the ground under
  // the camera never shows a level's edge; oblique views reach coarser levels by footprint.
  double texelsPerNadirPixel = 0.5;
  // Levels are recentred in steps of resolution / recentreDivisor texels, so the camera stays
  // at least (1/2 − 1/divisor) of a level from its edge and a level is rebuilt only after the
  // camera has moved that far.
  uint32_t recentreDivisor = 8;
};

// The patch texels a real-time frame may write (TerrainSettings::patchTexelsPerFrame): one
// recentre step of a level (an eighth of it by default), so that a level's move costs a frame its
// strip and a level built anew (the descent's new finest level, a jump) is spread over frames
// instead of costing one frame all of it (the benchmark's p99, issue 12 point 5).
inline uint64_t realTimePatchBudget(const PatchSettings& settings) {
  return uint64_t(settings.resolution) * (settings.resolution / settings.recentreDivisor);
}

// Throws planet::Error naming the first bad value (resolution outside kPatchMinResolution ..
// kPatchMaxResolution or not a multiple of recentreDivisor, levelCount outside 1 .. kPatchMaxLevels,
// texelsPerNadirPixel not finite and > 0, recentreDivisor outside 2 .. resolution).
void validatePatchSettings(const PatchSettings& settings);

// The layout for a camera in `cameraDirection` (planet frame, need not be unit) from the centre of
// a sphere of `radiusM`, whose pixels at the nadir cover `nadirPixelM` metres on the ground
// (radiusM · pixelFootprintTheta of clipmap_orientation.h). The face is the dominant face
// of the camera direction. The finest exponent is the largest e with
//   radiusM · 2^e / √(1 + a² + b²) <= nadirPixelM / texelsPerNadirPixel
// at the camera's face coordinates (a, b), clamped to [−60, 0]. Each level's origin is the
// camera's texel index minus resolution/2, rounded down to a multiple of
// resolution / recentreDivisor. Deterministic: the same inputs give the same layout.
// Throws as validatePatchSettings, and for a bad radius or a non-finite input.
PatchLayout choosePatchLayout(const PatchSettings& settings, double radiusM, const glm::dvec3& cameraDirection,
                              double nadirPixelM);

// Face coordinates of texel (x, y) of `level` (its centre).
glm::dvec2 patchTexelCoordinates(const PatchLevel& level, double x, double y);
// Ground spacing in metres between neighbouring texels of `level` at the level's centre:
// radiusM · Δ / √(1 + a_c² + b_c²) (the larger of the two gnomonic scales). The octave budget
// of the level's texels (octave_budget.h) is taken at this spacing.
double patchTexelSpacingM(const PatchLayout& layout, const PatchLevel& level, double radiusM);

}  // namespace planet
