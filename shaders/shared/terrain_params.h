// Terrain height evaluation at points given as offsets from an anchor (the rebased path of
// shaders/common/noise.glsl): layer parameters and bindings shared by C++ and GLSL.
#ifndef PLANET_SHARED_TERRAIN_PARAMS_H
#define PLANET_SHARED_TERRAIN_PARAMS_H

#include "shared/gpu_types.h"
#include "shared/noise_params.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kTerrainMaxLayers = 8u;

// Bindings of terrain_points.comp (set 0).
GPU_CONST uint kTerrainBindingOffsets = 0u;      // vec4[count]: sample minus anchor, metres (w unused)
GPU_CONST uint kTerrainBindingHeights = 1u;      // float[count]: metres above the radius sphere
GPU_CONST uint kTerrainBindingLayers = 2u;       // TerrainLayer[kTerrainMaxLayers]
GPU_CONST uint kTerrainBindingRemainders = 3u;   // vec4[kTerrainMaxLayers * kNoiseMaxOctaves]
GPU_CONST uint kTerrainBindingShifts = 4u;       // uvec4[kTerrainMaxLayers * kNoiseMaxOctaves]
GPU_CONST uint kTerrainBindingPermutations = 5u; // uint[kTerrainMaxLayers * kNoisePermutationSize]
GPU_CONST uint kTerrainWorkgroupSize = 64u;

// Specialization constants of the shaders that sum the planet's layers (patch_height.comp,
// terrain_heights.comp; declared in shaders/terrain_layer_specialization.glsl): the layer count
// and each layer's noise type and hash, so that the shader compiler removes the branches on them
// (lavapipe runs both sides of even a uniform branch; README.md, "Specialization, not branches").
GPU_CONST uint kTerrainSpecLayerCount = 0u;
GPU_CONST uint kTerrainSpecTypes = 1u;                       // + layer index
GPU_CONST uint kTerrainSpecHashes = 1u + kTerrainMaxLayers;  // + layer index
GPU_CONST uint kTerrainSpecCount = 1u + 2u * kTerrainMaxLayers;

struct TerrainLayer {
  NoiseParams noise;
  float amplitudeM;  // metres per unit of noise
  float pad0;
  float pad1;
  float pad2;
};
GPU_ASSERT_SIZE(TerrainLayer, 64)

struct TerrainPointsPush {
  uint layerCount;
  uint count;
  float baseHeightM;
  float heightScale;
};
GPU_ASSERT_SIZE(TerrainPointsPush, 16)

GPU_NAMESPACE_END

#endif
