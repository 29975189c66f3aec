// The relief cube (engine/render/relief_cube.h): the planet's heights and normals over the whole
// sphere at a fixed, coarse spacing, built once per planet by relief_cube.comp, sampled by the
// terrain and water shaders wherever the camera's patch textures do not reach (beyond the
// camera's cube face, or with patches off) and the mesh's vertices are coarser than its texels.
#ifndef PLANET_SHARED_RELIEF_PARAMS_H
#define PLANET_SHARED_RELIEF_PARAMS_H

#include "shared/gpu_types.h"
#include "shared/render_params.h"

GPU_NAMESPACE_BEGIN

// Bindings of relief_cube.comp (set 0).
GPU_CONST uint kReliefBindingImage = 0u;         // rgba16f cube (as a 2D array, mip 0): planet-frame normal, height m
GPU_CONST uint kReliefBindingLayers = 1u;        // TerrainLayer[kTerrainMaxLayers]
GPU_CONST uint kReliefBindingPermutations = 2u;  // uint[kTerrainMaxLayers · kNoisePermutationSize]
GPU_CONST uint kReliefBindingCount = 3u;
GPU_CONST uint kReliefWorkgroupSize = 8u;  // 8 × 8 texels per workgroup
// A cube of this size is a stand-in (TerrainSettings::relief off) that the shaders never sample.
GPU_CONST uint kReliefStandInSize = 8u;

struct ReliefPush {
  RingBudget budget;   // every layer's octaves at the cube's texel spacing (octave_budget.h)
  vec4 frequency[2];   // layer l's 1 / wavelength (per metre) in component l % 4 of frequency[l / 4]
  float radiusM;
  float baseHeightM;
  float heightScale;
  uint size;  // texels per face side
};
GPU_ASSERT_SIZE(ReliefPush, 112)

GPU_NAMESPACE_END

#endif
