#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/error.h"
#include "planet/terrain_height.h"
#include "vk/commands.h"
#include "vk/context.h"

namespace planet {
namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_SRGB;  // linear shading, sRGB-encoded on store
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;     // reversed Z needs float depth

}  // namespace

void validateRenderSettings(const RenderSettings& settings) {
  if (settings.width == 0 || settings.height == 0 || settings.width > kRenderMaxSize ||
      settings.height > kRenderMaxSize)
    throw Error(fmt::format("image size {}x{} is outside 1x1 .. {}x{}", settings.width, settings.height, kRenderMaxSize,
                            kRenderMaxSize));
  if (!(settings.fovYDeg > 0.0 && settings.fovYDeg <= 179.0))
    throw Error(fmt::format("field of view {} degrees is outside (0, 179]", settings.fovYDeg));
}

Renderer::Renderer(vk::Context& context, const PlanetDescription& planet, const RenderSettings& settings)
    : context_(context), planet_(planet), settings_(settings) {
  validateRenderSettings(settings);
  try {
    terrain_ = std::make_unique<TerrainPass>(context, planet, settings.terrain, kColorFormat, kDepthFormat);
    const VkExtent2D extent{settings.width, settings.height};
    color_ = vk::createImage2D(context, extent, kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
    depth_ = vk::createImage2D(context, extent, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
    if (context.timestampValidBits) {
      timer_.create(context, 16);
      timerCreated_ = true;
    }
  } catch (...) {
    release();
    throw;
  }
}

Renderer::~Renderer() { release(); }

void Renderer::release() {
  if (timerCreated_) timer_.destroy(context_);
  timerCreated_ = false;
  vk::destroyImage(context_, depth_);
  vk::destroyImage(context_, color_);
  terrain_.reset();
}

CameraPose Renderer::clampToGround(const CameraPose& camera, bool* raised) const {
  const double ground = terrainHeightM(planet_, directionFromLatLon(camera.latitudeDeg, camera.longitudeDeg));
  const double surface = planet_.hasOcean ? std::max(ground, planet_.seaLevelM) : ground;
  CameraPose result = camera;
  const bool below = camera.altitudeM < surface + kMinEyeHeightM;
  if (below) result.altitudeM = surface + kMinEyeHeightM;
  if (raised) *raised = below;
  return result;
}

RenderResult Renderer::render(const CameraPose& requested, const SunPose& sun) {
  RenderResult result;
  result.camera = clampToGround(requested, &result.cameraRaised);
  TerrainView view;
  view.camera = cameraBasis(result.camera, planet_.radiusM);
  view.fovYRad = settings_.fovYDeg * std::numbers::pi / 180.0;
  view.width = settings_.width;
  view.height = settings_.height;
  view.sunDirection = sunDirection(sun, result.camera);
  terrain_->prepare(view);

  vk::GpuTimer* timer = timerCreated_ ? &timer_ : nullptr;
  vk::submitAndWait(context_, [&](VkCommandBuffer cmd) {
    if (timer) timer->reset(cmd);
    terrain_->recordCompute(cmd, timer);
    // Earlier contents are discarded: the frame clears both attachments.
    color_.layout = VK_IMAGE_LAYOUT_UNDEFINED;
    depth_.layout = VK_IMAGE_LAYOUT_UNDEFINED;
    vk::transitionImage(cmd, color_, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                        VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    vk::transitionImage(cmd, depth_, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    VkRenderingAttachmentInfo colorAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    colorAttachment.imageView = color_.view;
    colorAttachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colorAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    colorAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    colorAttachment.clearValue.color = {{0.0f, 0.0f, 0.0f, 1.0f}};  // space (stars come with the sky pass)
    VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depthAttachment.imageView = depth_.view;
    depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depthAttachment.clearValue.depthStencil = {0.0f, 0};  // reversed Z: 0 is infinitely far
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {settings_.width, settings_.height}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachments = &colorAttachment;
    rendering.pDepthAttachment = &depthAttachment;
    vkCmdBeginRendering(cmd, &rendering);
    VkViewport viewport{0.0f, 0.0f, float(settings_.width), float(settings_.height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {settings_.width, settings_.height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    terrain_->recordDraw(cmd, timer);
    vkCmdEndRendering(cmd);
  });
  if (timer) result.timings = timer->results(context_);
  result.terrain = terrain_->frame();
  std::vector<uint8_t> pixels = vk::readbackImage(context_, color_);
  result.image.width = settings_.width;
  result.image.height = settings_.height;
  result.image.pixels = std::move(pixels);
  return result;
}

}  // namespace planet
