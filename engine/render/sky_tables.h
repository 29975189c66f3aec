// What the sky computes once per planet (issue 4): the atmosphere's transmittance table
// (shaders/atmosphere_transmittance.comp), its multiple-scattering table (issue 21, Hillaire
// 2020 §5.5: shaders/atmosphere_multiscatter.comp, from the transmittance table) and the cloud
// cover (cloud_cover.h), plus the sky irradiance table the CPU integrates. The GPU tables are
// built by the first frame's command buffer and then only read.
#pragma once

#include <array>
#include <span>
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

  // Records the builds the first time (then nothing) and leaves every image readable by
  // compute and fragment shaders.
  void recordBuild(VkCommandBuffer cmd, vk::GpuTimer* timer);
  bool built() const { return built_; }

  const gpu::AtmosphereParams& atmosphere() const { return atmosphere_; }
  const std::array<glm::vec4, kSkyIrradianceSamples>& skyIrradiance() const { return skyIrradiance_; }
  VkImageView transmittanceView() const { return transmittance_->view; }
  VkImageView multipleScatteringView() const { return multipleScattering_->view; }
  const CloudCover& clouds() const { return clouds_; }
  // Linear, clamped: for the transmittance and multiple-scattering tables and the cloud cover.
  VkSampler sampler() const { return sampler_.get(); }

  // For tests: the transmittance table (rgb, row-major, kTransmittanceWidth × Height).
  std::vector<glm::vec4> readTransmittance();
  // For tests: the multiple-scattering table (rgb Ψ_ms, a f_ms of green; kMultiScatteringSize²).
  std::vector<glm::vec4> readMultipleScattering();

  // Rays through the built tables (shaders/sky_ray.comp), blocking: per ray, the reference sky
  // pass's per-pixel march with `referenceSteps` samples, and the tables' single and multiple
  // scattering by the midpoint rule with `tableSteps` samples (planet sky, tests).
  struct RayQuery {
    double altitudeM = 0.0;  // above the planet's radius
    double mu = 1.0;         // view zenith cosine
    double muS = 1.0;        // sun zenith cosine
    double nu = 1.0;         // cosine between the view and the sun
  };
  struct RayResult {
    glm::dvec3 reference;               // single scattering, the reference sky.comp's march
    glm::dvec3 single;                  // single scattering, the tables' march
    glm::dvec3 multiple;                // second and higher orders, the tables' march
    glm::dvec3 transmittance;           // along the ray's stretch inside the atmosphere (the tables' march)
    glm::dvec3 referenceTransmittance;  // the same by the sky pass's march
    glm::dvec3 referenceTotal;          // single and multiple scattering, the reference sky.comp's march
  };
  std::vector<RayResult> evaluateRays(std::span<const RayQuery> rays, uint32_t referenceSteps, uint32_t tableSteps);

 private:
  vk::Context& context_;
  gpu::AtmosphereParams atmosphere_{};
  std::array<glm::vec4, kSkyIrradianceSamples> skyIrradiance_{};
  // In the order of creation (destroyed in reverse).
  vk::Owned<vk::Image> transmittance_;
  vk::Owned<vk::Image> multipleScattering_;
  CloudCover clouds_;
  vk::Owned<VkSampler> sampler_;
  vk::Owned<vk::ComputePipeline> transmittancePipeline_;
  VkDescriptorSet transmittanceSet_ = VK_NULL_HANDLE;  // from transmittancePipeline_'s pool
  vk::Owned<vk::ComputePipeline> multipleScatteringPipeline_;
  VkDescriptorSet multipleScatteringSet_ = VK_NULL_HANDLE;  // from multipleScatteringPipeline_'s pool
  bool built_ = false;
};

}  // namespace planet
