#include "vk/owned.h"

#include <type_traits>

#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/image.h"
#include "vk/pipeline.h"
#include "vk/swapchain.h"

namespace planet::vk {

// The overloads below tell handles apart by type: on 32-bit targets Vulkan's non-dispatchable
// handles are all uint64_t and would collide.
static_assert(!std::is_same_v<VkPipeline, VkSampler>, "Owned needs typed Vulkan handles (a 64-bit target)");

void destroyOwned(Context& context, Buffer& buffer) { destroyBuffer(context, buffer); }
void destroyOwned(Context& context, Image& image) { destroyImage(context, image); }
void destroyOwned(Context& context, ComputePipeline& pipeline) { destroyComputePipeline(context, pipeline); }
void destroyOwned(Context& context, Swapchain& swapchain) { destroySwapchain(context, swapchain); }

namespace {

// Destroys `handle` with the device-level `destroy` (a null handle is skipped) and clears it.
template <typename Handle>
void destroyDeviceHandle(Context& context, Handle& handle, void (*destroy)(VkDevice, Handle, const VkAllocationCallbacks*)) {
  if (handle) destroy(context.device, handle, nullptr);
  handle = VK_NULL_HANDLE;
}

}  // namespace

// A pipeline from the context's store goes back to it (vk/pipeline_store.h); layouts are
// forgotten by the store before their handles can be reused.
void destroyOwned(Context& context, VkPipeline& pipeline) {
  if (pipeline && context.pipelines.release(context.device, pipeline)) pipeline = VK_NULL_HANDLE;
  destroyDeviceHandle(context, pipeline, vkDestroyPipeline);
}
void destroyOwned(Context& context, VkPipelineLayout& layout) {
  if (layout) context.pipelines.forgetPipelineLayout(layout);
  destroyDeviceHandle(context, layout, vkDestroyPipelineLayout);
}
void destroyOwned(Context& context, VkDescriptorSetLayout& layout) {
  if (layout) context.pipelines.forgetSetLayout(layout);
  destroyDeviceHandle(context, layout, vkDestroyDescriptorSetLayout);
}
void destroyOwned(Context& context, VkDescriptorPool& pool) { destroyDeviceHandle(context, pool, vkDestroyDescriptorPool); }
void destroyOwned(Context& context, VkSampler& sampler) { destroyDeviceHandle(context, sampler, vkDestroySampler); }
void destroyOwned(Context& context, VkBufferView& view) { destroyDeviceHandle(context, view, vkDestroyBufferView); }
void destroyOwned(Context& context, VkShaderModule& module) { destroyDeviceHandle(context, module, vkDestroyShaderModule); }
void destroyOwned(Context& context, VkQueryPool& pool) { destroyDeviceHandle(context, pool, vkDestroyQueryPool); }
void destroyOwned(Context& context, VkCommandPool& pool) { destroyDeviceHandle(context, pool, vkDestroyCommandPool); }
void destroyOwned(Context& context, VkFence& fence) { destroyDeviceHandle(context, fence, vkDestroyFence); }
void destroyOwned(Context& context, VkSemaphore& semaphore) { destroyDeviceHandle(context, semaphore, vkDestroySemaphore); }
void destroyOwned(Context& context, VkRenderPass& pass) { destroyDeviceHandle(context, pass, vkDestroyRenderPass); }
void destroyOwned(Context& context, VkFramebuffer& framebuffer) {
  destroyDeviceHandle(context, framebuffer, vkDestroyFramebuffer);
}

// The surface belongs to the instance, not the device.
void destroyOwned(Context& context, VkSurfaceKHR& surface) {
  if (surface) vkDestroySurfaceKHR(context.instance, surface, nullptr);
  surface = VK_NULL_HANDLE;
}

}  // namespace planet::vk
