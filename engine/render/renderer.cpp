#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <glm/gtc/packing.hpp>

#include "core/error.h"
#include "planet/terrain_height.h"
#include "render/sky_tables.h"
#include "render/starfield.h"
#include "vk/commands.h"
#include "vk/context.h"

namespace planet {
namespace {

constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // linear radiance, composed in place
constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_SRGB;      // the tonemapped frame, sRGB-encoded on store
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;         // reversed Z needs float depth

}  // namespace

void validateRenderSettings(const RenderSettings& settings) {
  if (settings.width == 0 || settings.height == 0 || settings.width > kRenderMaxSize ||
      settings.height > kRenderMaxSize)
    throw Error(fmt::format("image size {}x{} is outside 1x1 .. {}x{}", settings.width, settings.height, kRenderMaxSize,
                            kRenderMaxSize));
  if (!(settings.fovYDeg > 0.0 && settings.fovYDeg <= kRenderMaxFovDeg))
    throw Error(fmt::format("field of view {} degrees is outside (0, {}]", settings.fovYDeg, kRenderMaxFovDeg));
}

Renderer::Renderer(vk::Context& context, const PlanetDescription& planet, const RenderSettings& settings)
    : context_(context), planet_(planet), settings_(settings) {
  validateRenderSettings(settings);
  try {
    skyTables_ = std::make_unique<SkyTables>(context, planet);
    terrain_ = std::make_unique<TerrainPass>(context, planet, settings.terrain, kHdrFormat, kDepthFormat, *skyTables_);
    sky_ = std::make_unique<SkyPass>(context, planet, *skyTables_, settings.sky, kColorFormat);
    if (planet.stars.enabled && planet.stars.brightness > 0.0) {
      StarSettings stars;
      stars.seed = planet.stars.seed;
      stars.faintestMagnitude = float(planet.stars.faintestMagnitude);
      stars.count = realisticStarCount(stars.faintestMagnitude);
      stars.brightness = float(planet.stars.brightness);
      stars_ = std::make_unique<Starfield>(context, stars, kHdrFormat, kDepthFormat);
    }
    createTargets();
    if (context.timestampValidBits) {
      for (vk::GpuTimer& timer : timers_) timer.create(context, 16);
      timerCreated_ = true;
    }
  } catch (...) {
    release();
    throw;
  }
}

Renderer::~Renderer() { release(); }

void Renderer::release() {
  // destroy() skips a timer that was never created (a throw between the two creates).
  for (vk::GpuTimer& timer : timers_) timer.destroy(context_);
  timerCreated_ = false;
  destroyTargets();
  stars_.reset();
  sky_.reset();
  terrain_.reset();
  skyTables_.reset();
}

void Renderer::createTargets() {
  const VkExtent2D extent{settings_.width, settings_.height};
  hdr_ =
      vk::createImage2D(context_, extent, kHdrFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT);
  color_ = vk::createImage2D(context_, extent, kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
  depth_ = vk::createImage2D(context_, extent, kDepthFormat,
                             VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
  sky_->setTargets(hdr_, depth_);
}

void Renderer::destroyTargets() {
  vk::destroyImage(context_, depth_);
  vk::destroyImage(context_, color_);
  vk::destroyImage(context_, hdr_);
}

void Renderer::resize(uint32_t width, uint32_t height) {
  RenderSettings next = settings_;
  next.width = width;
  next.height = height;
  validateRenderSettings(next);
  if (width == settings_.width && height == settings_.height) return;
  destroyTargets();
  settings_ = next;
  createTargets();
}

void Renderer::setSkySettings(const SkySettings& sky) {
  settings_.sky = sky;
  sky_->setSettings(sky);
}

std::vector<vk::GpuTiming> Renderer::lastTimings(uint32_t slot) const {
  vk::checkFrameSlot(slot);
  return timerCreated_ ? timers_[slot].results(context_) : std::vector<vk::GpuTiming>{};
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

namespace {

VkRenderingAttachmentInfo clearedAttachment(const vk::Image& image, VkImageLayout layout) {
  VkRenderingAttachmentInfo attachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  attachment.imageView = image.view;
  attachment.imageLayout = layout;
  attachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  return attachment;  // clear value zero: black, and reversed-Z depth 0 (infinitely far)
}

void beginRendering(VkCommandBuffer cmd, VkExtent2D extent, const VkRenderingAttachmentInfo* color,
                    const VkRenderingAttachmentInfo* depth) {
  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = {{0, 0}, extent};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachments = color;
  rendering.pDepthAttachment = depth;
  vkCmdBeginRendering(cmd, &rendering);
  VkViewport viewport{0.0f, 0.0f, float(extent.width), float(extent.height), 0.0f, 1.0f};
  VkRect2D scissor{{0, 0}, extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace

Renderer::Prepared Renderer::prepare(const CameraPose& requested, const glm::dvec3& sunPlanet, double timeS,
                                     uint32_t slot) {
  bool raised = false;
  const CameraPose camera = clampToGround(requested, &raised);
  return prepareClamped(camera, raised, sunPlanet, timeS, slot);
}

Renderer::Prepared Renderer::prepareClamped(const CameraPose& camera, bool raised, const glm::dvec3& sunPlanet,
                                            double timeS, uint32_t slot) {
  vk::checkFrameSlot(slot);
  preparedSlot_ = UINT32_MAX;  // until this prepare() completed
  Prepared prepared;
  prepared.camera = camera;
  prepared.cameraRaised = raised;
  TerrainView view;
  view.camera = cameraBasis(prepared.camera, planet_.radiusM);
  view.fovYRad = settings_.fovYDeg * std::numbers::pi / 180.0;
  view.width = settings_.width;
  view.height = settings_.height;
  view.sunDirection = sunPlanet;
  view.timeS = timeS;
  const TerrainFrameInfo& frame = terrain_->prepare(view, slot);

  // The sky is drawn around the camera: its frame, also while the terrain's LOD is frozen.
  const glm::dmat3 planetToLocal = glm::transpose(frame.viewOrientation.localToPlanet);
  SkyView skyView;
  skyView.lowestSurfaceM = terrain_->lowestSurfaceM();
  skyView.viewProjection =
      reversedZPerspective(view.fovYRad, double(view.width) / double(view.height), frame.nearPlaneM) *
      viewMatrix(planetToLocal * view.camera.forward, planetToLocal * view.camera.up);
  skyView.localToPlanet = frame.viewOrientation.localToPlanet;
  skyView.forward = planetToLocal * view.camera.forward;
  skyView.sunLocal = planetToLocal * view.sunDirection;
  skyView.cameraPlanet = view.camera.position;
  skyView.altitudeM = frame.viewOrientation.altitudeM;
  skyView.nearPlaneM = frame.nearPlaneM;
  skyView.timeS = timeS;
  skyView.pixelAngleRad = view.fovYRad / double(view.height);
  sky_->prepare(skyView, settings_.width, settings_.height, slot);
  // Stars are fixed in the planet frame: planet direction → local → clip (a push constant).
  starsToClip_ = glm::mat4(skyView.viewProjection * glm::dmat4(planetToLocal));
  prepared.terrain = frame;
  preparedSlot_ = slot;
  return prepared;
}

void Renderer::record(VkCommandBuffer cmd, uint32_t slot) {
  vk::checkFrameSlot(slot);
  if (slot != preparedSlot_)
    throw Error(fmt::format("Renderer::record for frame slot {} without a prepare() for it", slot));
  preparedSlot_ = UINT32_MAX;
  const VkExtent2D extent{settings_.width, settings_.height};
  vk::GpuTimer* timer = timerCreated_ ? &timers_[slot] : nullptr;
  if (timer) timer->reset(cmd);
  skyTables_->recordBuild(cmd, timer);
  if (stars_) stars_->recordGenerate(cmd, timer);
  terrain_->recordCompute(cmd, timer);
  // Earlier contents are discarded: the frame clears the HDR target and the depth. The source
  // scope covers every earlier command on the queue (a previous frame still reading them).
  hdr_.layout = VK_IMAGE_LAYOUT_UNDEFINED;
  depth_.layout = VK_IMAGE_LAYOUT_UNDEFINED;
  color_.layout = VK_IMAGE_LAYOUT_UNDEFINED;
  vk::transitionImage(cmd, hdr_, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  vk::transitionImage(cmd, depth_, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
  const VkRenderingAttachmentInfo hdrAttachment = clearedAttachment(hdr_, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  const VkRenderingAttachmentInfo depthAttachment = clearedAttachment(depth_, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
  beginRendering(cmd, extent, &hdrAttachment, &depthAttachment);
  // Stars first, at infinity; everything drawn later covers them.
  if (stars_) stars_->recordDraw(cmd, starsToClip_, float(settings_.height), timer);
  terrain_->recordDraw(cmd, timer);
  vkCmdEndRendering(cmd);
  // The compose pass reads and writes the HDR colour and samples the depth.
  vk::transitionImage(cmd, hdr_, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vk::transitionImage(cmd, depth_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  sky_->recordCompose(cmd, timer);
  // The tonemap's fragments read what the compose pass wrote.
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
  vk::transitionImage(cmd, color_, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  const VkRenderingAttachmentInfo colorAttachment = clearedAttachment(color_, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  beginRendering(cmd, extent, &colorAttachment, nullptr);
  sky_->recordTonemap(cmd, timer);
  vkCmdEndRendering(cmd);
}

RenderResult Renderer::render(const CameraPose& requested, const SunPose& sun, double timeS, bool readHdr) {
  RenderResult result;
  // The sun is placed from the camera's ground point as rendered (after the eye-height rule,
  // applied once here). One frame at a time (the submission is waited for): slot 0 always.
  bool raised = false;
  const CameraPose camera = clampToGround(requested, &raised);
  const Prepared prepared = prepareClamped(camera, raised, sunDirection(sun, camera), timeS, 0);
  result.camera = prepared.camera;
  result.cameraRaised = prepared.cameraRaised;
  vk::submitAndWait(context_, [&](VkCommandBuffer cmd) { record(cmd, 0); });
  result.timings = lastTimings(0);
  result.terrain = terrain_->frame();
  std::vector<uint8_t> pixels = vk::readbackImage(context_, color_);
  result.image.width = settings_.width;
  result.image.height = settings_.height;
  result.image.pixels = std::move(pixels);
  if (readHdr) result.hdr = readHdrImage();
  return result;
}

std::vector<glm::vec4> Renderer::readHdrImage() {
  std::vector<uint8_t> bytes = vk::readbackImage(context_, hdr_);
  std::vector<glm::vec4> texels(size_t(settings_.width) * settings_.height);
  const auto* halves = reinterpret_cast<const uint16_t*>(bytes.data());
  for (size_t i = 0; i < texels.size(); ++i)
    for (int c = 0; c < 4; ++c) texels[i][c] = glm::unpackHalf1x16(halves[4 * i + size_t(c)]);
  return texels;
}

}  // namespace planet
