// The planet's layer count and each layer's noise type and hash as specialization constants
// (gpu::kTerrainSpec*, shared/terrain_params.h; the host fills them with layerSpecialization()
// of engine/planet/planet_gpu_data.h): one pipeline per planet, and the shader compiler folds
// the branches on them. Its includers sum the layers with common/terrain_height.glsl's
// TERRAIN_UNROLLED_LAYERS, one line per layer with a constant index, so that the conditions and
// specLayerType/specLayerHash of a constant index fold away too.
#ifndef PLANET_TERRAIN_LAYER_SPECIALIZATION_GLSL
#define PLANET_TERRAIN_LAYER_SPECIALIZATION_GLSL

#include "shared/terrain_params.h"

layout(constant_id = kTerrainSpecLayerCount) const uint kSpecLayerCount = 1u;
layout(constant_id = kTerrainSpecTypes + 0u) const uint kSpecType0 = 1u;
layout(constant_id = kTerrainSpecTypes + 1u) const uint kSpecType1 = 1u;
layout(constant_id = kTerrainSpecTypes + 2u) const uint kSpecType2 = 1u;
layout(constant_id = kTerrainSpecTypes + 3u) const uint kSpecType3 = 1u;
layout(constant_id = kTerrainSpecTypes + 4u) const uint kSpecType4 = 1u;
layout(constant_id = kTerrainSpecTypes + 5u) const uint kSpecType5 = 1u;
layout(constant_id = kTerrainSpecTypes + 6u) const uint kSpecType6 = 1u;
layout(constant_id = kTerrainSpecTypes + 7u) const uint kSpecType7 = 1u;
layout(constant_id = kTerrainSpecHashes + 0u) const uint kSpecHash0 = 0u;
layout(constant_id = kTerrainSpecHashes + 1u) const uint kSpecHash1 = 0u;
layout(constant_id = kTerrainSpecHashes + 2u) const uint kSpecHash2 = 0u;
layout(constant_id = kTerrainSpecHashes + 3u) const uint kSpecHash3 = 0u;
layout(constant_id = kTerrainSpecHashes + 4u) const uint kSpecHash4 = 0u;
layout(constant_id = kTerrainSpecHashes + 5u) const uint kSpecHash5 = 0u;
layout(constant_id = kTerrainSpecHashes + 6u) const uint kSpecHash6 = 0u;
layout(constant_id = kTerrainSpecHashes + 7u) const uint kSpecHash7 = 0u;

// Layer l's fractal type and lattice hash (l < kTerrainMaxLayers).
uint specLayerType(uint l) {
  return l == 0u ? kSpecType0 : l == 1u ? kSpecType1 : l == 2u ? kSpecType2 : l == 3u ? kSpecType3
       : l == 4u ? kSpecType4 : l == 5u ? kSpecType5 : l == 6u ? kSpecType6 : kSpecType7;
}
uint specLayerHash(uint l) {
  return l == 0u ? kSpecHash0 : l == 1u ? kSpecHash1 : l == 2u ? kSpecHash2 : l == 3u ? kSpecHash3
       : l == 4u ? kSpecHash4 : l == 5u ? kSpecHash5 : l == 6u ? kSpecHash6 : kSpecHash7;
}

#endif
