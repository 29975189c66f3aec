#include "render/cloud_cover.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>

#include "noise/noise_settings.h"
#include "spv/clouds_cover.comp.h"
#include "vk/commands.h"
#include "vk/context.h"

namespace planet {
namespace {

float uintBitsAsFloat(uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, sizeof(f));
  return f;
}

// Texels per face side of the cube each planet gets (a planet without clouds: a tiny one).
uint32_t coverSize(const CloudDescription& clouds) { return clouds.enabled ? uint32_t(clouds.resolution) : 8u; }



constexpr VkPipelineStageFlags2 kSampledStages =
    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;

}  // namespace

std::vector<gpu::CloudVortex> cloudVortices(const CloudDescription& clouds, double radiusM) {
  std::vector<gpu::CloudVortex> vortices;
  std::mt19937 random(clouds.seed * 2654435761u + 17u);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int tropical = clouds.cyclones / 5;
  for (int hemisphere : {1, -1})
    for (int k = 0; k < clouds.cyclones; ++k) {
      const bool isTropical = k < tropical;
      // Uniform in area within the band: sin(latitude) uniform.
      const double lo = (isTropical ? 10.0 : 35.0) * std::numbers::pi / 180.0;
      const double hi = (isTropical ? 22.0 : 65.0) * std::numbers::pi / 180.0;
      const double lat = std::asin(std::sin(lo) + unit(random) * (std::sin(hi) - std::sin(lo))) * hemisphere;
      const double lon = (2.0 * unit(random) - 1.0) * std::numbers::pi;
      const double size = isTropical ? 0.4 : 0.7 + 0.6 * unit(random);  // of cyclone_radius_m
      gpu::CloudVortex v{};
      v.centre = glm::vec4(float(std::cos(lat) * std::cos(lon)), float(std::cos(lat) * std::sin(lon)),
                           float(std::sin(lat)), float(clouds.cycloneRadiusM * size / radiusM));
      const double turns = clouds.swirl * (isTropical ? 1.5 : 0.6 + 0.8 * unit(random));
      v.shape = glm::vec4(float(hemisphere * 2.0 * std::numbers::pi * turns), isTropical ? 0.22f : 0.10f,
                          isTropical ? 0.12f : 0.0f, 0.0f);
      vortices.push_back(v);
    }
  return vortices;
}

CloudCover::CloudCover(vk::Context& context, const PlanetDescription& planet)
    : clouds_(planet.clouds), radiusM_(planet.radiusM), context_(context) {
  const uint32_t size = coverSize(clouds_);
  mipLevels_ = uint32_t(std::bit_width(size));
  image_ = {context, vk::createImageCube(context, size, VK_FORMAT_R8G8B8A8_UNORM,
                                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, mipLevels_)};
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.maxLod = VK_LOD_CLAMP_NONE;
  sampler_ = {context, vk::createSampler(context, info)};
  weather_ = {context, vk::createBuffer(context, sizeof(gpu::CloudWeather), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        vk::MemoryUsage::Upload)};
  const VkDescriptorType bindings[] = {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  pipeline_ = {context,
               vk::createComputePipeline(context, kSpv_clouds_cover_comp, bindings, sizeof(gpu::NoiseParams), {}, 1)};
  set_ = vk::allocateSet(context, pipeline_->descriptorPool, pipeline_->setLayout);
  vk::writeImageDescriptor(context, set_, 0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, image_->view, VK_IMAGE_LAYOUT_GENERAL);
  vk::writeBufferDescriptor(context, set_, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, *weather_);

  const CloudDescription& c = clouds_;
  gpu::CloudWeather weather{};
  double weightSum = 0.0;
  for (int i = 0; i < c.octaves; ++i) weightSum += std::pow(2.0, -0.6 * i);
  weather.shape = glm::vec4(float(radiusM_ / c.wavelengthM), float(size), uintBitsAsFloat(c.seed),
                            float(1.0 / weightSum));
  const std::vector<gpu::CloudVortex> vortices = c.enabled ? cloudVortices(c, radiusM_) : std::vector<gpu::CloudVortex>{};
  weather.cover = glm::vec4(float(c.coverage), float(std::log(1.0 / c.sharpness)), float(c.climate),
                            float(vortices.size()));
  // The jets meander by ±0.12 rad of latitude; the warp's field has a wavelength of a fifth of
  // the planet's circumference (continental weather systems).
  weather.flow = glm::vec4(float(c.shear), float(c.warp), 0.12f, 5.0f);
  std::copy(vortices.begin(), vortices.end(), weather.vortices);
  vk::uploadBuffer(context, *weather_, &weather, sizeof(weather));
}

void CloudCover::recordBuild(VkCommandBuffer cmd) {
  vk::Image& image = *image_;
  const uint32_t size = image.extent.width;
  // Level 0 starts undefined and compute (or a clear) writes it in GENERAL; recordMipChain makes the others.
  vk::transitionLevels(cmd, image, 0, 1, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE,
                       0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
  if (clouds_.enabled) {
    noise::NoiseSettings fbm;
    fbm.type = noise::NoiseType::Fbm;
    fbm.octaves = clouds_.octaves;
    fbm.lacunarity = 2.0;
    fbm.H = 0.6;
    const gpu::NoiseParams push = noise::toNoiseParams(fbm);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout, 0, 1, &set_, 0, nullptr);
    vkCmdPushConstants(cmd, pipeline_->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    const uint32_t group = gpu::kSkyWorkgroupSize;
    vkCmdDispatch(cmd, (size + group - 1) / group, (size + group - 1) / group, 6);
  } else {
    // Nothing writes the tiny cube of a cloudless planet; clear it so that it is defined.
    const VkClearColorValue zero{};
    const VkImageSubresourceRange level0{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 6};
    vkCmdClearColorImage(cmd, image.image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &level0);
  }
  // Each level is the box average of the one above (density averages as the eye would); from
  // then on the cover is only sampled (sky compose).
  vk::recordMipChain(cmd, image, VK_IMAGE_LAYOUT_GENERAL,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT,
                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, kSampledStages);
}

std::vector<uint8_t> CloudCover::readLevel0() {
  vk::Image& image = *image_;
  const uint32_t size = image.extent.width;
  const size_t bytes = size_t(size) * size * 6 * 4;
  const vk::Owned<vk::Buffer> staging(context_, vk::createBuffer(context_, bytes, 0, vk::MemoryUsage::Readback));
  vk::submitAndWait(context_, [&](VkCommandBuffer cmd) {
    // The build (an earlier submission) wrote the cover; the copy reads level 0.
    vk::transitionLevels(cmd, image, 0, 1, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                 VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 6};
    region.imageExtent = {size, size, 1};
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging->buffer, 1, &region);
    // Back to what the sky pass samples, after the copy.
    vk::transitionLevels(cmd, image, 0, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                 VK_PIPELINE_STAGE_2_COPY_BIT, 0, kSampledStages, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    // The host reads the staging buffer after the fence.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                      VK_ACCESS_2_HOST_READ_BIT);
  });
  context_.allocator.invalidate(staging->allocation);
  std::vector<uint8_t> texels(bytes);
  std::memcpy(texels.data(), staging->mapped(), bytes);
  return texels;
}

CloudCover::Layer CloudCover::layerAt(double timeS) const {
  const CloudDescription& c = clouds_;
  const double thicknessM = c.topM - c.bottomM;
  Layer layer;
  // A full-density column has optical depth `opacity`; clouds are about twice as wide as the
  // layer is thick, which bounds the slant path through one.
  layer.clouds = glm::vec4(float(c.bottomM), float(c.topM), float(c.opacity / thicknessM), 2.0f);
  // One level-0 texel spans 2 / size of a face at its centre (the cube's tangent plane at 1).
  const float texelAngle = 2.0f / float(image_->extent.width);
  // Two segments per stretch of the ray in the layer: the sky pass's budget (issue 12).
  layer.shape = glm::vec4(texelAngle, float(mipLevels_ - 1), 2.0f, 0.0f);
  const CloudMotion motion = cloudMotion(c, radiusM_, timeS);
  layer.motion = glm::vec4(motion.weights, motion.driftRad);
  return layer;
}

void CloudCover::writeUniforms(gpu::SkyUniforms& u, double timeS) const {
  const Layer layer = layerAt(timeS);
  u.clouds = layer.clouds;
  u.cloudShape = layer.shape;
  u.cloudMotion = layer.motion;
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
