// Terrain heights at points on the GPU (terrain_points.comp): the rebased float path of
// terrain_rebase.h, evaluated by a compute shader. On lavapipe it is bit-identical to
// terrainHeightRebased() on the CPU.
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "planet/planet_description.h"
#include "planet/planet_gpu_data.h"
#include "planet/terrain_rebase.h"
#include "vk/buffer.h"
#include "vk/owned.h"
#include "vk/pipeline.h"

namespace planet::vk {
class Context;
}

namespace planet {

class GpuTerrainPoints {
 public:
  // Throws planet::Error if the planet has more layers than the shader holds.
  GpuTerrainPoints(vk::Context& context, const PlanetDescription& planet);
  GpuTerrainPoints(const GpuTerrainPoints&) = delete;
  GpuTerrainPoints& operator=(const GpuTerrainPoints&) = delete;

  // Heights in metres at anchor + offsetsM[i] (on the radius sphere; see terrain_rebase.h).
  std::vector<float> evaluate(const OctaveTables& tables, std::span<const glm::vec3> offsetsM);

 private:
  vk::Context& context_;
  PlanetDescription planet_;
  // In the order of creation (destroyed in reverse).
  PlanetGpuData data_;
  vk::Owned<vk::ComputePipeline> pipeline_;
  vk::Owned<vk::Buffer> remainders_;
  vk::Owned<vk::Buffer> shifts_;
};

}  // namespace planet
