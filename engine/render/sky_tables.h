// What the sky computes once per planet (issue 4): the atmosphere's transmittance table
// (shaders/atmosphere_transmittance.comp) and the three cloud-cover images
// (shaders/clouds_cover.comp), plus the sky irradiance table the CPU integrates. Both GPU
// tables are built by the first frame's command buffer and then only read.
#pragma once

#include <array>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "planet/planet_description.h"
#include "reference/atmosphere_model.h"
#include "shared/sky_params.h"
#include "vk/image.h"
#include "vk/pipeline.h"

namespace planet::vk {
class Context;
class GpuTimer;
}  // namespace planet::vk

namespace planet {

inline constexpr uint32_t kCloudCoverSize = 512;  // texels per cube face side (~20 km on Earth)

class SkyTables {
 public:
  SkyTables(vk::Context& context, const PlanetDescription& planet);
  ~SkyTables();
  SkyTables(const SkyTables&) = delete;
  SkyTables& operator=(const SkyTables&) = delete;

  // Records the builds the first time (then nothing) and leaves both images readable by
  // compute and fragment shaders.
  void recordBuild(VkCommandBuffer cmd, vk::GpuTimer* timer);
  bool built() const { return built_; }

  const gpu::AtmosphereParams& atmosphere() const { return atmosphere_; }
  const std::array<glm::vec4, kSkyIrradianceSamples>& skyIrradiance() const { return skyIrradiance_; }
  VkImageView transmittanceView() const { return transmittance_.view; }
  VkImageView cloudCoverView() const { return clouds_.cubeView; }
  VkSampler sampler() const { return sampler_; }

  // For tests: the transmittance table (rgb, row-major, kTransmittanceWidth × Height).
  std::vector<glm::vec4> readTransmittance();

 private:
  void release();

  vk::Context& context_;
  PlanetDescription planet_;
  gpu::AtmosphereParams atmosphere_{};
  std::array<glm::vec4, kSkyIrradianceSamples> skyIrradiance_{};
  vk::Image transmittance_;
  vk::Image clouds_;
  VkSampler sampler_ = VK_NULL_HANDLE;
  vk::ComputePipeline transmittancePipeline_;
  vk::ComputePipeline cloudPipeline_;
  VkDescriptorSet transmittanceSet_ = VK_NULL_HANDLE;
  VkDescriptorSet cloudSet_ = VK_NULL_HANDLE;
  bool built_ = false;
};

// The cloud layer's state at `timeS` (seed 001 §4.4): the weights of the three cover images
// (its eq. 4.2, summing to 1) and the drift angle about the planet's axis.
struct CloudMotion {
  glm::vec3 weights;
  float driftRad;
};
CloudMotion cloudMotion(const CloudDescription& clouds, double radiusM, double timeS);

}  // namespace planet
