// The command buffers, fences and acquire semaphores of kFramesInFlight frame slots: the viewer's,
// and, without a swapchain, the soak's and the frames-in-flight test's, which drive a Renderer the
// same way.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "vk/buffer.h"
#include "vk/owned.h"

namespace planet::vk {

class Context;

class FrameRing {
 public:
  explicit FrameRing(Context& context);
  ~FrameRing();  // waits for every submitted frame first
  FrameRing(const FrameRing&) = delete;
  FrameRing& operator=(const FrameRing&) = delete;

  // Resets the slot's command buffer and begins it (one-time submit). Wait for the slot first.
  VkCommandBuffer begin(uint32_t slot);
  // Ends the slot's command buffer and submits it on the graphics queue with the slot's fence.
  void submit(uint32_t slot);
  // As submit, for a frame drawn into a swapchain image acquired with acquireSemaphore(slot):
  // the commands wait for that semaphore at `acquireStage`, and `rendered` (the image's present
  // semaphore) is signalled when they complete.
  void submitForPresent(uint32_t slot, VkPipelineStageFlags2 acquireStage, VkSemaphore rendered);
  // Waits for the slot's last frame; true when there was one.
  bool wait(uint32_t slot);
  void waitAll();

  // The binary semaphore vkAcquireNextImageKHR signals for the slot's frame (unused without a
  // swapchain). Each slot has its own: the other slot's acquire may still be pending.
  VkSemaphore acquireSemaphore(uint32_t slot) const;

 private:
  void submitWith(uint32_t slot, const VkSemaphoreSubmitInfo* wait, const VkSemaphoreSubmitInfo* signal);

  Context& context_;
  bool submitted_[kFramesInFlight] = {};
  // In the order of creation (destroyed in reverse).
  Owned<VkCommandPool> pool_;
  VkCommandBuffer cmd_[kFramesInFlight] = {};  // from pool_
  Owned<VkFence> fences_[kFramesInFlight];
  Owned<VkSemaphore> acquired_[kFramesInFlight];
};

}  // namespace planet::vk
