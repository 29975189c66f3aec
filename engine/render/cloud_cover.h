// The clouds (issue 4; seed 001 §4.4; issue 20 point 4): a layer between two heights whose
// density comes from three cube maps of weather-shaped fractal noise (shaders/clouds_cover.comp:
// cyclones, zonal winds, domain warping, latitude bands), built once per planet with the sky
// tables together with their mip levels, blended over time (cloudMotion) and drifting with the
// wind. The sky pass composes them (shaders/sky.comp: a few samples through the layer, lit through
// its thickness, and their shadows) from the values writeUniforms gives it.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "planet/planet_description.h"
#include "shared/sky_params.h"
#include "vk/buffer.h"
#include "vk/image.h"
#include "vk/owned.h"
#include "vk/pipeline.h"

namespace planet::vk {
class Context;
}  // namespace planet::vk

namespace planet {

// The cloud layer's state at `timeS` (seed 001 §4.4): the weights of the three cover images
// (its eq. 4.2, summing to 1) and the drift angle about the planet's axis.
struct CloudMotion {
  glm::vec3 weights;
  float driftRad;
};
CloudMotion cloudMotion(const CloudDescription& clouds, double radiusM, double timeS);

// The cyclones of the cover (CloudDescription::cyclones per hemisphere, from its seed): mid-
// latitude ones between 35° and 65°, a fifth of them tropical (10–22°, smaller, tighter, with a
// clear eye); the twist is counter-clockwise seen from above in the north, clockwise in the south.
std::vector<gpu::CloudVortex> cloudVortices(const CloudDescription& clouds, double radiusM);

// The cover images (rgb: the three images, one per channel) and the compute pass that fills them.
class CloudCover {
 public:
  // A planet without clouds gets a tiny cube that is bound but never sampled.
  CloudCover(vk::Context& context, const PlanetDescription& planet);

  // Records the build: the noise into level 0 (planets with clouds), the mip levels by halving
  // blits, and every level to SHADER_READ_ONLY_OPTIMAL for compute and fragment shaders. Once per
  // planet (the sky tables' first frame), inside their timing scope.
  void recordBuild(VkCommandBuffer cmd);

  // The cube view (all mip levels) the sky pass samples, with its trilinear sampler.
  VkImageView view() const { return image_->cubeView; }
  VkSampler sampler() const { return sampler_.get(); }
  uint32_t size() const { return image_->extent.width; }
  uint32_t mipLevels() const { return mipLevels_; }
  // For tests: level 0 of the built cover (rgba8, face after face, row-major), blocking.
  std::vector<uint8_t> readLevel0();
  // The layer's values for a frame at `timeS`, as SkyUniforms::clouds, cloudShape and cloudMotion
  // hold them (the sea's FrameUniforms the same; whether clouds are drawn at all is each pass's).
  struct Layer {
    glm::vec4 clouds;
    glm::vec4 shape;
    glm::vec4 motion;
  };
  Layer layerAt(double timeS) const;
  // The sky pass's: SkyUniforms::clouds, cloudShape and cloudMotion.
  void writeUniforms(gpu::SkyUniforms& u, double timeS) const;

 private:
  CloudDescription clouds_;
  double radiusM_ = 0.0;
  vk::Context& context_;
  uint32_t mipLevels_ = 1;
  // In the order of creation (destroyed in reverse).
  vk::Owned<vk::Image> image_;
  vk::Owned<VkSampler> sampler_;
  vk::Owned<vk::Buffer> weather_;  // gpu::CloudWeather
  vk::Owned<vk::ComputePipeline> pipeline_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;  // from pipeline_'s pool
};

}  // namespace planet
