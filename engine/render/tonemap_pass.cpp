#include "render/tonemap_pass.h"

#include <glm/glm.hpp>

#include "spv/tonemap.frag.h"
#include "spv/tonemap.vert.h"
#include "vk/context.h"
#include "vk/graphics_pipeline.h"
#include "vk/pipeline.h"
#include "vk/timer.h"

namespace planet {
namespace {

constexpr VkDescriptorType kBindings[] = {
    VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,   // the HDR colour
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,  // the adapted exposure (ExposureState)
};

}  // namespace

TonemapPass::TonemapPass(vk::Context& context, VkFormat outputFormat, double exposure, const vk::Buffer& adapted)
    : context_(context), exposure_(exposure) {
  setLayout_ = {context, vk::createSetLayout(context, kBindings, VK_SHADER_STAGE_FRAGMENT_BIT)};
  pool_ = {context, vk::createDescriptorPool(context, kBindings, 1)};
  set_ = vk::allocateSet(context, pool_.get(), setLayout_.get());
  vk::writeBufferDescriptor(context, set_, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, adapted);
  layout_ = {context,
             vk::createPipelineLayout(context, setLayout_.get(), sizeof(glm::vec4), VK_SHADER_STAGE_FRAGMENT_BIT)};
  vk::GraphicsPipelineDesc desc;
  desc.vertexSpirv = kSpv_tonemap_vert;
  desc.fragmentSpirv = kSpv_tonemap_frag;
  desc.layout = layout_.get();
  desc.colorFormat = outputFormat;
  desc.cullMode = VK_CULL_MODE_NONE;
  desc.depthTest = false;
  desc.depthWrite = false;
  pipeline_ = {context, vk::createGraphicsPipeline(context, desc)};
}

void TonemapPass::setSource(const vk::Image& hdr) {
  vk::writeImageDescriptor(context_, set_, 0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, hdr.view, VK_IMAGE_LAYOUT_GENERAL);
}

void TonemapPass::recordDraw(VkCommandBuffer cmd, vk::GpuTimer* timer) {
  if (timer) timer->begin(cmd, "tonemap");
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 1, &set_, 0, nullptr);
  // A fixed exposure scales by params.x; an adapted one (params.y = 1) by the buffer's, the stars'
  // share of a pixel by gpu::kExposureStarExposure.
  const glm::vec4 params(adapting_ ? 1.0f : float(exposure_), adapting_ ? 1.0f : 0.0f, 0.0f, 0.0f);
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(params), &params);
  vkCmdDraw(cmd, 3, 1, 0, 0);
  if (timer) timer->end(cmd);
}

}  // namespace planet
