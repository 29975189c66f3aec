#include "vk/commands.h"

#include "core/error.h"
#include "vk/context.h"
#include "vk/owned.h"

namespace planet::vk {

VkCommandPool createCommandPool(Context& context, VkCommandPoolCreateFlags flags) {
  VkCommandPoolCreateInfo info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  info.flags = flags;
  info.queueFamilyIndex = context.universalFamily;
  VkCommandPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateCommandPool(context.device, &info, nullptr, &pool));
  return pool;
}

VkFence createFence(Context& context) {
  VkFenceCreateInfo info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  VK_CHECK(vkCreateFence(context.device, &info, nullptr, &fence));
  return fence;
}

VkSemaphore createSemaphore(Context& context) {
  VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VkSemaphore semaphore = VK_NULL_HANDLE;
  VK_CHECK(vkCreateSemaphore(context.device, &info, nullptr, &semaphore));
  return semaphore;
}

void submitAndWait(Context& context, const std::function<void(VkCommandBuffer)>& record) {
  // The pool and the fence are destroyed on every path, including a throwing `record`.
  const Owned<VkCommandPool> pool(context, createCommandPool(context, VK_COMMAND_POOL_CREATE_TRANSIENT_BIT));

  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = pool.get();
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateCommandBuffers(context.device, &allocInfo, &cmd));

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  record(cmd);
  VK_CHECK(vkEndCommandBuffer(cmd));

  const Owned<VkFence> fence(context, createFence(context));
  VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmdInfo.commandBuffer = cmd;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmdInfo;
  VK_CHECK(queueSubmit(context, context.graphicsQueue, submit, fence.get()));
  VkResult wait = vkWaitForFences(context.device, 1, &fence.get(), VK_TRUE, kSubmitTimeoutNs);
  if (wait == VK_TIMEOUT)
    throw VulkanError(VK_ERROR_DEVICE_LOST,
                      "GPU work did not finish within " + std::to_string(kSubmitTimeoutNs / 1000000000) + " s");
  VK_CHECK(wait);
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  barrier.srcStageMask = srcStage;
  barrier.srcAccessMask = srcAccess;
  barrier.dstStageMask = dstStage;
  barrier.dstAccessMask = dstAccess;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace planet::vk
