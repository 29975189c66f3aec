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

// A layer's shaping (README, "Planets"; shaders/common/terrain_height.glsl): its noise value v
// goes through a transfer curve (none: v itself), is multiplied by a mask read from an earlier
// layer's value through a mask curve, and the result, the layer's value, times amplitudeM is its
// term. Curves are monotone cubic Hermite splines through knots (x, y, dy/dx at x, unused),
// built on the CPU in double (planet/terrain_shape.h); outside the knots a curve holds its end
// values.
GPU_CONST uint kTerrainCurveKnots = 16u;   // transfer curve knots at most (knots[0 .. 15])
GPU_CONST uint kTerrainMaskKnots = 8u;     // mask curve knots at most (knots[16 .. 23])
GPU_CONST uint kTerrainKnots = kTerrainCurveKnots + kTerrainMaskKnots;
GPU_CONST uint kTerrainNoMask = 0xffffffffu;

struct TerrainLayer {
  NoiseParams noise;
  float amplitudeM;    // metres per unit of the layer's value
  uint curveKnots;     // 0: no transfer curve, else 2 .. kTerrainCurveKnots
  uint maskLayer;      // an earlier layer whose value masks this one, or kTerrainNoMask
  uint maskKnots;      // 0: the mask is that layer's value itself, else 2 .. kTerrainMaskKnots
  vec4 knots[kTerrainKnots];  // the transfer curve's, then (from kTerrainCurveKnots) the mask curve's
};
GPU_ASSERT_SIZE(TerrainLayer, 448)

struct TerrainPointsPush {
  uint layerCount;
  uint count;
  float baseHeightM;
  float heightScale;
};
GPU_ASSERT_SIZE(TerrainPointsPush, 16)

GPU_NAMESPACE_END

#endif
