// A planet's noise stack prepared for the terrain height's C++ evaluations (the layer sum of
// shaders/common/terrain_height.glsl inside noise::NoiseKernel): each layer's permutation table,
// its parameters with the octave budget of `spacingM` applied, amplitude and frequency, in the
// precision of the evaluation, and its shaping (curves and mask, planet/terrain_shape.h). Shared by the double reference (terrain_height.cpp) and the
// rebased float path (terrain_rebase.cpp).
#pragma once

#include <array>

#include <fmt/format.h>

#include "core/error.h"
#include "noise/noise_kernel.h"
#include "noise/noise_settings.h"
#include "noise/permutation.h"
#include "planet/octave_budget.h"
#include "planet/planet_description.h"
#include "planet/terrain_shape.h"
#include "shared/terrain_params.h"

namespace planet {

template <typename Real>
struct TerrainKernelLayers {
  std::array<typename noise::NoiseKernel<Real>::TerrainKernelLayer, gpu::kTerrainMaxLayers> layers{};
  uint32_t count = 0;

  // Points `kernel` at these layers.
  void attach(noise::NoiseKernel<Real>& kernel, bool rebased) const {
    kernel.terrainLayers = layers.data();
    kernel.terrainLayerCount = count;
    kernel.terrainRebased = rebased ? 1u : 0u;
  }
};

template <typename Real>
TerrainKernelLayers<Real> terrainKernelLayers(const PlanetDescription& planet, double spacingM) {
  if (planet.layers.size() > gpu::kTerrainMaxLayers)
    throw Error(fmt::format("planet has {} noise layers, at most {} are supported", planet.layers.size(),
                            gpu::kTerrainMaxLayers));
  TerrainKernelLayers<Real> result;
  result.count = uint32_t(planet.layers.size());
  for (size_t l = 0; l < planet.layers.size(); ++l) {
    const NoiseLayer& layer = planet.layers[l];
    auto& out = result.layers[l];
    out.permutation = noise::permutationTable(layer.noise.seed).data();
    out.shape = terrainLayerShape(planet, l);
    out.params = out.shape.noise;
    const OctaveBudget budget = octaveBudget(layer, spacingM);
    out.params.octaves = budget.octaves;
    out.params.lastOctaveWeight = budget.lastOctaveWeight;
    out.amplitude = Real(layer.amplitudeM);
    out.frequency = Real(layer.frequency);
  }
  return result;
}

}  // namespace planet
