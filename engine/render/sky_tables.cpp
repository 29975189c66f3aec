#include "render/sky_tables.h"

#include <cstring>

#include "spv/atmosphere_multiscatter.comp.h"
#include "spv/atmosphere_transmittance.comp.h"
#include "spv/sky_ray.comp.h"
#include "vk/buffer.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/timer.h"

namespace planet {
namespace {

vk::Image createTransmittance(vk::Context& context) {
  return vk::createImage2D(context, {gpu::kTransmittanceWidth, gpu::kTransmittanceHeight},
                           VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
}

// vec4s sky_ray.comp writes per ray.
constexpr size_t kRayResultTexels = 6;

vk::Image createMultipleScattering(vk::Context& context) {
  return vk::createImage2D(context, {gpu::kMultiScatteringSize, gpu::kMultiScatteringSize},
                           VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
}

std::vector<glm::vec4> readTable(vk::Context& context, vk::Image& image) {
  std::vector<uint8_t> bytes = vk::readbackImage(context, image);
  std::vector<glm::vec4> texels(bytes.size() / sizeof(glm::vec4));
  std::memcpy(texels.data(), bytes.data(), texels.size() * sizeof(glm::vec4));
  // Back to what the passes expect.
  vk::submitAndWait(context, [&](VkCommandBuffer cmd) {
    vk::transitionImage(cmd, image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  });
  return texels;
}

}  // namespace

SkyTables::SkyTables(vk::Context& context, const PlanetDescription& planet)
    : context_(context),
      atmosphere_(makeAtmosphereParams(planet)),
      skyIrradiance_(skyIrradianceTable(atmosphere_)),
      transmittance_(context, createTransmittance(context)),
      multipleScattering_(context, createMultipleScattering(context)),
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

  const VkDescriptorType tableAndStorage[] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                              VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
  multipleScatteringPipeline_ = {context,
                                 vk::createComputePipeline(context, kSpv_atmosphere_multiscatter_comp, tableAndStorage,
                                                           sizeof(gpu::AtmosphereParams), {}, 1)};
  multipleScatteringSet_ =
      vk::allocateSet(context, multipleScatteringPipeline_->descriptorPool, multipleScatteringPipeline_->setLayout);
  vk::writeImageDescriptor(context, multipleScatteringSet_, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                           transmittance_->view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampler_.get());
  vk::writeImageDescriptor(context, multipleScatteringSet_, 1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                           multipleScattering_->view, VK_IMAGE_LAYOUT_GENERAL);
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
  // From now on the table is only sampled (the multiple-scattering build below, sky compose,
  // terrain and water fragments).
  vk::transitionImage(cmd, *transmittance_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  // The multiple-scattering table starts undefined; compute writes it in GENERAL.
  vk::transitionImage(cmd, *multipleScattering_, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, 0,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, multipleScatteringPipeline_->pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, multipleScatteringPipeline_->layout, 0, 1,
                          &multipleScatteringSet_, 0, nullptr);
  vkCmdPushConstants(cmd, multipleScatteringPipeline_->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(atmosphere_),
                     &atmosphere_);
  vkCmdDispatch(cmd, (gpu::kMultiScatteringSize + group - 1) / group, (gpu::kMultiScatteringSize + group - 1) / group,
                1);
  // Then it is only sampled too.
  vk::transitionImage(cmd, *multipleScattering_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  if (timer) timer->end(cmd);
  built_ = true;
}

std::vector<glm::vec4> SkyTables::readTransmittance() { return readTable(context_, *transmittance_); }

std::vector<glm::vec4> SkyTables::readMultipleScattering() { return readTable(context_, *multipleScattering_); }

std::vector<SkyTables::RayResult> SkyTables::evaluateRays(std::span<const RayQuery> rays, uint32_t referenceSteps,
                                                          uint32_t tableSteps) {
  if (!built_) vk::submitAndWait(context_, [&](VkCommandBuffer cmd) { recordBuild(cmd, nullptr); });
  std::vector<RayResult> results(rays.size());
  if (rays.empty()) return results;
  std::vector<glm::vec4> queries(rays.size());
  for (size_t i = 0; i < rays.size(); ++i)
    queries[i] = glm::vec4(float(rays[i].altitudeM), float(rays[i].mu), float(rays[i].muS), float(rays[i].nu));
  const VkDescriptorType bindings[] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                       VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                       VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  vk::Owned<vk::ComputePipeline> pipeline(
      context_, vk::createComputePipeline(context_, kSpv_sky_ray_comp, bindings, sizeof(gpu::SkyRayPush), {}, 1));
  const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  vk::Owned<vk::Buffer> input(
      context_, vk::createBuffer(context_, queries.size() * sizeof(glm::vec4), usage, vk::MemoryUsage::DeviceLocal));
  const size_t outputBytes = queries.size() * kRayResultTexels * sizeof(glm::vec4);
  vk::Owned<vk::Buffer> output(context_, vk::createBuffer(context_, outputBytes, usage, vk::MemoryUsage::DeviceLocal));
  vk::uploadBuffer(context_, *input, queries.data(), queries.size() * sizeof(glm::vec4));
  VkDescriptorSet set = vk::allocateSet(context_, pipeline->descriptorPool, pipeline->setLayout);
  vk::writeImageDescriptor(context_, set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, transmittance_->view,
                           VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampler_.get());
  vk::writeImageDescriptor(context_, set, 1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, multipleScattering_->view,
                           VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampler_.get());
  vk::writeBufferDescriptor(context_, set, 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, *input);
  vk::writeBufferDescriptor(context_, set, 3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, *output);
  gpu::SkyRayPush push{};
  push.atmosphere = atmosphere_;
  push.counts = glm::vec4(float(queries.size()), float(referenceSteps), float(tableSteps), 0.0f);
  vk::submitAndWait(context_, [&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline->layout, 0, 1, &set, 0, nullptr);
    vkCmdPushConstants(cmd, pipeline->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    const uint32_t group = gpu::kSkyRayWorkgroupSize;
    vkCmdDispatch(cmd, (uint32_t(queries.size()) + group - 1) / group, 1, 1);
    // The results are read by a copy or directly by the host.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
                      VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_HOST_READ_BIT);
  });
  std::vector<glm::vec4> values(queries.size() * kRayResultTexels);
  vk::readbackBuffer(context_, *output, values.data(), outputBytes);
  for (size_t i = 0; i < rays.size(); ++i) {
    const glm::vec4* v = &values[kRayResultTexels * i];
    results[i] = {glm::dvec3(v[0]), glm::dvec3(v[1]), glm::dvec3(v[2]),
                  glm::dvec3(v[3]), glm::dvec3(v[4]), glm::dvec3(v[5])};
  }
  return results;
}

}  // namespace planet
