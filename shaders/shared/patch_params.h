// World-anchored patch textures (engine/render/patch_textures.h): the per-level parameters the
// CPU prepares in double, and the bindings of patch_height.comp and patch_normal.comp (the
// height pass's specialization constants are those of shared/terrain_params.h).
//
// Texels are grouped into square tiles fixed on the cube face (tile k along a covers the texels
// whose index on the face, originA + x, lies in [k·T, (k+1)·T)). Each tile has its own anchor,
// its centre texel, with octave tables built in double on the CPU. A texel is evaluated from its
// exact integer offset to its tile's anchor, so its value depends only on where it lies on the
// face (and on the level's octave budget), not on where the level's origin is.
#ifndef PLANET_SHARED_PATCH_PARAMS_H
#define PLANET_SHARED_PATCH_PARAMS_H

#include "shared/gpu_types.h"
#include "shared/terrain_params.h"

GPU_NAMESPACE_BEGIN

// Bindings of both passes (set 0; each pass declares the ones it uses).
GPU_CONST uint kPatchBindingLevel = 0u;         // PatchLevelParams, then PatchTile[tilesPerSide²]
GPU_CONST uint kPatchBindingRemainders = 1u;    // samplerBuffer: vec4[tiles · layerCount · kNoiseMaxOctaves]
GPU_CONST uint kPatchBindingShifts = 2u;        // usamplerBuffer: uvec4[tiles · layerCount · kNoiseMaxOctaves]
GPU_CONST uint kPatchBindingHeights = 3u;       // float[(resolution + 2)²]: heights with a 1-texel border
GPU_CONST uint kPatchBindingLayers = 4u;        // TerrainLayer[kTerrainMaxLayers]
GPU_CONST uint kPatchBindingPermutations = 5u;  // uint[kTerrainMaxLayers · kNoisePermutationSize]
GPU_CONST uint kPatchBindingImage = 6u;         // rgba32f 2D array: (normal, height) per texel
GPU_CONST uint kPatchBindingCount = 7u;
GPU_CONST uint kPatchWorkgroupSize = 8u;  // 8 × 8 invocations per workgroup, both passes
// Tiles are about resolution / kPatchTileDivisor texels wide, rounded down to a multiple of the
// workgroup size (at least one workgroup): about 10 × 10 tiles per level (cheap tables), offsets
// of at most ~45 texels from an anchor at the default 512, and every height-pass workgroup lies
// in one tile.
GPU_CONST uint kPatchTileDivisor = 8u;

// The octave budget of one noise layer (octave_budget.h), computed on the CPU per level.
struct PatchLayerBudget {
  uint octaves;            // NoiseParams.octaves for this level
  float lastOctaveWeight;  // NoiseParams.lastOctaveWeight for this level
  uint pad0;
  uint pad1;
};
GPU_ASSERT_SIZE(PatchLayerBudget, 16)

// One tile's anchor: the centre texel of the tile, computed in double and rounded once.
struct PatchTile {
  vec4 anchor;  // xyz: unit direction c of the anchor (planet frame); w: s = |N + a_t·A + b_t·B|
  vec4 coords;  // x, y: the anchor's face coordinates (a_t, b_t); z, w: unused
};
GPU_ASSERT_SIZE(PatchTile, 32)

// One region of one level (= one array layer) of the patch textures: the whole level, or the
// strip of texels a level that moved by a few texels has not computed yet. Height-buffer texel
// (i, j), i.e. region texel (i − 1, j − 1), is local texel (i + shiftA, j + shiftB) of the
// region's first tile row and column: tile (tx, ty) = local / tileSize, and it lies
// local − tile·tileSize − tileSize/2 texels from its tile's anchor. The height pass runs over
// local texels, from workgroup (firstGroupA, firstGroupB) = (shiftA, shiftB) / kPatchWorkgroupSize
// on.
//
// Storage is toroidal: the texel with face index (i, j) (origin + texel index) lives at image
// texel (i mod resolution, j mod resolution) of its layer, whatever the level's origin, so a
// level that moves keeps the texels it still covers where they are and only the new strips are
// computed. Region texel (x, y) is stored at ((x + storeOffsetA) mod resolution, (y +
// storeOffsetB) mod resolution), storeOffset = the region's first face index mod resolution.
struct PatchLevelParams {
  vec4 axisA;         // xyz: the face's axis A; w: unused
  vec4 axisB;         // xyz: the face's axis B; w: unused
  float texelSize;    // Δ = 2^exponent face units (a power of two: exact in float)
  float radiusM;      // R, the radius sphere the heights are measured from
  float baseHeightM;  // PlanetDescription::baseHeightM
  float heightScale;  // PlanetDescription::heightScale
  int shiftA;         // face index of height-buffer column 0 minus the first tile's first index
  int shiftB;
  uint tileSize;      // T, texels per tile side
  uint tilesPerSide;  // row length of the tile array
  uint resolution;    // texels per side of the level (and of the image)
  uint layerCount;    // noise layers: each tile has layerCount · kNoiseMaxOctaves table rows
  uint imageLayer;    // array layer of the patch image this level is written to
  uint firstGroupA;   // shiftA / kPatchWorkgroupSize
  uint firstGroupB;   // shiftB / kPatchWorkgroupSize
  uint regionWidth;   // texels of the region along a (the height buffer has regionWidth + 2)
  uint regionHeight;  // texels of the region along b
  uint storeOffsetA;  // the region's first face index along a, mod resolution
  uint storeOffsetB;
  uint pad0;
  uint pad1;
  uint pad2;
  PatchLayerBudget budgets[kTerrainMaxLayers];
};
GPU_ASSERT_SIZE(PatchLevelParams, 240)

GPU_NAMESPACE_END

#ifndef __cplusplus
// p − c for the texel (dx, dy) texels from an anchor, with p = (g + u)/|g + u| its unit
// direction, g = N + a_t·A + b_t·B (|g| = s, c = g/s) and u = Δa·A + Δb·B, Δa = dx·Δ, Δb = dy·Δ.
// With s'² = |g + u|² = s² + k, k = 2 g·u + u·u = 2(Δa·a_t + Δb·b_t) + Δa² + Δb² (A, B, N
// orthonormal), and 1/s' − 1/s = −k / (s·s'·(s + s')):
//   p − c = u/s' − c·k / ((s + s')·s').
// Every term is of the size of the offset, so the result keeps float precision relative to
// the offset itself (~1e-7 of it), where p − c formed from two unit vectors would lose all
// digits below 6e-8 of R (0.4 m on Earth).
vec3 patchDirectionOffset(vec3 axisA, vec3 axisB, float texelSize, PatchTile tile, int dx, int dy) {
  precise float da = float(dx) * texelSize;
  precise float db = float(dy) * texelSize;
  precise float k = 2.0f * (da * tile.coords.x + db * tile.coords.y) + (da * da + db * db);
  precise float s = tile.anchor.w;
  precise float s1 = sqrt(s * s + k);
  precise vec3 u = da * axisA + db * axisB;
  precise vec3 offset = u / s1 - tile.anchor.xyz * (k / ((s + s1) * s1));
  return offset;
}

// Which tile height-buffer texel `id` lies in, and its offset in texels from that tile's anchor.
void patchTileOf(PatchLevelParams level, uvec2 id, out uint tile, out int dx, out int dy) {
  int size = int(level.tileSize);
  int localX = int(id.x) + level.shiftA;
  int localY = int(id.y) + level.shiftB;
  int tileX = localX / size;
  int tileY = localY / size;
  tile = uint(tileY) * level.tilesPerSide + uint(tileX);
  dx = localX - tileX * size - size / 2;
  dy = localY - tileY * size - size / 2;
}
#endif

#endif
