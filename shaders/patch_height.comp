#version 450
// Patch textures, pass 1 (engine/render/patch_textures.h): terrain heights of one region of a
// level plus a one-texel border, through the rebased octave tables the CPU built in double at each tile's
// anchor (DESIGN.md, "Earth-scale precision"; shared/patch_params.h). Height-buffer texel
// (i, j) is region texel (i − 1, j − 1); the border feeds the normal pass's central differences.
#extension GL_GOOGLE_include_directive : require

#include "shared/patch_params.h"

layout(local_size_x = kPatchWorkgroupSize, local_size_y = kPatchWorkgroupSize) in;

// The planet's layer count, types and hashes: one pipeline per planet.
#include "terrain_layer_specialization.glsl"

layout(std430, set = 0, binding = kPatchBindingLevel) readonly buffer Level {
  PatchLevelParams level;
  PatchTile tiles[];
};
// The octave tables, read at every octave: texel buffers, which lavapipe (Mesa 22.3) reads with
// one vector load per lane, where a storage buffer read inside a loop is a bounds-checked scalar
// load per lane and component (as the height pass's, terrain_vertex_surface.glsl; the tables of
// all a level's tiles are too large for a uniform buffer).
layout(set = 0, binding = kPatchBindingRemainders) uniform samplerBuffer remainders;
layout(set = 0, binding = kPatchBindingShifts) uniform usamplerBuffer shifts;
layout(std430, set = 0, binding = kPatchBindingHeights) writeonly buffer Heights { float heights[]; };
layout(std430, set = 0, binding = kPatchBindingLayers) readonly buffer Layers { TerrainLayer layers[]; };
layout(std430, set = 0, binding = kPatchBindingPermutations) readonly buffer Permutations { uint permutations[]; };

// Each layer has its own seed, so its own reference permutation table; each tile its own tables.
uint gPermutationBase = 0u;
uint gTableBase = 0u;
#define PERM(i) permutations[gPermutationBase + (i)]
#define OCTAVE_REMAINDER(layer, i) texelFetch(remainders, int(gTableBase + (layer) * kNoiseMaxOctaves + (i)))
#define OCTAVE_SHIFT(layer, i) texelFetch(shifts, int(gTableBase + (layer) * kNoiseMaxOctaves + (i)))
#include "common/noise.glsl"

// Layer l's noise value at `offset` (sample minus tile anchor, metres), limited to the octaves
// this level's texel spacing can show, the last one faded (octave_budget.h); none where
// `needed` is false (the layer's mask is 0 there).
float layerNoise(uint l, vec3 offset, bool needed);
#define TERRAIN_UNROLLED_LAYERS
#define TERRAIN_LAYER_COUNT kSpecLayerCount
#define TERRAIN_LAYER_NOISE(l, p, context, needed) layerNoise(l, p, needed)
#define TERRAIN_LAYER(l) layers[l]
#define TERRAIN_LAYER_AMPLITUDE(l) layers[l].amplitudeM
#include "common/terrain_height.glsl"

float layerNoise(uint l, vec3 offset, bool needed) {
  gPermutationBase = l * kNoisePermutationSize;
  uint octaves = needed ? level.budgets[l].octaves : 0u;
  NoiseParams params = terrainLayerParams(layers[l].noise, specLayerType(l), specLayerHash(l), octaves,
                                          level.budgets[l].lastOctaveWeight);
  return rebasedLayerNoise(params, l, offset);
}

void main() {
  // Local texel of this invocation. Tiles are whole workgroups, so the tile follows from the
  // workgroup alone and every invocation, also one outside the level, reads a filled tile.
  uvec2 group = (gl_WorkGroupID.xy + uvec2(level.firstGroupA, level.firstGroupB)) * kPatchWorkgroupSize;
  ivec2 local = ivec2(group + gl_LocalInvocationID.xy);
  ivec2 id = local - ivec2(level.shiftA, level.shiftB);
  int sideA = int(level.regionWidth) + 2;
  int sideB = int(level.regionHeight) + 2;
  // No early return: lavapipe turns loads with uniform addresses into one scalar load only
  // outside control flow, so the layer parameters below stay cheap; the store is guarded.
  bool inside = id.x >= 0 && id.y >= 0 && id.x < sideA && id.y < sideB;
  uvec2 tileXY = group / level.tileSize;
  uint tile = tileXY.y * level.tilesPerSide + tileXY.x;
  int size = int(level.tileSize);
  int dx = local.x - int(tileXY.x) * size - size / 2;
  int dy = local.y - int(tileXY.y) * size - size / 2;
  gTableBase = tile * level.layerCount * kNoiseMaxOctaves;
  // Sample minus anchor on the radius sphere, in metres: small, as the rebased walk needs.
  precise vec3 offset =
      level.radiusM * patchDirectionOffset(level.axisA.xyz, level.axisB.xyz, level.texelSize, tiles[tile], dx, dy);
  float height = terrainHeightSum(level.baseHeightM, level.heightScale, offset, 0u);
  if (inside) heights[id.y * sideA + id.x] = height;
}
