// The per-planet data every terrain shader reads (shaders/shared/terrain_params.h): the layer
// parameters and each layer's reference permutation table, uploaded once to device-local
// buffers. The per-frame octave tables (terrain_rebase.h) belong to each pass.
#pragma once

#include <cstdint>
#include <vector>

#include "planet/planet_description.h"
#include "vk/buffer.h"
#include "vk/owned.h"

namespace planet::vk {
class Context;
}

namespace planet {

// The specialization constants of the shaders that sum the planet's layers (gpu::kTerrainSpec*,
// shaders/terrain_layer_specialization.glsl): layer count, then each layer's noise type and hash
// (0 for unused layers), kTerrainSpecCount values.
std::vector<uint32_t> layerSpecialization(const PlanetDescription& planet);

// Whether a layer of `planet` is of type craters. The shaders specialized on the layers come in
// two variants (shaders/CMakeLists.txt): with the crater fractal, and without it (the default for
// planets that have no crater layer, whose pipelines then compile faster in less memory).
bool hasCraterLayer(const PlanetDescription& planet);

// Whether a layer of `planet` is of type damped or eroded (shaders/common/noise_erosion.glsl).
bool hasErosionLayer(const PlanetDescription& planet);

// Whether a layer of `planet` is of type faults, mpd or mpd_ico (shaders/common/noise_generators.glsl).
bool hasGeneratorLayer(const PlanetDescription& planet);

// Whether the shaders specialized on the layers need their full variant: a crater, erosion or
// generator layer. The other variant (NOISE_NO_CRATERS, which implies NOISE_NO_EROSION and
// NOISE_NO_GENERATORS in noise.glsl) leaves them out; the erosion code alone doubles a noise pipeline's compile time on
// lavapipe.
bool needsFullNoiseShaders(const PlanetDescription& planet);

class PlanetGpuData {
 public:
  // Throws planet::Error if the planet has more layers than the shaders hold.
  PlanetGpuData(vk::Context& context, const PlanetDescription& planet);
  PlanetGpuData(const PlanetGpuData&) = delete;
  PlanetGpuData& operator=(const PlanetGpuData&) = delete;

  const PlanetDescription& planet() const { return planet_; }
  const vk::Buffer& layers() const { return *layers_; }              // gpu::TerrainLayer[kTerrainMaxLayers]
  const vk::Buffer& permutations() const { return *permutations_; }  // uint[kTerrainMaxLayers * kNoisePermutationSize]

 private:
  PlanetDescription planet_;
  // In the order of creation (destroyed in reverse).
  vk::Owned<vk::Buffer> layers_;
  vk::Owned<vk::Buffer> permutations_;
};

}  // namespace planet
