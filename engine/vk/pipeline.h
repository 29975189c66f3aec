// Compute pipelines from embedded SPIR-V, with one descriptor set of storage buffers and a
// push-constant block, and the descriptor pool that feeds them.
#pragma once

#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

namespace planet::vk {

class Context;
struct Buffer;

struct ComputePipeline {
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkDescriptorPool descriptorPool = VK_NULL_HANDLE;
  uint32_t pushConstantSize = 0;
};

VkShaderModule createShaderModule(Context& context, std::span<const uint32_t> spirv);

// A compute pipeline whose set 0 holds `storageBufferCount` storage buffers at bindings
// 0..n-1 and whose push constants are `pushConstantSize` bytes. `specialization[i]` is the
// value of the uint specialization constant with constant_id i. `maxSets` descriptor sets
// can be allocated from its pool.
ComputePipeline createComputePipeline(Context& context, std::span<const uint32_t> spirv, uint32_t storageBufferCount,
                                      uint32_t pushConstantSize, std::span<const uint32_t> specialization = {},
                                      uint32_t maxSets = 4);
void destroyComputePipeline(Context& context, ComputePipeline& pipeline);

// Allocates a set from the pipeline's pool and points binding i at buffers[i] (whole range).
VkDescriptorSet allocateStorageSet(Context& context, const ComputePipeline& pipeline,
                                   std::span<const Buffer* const> buffers);

}  // namespace planet::vk
