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
// The general form: set 0 binding i has type bindings[i] (storage buffer, storage image,
// combined image sampler, uniform buffer), one descriptor each.
ComputePipeline createComputePipeline(Context& context, std::span<const uint32_t> spirv,
                                      std::span<const VkDescriptorType> bindings, uint32_t pushConstantSize,
                                      std::span<const uint32_t> specialization = {}, uint32_t maxSets = 4);
void destroyComputePipeline(Context& context, ComputePipeline& pipeline);

// A pipeline layout over one descriptor set layout (or none) plus a push-constant range of
// `pushConstantSize` bytes (none when 0) for `pushStages`.
VkPipelineLayout createPipelineLayout(Context& context, VkDescriptorSetLayout setLayout, uint32_t pushConstantSize,
                                      VkShaderStageFlags pushStages);
// A compute pipeline over an existing layout; `specialization[i]` is the uint specialization
// constant with constant_id i. Passes that share one set between compute and graphics shaders
// use this directly. Taken from the context's pipeline store (vk/pipeline_store.h) when it has it.
VkPipeline createComputePipelineWithLayout(Context& context, std::span<const uint32_t> spirv, VkPipelineLayout layout,
                                           std::span<const uint32_t> specialization = {});

// A descriptor set layout with bindings[i] at binding i, visible to `stages`, and a pool for
// `maxSets` such sets (graphics passes use these; compute pipelines make their own).
VkDescriptorSetLayout createSetLayout(Context& context, std::span<const VkDescriptorType> bindings,
                                      VkShaderStageFlags stages);
VkDescriptorPool createDescriptorPool(Context& context, std::span<const VkDescriptorType> bindings, uint32_t maxSets);
// createSetLayout and createPipelineLayout without telling the context's pipeline store of them:
// the store makes its own layouts with these.
VkDescriptorSetLayout createSetLayoutOn(VkDevice device, std::span<const VkDescriptorType> bindings,
                                        VkShaderStageFlags stages);
VkPipelineLayout createPipelineLayoutOn(VkDevice device, VkDescriptorSetLayout setLayout, uint32_t pushConstantSize,
                                        VkShaderStageFlags pushStages);
VkDescriptorSet allocateSet(Context& context, VkDescriptorPool pool, VkDescriptorSetLayout layout);
// Points one binding of `set` at a whole buffer (storage or uniform, as `type` says).
void writeBufferDescriptor(Context& context, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                           const Buffer& buffer);
// Points one binding of `set` (a uniform texel buffer) at a buffer view.
void writeTexelBufferDescriptor(Context& context, VkDescriptorSet set, uint32_t binding, VkBufferView view);
// Points one binding of `set` at an image view (storage image: sampler null; combined image sampler).
void writeImageDescriptor(Context& context, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                          VkImageView view, VkImageLayout layout, VkSampler sampler = VK_NULL_HANDLE);

// Allocates a set from the pipeline's pool and points binding i at buffers[i] (whole range).
VkDescriptorSet allocateStorageSet(Context& context, const ComputePipeline& pipeline,
                                   std::span<const Buffer* const> buffers);

}  // namespace planet::vk
