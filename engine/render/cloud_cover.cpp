#include "render/cloud_cover.h"

#include <cmath>
#include <cstring>
#include <numbers>

#include "noise/noise_settings.h"
#include "spv/clouds_cover.comp.h"
#include "vk/context.h"

namespace planet {
namespace {

struct CloudPush {
  gpu::NoiseParams noise;
  glm::vec4 shape;
};
static_assert(sizeof(CloudPush) == 64);

float uintBitsAsFloat(uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, sizeof(f));
  return f;
}

// The detail noise's seed, mixed once here as the noise code would (noise_settings.h).
uint32_t detailSeedMix(uint32_t seed) {
  noise::NoiseSettings settings;
  settings.seed = seed + 99u;
  return noise::toNoiseParams(settings).seedMix;
}

}  // namespace

CloudCover::CloudCover(vk::Context& context, const PlanetDescription& planet)
    : clouds_(planet.clouds), radiusM_(planet.radiusM) {
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  image_ = {context,
            vk::createImageCube(context, clouds_.enabled ? kCloudCoverSize : 8, VK_FORMAT_R8G8B8A8_UNORM, usage)};
  const VkDescriptorType storageImage[] = {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
  pipeline_ = {context,
               vk::createComputePipeline(context, kSpv_clouds_cover_comp, storageImage, sizeof(CloudPush), {}, 1)};
  set_ = vk::allocateSet(context, pipeline_->descriptorPool, pipeline_->setLayout);
  vk::writeImageDescriptor(context, set_, 0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, image_->view, VK_IMAGE_LAYOUT_GENERAL);
}

void CloudCover::recordBuild(VkCommandBuffer cmd) {
  vk::Image& image = *image_;
  // The cube starts undefined; compute writes it in GENERAL.
  vk::transitionImage(cmd, image, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, 0,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  if (clouds_.enabled) {
    const CloudDescription& c = clouds_;
    noise::NoiseSettings fbm;
    fbm.type = noise::NoiseType::Fbm;
    fbm.octaves = c.octaves;
    fbm.lacunarity = 2.0;
    fbm.H = 0.6;
    CloudPush push{};
    push.noise = noise::toNoiseParams(fbm);
    double weightSum = 0.0;
    for (int i = 0; i < c.octaves; ++i) weightSum += std::pow(2.0, -fbm.H * i);
    push.shape = glm::vec4(float(radiusM_ / c.wavelengthM), float(image.extent.width), uintBitsAsFloat(c.seed),
                           float(1.0 / weightSum));
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout, 0, 1, &set_, 0, nullptr);
    vkCmdPushConstants(cmd, pipeline_->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    const uint32_t group = gpu::kSkyWorkgroupSize;
    const uint32_t size = image.extent.width;
    vkCmdDispatch(cmd, (size + group - 1) / group, (size + group - 1) / group, 6);
  }
  // From now on the cover is only sampled (sky compose).
  vk::transitionImage(cmd, image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

void CloudCover::writeUniforms(gpu::SkyUniforms& u, double timeS) const {
  const CloudDescription& c = clouds_;
  u.clouds = glm::vec4(float(c.bottomM), float(c.topM), float(c.coverage), float(c.sharpness));
  // Detail noise: 3 octaves from 12 km down, finer than the cover images' texels.
  const double detailWavelengthM = 12'000.0;
  u.cloudShape =
      glm::vec4(float(c.opacity), float(1.0 / detailWavelengthM), 0.12f, uintBitsAsFloat(detailSeedMix(c.seed)));
  const CloudMotion motion = cloudMotion(c, radiusM_, timeS);
  u.cloudMotion = glm::vec4(motion.weights, motion.driftRad);
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
