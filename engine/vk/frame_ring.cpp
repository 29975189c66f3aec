#include "vk/frame_ring.h"

#include "core/error.h"
#include "vk/commands.h"
#include "vk/context.h"

namespace planet::vk {

FrameRing::FrameRing(Context& context) : context_(context) {
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = context.universalFamily;
  VK_CHECK(vkCreateCommandPool(context.device, &poolInfo, nullptr, &pool_));
  try {
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = kFramesInFlight;
    VK_CHECK(vkAllocateCommandBuffers(context.device, &alloc, cmd_));
    for (VkFence& fence : fences_) {
      VkFenceCreateInfo info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
      VK_CHECK(vkCreateFence(context.device, &info, nullptr, &fence));
    }
    for (VkSemaphore& semaphore : acquired_) {
      VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
      VK_CHECK(vkCreateSemaphore(context.device, &info, nullptr, &semaphore));
    }
  } catch (...) {
    release();
    throw;
  }
}

FrameRing::~FrameRing() {
  // Nothing may still execute when the fences and command buffers go.
  for (bool submitted : submitted_)
    if (submitted) {
      vkDeviceWaitIdle(context_.device);
      break;
    }
  release();
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
  wait.semaphore = acquired_[slot];
  wait.stageMask = acquireStage;
  VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  signal.semaphore = rendered;
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  submitWith(slot, &wait, &signal);
}

void FrameRing::submitWith(uint32_t slot, const VkSemaphoreSubmitInfo* wait, const VkSemaphoreSubmitInfo* signal) {
  checkFrameSlot(slot);
  VK_CHECK(vkEndCommandBuffer(cmd_[slot]));
  VK_CHECK(vkResetFences(context_.device, 1, &fences_[slot]));
  VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmdInfo.commandBuffer = cmd_[slot];
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.waitSemaphoreInfoCount = wait ? 1 : 0;
  submit.pWaitSemaphoreInfos = wait;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmdInfo;
  submit.signalSemaphoreInfoCount = signal ? 1 : 0;
  submit.pSignalSemaphoreInfos = signal;
  VK_CHECK(queueSubmit(context_, context_.graphicsQueue, submit, fences_[slot]));
  submitted_[slot] = true;
}

bool FrameRing::wait(uint32_t slot) {
  checkFrameSlot(slot);
  if (!submitted_[slot]) return false;
  VK_CHECK(vkWaitForFences(context_.device, 1, &fences_[slot], VK_TRUE, kSubmitTimeoutNs));
  submitted_[slot] = false;
  return true;
}

void FrameRing::waitAll() {
  for (uint32_t slot = 0; slot < kFramesInFlight; ++slot) wait(slot);
}

VkSemaphore FrameRing::acquireSemaphore(uint32_t slot) const {
  checkFrameSlot(slot);
  return acquired_[slot];
}

void FrameRing::release() {
  for (VkSemaphore semaphore : acquired_)
    if (semaphore) vkDestroySemaphore(context_.device, semaphore, nullptr);
  for (VkFence fence : fences_)
    if (fence) vkDestroyFence(context_.device, fence, nullptr);
  if (pool_) vkDestroyCommandPool(context_.device, pool_, nullptr);
}

}  // namespace planet::vk
