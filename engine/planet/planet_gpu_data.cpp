#include "planet/planet_gpu_data.h"

#include <algorithm>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "noise/noise_settings.h"
#include "noise/permutation.h"
#include "planet/terrain_shape.h"
#include "shared/terrain_params.h"
#include "vk/context.h"

namespace planet {

std::vector<uint32_t> layerSpecialization(const PlanetDescription& planet) {
  std::vector<uint32_t> values(gpu::kTerrainSpecCount, 0u);
  values[gpu::kTerrainSpecLayerCount] = uint32_t(planet.layers.size());
  for (size_t l = 0; l < planet.layers.size() && l < gpu::kTerrainMaxLayers; ++l) {
    const gpu::NoiseParams params = noise::toNoiseParams(planet.layers[l].noise);
    values[gpu::kTerrainSpecTypes + l] = params.type;
    values[gpu::kTerrainSpecHashes + l] = params.hash;
  }
  return values;
}

bool hasCraterLayer(const PlanetDescription& planet) {
  return std::any_of(planet.layers.begin(), planet.layers.end(),
                     [](const NoiseLayer& layer) { return layer.noise.type == noise::NoiseType::Craters; });
}

bool hasErosionLayer(const PlanetDescription& planet) {
  return std::any_of(planet.layers.begin(), planet.layers.end(), [](const NoiseLayer& layer) {
    return layer.noise.type == noise::NoiseType::Damped || layer.noise.type == noise::NoiseType::Eroded;
  });
}

bool hasGeneratorLayer(const PlanetDescription& planet) {
  return std::any_of(planet.layers.begin(), planet.layers.end(),
                     [](const NoiseLayer& layer) { return noise::isGenerator(layer.noise.type); });
}

bool needsFullNoiseShaders(const PlanetDescription& planet) {
  return hasCraterLayer(planet) || hasErosionLayer(planet) || hasGeneratorLayer(planet);
}

PlanetGpuData::PlanetGpuData(vk::Context& context, const PlanetDescription& planet) : planet_(planet) {
  if (planet.layers.size() > gpu::kTerrainMaxLayers)
    throw Error(fmt::format("planet '{}' has {} layers; the GPU terrain holds at most {}", planet.name,
                            planet.layers.size(), gpu::kTerrainMaxLayers));
  std::vector<gpu::TerrainLayer> layers(gpu::kTerrainMaxLayers, gpu::TerrainLayer{});
  std::vector<uint32_t> permutations(size_t(gpu::kTerrainMaxLayers) * gpu::kNoisePermutationSize, 0u);
  for (size_t l = 0; l < planet.layers.size(); ++l) {
    layers[l] = terrainLayerShape(planet, l);
    const noise::PermutationTable& table = noise::permutationTable(planet.layers[l].noise.seed);
    std::copy(table.begin(), table.end(), permutations.begin() + l * gpu::kNoisePermutationSize);
  }
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  // All kTerrainMaxLayers: the height pass reads them as a uniform block of that many
  // (shaders/terrain_vertex_surface.glsl), the patch and relief passes as a storage buffer.
  layers_ = {context, vk::createBuffer(context, layers.size() * sizeof(gpu::TerrainLayer),
                                       storage | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, vk::MemoryUsage::DeviceLocal)};
  vk::uploadBuffer(context, *layers_, layers.data(), layers.size() * sizeof(gpu::TerrainLayer));
  permutations_ = {context, vk::createBuffer(context, permutations.size() * sizeof(uint32_t), storage,
                                             vk::MemoryUsage::DeviceLocal)};
  vk::uploadBuffer(context, *permutations_, permutations.data(), permutations.size() * sizeof(uint32_t));
}

}  // namespace planet
