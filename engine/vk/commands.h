// One-shot command submission: record with a callback, submit, wait. For uploads, readbacks
// and headless work; the frame ring (frame_ring.h) reuses its own pool instead. Also the plain
// creation of the objects both need (vk::Owned destroys them).
#pragma once

#include <cstdint>
#include <functional>

#include <vulkan/vulkan.h>

namespace planet::vk {

class Context;

// How long submitAndWait waits for the GPU before treating it as hung (VK_ERROR_DEVICE_LOST).
inline constexpr uint64_t kSubmitTimeoutNs = 120ull * 1000 * 1000 * 1000;

// A command pool on the universal queue family.
VkCommandPool createCommandPool(Context& context, VkCommandPoolCreateFlags flags);
// An unsignalled fence.
VkFence createFence(Context& context);
// A binary semaphore.
VkSemaphore createSemaphore(Context& context);

// Records `record` into a fresh primary command buffer on the universal queue, submits it
// and blocks until it completes. Throws planet::VulkanError on failure or timeout.
void submitAndWait(Context& context, const std::function<void(VkCommandBuffer)>& record);

// A global memory barrier between two (stage, access) pairs, for the common compute ->
// transfer / transfer -> compute hand-overs.
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

}  // namespace planet::vk
