#include "render/relief_cube.h"

#include <algorithm>
#include <bit>
#include <span>

#include <fmt/format.h>

#include "core/error.h"
#include "planet/octave_budget.h"
#include "planet/planet_gpu_data.h"
#include "shared/relief_params.h"
#include "spv/relief_cube.comp.h"
#include "spv/relief_cube_no_craters.comp.h"
#include "vk/commands.h"
#include "vk/context.h"

namespace planet {
namespace {

constexpr VkFormat kReliefFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

constexpr VkDescriptorType kBindings[gpu::kReliefBindingCount] = {
    VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,   // relief (mip 0)
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,  // layers
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,  // permutations
};

}  // namespace

ReliefCube::ReliefCube(vk::Context& context, const PlanetGpuData& data, uint32_t size) {
  static_assert(kReliefStandInSize == gpu::kReliefStandInSize);
  const bool standIn = size == kReliefStandInSize;
  if (!standIn && (size < kReliefMinSize || size > kReliefMaxSize || size % gpu::kReliefWorkgroupSize != 0))
    throw Error(fmt::format("relief cube size {} is not a multiple of {} in {}..{}", size, gpu::kReliefWorkgroupSize,
                            kReliefMinSize, kReliefMaxSize));
  vk::requireFormatFeatures(context, kReliefFormat,
                            VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT | VK_FORMAT_FEATURE_BLIT_SRC_BIT |
                                VK_FORMAT_FEATURE_BLIT_DST_BIT,
                            "the relief cube (stored, filtered, its mips blitted)");
  image_ = {context, vk::createImageCube(context, size, kReliefFormat,
                                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, uint32_t(std::bit_width(size)))};
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.maxLod = float(image_->mipLevels - 1);
  sampler_ = {context, vk::createSampler(context, info)};
  if (standIn) {
    // Never sampled: only the layout the descriptor names.
    vk::submitAndWait(context, [&](VkCommandBuffer cmd) {
      vk::transitionImage(cmd, *image_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                          VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    });
    return;
  }
  build(context, data);
}

double ReliefCube::texelAngleRad() const { return 2.0 / double(size()); }

void ReliefCube::build(vk::Context& context, const PlanetGpuData& data) {
  const PlanetDescription& planet = data.planet();
  gpu::ReliefPush push{};
  // Texels are smallest at a face's centre (2 / size of the tangent plane, as many radians).
  const double spacingM = planet.radiusM * texelAngleRad();
  for (size_t l = 0; l < planet.layers.size(); ++l) {
    const OctaveBudget budget = octaveBudget(planet.layers[l], spacingM);
    push.budget.octaves[l] = budget.octaves;
    push.budget.lastOctaveWeight[l] = budget.lastOctaveWeight;
    push.frequency[l / 4][l % 4] = float(planet.layers[l].frequency);
  }
  push.radiusM = float(planet.radiusM);
  push.baseHeightM = float(planet.baseHeightM);
  push.heightScale = float(planet.heightScale);
  push.size = size();

  const std::span<const uint32_t> spirv = needsFullNoiseShaders(planet)
                                              ? std::span<const uint32_t>(kSpv_relief_cube_comp)
                                              : kSpv_relief_cube_no_craters_comp;
  vk::Owned<vk::ComputePipeline> pipeline{
      context, vk::createComputePipeline(context, spirv, kBindings, sizeof(push), layerSpecialization(planet), 1)};
  VkDescriptorSet set = vk::allocateSet(context, pipeline->descriptorPool, pipeline->setLayout);
  vk::writeImageDescriptor(context, set, gpu::kReliefBindingImage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, image_->view,
                           VK_IMAGE_LAYOUT_GENERAL);
  vk::writeBufferDescriptor(context, set, gpu::kReliefBindingLayers, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, data.layers());
  vk::writeBufferDescriptor(context, set, gpu::kReliefBindingPermutations, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                            data.permutations());

  vk::Image& image = *image_;
  vk::submitAndWait(context, [&](VkCommandBuffer cmd) {
    vk::transitionLevels(cmd, image, 0, 1, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                         VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                         VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline->layout, 0, 1, &set, 0, nullptr);
    vkCmdPushConstants(cmd, pipeline->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    const uint32_t groups = size() / gpu::kReliefWorkgroupSize;
    vkCmdDispatch(cmd, groups, groups, 6);
    // The mip chain: heights and normals averaged (the shaders renormalize the normal).
    vk::recordMipChain(cmd, image, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT);
  });
}

}  // namespace planet
