#include "render/sky_tables.h"

#include <cstring>

#include "spv/atmosphere_transmittance.comp.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/timer.h"

namespace planet {
namespace {

vk::Image createTransmittance(vk::Context& context) {
  return vk::createImage2D(context, {gpu::kTransmittanceWidth, gpu::kTransmittanceHeight},
                           VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
}

}  // namespace

SkyTables::SkyTables(vk::Context& context, const PlanetDescription& planet)
    : context_(context),
      atmosphere_(makeAtmosphereParams(planet)),
      skyIrradiance_(skyIrradianceTable(atmosphere_)),
      transmittance_(context, createTransmittance(context)),
      clouds_(context, planet) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  sampler_ = {context, vk::createSampler(context, info)};

  const VkDescriptorType storageImage[] = {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
  transmittancePipeline_ = {context, vk::createComputePipeline(context, kSpv_atmosphere_transmittance_comp,
                                                               storageImage, sizeof(gpu::AtmosphereParams), {}, 1)};
  transmittanceSet_ =
      vk::allocateSet(context, transmittancePipeline_->descriptorPool, transmittancePipeline_->setLayout);
  vk::writeImageDescriptor(context, transmittanceSet_, 0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, transmittance_->view,
                           VK_IMAGE_LAYOUT_GENERAL);
}

void SkyTables::recordBuild(VkCommandBuffer cmd, vk::GpuTimer* timer) {
  if (built_) return;
  if (timer) timer->begin(cmd, "sky tables");
  // The table starts undefined; compute writes it in GENERAL.
  vk::transitionImage(cmd, *transmittance_, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, 0,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, transmittancePipeline_->pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, transmittancePipeline_->layout, 0, 1, &transmittanceSet_,
                          0, nullptr);
  vkCmdPushConstants(cmd, transmittancePipeline_->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(atmosphere_),
                     &atmosphere_);
  const uint32_t group = gpu::kSkyWorkgroupSize;
  vkCmdDispatch(cmd, (gpu::kTransmittanceWidth + group - 1) / group, (gpu::kTransmittanceHeight + group - 1) / group,
                1);
  clouds_.recordBuild(cmd);
  // From now on the table is only sampled (sky compose, terrain and water fragments).
  vk::transitionImage(cmd, *transmittance_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  if (timer) timer->end(cmd);
  built_ = true;
}

std::vector<glm::vec4> SkyTables::readTransmittance() {
  std::vector<uint8_t> bytes = vk::readbackImage(context_, *transmittance_);
  std::vector<glm::vec4> texels(bytes.size() / sizeof(glm::vec4));
  std::memcpy(texels.data(), bytes.data(), texels.size() * sizeof(glm::vec4));
  // Back to what the passes expect.
  vk::submitAndWait(context_, [&](VkCommandBuffer cmd) {
    vk::transitionImage(cmd, *transmittance_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                        VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  });
  return texels;
}

}  // namespace planet
