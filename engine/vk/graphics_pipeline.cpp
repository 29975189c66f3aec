#include "vk/graphics_pipeline.h"

#include <algorithm>
#include <string>
#include <vector>

#include "core/error.h"
#include "vk/context.h"
#include "vk/owned.h"
#include "vk/pipeline.h"

namespace planet::vk {

namespace {

// Every input of the creation but the layout, for the context's pipeline store: a field of
// GraphicsPipelineDesc missing here would hand out a pipeline made with another value of it. The
// structured binding names every field, so adding one to the struct stops this from compiling
// until the key takes it (or says here why not, as for the layout).
std::string storeKey(const GraphicsPipelineDesc& desc) {
  const auto& [vertexSpirv, fragmentSpirv, vertexSpecialization, fragmentSpecialization, vertexStrides, layout,
               colorFormat, colorAttachments, depthFormat, topology, polygonMode, cullMode, frontFace, depthTest,
               depthWrite, depthCompare, alphaBlend, premultipliedAlpha, alphaKeepsUncovered, additiveBlend] = desc;
  // The layout goes to the store beside the key, which looks up its definition (PipelineStore::get).
  static_cast<void>(layout);
  std::string key = "graphics";
  appendSpirvKey(key, vertexSpirv);
  appendSpirvKey(key, fragmentSpirv);
  appendKeySpan(key, vertexSpecialization);
  appendKeySpan(key, fragmentSpecialization);
  appendKeySpan(key, vertexStrides);
  appendKey(key, colorFormat);
  appendKey(key, colorAttachments);
  appendKey(key, depthFormat);
  appendKey(key, topology);
  appendKey(key, polygonMode);
  appendKey(key, cullMode);
  appendKey(key, frontFace);
  appendKey(key, depthCompare);
  const uint8_t flags[] = {depthTest, depthWrite, alphaBlend, premultipliedAlpha, alphaKeepsUncovered, additiveBlend};
  appendKey(key, flags);
  return key;
}

VkPipeline createUnshared(Context& context, const GraphicsPipelineDesc& desc) {
  // Needed only while the pipeline is created: destroyed on return (or throw), fragment first.
  const Owned<VkShaderModule> vertex(context, createShaderModule(context, desc.vertexSpirv));
  const Owned<VkShaderModule> fragment(context, createShaderModule(context, desc.fragmentSpirv));
  VkPipelineShaderStageCreateInfo stages[2]{};
  stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vertex.get();
  stages[0].pName = "main";
  stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fragment.get();
  stages[1].pName = "main";
  // Value i of a stage's list is its constant_id i: one map serves both stages.
  std::vector<VkSpecializationMapEntry> entries(
      std::max(desc.vertexSpecialization.size(), desc.fragmentSpecialization.size()));
  for (uint32_t i = 0; i < entries.size(); ++i) entries[i] = {i, uint32_t(i * sizeof(uint32_t)), sizeof(uint32_t)};
  const VkSpecializationInfo vertexSpecialization{uint32_t(desc.vertexSpecialization.size()), entries.data(),
                                                  desc.vertexSpecialization.size_bytes(),
                                                  desc.vertexSpecialization.data()};
  const VkSpecializationInfo fragmentSpecialization{uint32_t(desc.fragmentSpecialization.size()), entries.data(),
                                                    desc.fragmentSpecialization.size_bytes(),
                                                    desc.fragmentSpecialization.data()};
  if (!desc.vertexSpecialization.empty()) stages[0].pSpecializationInfo = &vertexSpecialization;
  if (!desc.fragmentSpecialization.empty()) stages[1].pSpecializationInfo = &fragmentSpecialization;

  std::vector<VkVertexInputBindingDescription> vertexBindings(desc.vertexStrides.size());
  std::vector<VkVertexInputAttributeDescription> vertexAttributes(desc.vertexStrides.size());
  for (uint32_t i = 0; i < desc.vertexStrides.size(); ++i) {
    vertexBindings[i] = {i, desc.vertexStrides[i], VK_VERTEX_INPUT_RATE_VERTEX};
    vertexAttributes[i] = {i, i, VK_FORMAT_R32G32B32A32_SFLOAT, 0};
  }
  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vertexInput.vertexBindingDescriptionCount = uint32_t(vertexBindings.size());
  vertexInput.pVertexBindingDescriptions = vertexBindings.data();
  vertexInput.vertexAttributeDescriptionCount = uint32_t(vertexAttributes.size());
  vertexInput.pVertexAttributeDescriptions = vertexAttributes.data();
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = desc.topology;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = desc.polygonMode;
  raster.cullMode = desc.cullMode;
  raster.frontFace = desc.frontFace;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = desc.depthTest && desc.depthFormat != VK_FORMAT_UNDEFINED;
  depth.depthWriteEnable = desc.depthWrite && desc.depthFormat != VK_FORMAT_UNDEFINED;
  depth.depthCompareOp = desc.depthCompare;
  VkPipelineColorBlendAttachmentState attachment{};
  attachment.colorWriteMask =
      VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  if (desc.alphaBlend) {
    attachment.blendEnable = VK_TRUE;
    attachment.srcColorBlendFactor = desc.premultipliedAlpha ? VK_BLEND_FACTOR_ONE : VK_BLEND_FACTOR_SRC_ALPHA;
    attachment.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    attachment.colorBlendOp = VK_BLEND_OP_ADD;
    attachment.srcAlphaBlendFactor = desc.alphaKeepsUncovered ? VK_BLEND_FACTOR_ZERO : VK_BLEND_FACTOR_ONE;
    attachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    attachment.alphaBlendOp = VK_BLEND_OP_ADD;
  } else if (desc.additiveBlend) {
    attachment.blendEnable = VK_TRUE;
    attachment.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
    attachment.dstColorBlendFactor = VK_BLEND_FACTOR_ONE;
    attachment.colorBlendOp = VK_BLEND_OP_ADD;
    attachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    attachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    attachment.alphaBlendOp = VK_BLEND_OP_ADD;
  }
  const std::vector<VkPipelineColorBlendAttachmentState> attachments(desc.colorAttachments, attachment);
  const std::vector<VkFormat> colorFormats(desc.colorAttachments, desc.colorFormat);
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = desc.colorAttachments;
  blend.pAttachments = attachments.data();
  VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamicStates;

  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = desc.colorAttachments;
  rendering.pColorAttachmentFormats = colorFormats.data();
  rendering.depthAttachmentFormat = desc.depthFormat;

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.pNext = &rendering;
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = desc.layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkResult result = vkCreateGraphicsPipelines(context.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
  VK_CHECK(result);
  return pipeline;
}

}  // namespace

VkPipeline createGraphicsPipeline(Context& context, const GraphicsPipelineDesc& desc) {
  if (desc.alphaBlend && desc.additiveBlend)
    throw Error("a graphics pipeline blends either alpha or additively, not both");
  if (desc.alphaKeepsUncovered && !desc.alphaBlend)
    throw Error("a graphics pipeline keeps the uncovered share in alpha only with alpha blending");
  return context.pipelines.get(context.device, desc.layout, storeKey(desc), [&](VkPipelineLayout layout) {
    GraphicsPipelineDesc withLayout = desc;
    withLayout.layout = layout;
    return createUnshared(context, withLayout);
  });
}

}  // namespace planet::vk
