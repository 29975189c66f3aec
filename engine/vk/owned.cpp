#include "vk/owned.h"

#include <type_traits>

#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/image.h"
#include "vk/pipeline.h"

namespace planet::vk {

// The overloads below tell handles apart by type: on 32-bit targets Vulkan's non-dispatchable
// handles are all uint64_t and would collide.
static_assert(!std::is_same_v<VkPipeline, VkSampler>, "Owned needs typed Vulkan handles (a 64-bit target)");

void destroyOwned(Context& context, Buffer& buffer) { destroyBuffer(context, buffer); }
void destroyOwned(Context& context, Image& image) { destroyImage(context, image); }
void destroyOwned(Context& context, ComputePipeline& pipeline) { destroyComputePipeline(context, pipeline); }

void destroyOwned(Context& context, VkPipeline& pipeline) {
  if (pipeline) vkDestroyPipeline(context.device, pipeline, nullptr);
  pipeline = VK_NULL_HANDLE;
}

void destroyOwned(Context& context, VkPipelineLayout& layout) {
  if (layout) vkDestroyPipelineLayout(context.device, layout, nullptr);
  layout = VK_NULL_HANDLE;
}

void destroyOwned(Context& context, VkDescriptorSetLayout& layout) {
  if (layout) vkDestroyDescriptorSetLayout(context.device, layout, nullptr);
  layout = VK_NULL_HANDLE;
}

void destroyOwned(Context& context, VkDescriptorPool& pool) {
  if (pool) vkDestroyDescriptorPool(context.device, pool, nullptr);
  pool = VK_NULL_HANDLE;
}

void destroyOwned(Context& context, VkSampler& sampler) {
  if (sampler) vkDestroySampler(context.device, sampler, nullptr);
  sampler = VK_NULL_HANDLE;
}

void destroyOwned(Context& context, VkShaderModule& module) {
  if (module) vkDestroyShaderModule(context.device, module, nullptr);
  module = VK_NULL_HANDLE;
}

void destroyOwned(Context& context, VkQueryPool& pool) {
  if (pool) vkDestroyQueryPool(context.device, pool, nullptr);
  pool = VK_NULL_HANDLE;
}

}  // namespace planet::vk
