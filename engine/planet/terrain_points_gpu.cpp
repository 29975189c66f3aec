#include "planet/terrain_points_gpu.h"

#include <fmt/format.h>

#include "core/error.h"
#include "shared/terrain_params.h"
#include "spv/terrain_points.comp.h"
#include "vk/commands.h"
#include "vk/context.h"

namespace planet {
namespace {

constexpr uint32_t kBufferCount = 6;  // shaders/shared/terrain_params.h, bindings 0..5
constexpr VkDeviceSize kTableRows = VkDeviceSize(gpu::kTerrainMaxLayers) * gpu::kNoiseMaxOctaves;

}  // namespace

GpuTerrainPoints::GpuTerrainPoints(vk::Context& context, const PlanetDescription& planet)
    : context_(context), planet_(planet), data_(context, planet) {
  static_assert(gpu::kTerrainBindingOffsets == 0 && gpu::kTerrainBindingPermutations == kBufferCount - 1);
  pipeline_ = {context, vk::createComputePipeline(context, kSpv_terrain_points_comp, kBufferCount,
                                                  sizeof(gpu::TerrainPointsPush), {}, 1)};
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  remainders_ = {context, vk::createBuffer(context, kTableRows * sizeof(glm::vec4), storage, vk::MemoryUsage::Upload)};
  shifts_ = {context, vk::createBuffer(context, kTableRows * sizeof(glm::uvec4), storage, vk::MemoryUsage::Upload)};
}

std::vector<float> GpuTerrainPoints::evaluate(const OctaveTables& tables, std::span<const glm::vec3> offsetsM) {
  if (offsetsM.empty()) return {};
  if (tables.remainders.size() != planet_.layers.size() * gpu::kNoiseMaxOctaves)
    throw Error("octave tables were built for another planet");
  // The tables change with the anchor (every frame in the renderer): host-visible buffers.
  vk::uploadBuffer(context_, *remainders_, tables.remainders.data(), tables.remainders.size() * sizeof(glm::vec4));
  vk::uploadBuffer(context_, *shifts_, tables.shifts.data(), tables.shifts.size() * sizeof(glm::uvec4));

  std::vector<glm::vec4> padded(offsetsM.size());
  for (size_t i = 0; i < offsetsM.size(); ++i) padded[i] = glm::vec4(offsetsM[i], 0.0f);
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  vk::Owned<vk::Buffer> offsets(
      context_, vk::createBuffer(context_, padded.size() * sizeof(glm::vec4), storage, vk::MemoryUsage::DeviceLocal));
  vk::uploadBuffer(context_, *offsets, padded.data(), padded.size() * sizeof(glm::vec4));
  const vk::Owned<vk::Buffer> heights(
      context_, vk::createBuffer(context_, offsetsM.size() * sizeof(float), storage, vk::MemoryUsage::DeviceLocal));

  VK_CHECK(vkResetDescriptorPool(context_.device, pipeline_->descriptorPool, 0));
  const vk::Buffer* buffers[kBufferCount] = {&*offsets,     &*heights, &data_.layers(),
                                             &*remainders_, &*shifts_, &data_.permutations()};
  VkDescriptorSet set = vk::allocateStorageSet(context_, *pipeline_, buffers);
  gpu::TerrainPointsPush push{uint32_t(planet_.layers.size()), uint32_t(offsetsM.size()), float(planet_.baseHeightM),
                              float(planet_.heightScale)};
  const uint32_t groups = uint32_t((offsetsM.size() + gpu::kTerrainWorkgroupSize - 1) / gpu::kTerrainWorkgroupSize);
  if (groups > context_.properties.limits.maxComputeWorkGroupCount[0])
    throw Error(fmt::format("{} points exceed one dispatch", offsetsM.size()));
  vk::submitAndWait(context_, [&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout, 0, 1, &set, 0, nullptr);
    vkCmdPushConstants(cmd, pipeline_->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, groups, 1, 1);
    // The heights are copied out by the readback's transfer.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  });
  std::vector<float> result(offsetsM.size());
  vk::readbackBuffer(context_, *heights, result.data(), result.size() * sizeof(float));
  return result;
}

}  // namespace planet
