#include "render/luminance_pass.h"

#include <cstring>

#include "spv/luminance_exposure.comp.h"
#include "spv/luminance_histogram.comp.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/pipeline.h"
#include "vk/timer.h"

namespace planet {
namespace {

// Both dispatches share one layout; each reads the bindings it names.
constexpr VkDescriptorType kBindings[] = {
    VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,   // kExposureBindingColor
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,  // kExposureBindingHistogram
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,  // kExposureBindingState
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,  // kExposureBindingReport
};
static_assert(gpu::kExposureBindingColor == 0 && gpu::kExposureBindingHistogram == 1 &&
              gpu::kExposureBindingState == 2 && gpu::kExposureBindingReport == 3);
// One invocation per bin in the histogram's shared-memory pass.
static_assert(gpu::kExposureBins == gpu::kExposureWorkgroupSize * gpu::kExposureWorkgroupSize);

constexpr VkDeviceSize kHistogramBytes = sizeof(uint32_t) * gpu::kExposureBins;

}  // namespace

LuminancePass::LuminancePass(vk::Context& context) : context_(context) {
  const VkBufferUsageFlags usage =
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  histogram_ = {context, vk::createBuffer(context, kHistogramBytes, usage, vk::MemoryUsage::DeviceLocal)};
  state_ = {context, vk::createBuffer(context, sizeof(gpu::ExposureState), usage, vk::MemoryUsage::DeviceLocal)};
  for (vk::Owned<vk::Buffer>& report : reports_) {
    report = {context, vk::createBuffer(context, sizeof(gpu::ExposureState), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        vk::MemoryUsage::Readback)};
    std::memset(report->mapped(), 0, sizeof(gpu::ExposureState));
  }
  // No exposure yet: the first adapted frame takes its target outright, and the tonemap of a
  // fixed-exposure frame, which binds the state too, reads a finite number.
  vk::submitAndWait(context, [&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, state_->buffer, 0, VK_WHOLE_SIZE, 0);
    vkCmdFillBuffer(cmd, histogram_->buffer, 0, VK_WHOLE_SIZE, 0);
  });

  setLayout_ = {context, vk::createSetLayout(context, kBindings, VK_SHADER_STAGE_COMPUTE_BIT)};
  pool_ = {context, vk::createDescriptorPool(context, kBindings, vk::kFramesInFlight)};
  layout_ = {context, vk::createPipelineLayout(context, setLayout_.get(), sizeof(gpu::ExposurePush),
                                               VK_SHADER_STAGE_COMPUTE_BIT)};
  histogramPipeline_ = {context,
                        vk::createComputePipelineWithLayout(context, kSpv_luminance_histogram_comp, layout_.get())};
  exposurePipeline_ = {context,
                       vk::createComputePipelineWithLayout(context, kSpv_luminance_exposure_comp, layout_.get())};
  for (uint32_t slot = 0; slot < vk::kFramesInFlight; ++slot) {
    VkDescriptorSet set = sets_[slot] = vk::allocateSet(context, pool_.get(), setLayout_.get());
    vk::writeBufferDescriptor(context, set, gpu::kExposureBindingHistogram, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                              *histogram_);
    vk::writeBufferDescriptor(context, set, gpu::kExposureBindingState, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, *state_);
    vk::writeBufferDescriptor(context, set, gpu::kExposureBindingReport, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                              *reports_[slot]);
  }
}

void LuminancePass::setSource(const vk::Image& hdr) {
  for (VkDescriptorSet set : sets_)
    vk::writeImageDescriptor(context_, set, gpu::kExposureBindingColor, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, hdr.view,
                             VK_IMAGE_LAYOUT_GENERAL);
  width_ = hdr.extent.width;
  height_ = hdr.extent.height;
}

void LuminancePass::record(VkCommandBuffer cmd, uint32_t slot, double stepS, vk::GpuTimer* timer) {
  vk::checkFrameSlot(slot);
  if (timer) timer->begin(cmd, "luminance");
  // The histogram reads what the compose pass wrote; the clear below overwrites the counts the
  // previous frame's exposure dispatch read, and that dispatch's state the tonemap read.
  vk::memoryBarrier(
      cmd,
      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
          VK_PIPELINE_STAGE_2_TRANSFER_BIT,
      VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
  vkCmdFillBuffer(cmd, histogram_->buffer, 0, VK_WHOLE_SIZE, 0);
  // The groups add their counts to the cleared histogram.
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  gpu::ExposurePush push{};
  push.frame = glm::vec4(float(width_), float(height_), float(stepS), lightsPhysical_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &sets_[slot], 0, nullptr);
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, histogramPipeline_.get());
  const uint32_t group = 2 * gpu::kExposureWorkgroupSize;  // pixels: each invocation measures a 2 × 2 block
  vkCmdDispatch(cmd, (width_ + group - 1) / group, (height_ + group - 1) / group, 1);
  // The exposure dispatch reads the finished histogram.
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, exposurePipeline_.get());
  vkCmdDispatch(cmd, 1, 1, 1);
  // The tonemap's fragments read the exposure; the host reads the slot's report after the fence.
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_HOST_READ_BIT);
  if (timer) timer->end(cmd);
}

ExposureReport LuminancePass::report(uint32_t slot) const {
  vk::checkFrameSlot(slot);
  context_.allocator.invalidate(reports_[slot]->allocation);
  gpu::ExposureState state;
  std::memcpy(&state, reports_[slot]->mapped(), sizeof(state));
  ExposureReport report;
  report.exposure = state.values.x;
  report.target = state.values.y;
  report.log2Luminance = state.values.z;
  report.pixels = state.values.w;
  return report;
}

ExposureHistogram LuminancePass::readHistogram() {
  ExposureHistogram histogram{};
  vk::readbackBuffer(context_, *histogram_, histogram.data(), kHistogramBytes);
  return histogram;
}

}  // namespace planet
