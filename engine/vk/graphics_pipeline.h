// Graphics pipelines for dynamic rendering (Vulkan 1.3): one vertex and one fragment shader from
// embedded SPIR-V, no vertex input (shaders pull from storage buffers by gl_VertexIndex), one
// colour attachment and an optional depth attachment, viewport and scissor dynamic.
#pragma once

#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

namespace planet::vk {

class Context;

struct GraphicsPipelineDesc {
  std::span<const uint32_t> vertexSpirv;
  std::span<const uint32_t> fragmentSpirv;
  // Each stage's specialization constants: value i goes to constant_id i of that stage.
  std::span<const uint32_t> vertexSpecialization;
  std::span<const uint32_t> fragmentSpecialization;
  // Vertex buffers: binding i feeds the vertex shader's input at location i, an RGBA32F vec4 at
  // the start of each element, elements vertexStrides[i] bytes apart (empty: no vertex input).
  std::span<const uint32_t> vertexStrides;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkFormat colorFormat = VK_FORMAT_UNDEFINED;
  // Colour attachments, all of colorFormat and blended alike (the ground's G-buffer has four).
  uint32_t colorAttachments = 1;
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;  // UNDEFINED: no depth attachment
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPolygonMode polygonMode = VK_POLYGON_MODE_FILL;  // LINE needs the fillModeNonSolid feature
  VkCullModeFlags cullMode = VK_CULL_MODE_BACK_BIT;
  VkFrontFace frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  bool depthTest = true;
  bool depthWrite = true;
  VkCompareOp depthCompare = VK_COMPARE_OP_GREATER;  // reversed Z: nearer is larger
  bool alphaBlend = false;                           // "over" blending: src·α + dst·(1 − α)
  bool premultipliedAlpha = false;                   // with alphaBlend: src + dst·(1 − α) (colour already weighted)
  // With alphaBlend: the target's alpha becomes dst α · (1 − α), the share of the pixel still
  // showing what was there before (the sea: what the sky pass's cloud shadow still darkens),
  // instead of the coverage α + dst α · (1 − α).
  bool alphaKeepsUncovered = false;
  bool additiveBlend = false;                        // ONE + ONE: light that adds up (stars)
};

VkPipeline createGraphicsPipeline(Context& context, const GraphicsPipelineDesc& desc);

}  // namespace planet::vk
