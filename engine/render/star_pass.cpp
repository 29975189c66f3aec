#include "render/star_pass.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "common/definitions.h"
#include "core/error.h"
#include "spv/stars.comp.h"
#include "spv/stars.frag.h"
#include "spv/stars.vert.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/graphics_pipeline.h"
#include "vk/pipeline.h"
#include "vk/timer.h"

namespace planet {
namespace {

using namespace planet::gpu;

// shaders/common/star_visibility.glsl compiled as C++ in float, as the GPU runs it.
struct StarVisibilityKernel {
  PLANET_GLSL_KERNEL(float)
  static real log2(real x) { return std::log2(x); }
#include "common/star_visibility.glsl"
};

constexpr VkDescriptorType kBindingTypes[] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};  // kStarBindingCatalogue
// One pipeline layout for both pipelines: the compute shader reads the first 16 bytes of the
// push constants (StarGeneratePush), the vertex shader all 80 (StarDrawPush).
constexpr VkShaderStageFlags kPushStages = VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT;
static_assert(sizeof(gpu::StarGeneratePush) <= sizeof(gpu::StarDrawPush));

}  // namespace

StarPass::StarPass(vk::Context& context, const StarSettings& settings, VkFormat colorFormat, VkFormat depthFormat)
    : context_(context), settings_(settings) {
  static_assert(gpu::kStarBindingCatalogue == 0);
  validateStarSettings(settings);
  // Sprites larger than one pixel need the largePoints feature, which vk/context.cpp enables
  // whenever the device supports it (lavapipe does, up to 255 px).
  VkPhysicalDeviceFeatures features{};
  vkGetPhysicalDeviceFeatures(context.physicalDevice, &features);
  maxPointSize_ = features.largePoints ? std::max(1.0f, context.properties.limits.pointSizeRange[1]) : 1.0f;
  for (uint32_t t = 0; t < gpu::kStarTileCount; ++t) caps_.push_back(starTileCap(t));
  for (uint32_t t = 0; t <= gpu::kStarTileCount; ++t) tileFirst_.push_back(starTileFirstIndex(t, settings.count));
  catalogue_ = {context, vk::createBuffer(context, VkDeviceSize(settings.count) * sizeof(gpu::StarRecord),
                                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::DeviceLocal)};
  setLayout_ = {context,
                vk::createSetLayout(context, kBindingTypes, VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT)};
  pool_ = {context, vk::createDescriptorPool(context, kBindingTypes, 1)};
  set_ = vk::allocateSet(context, pool_.get(), setLayout_.get());
  vk::writeBufferDescriptor(context, set_, gpu::kStarBindingCatalogue, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, *catalogue_);
  layout_ = {context, vk::createPipelineLayout(context, setLayout_.get(), sizeof(gpu::StarDrawPush), kPushStages)};
  generatePipeline_ = {context, vk::createComputePipelineWithLayout(context, kSpv_stars_comp, layout_.get())};
  vk::GraphicsPipelineDesc desc;
  desc.vertexSpirv = kSpv_stars_vert;
  desc.fragmentSpirv = kSpv_stars_frag;
  desc.layout = layout_.get();
  desc.colorFormat = colorFormat;
  desc.depthFormat = depthFormat;
  desc.topology = VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
  desc.cullMode = VK_CULL_MODE_NONE;
  // At infinity, drawn first: nothing to test against, and the terrain must not be hidden.
  desc.depthTest = false;
  desc.depthWrite = false;
  desc.additiveBlend = true;
  drawPipeline_ = {context, vk::createGraphicsPipeline(context, desc)};
}

void StarPass::recordGenerate(VkCommandBuffer cmd, vk::GpuTimer* timer) {
  if (generated_) return;
  if (timer) timer->begin(cmd, "star catalogue");
  gpu::StarGeneratePush push{};
  push.count = settings_.count;
  push.seed = settings_.seed;
  push.faintestMagnitude = settings_.faintestMagnitude;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, generatePipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &set_, 0, nullptr);
  vkCmdPushConstants(cmd, layout_.get(), kPushStages, 0, sizeof(push), &push);
  vkCmdDispatch(cmd, (settings_.count + gpu::kStarWorkgroupSize - 1) / gpu::kStarWorkgroupSize, 1, 1);
  // Every later draw's vertex shader reads the catalogue; readCatalogue copies or maps it.
  vk::memoryBarrier(
      cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
      VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_HOST_READ_BIT);
  if (timer) timer->end(cmd);
  generated_ = true;
}

void StarPass::recordDraw(VkCommandBuffer cmd, const glm::mat4& directionToClip, float viewportHeightPx,
                          vk::GpuTimer* timer) {
  if (!generated_) throw Error("StarPass::recordDraw before recordGenerate: the catalogue does not exist yet");
  if (!(std::isfinite(viewportHeightPx) && viewportHeightPx > 0.0f))
    throw Error(fmt::format("star viewport height {} px is not a positive number", viewportHeightPx));
  if (timer) timer->begin(cmd, "stars");
  gpu::StarDrawPush push{};
  push.directionToClip = directionToClip;
  push.brightness = settings_.brightness;
  push.pixelScale = std::max(1.0f, viewportHeightPx / kStarReferenceHeightPx);
  push.maxPointSize = maxPointSize_;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, drawPipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 1, &set_, 0, nullptr);
  vkCmdPushConstants(cmd, layout_.get(), kPushStages, 0, sizeof(push), &push);
  // A direction d is inside the view when w ≥ |x| and w ≥ |y| for (x, y, _, w) = M·(d, 0): four
  // half-spaces n·d ≥ 0 with n = row w ± row x, row w ± row y. A cap of radius r around axis a
  // reaches into {n·d ≥ 0} when the angle between a and n is below 90° + r.
  glm::dvec3 planes[4];
  const glm::dmat4 m(directionToClip);
  const glm::dvec3 rowX(m[0][0], m[1][0], m[2][0]), rowY(m[0][1], m[1][1], m[2][1]), rowW(m[0][3], m[1][3], m[2][3]);
  planes[0] = rowW + rowX;
  planes[1] = rowW - rowX;
  planes[2] = rowW + rowY;
  planes[3] = rowW - rowY;
  for (glm::dvec3& n : planes) n = glm::length(n) > 0.0 ? glm::normalize(n) : n;
  auto visible = [&](uint32_t tile) {
    if (!settings_.cullTiles) return true;
    const StarTileCap& cap = caps_[tile];
    const double reach = cap.radiusRad + kStarCullMarginRad;
    if (reach >= 0.5 * std::numbers::pi) return true;
    for (const glm::dvec3& n : planes)
      if (glm::dot(n, cap.axis) < -std::sin(reach)) return false;
    return true;
  };
  // One draw per run of consecutive visible tiles (the catalogue is ordered by tile).
  drawnStars_ = 0;
  for (uint32_t t = 0; t < gpu::kStarTileCount;) {
    if (!visible(t)) {
      ++t;
      continue;
    }
    const uint32_t first = t;
    while (t < gpu::kStarTileCount && visible(t)) ++t;
    const uint32_t count = tileFirst_[t] - tileFirst_[first];
    if (count) vkCmdDraw(cmd, count, 1, tileFirst_[first], 0);
    drawnStars_ += count;
  }
  if (timer) timer->end(cmd);
}

std::vector<gpu::StarRecord> StarPass::readCatalogue() {
  if (!generated_) throw Error("StarPass::readCatalogue before recordGenerate: the catalogue does not exist yet");
  std::vector<gpu::StarRecord> stars(settings_.count);
  vk::readbackBuffer(context_, *catalogue_, stars.data(), stars.size() * sizeof(gpu::StarRecord));
  return stars;
}

double starLimitingMagnitude(double sky) { return StarVisibilityKernel{}.starLimitingMagnitude(float(sky)); }

double starVisibleShare(double relativeFlux, double sky) {
  return StarVisibilityKernel{}.starVisibleShare(float(relativeFlux), float(sky));
}

}  // namespace planet
