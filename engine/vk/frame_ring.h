// The command buffers and fences of kFramesInFlight frame slots, as the viewer has them, without
// a swapchain: for the soak and the frames-in-flight test, which drive a Renderer the same way.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "vk/buffer.h"

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
  // Waits for the slot's last frame; true when there was one.
  bool wait(uint32_t slot);
  void waitAll();

 private:
  void release();

  Context& context_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_[kFramesInFlight] = {};
  VkFence fences_[kFramesInFlight] = {};
  bool submitted_[kFramesInFlight] = {};
};

}  // namespace planet::vk
