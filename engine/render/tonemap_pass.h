// The tonemap pass (issue 4, point 2; DESIGN.md "One frame", the last step): a full-screen
// triangle that reads the composed HDR target and writes the display target with an exposure and
// a filmic curve (shaders/tonemap.frag). One per frame, after every body's sky pass and, with
// eye adaptation, after the luminance pass (luminance_pass.h) that measured the frame.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "vk/buffer.h"
#include "vk/image.h"
#include "vk/owned.h"

namespace planet::vk {
class Context;
class GpuTimer;
}  // namespace planet::vk

namespace planet {

class TonemapPass {
 public:
  // Timing scopes a frame records at most: "tonemap".
  static constexpr uint32_t kTimingScopes = 1;

  // The pipeline draws into a dynamic-rendering scope of one colour attachment of outputFormat.
  // `exposure` scales the HDR values before the curve (SkySettings::exposure) while the pass is
  // not adapting; `adapted` (an ExposureState, LuminancePass::exposure()) holds the exposure it
  // applies while it is, and must outlive the pass.
  TonemapPass(vk::Context& context, VkFormat outputFormat, double exposure, const vk::Buffer& adapted);

  // Points the pass at the HDR colour it reads (storage image, GENERAL); call again when it is
  // recreated.
  void setSource(const vk::Image& hdr);
  // Takes effect at the next recordDraw (a push constant).
  void setExposure(double exposure) { exposure_ = exposure; }
  // Takes effect at the next recordDraw: true applies the exposure in `adapted` (written earlier
  // in the same frame, with a barrier to fragment shaders), false the fixed one.
  void setAdapting(bool adapting) { adapting_ = adapting; }
  // Inside a dynamic-rendering scope on the output target, after the sky passes' writes are
  // visible to fragment shaders.
  void recordDraw(VkCommandBuffer cmd, vk::GpuTimer* timer);

 private:
  vk::Context& context_;
  double exposure_ = 1.0;
  bool adapting_ = false;
  // In the order of creation (destroyed in reverse).
  vk::Owned<VkDescriptorSetLayout> setLayout_;
  vk::Owned<VkDescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;  // from pool_
  vk::Owned<VkPipelineLayout> layout_;
  vk::Owned<VkPipeline> pipeline_;
};

}  // namespace planet
