#include "vk/frame_ring.h"

#include "core/error.h"
#include "vk/commands.h"
#include "vk/context.h"

namespace planet::vk {

FrameRing::FrameRing(Context& context) : context_(context) {
  pool_ = {context, createCommandPool(context, VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT)};
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = pool_.get();
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = kFramesInFlight;
  VK_CHECK(vkAllocateCommandBuffers(context.device, &alloc, cmd_));
  for (Owned<VkFence>& fence : fences_) fence = {context, createFence(context)};
  for (Owned<VkSemaphore>& semaphore : acquired_) semaphore = {context, createSemaphore(context)};
}

FrameRing::~FrameRing() {
  // Nothing may still execute when the fences and command buffers go (the members, after this).
  for (bool submitted : submitted_)
    if (submitted) {
      vkDeviceWaitIdle(context_.device);
      break;
    }
}

VkCommandBuffer FrameRing::begin(uint32_t slot) {
  checkFrameSlot(slot);
  VK_CHECK(vkResetCommandBuffer(cmd_[slot], 0));
  VkCommandBufferBeginInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd_[slot], &info));
  return cmd_[slot];
}

void FrameRing::submit(uint32_t slot) { submitWith(slot, nullptr, nullptr); }

void FrameRing::submitForPresent(uint32_t slot, VkPipelineStageFlags2 acquireStage, VkSemaphore rendered) {
  checkFrameSlot(slot);
  VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  wait.semaphore = acquired_[slot].get();
  wait.stageMask = acquireStage;
  VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  signal.semaphore = rendered;
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  submitWith(slot, &wait, &signal);
}

void FrameRing::submitWith(uint32_t slot, const VkSemaphoreSubmitInfo* wait, const VkSemaphoreSubmitInfo* signal) {
  checkFrameSlot(slot);
  VK_CHECK(vkEndCommandBuffer(cmd_[slot]));
  VK_CHECK(vkResetFences(context_.device, 1, &fences_[slot].get()));
  VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmdInfo.commandBuffer = cmd_[slot];
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.waitSemaphoreInfoCount = wait ? 1 : 0;
  submit.pWaitSemaphoreInfos = wait;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmdInfo;
  submit.signalSemaphoreInfoCount = signal ? 1 : 0;
  submit.pSignalSemaphoreInfos = signal;
  VK_CHECK(queueSubmit(context_, context_.graphicsQueue, submit, fences_[slot].get()));
  submitted_[slot] = true;
}

bool FrameRing::wait(uint32_t slot) {
  checkFrameSlot(slot);
  if (!submitted_[slot]) return false;
  VK_CHECK(vkWaitForFences(context_.device, 1, &fences_[slot].get(), VK_TRUE, kSubmitTimeoutNs));
  submitted_[slot] = false;
  return true;
}

void FrameRing::waitAll() {
  for (uint32_t slot = 0; slot < kFramesInFlight; ++slot) wait(slot);
}

VkSemaphore FrameRing::acquireSemaphore(uint32_t slot) const {
  checkFrameSlot(slot);
  return acquired_[slot].get();
}

}  // namespace planet::vk
