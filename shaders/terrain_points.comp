#version 450
// Terrain heights at points given as float offsets from an anchor, through the rebased octave
// tables the CPU built in double (Earth-scale precision): `planet height --backend gpu` and the
// GPU side of the precision tests. The layer sum is common/terrain_height.glsl, as in
// terrainHeightRebased() on the CPU.
#extension GL_GOOGLE_include_directive : require

#include "shared/terrain_params.h"

layout(local_size_x = kTerrainWorkgroupSize) in;

layout(push_constant) uniform Push { TerrainPointsPush push; };

layout(std430, set = 0, binding = kTerrainBindingOffsets) readonly buffer Offsets { vec4 offsets[]; };
layout(std430, set = 0, binding = kTerrainBindingHeights) writeonly buffer Heights { float heights[]; };
layout(std430, set = 0, binding = kTerrainBindingLayers) readonly buffer Layers { TerrainLayer layers[]; };
layout(std430, set = 0, binding = kTerrainBindingRemainders) readonly buffer Remainders { vec4 remainders[]; };
layout(std430, set = 0, binding = kTerrainBindingShifts) readonly buffer Shifts { uvec4 shifts[]; };
layout(std430, set = 0, binding = kTerrainBindingPermutations) readonly buffer Permutations { uint permutations[]; };

// Each layer has its own seed, so its own reference permutation table.
uint gPermutationBase = 0u;
#define PERM(i) permutations[gPermutationBase + (i)]
#define OCTAVE_REMAINDER(layer, i) remainders[(layer) * kNoiseMaxOctaves + (i)]
#define OCTAVE_SHIFT(layer, i) shifts[(layer) * kNoiseMaxOctaves + (i)]
#include "common/noise.glsl"

// Layer l's noise value at `offset` (sample minus anchor, metres), every octave of the layer
// (none where `needed` is false: its mask is 0 there).
float layerNoise(uint l, vec3 offset, bool needed);
#define TERRAIN_LAYER_COUNT push.layerCount
#define TERRAIN_LAYER_NOISE(l, p, context, needed) layerNoise(l, p, needed)
#define TERRAIN_LAYER(l) layers[l]
#define TERRAIN_LAYER_AMPLITUDE(l) layers[l].amplitudeM
#include "common/terrain_height.glsl"

float layerNoise(uint l, vec3 offset, bool needed) {
  gPermutationBase = l * kNoisePermutationSize;
  NoiseParams params = layers[l].noise;
  if (!needed) params.octaves = 0u;
  return rebasedLayerNoise(params, l, offset);
}

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= push.count) return;
  heights[index] = terrainHeightSum(push.baseHeightM, push.heightScale, offsets[index].xyz, 0u);
}
