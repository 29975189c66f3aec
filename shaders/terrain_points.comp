#version 450
// Terrain heights at points given as float offsets from an anchor, through the rebased octave
// tables the CPU built in double (Earth-scale precision): `planet height --backend gpu` and the
// GPU side of the precision tests. The same arithmetic as terrainHeightRebased() on the CPU.
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

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= push.count) return;
  precise float sum = push.baseHeightM;
  for (uint l = 0u; l < push.layerCount; ++l) {
    gPermutationBase = l * kNoisePermutationSize;
    NoiseParams params = layers[l].noise;
    OctaveWalk walk;
    walk.q = vec3(0.0f);
    walk.lacunarity = params.lacunarity;
    walk.offset = offsets[index].xyz;
    walk.layer = l;
    walk.octave = 0u;
    walk.rebased = 1u;
    sum += layers[l].amplitudeM * fractalNoise(params, walk);
  }
  heights[index] = push.heightScale * sum;
}
