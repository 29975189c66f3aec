// The planet's layer count and each layer's noise type and hash as specialization constants
// (gpu::kTerrainSpec*, shared/terrain_params.h; the host fills them with layerSpecialization()
// of engine/planet/planet_gpu_data.h): one pipeline per planet, and the shader compiler folds
// the branches on them. An includer sums its layers as
//   if (kSpecLayerCount > 0u) sum += ... layer 0 with kSpecType0, kSpecHash0 ...;
// one line per layer up to kTerrainMaxLayers, so that the conditions fold away too.
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

#endif
