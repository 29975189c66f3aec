// The CPU reference of the noise: shaders/common/noise.glsl compiled as C++, with the terrain's
// layer sum and surface attributes that build on it (shaders/common/terrain_height.glsl,
// surface_attributes.glsl).
//
// The GLSL functions become member functions of NoiseKernel<real>, so one source yields the
// float reference (bit-identical to the GPU on lavapipe) and a double-precision one (the
// accuracy reference for Earth-scale tests). The translation units that instantiate it are
// compiled with -ffp-contract=off (never -ffast-math) so that no multiply-add is fused.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "common/definitions.h"
#include "shared/noise_params.h"
#include "shared/terrain_params.h"

namespace planet::noise {
namespace kernel_detail {

using namespace planet::gpu;

template <typename Real>
struct NoiseKernel {
  PLANET_GLSL_KERNEL(Real)

  // The reference hash's 512-entry permutation table (permutationTable()); unused by the fast hash.
  const uint* permutation = nullptr;
  // Rebased octave tables (OctaveWalk), kNoiseMaxOctaves entries per layer; unused by plain walks.
  const glm::vec4* octaveRemainders = nullptr;
  const glm::uvec4* octaveShifts = nullptr;

  // A terrain's layers as the C++ paths of common/terrain_height.glsl evaluate them
  // (engine/planet/terrain_kernel.h fills them from a planet description).
  struct TerrainKernelLayer {
    const uint* permutation = nullptr;  // the layer's reference permutation table
    NoiseParams params{};               // its octave budget applied
    real amplitude = real(0);
    real frequency = real(0);                  // plain walks sample p · frequency
    TerrainLayer shape{};                      // its curves and mask (the GPU's struct, in float)
  };
  const TerrainKernelLayer* terrainLayers = nullptr;
  uint terrainLayerCount = 0u;
  // 0: p is a planet-frame point, each layer walks plainly from p · frequency (the double
  // reference); 1: p is an offset from the anchor of the rebased octave tables (float path).
  uint terrainRebased = 0u;

  // TERRAIN_LAYER_NOISE of common/terrain_height.glsl.
  real terrainLayerNoise(uint l, vec3 p, uint /*context: unused on the CPU*/, bool needed) {
    const TerrainKernelLayer& layer = terrainLayers[l];
    permutation = layer.permutation;
    NoiseParams params = layer.params;
    if (!needed) params.octaves = 0u;
    if (terrainRebased != 0u) return rebasedLayerNoise(params, l, p);
    return evaluateNoise(params, p * layer.frequency);
  }

  // TERRAIN_LAYER_NOISE_GRADIENT: the same noise with its gradient with respect to p (a plain
  // walk samples p · frequency, so its gradient is the noise's times the frequency).
  vec4 terrainLayerNoiseGradient(uint l, vec3 p, uint /*context: unused on the CPU*/, bool needed) {
    const TerrainKernelLayer& layer = terrainLayers[l];
    permutation = layer.permutation;
    NoiseParams params = layer.params;
    if (!needed) params.octaves = 0u;
    if (terrainRebased != 0u) return rebasedLayerNoiseGradient(params, l, p);
    const vec4 noise = evaluateNoiseGradient(params, p * layer.frequency);
    return withGradient(noise.x, gradientOf(noise) * layer.frequency);
  }

#define OCTAVE_REMAINDER(layer, i) vec4(octaveRemainders[(layer)*kNoiseMaxOctaves + (i)])
#define OCTAVE_SHIFT(layer, i) octaveShifts[(layer)*kNoiseMaxOctaves + (i)]
#define PERM(i) permutation[i]
#define TERRAIN_LAYER_COUNT terrainLayerCount
#define TERRAIN_LAYER_NOISE(l, p, context, needed) terrainLayerNoise(l, p, context, needed)
#define TERRAIN_LAYER_NOISE_GRADIENT(l, p, context, needed) terrainLayerNoiseGradient(l, p, context, needed)
#define TERRAIN_LAYER(l) terrainLayers[l].shape
#define TERRAIN_LAYER_AMPLITUDE(l) terrainLayers[l].amplitude
#include "common/noise.glsl"
#include "common/terrain_height.glsl"
#include "common/surface_attributes.glsl"
#undef OCTAVE_REMAINDER
#undef OCTAVE_SHIFT
#undef PERM
#undef TERRAIN_LAYER_COUNT
#undef TERRAIN_LAYER_NOISE
#undef TERRAIN_LAYER_NOISE_GRADIENT
#undef TERRAIN_LAYER
#undef TERRAIN_LAYER_AMPLITUDE
};

}  // namespace kernel_detail

using kernel_detail::NoiseKernel;

}  // namespace planet::noise
