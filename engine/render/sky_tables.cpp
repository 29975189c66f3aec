#include "render/sky_tables.h"

#include <cmath>
#include <cstring>
#include <numbers>

#include "noise/noise_settings.h"
#include "spv/atmosphere_transmittance.comp.h"
#include "spv/clouds_cover.comp.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/timer.h"

namespace planet {
namespace {

struct CloudPush {
  gpu::NoiseParams noise;
  glm::vec4 shape;
};
static_assert(sizeof(CloudPush) == 64);

}  // namespace

SkyTables::SkyTables(vk::Context& context, const PlanetDescription& planet) : context_(context), planet_(planet) {
  atmosphere_ = makeAtmosphereParams(planet);
  skyIrradiance_ = skyIrradianceTable(atmosphere_);
  try {
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    transmittance_ = vk::createImage2D(context, {gpu::kTransmittanceWidth, gpu::kTransmittanceHeight},
                                       VK_FORMAT_R32G32B32A32_SFLOAT, usage);
    // Without clouds the cube is still bound (never sampled): keep it tiny.
    clouds_ =
        vk::createImageCube(context, planet.clouds.enabled ? kCloudCoverSize : 8, VK_FORMAT_R8G8B8A8_UNORM, usage);
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = info.minFilter = VK_FILTER_LINEAR;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    VK_CHECK(vkCreateSampler(context.device, &info, nullptr, &sampler_));

    const VkDescriptorType storageImage[] = {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
    transmittancePipeline_ = vk::createComputePipeline(context, kSpv_atmosphere_transmittance_comp, storageImage,
                                                       sizeof(gpu::AtmosphereParams), {}, 1);
    transmittanceSet_ =
        vk::allocateSet(context, transmittancePipeline_.descriptorPool, transmittancePipeline_.setLayout);
    vk::writeImageDescriptor(context, transmittanceSet_, 0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, transmittance_.view,
                             VK_IMAGE_LAYOUT_GENERAL);
    cloudPipeline_ = vk::createComputePipeline(context, kSpv_clouds_cover_comp, storageImage, sizeof(CloudPush), {}, 1);
    cloudSet_ = vk::allocateSet(context, cloudPipeline_.descriptorPool, cloudPipeline_.setLayout);
    vk::writeImageDescriptor(context, cloudSet_, 0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, clouds_.view,
                             VK_IMAGE_LAYOUT_GENERAL);
  } catch (...) {
    release();
    throw;
  }
}

SkyTables::~SkyTables() { release(); }

void SkyTables::release() {
  vk::destroyComputePipeline(context_, cloudPipeline_);
  vk::destroyComputePipeline(context_, transmittancePipeline_);
  if (sampler_) vkDestroySampler(context_.device, sampler_, nullptr);
  sampler_ = VK_NULL_HANDLE;
  vk::destroyImage(context_, clouds_);
  vk::destroyImage(context_, transmittance_);
}

void SkyTables::recordBuild(VkCommandBuffer cmd, vk::GpuTimer* timer) {
  if (built_) return;
  if (timer) timer->begin(cmd, "sky tables");
  // Both images start undefined; compute writes them in GENERAL.
  vk::transitionImage(cmd, transmittance_, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, 0,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vk::transitionImage(cmd, clouds_, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, 0,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, transmittancePipeline_.pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, transmittancePipeline_.layout, 0, 1, &transmittanceSet_,
                          0, nullptr);
  vkCmdPushConstants(cmd, transmittancePipeline_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(atmosphere_),
                     &atmosphere_);
  const uint32_t group = gpu::kSkyWorkgroupSize;
  vkCmdDispatch(cmd, (gpu::kTransmittanceWidth + group - 1) / group, (gpu::kTransmittanceHeight + group - 1) / group,
                1);
  if (planet_.clouds.enabled) {
    const CloudDescription& c = planet_.clouds;
    noise::NoiseSettings fbm;
    fbm.type = noise::NoiseType::Fbm;
    fbm.octaves = c.octaves;
    fbm.lacunarity = 2.0;
    fbm.H = 0.6;
    CloudPush push{};
    push.noise = noise::toNoiseParams(fbm);
    double weightSum = 0.0;
    for (int i = 0; i < c.octaves; ++i) weightSum += std::pow(2.0, -fbm.H * i);
    uint32_t seedBits = c.seed;
    float seedFloat;
    std::memcpy(&seedFloat, &seedBits, sizeof(seedFloat));
    push.shape = glm::vec4(float(planet_.radiusM / c.wavelengthM), float(clouds_.extent.width), seedFloat,
                           float(1.0 / weightSum));
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cloudPipeline_.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cloudPipeline_.layout, 0, 1, &cloudSet_, 0, nullptr);
    vkCmdPushConstants(cmd, cloudPipeline_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    const uint32_t size = clouds_.extent.width;
    vkCmdDispatch(cmd, (size + group - 1) / group, (size + group - 1) / group, 6);
  }
  // From now on the tables are only sampled (sky compose, terrain and water fragments).
  const VkPipelineStageFlags2 readers =
      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
  vk::transitionImage(cmd, transmittance_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, readers,
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  vk::transitionImage(cmd, clouds_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, readers, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  if (timer) timer->end(cmd);
  built_ = true;
}

std::vector<glm::vec4> SkyTables::readTransmittance() {
  std::vector<uint8_t> bytes = vk::readbackImage(context_, transmittance_);
  std::vector<glm::vec4> texels(bytes.size() / sizeof(glm::vec4));
  std::memcpy(texels.data(), bytes.data(), texels.size() * sizeof(glm::vec4));
  // Back to what the passes expect.
  vk::submitAndWait(context_, [&](VkCommandBuffer cmd) {
    vk::transitionImage(cmd, transmittance_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                        0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  });
  return texels;
}

CloudMotion cloudMotion(const CloudDescription& clouds, double radiusM, double timeS) {
  CloudMotion m;
  const double t = 2.0 * std::numbers::pi * timeS / clouds.evolvePeriodS;
  for (int i = 0; i < 3; ++i) m.weights[i] = float((1.0 + std::cos(t - 2.0 * std::numbers::pi * i / 3.0)) / 3.0);
  const double layerRadius = radiusM + 0.5 * (clouds.bottomM + clouds.topM);
  m.driftRad = float(std::remainder(clouds.windMps * timeS / layerRadius, 2.0 * std::numbers::pi));
  return m;
}

}  // namespace planet
