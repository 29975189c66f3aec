// The terrain height of a planet, its noise stack summed (README, "Planets"):
//   height = heightScale · (baseHeight + Σ_l amplitude_l · noise_l(p)),
// written once for every place that evaluates it: the double reference (terrainHeightM,
// engine/planet/terrain_height.cpp), the rebased float path (terrainHeightRebased,
// engine/planet/terrain_rebase.cpp, and so the CPU height source), and the shaders
// terrain_heights.comp and terrain_noise.vert (through terrain_vertex_surface.glsl),
// patch_height.comp and terrain_points.comp. Common subset: definitions.glsl; include it after
// noise.glsl (C++: noise_kernel.h does).
//
// The includer defines, before including:
//   TERRAIN_LAYER_COUNT                the number of layers (at most kTerrainMaxLayers)
//   TERRAIN_LAYER_TERM(l, p, context)  layer l's term amplitude_l · noise_l(p), through
//                                      terrainLayerParams and rebasedLayerNoise below (or
//                                      evaluateNoise for the double reference); `context` is
//                                      what terrainHeightSum was given (the mesh: the ring)
// and TERRAIN_UNROLLED_LAYERS where layer indices must be constants: a shader specialized on the
// layers' types and hashes (terrain_layer_specialization.glsl) names a layer's type by its
// index, and with constant indices its compiler folds each layer's branches away.
#ifndef PLANET_COMMON_TERRAIN_HEIGHT_GLSL
#define PLANET_COMMON_TERRAIN_HEIGHT_GLSL

#include "common/definitions.glsl"

// A layer's noise parameters as one evaluation uses them: its fractal type and lattice hash
// (specialized shaders pass constants), limited to `octaves`, the last one weighted
// `lastOctaveWeight` (the octave budget of the point's spacing, planet/octave_budget.h).
NoiseParams terrainLayerParams(NoiseParams params, uint type, uint hash, uint octaves, float lastOctaveWeight) {
  params.type = type;
  params.hash = hash;
  params.octaves = octaves;
  params.lastOctaveWeight = lastOctaveWeight;
  return params;
}

// Layer `layer`'s fractal at `offset` (metres from the anchor of the rebased octave tables,
// planet frame), walking row `layer` of the tables (DESIGN.md, "Earth-scale precision").
real rebasedLayerNoise(IN(NoiseParams) params, uint layer, vec3 offset) {
  OctaveWalk walk;
  walk.q = vec3(real(0.0f));
  walk.lacunarity = real(params.lacunarity);
  walk.offset = offset;
  walk.layer = layer;
  walk.octave = 0u;
  walk.rebased = 1u;
  return fractalNoise(params, walk);
}

// The height at p: the layers in order, each term added to the base as it comes, then scaled.
real terrainHeightSum(real baseHeight, real heightScale, vec3 p, uint context) {
  PRECISE real sum = baseHeight;
#ifdef TERRAIN_UNROLLED_LAYERS
  if (TERRAIN_LAYER_COUNT > 0u) sum += TERRAIN_LAYER_TERM(0u, p, context);
  if (TERRAIN_LAYER_COUNT > 1u) sum += TERRAIN_LAYER_TERM(1u, p, context);
  if (TERRAIN_LAYER_COUNT > 2u) sum += TERRAIN_LAYER_TERM(2u, p, context);
  if (TERRAIN_LAYER_COUNT > 3u) sum += TERRAIN_LAYER_TERM(3u, p, context);
  if (TERRAIN_LAYER_COUNT > 4u) sum += TERRAIN_LAYER_TERM(4u, p, context);
  if (TERRAIN_LAYER_COUNT > 5u) sum += TERRAIN_LAYER_TERM(5u, p, context);
  if (TERRAIN_LAYER_COUNT > 6u) sum += TERRAIN_LAYER_TERM(6u, p, context);
  if (TERRAIN_LAYER_COUNT > 7u) sum += TERRAIN_LAYER_TERM(7u, p, context);
#else
  for (uint l = 0u; l < TERRAIN_LAYER_COUNT; ++l) sum += TERRAIN_LAYER_TERM(l, p, context);
#endif
  return heightScale * sum;
}

#endif
