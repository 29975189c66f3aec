// The luminance pass (issue 21, point 4): eye adaptation's measurement. Two compute dispatches
// after the sky's compose pass and before the tonemap of the same frame: the luminance
// histogram of the HDR frame (shaders/luminance_histogram.comp), then the trimmed log-average,
// the exposure for it and the exposure applied (shaders/luminance_exposure.comp), written to a
// buffer the tonemap reads. A histogram, not a plain log-average, because the frames this
// renderer draws are often half black (space, the night sky, an airless body's sky), and a
// log-average over black pixels depends on the floor chosen for them: ranking the pixels and
// measuring the brighter half exposes the lit part of the view whatever the black part is.
// The method and its numbers are in render/exposure.h, which holds its CPU reference.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "render/exposure.h"
#include "vk/buffer.h"
#include "vk/image.h"
#include "vk/owned.h"

namespace planet::vk {
class Context;
class GpuTimer;
}  // namespace planet::vk

namespace planet {

class LuminancePass {
 public:
  // Timing scopes a frame records at most: "luminance".
  static constexpr uint32_t kTimingScopes = 1;

  explicit LuminancePass(vk::Context& context);

  // Points the pass at the HDR colour it reads (storage image, GENERAL); call again when it is
  // recreated. The exposure carried over frames stays.
  void setSource(const vk::Image& hdr);
  // The city lights' gain (the preset's `[lights] gain`, 1 without lights): the measurement
  // counts their light divided by it (shared/exposure_params.h).
  void setLightsGain(double gain) { lightsPhysical_ = exposureLightsPhysical(gain); }
  // Records both dispatches for frame slot `slot`, with the HDR frame in GENERAL after the
  // compose pass's writes (the pass's first barrier orders them). `stepS`: seconds since the
  // last frame this pass adapted, for the viewer's adaptation; negative: this frame's exposure
  // outright (planet render, planet bench). Ends with exposure() visible to fragment shaders
  // and the slot's report to the host.
  void record(VkCommandBuffer cmd, uint32_t slot, double stepS, vk::GpuTimer* timer);

  // The buffer the tonemap reads (ExposureState): zero before the first frame.
  const vk::Buffer& exposure() const { return *state_; }
  // What the last frame recorded for `slot` measured and applied: read after its fence
  // signalled (zeros before the slot's first frame).
  ExposureReport report(uint32_t slot) const;
  // The last frame's histogram (blocking read-back; call when no frame is in flight).
  ExposureHistogram readHistogram();

 private:
  vk::Context& context_;
  uint32_t width_ = 0, height_ = 0;
  float lightsPhysical_ = 1.0f;
  // In the order of creation (destroyed in reverse).
  vk::Owned<vk::Buffer> histogram_;
  vk::Owned<vk::Buffer> state_;
  vk::Owned<vk::Buffer> reports_[vk::kFramesInFlight];  // host-visible, per frame slot
  vk::Owned<VkDescriptorSetLayout> setLayout_;
  vk::Owned<VkDescriptorPool> pool_;
  vk::Owned<VkPipelineLayout> layout_;
  vk::Owned<VkPipeline> histogramPipeline_;
  vk::Owned<VkPipeline> exposurePipeline_;
  VkDescriptorSet sets_[vk::kFramesInFlight] = {};  // from pool_, each writes its slot's report
};

}  // namespace planet
