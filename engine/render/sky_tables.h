// What the sky computes once per planet (issue 4): the atmosphere's transmittance table
// (shaders/atmosphere_transmittance.comp) and the cloud cover (cloud_cover.h), plus the sky
// irradiance table the CPU integrates. Both GPU tables are built by the first frame's command
// buffer and then only read.
#pragma once

#include <array>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "planet/planet_description.h"
#include "reference/atmosphere_model.h"
#include "render/cloud_cover.h"
#include "shared/sky_params.h"
#include "vk/image.h"
#include "vk/owned.h"
#include "vk/pipeline.h"

namespace planet::vk {
class Context;
class GpuTimer;
}  // namespace planet::vk

namespace planet {

class SkyTables {
 public:
  // Timing scopes a frame records at most: "sky tables" (the first frame).
  static constexpr uint32_t kTimingScopes = 1;

  SkyTables(vk::Context& context, const PlanetDescription& planet);

  // Records the builds the first time (then nothing) and leaves both images readable by
  // compute and fragment shaders.
  void recordBuild(VkCommandBuffer cmd, vk::GpuTimer* timer);
  bool built() const { return built_; }

  const gpu::AtmosphereParams& atmosphere() const { return atmosphere_; }
  const std::array<glm::vec4, kSkyIrradianceSamples>& skyIrradiance() const { return skyIrradiance_; }
  VkImageView transmittanceView() const { return transmittance_->view; }
  const CloudCover& clouds() const { return clouds_; }
  // Linear, clamped: for the transmittance table and the cloud cover.
  VkSampler sampler() const { return sampler_.get(); }

  // For tests: the transmittance table (rgb, row-major, kTransmittanceWidth × Height).
  std::vector<glm::vec4> readTransmittance();

 private:
  vk::Context& context_;
  gpu::AtmosphereParams atmosphere_{};
  std::array<glm::vec4, kSkyIrradianceSamples> skyIrradiance_{};
  // In the order of creation (destroyed in reverse).
  vk::Owned<vk::Image> transmittance_;
  CloudCover clouds_;
  vk::Owned<VkSampler> sampler_;
  vk::Owned<vk::ComputePipeline> transmittancePipeline_;
  VkDescriptorSet transmittanceSet_ = VK_NULL_HANDLE;  // from transmittancePipeline_'s pool
  bool built_ = false;
};

}  // namespace planet
