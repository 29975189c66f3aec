#include "vk/pipeline.h"

#include <algorithm>
#include <string>
#include <vector>

#include "core/error.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/owned.h"

namespace planet::vk {

VkShaderModule createShaderModule(Context& context, std::span<const uint32_t> spirv) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = spirv.size_bytes();
  info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  VK_CHECK(vkCreateShaderModule(context.device, &info, nullptr, &module));
  return module;
}

ComputePipeline createComputePipeline(Context& context, std::span<const uint32_t> spirv, uint32_t storageBufferCount,
                                      uint32_t pushConstantSize, std::span<const uint32_t> specialization,
                                      uint32_t maxSets) {
  std::vector<VkDescriptorType> bindings(storageBufferCount, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  return createComputePipeline(context, spirv, bindings, pushConstantSize, specialization, maxSets);
}

VkDescriptorSetLayout createSetLayout(Context& context, std::span<const VkDescriptorType> bindings,
                                      VkShaderStageFlags stages) {
  VkDescriptorSetLayout layout = createSetLayoutOn(context.device, bindings, stages);
  context.pipelines.noteSetLayout(layout, bindings, stages);
  return layout;
}

VkDescriptorSetLayout createSetLayoutOn(VkDevice device, std::span<const VkDescriptorType> bindings,
                                        VkShaderStageFlags stages) {
  std::vector<VkDescriptorSetLayoutBinding> entries(bindings.size());
  for (uint32_t i = 0; i < entries.size(); ++i) entries[i] = {i, bindings[i], 1, stages, nullptr};
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = uint32_t(entries.size());
  setInfo.pBindings = entries.data();
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &layout));
  return layout;
}

VkDescriptorPool createDescriptorPool(Context& context, std::span<const VkDescriptorType> bindings, uint32_t maxSets) {
  std::vector<VkDescriptorPoolSize> sizes;
  for (VkDescriptorType type : bindings) {
    auto it = std::find_if(sizes.begin(), sizes.end(), [&](const VkDescriptorPoolSize& s) { return s.type == type; });
    if (it == sizes.end())
      sizes.push_back({type, maxSets});
    else
      it->descriptorCount += maxSets;
  }
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = maxSets;
  poolInfo.poolSizeCount = uint32_t(sizes.size());
  poolInfo.pPoolSizes = sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorPool(context.device, &poolInfo, nullptr, &pool));
  return pool;
}

VkPipelineLayout createPipelineLayout(Context& context, VkDescriptorSetLayout setLayout, uint32_t pushConstantSize,
                                      VkShaderStageFlags pushStages) {
  VkPipelineLayout layout = createPipelineLayoutOn(context.device, setLayout, pushConstantSize, pushStages);
  context.pipelines.notePipelineLayout(layout, setLayout, pushConstantSize, pushStages);
  return layout;
}

VkPipelineLayout createPipelineLayoutOn(VkDevice device, VkDescriptorSetLayout setLayout, uint32_t pushConstantSize,
                                        VkShaderStageFlags pushStages) {
  VkPushConstantRange range{pushStages, 0, pushConstantSize};
  VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  info.setLayoutCount = setLayout ? 1 : 0;
  info.pSetLayouts = &setLayout;
  info.pushConstantRangeCount = pushConstantSize ? 1 : 0;
  info.pPushConstantRanges = &range;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VK_CHECK(vkCreatePipelineLayout(device, &info, nullptr, &layout));
  return layout;
}

namespace {

// Made for the caller alone, never taken from or given to the context's pipeline store.
VkPipeline createComputePipelineUnshared(Context& context, std::span<const uint32_t> spirv, VkPipelineLayout layout,
                                         std::span<const uint32_t> specialization) {
  std::vector<VkSpecializationMapEntry> entries(specialization.size());
  for (uint32_t i = 0; i < entries.size(); ++i) entries[i] = {i, i * uint32_t(sizeof(uint32_t)), sizeof(uint32_t)};
  VkSpecializationInfo specInfo{uint32_t(entries.size()), entries.data(), specialization.size_bytes(),
                                specialization.data()};
  VkShaderModule module = createShaderModule(context, spirv);
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = specialization.empty() ? nullptr : &specInfo;
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkResult created = vkCreateComputePipelines(context.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
  vkDestroyShaderModule(context.device, module, nullptr);
  VK_CHECK(created);
  return pipeline;
}

}  // namespace

VkPipeline createComputePipelineWithLayout(Context& context, std::span<const uint32_t> spirv, VkPipelineLayout layout,
                                           std::span<const uint32_t> specialization) {
  std::string state = "compute";
  appendSpirvKey(state, spirv);
  appendKeySpan(state, specialization);
  return context.pipelines.get(context.device, layout, state, [&](VkPipelineLayout withLayout) {
    return createComputePipelineUnshared(context, spirv, withLayout, specialization);
  });
}

ComputePipeline createComputePipeline(Context& context, std::span<const uint32_t> spirv,
                                      std::span<const VkDescriptorType> bindings, uint32_t pushConstantSize,
                                      std::span<const uint32_t> specialization, uint32_t maxSets) {
  // Owned until all four exist: a throw destroys those created so far.
  Owned<VkDescriptorSetLayout> setLayout(context, createSetLayout(context, bindings, VK_SHADER_STAGE_COMPUTE_BIT));
  Owned<VkPipelineLayout> layout(
      context, createPipelineLayout(context, setLayout.get(), pushConstantSize, VK_SHADER_STAGE_COMPUTE_BIT));
  Owned<VkPipeline> pipeline(context, createComputePipelineWithLayout(context, spirv, layout.get(), specialization));
  Owned<VkDescriptorPool> pool(context, createDescriptorPool(context, bindings, maxSets));
  ComputePipeline result;
  result.pushConstantSize = pushConstantSize;
  result.setLayout = setLayout.release();
  result.layout = layout.release();
  result.pipeline = pipeline.release();
  result.descriptorPool = pool.release();
  return result;
}

void destroyComputePipeline(Context& context, ComputePipeline& pipeline) {
  if (pipeline.descriptorPool) vkDestroyDescriptorPool(context.device, pipeline.descriptorPool, nullptr);
  destroyOwned(context, pipeline.pipeline);
  destroyOwned(context, pipeline.layout);
  destroyOwned(context, pipeline.setLayout);
  pipeline = ComputePipeline{};
}

VkDescriptorSet allocateSet(Context& context, VkDescriptorPool pool, VkDescriptorSetLayout layout) {
  VkDescriptorSetAllocateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  info.descriptorPool = pool;
  info.descriptorSetCount = 1;
  info.pSetLayouts = &layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateDescriptorSets(context.device, &info, &set));
  return set;
}

namespace {

// One descriptor of `type` at `binding` of `set`; the caller points it at its resource.
VkWriteDescriptorSet descriptorWrite(VkDescriptorSet set, uint32_t binding, VkDescriptorType type) {
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstSet = set;
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = type;
  return write;
}

}  // namespace

void writeBufferDescriptor(Context& context, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                           const Buffer& buffer) {
  VkDescriptorBufferInfo info{buffer.buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet write = descriptorWrite(set, binding, type);
  write.pBufferInfo = &info;
  vkUpdateDescriptorSets(context.device, 1, &write, 0, nullptr);
}

void writeTexelBufferDescriptor(Context& context, VkDescriptorSet set, uint32_t binding, VkBufferView view) {
  VkWriteDescriptorSet write = descriptorWrite(set, binding, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER);
  write.pTexelBufferView = &view;
  vkUpdateDescriptorSets(context.device, 1, &write, 0, nullptr);
}

void writeImageDescriptor(Context& context, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                          VkImageView view, VkImageLayout layout, VkSampler sampler) {
  VkDescriptorImageInfo info{sampler, view, layout};
  VkWriteDescriptorSet write = descriptorWrite(set, binding, type);
  write.pImageInfo = &info;
  vkUpdateDescriptorSets(context.device, 1, &write, 0, nullptr);
}

VkDescriptorSet allocateStorageSet(Context& context, const ComputePipeline& pipeline,
                                   std::span<const Buffer* const> buffers) {
  VkDescriptorSet set = allocateSet(context, pipeline.descriptorPool, pipeline.setLayout);

  std::vector<VkDescriptorBufferInfo> infos(buffers.size());
  std::vector<VkWriteDescriptorSet> writes(buffers.size());
  for (size_t i = 0; i < buffers.size(); ++i) {
    infos[i] = {buffers[i]->buffer, 0, VK_WHOLE_SIZE};
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set;
    writes[i].dstBinding = uint32_t(i);
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(context.device, uint32_t(writes.size()), writes.data(), 0, nullptr);
  return set;
}

}  // namespace planet::vk
