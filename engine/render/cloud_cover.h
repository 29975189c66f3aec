// The clouds (issue 4; seed 001 §4.4): a layer between two heights whose coverage comes from
// three cube maps of fractal noise (shaders/clouds_cover.comp), built once per planet with the
// sky tables, blended over time (cloudMotion) and drifting with the wind. The sky pass composes
// them (shaders/sky.comp: the layer crossed by each pixel's ray, detail noise, their shadows) from
// the values writeUniforms gives it.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "planet/planet_description.h"
#include "shared/sky_params.h"
#include "vk/image.h"
#include "vk/owned.h"
#include "vk/pipeline.h"

namespace planet::vk {
class Context;
}  // namespace planet::vk

namespace planet {

inline constexpr uint32_t kCloudCoverSize = 512;  // texels per cube face side (~20 km on Earth)

// The cloud layer's state at `timeS` (seed 001 §4.4): the weights of the three cover images
// (its eq. 4.2, summing to 1) and the drift angle about the planet's axis.
struct CloudMotion {
  glm::vec3 weights;
  float driftRad;
};
CloudMotion cloudMotion(const CloudDescription& clouds, double radiusM, double timeS);

// The cover images (rgb: the three images, one per channel) and the compute pass that fills them.
class CloudCover {
 public:
  // A planet without clouds gets a tiny cube that is bound but never sampled.
  CloudCover(vk::Context& context, const PlanetDescription& planet);

  // Records the build: the cube from undefined to GENERAL, the noise (planets with clouds), and
  // the cube to SHADER_READ_ONLY_OPTIMAL for compute and fragment shaders. Once per planet (the
  // sky tables' first frame), inside their timing scope.
  void recordBuild(VkCommandBuffer cmd);

  // The cube view the sky pass samples.
  VkImageView view() const { return image_->cubeView; }
  // The sky pass's cloud values for a frame at `timeS`: SkyUniforms::clouds, cloudShape and
  // cloudMotion (whether clouds are drawn at all is the sky pass's cameraPlanet.w).
  void writeUniforms(gpu::SkyUniforms& u, double timeS) const;

 private:
  CloudDescription clouds_;
  double radiusM_ = 0.0;
  // In the order of creation (destroyed in reverse).
  vk::Owned<vk::Image> image_;
  vk::Owned<vk::ComputePipeline> pipeline_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;  // from pipeline_'s pool
};

}  // namespace planet
