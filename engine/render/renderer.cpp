#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "core/error.h"
#include "planet/terrain_height.h"
#include "reference/eclipse.h"
#include "reference/sunlight.h"
#include "render/luminance_pass.h"
#include "render/ring_pass.h"
#include "render/sky_tables.h"
#include "render/star_pass.h"
#include "render/tonemap_pass.h"
#include "vk/commands.h"
#include "vk/context.h"

namespace planet {
namespace {

// Linear radiance, composed in place. Float, not half: a sky 10° past sunset is 4e-8 of the sun's
// irradiance, below half's smallest subnormal (6e-8), and auto exposure brings it into view.
constexpr VkFormat kHdrFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
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

namespace {

std::vector<PlanetDescription> scenePlanets(const SceneDescription& scene) {
  std::vector<PlanetDescription> planets;
  for (const BodyDescription& body : scene.bodies) planets.push_back(body.planet);
  return planets;
}
std::vector<std::optional<RingDescription>> sceneRings(const SceneDescription& scene) {
  std::vector<std::optional<RingDescription>> rings;
  for (const BodyDescription& body : scene.bodies) rings.push_back(body.rings);
  return rings;
}

}  // namespace

Renderer::Renderer(vk::Context& context, const PlanetDescription& planet, const RenderSettings& settings)
    : Renderer(context, std::vector<PlanetDescription>{planet}, {std::nullopt}, settings) {}

Renderer::Renderer(vk::Context& context, const SceneDescription& scene, const RenderSettings& settings)
    : Renderer(context, scenePlanets(scene), sceneRings(scene), settings) {}

Renderer::Renderer(vk::Context& context, const std::vector<PlanetDescription>& bodies,
                   const std::vector<std::optional<RingDescription>>& rings, const RenderSettings& settings)
    : context_(context), settings_(settings) {
  validateRenderSettings(settings);
  if (bodies.empty() || bodies.size() > kMaxSceneBodies)
    throw Error(fmt::format("a renderer draws 1 to {} bodies, got {}", kMaxSceneBodies, bodies.size()));
  // The G-buffer holds one body's ground: its compute pass shades with that body's uniforms.
  if (settings.terrain.deferredShading && bodies.size() > 1)
    throw Error(
        fmt::format("terrain shading 'deferred' draws one body, the scene has {}; use 'forward'", bodies.size()));
  createBodies(bodies, rings);
  for (const PlanetDescription& planet : bodies) {
    if (!planet.stars.enabled || !(planet.stars.brightness > 0.0)) continue;
    StarSettings stars;
    stars.seed = planet.stars.seed;
    stars.faintestMagnitude = float(planet.stars.faintestMagnitude);
    stars.count = realisticStarCount(stars.faintestMagnitude);
    stars.brightness = float(planet.stars.brightness);
    stars_ = std::make_unique<StarPass>(context, stars, kHdrFormat, kDepthFormat);
    break;
  }
  // Made whether or not the frames adapt, so that the viewer can switch without a rebuild.
  luminance_ = std::make_unique<LuminancePass>(context);
  // The measurement counts city lights at their physical radiance: the first body's with lights
  // (one gain for the frame; of the presets only Earth has them).
  for (const PlanetDescription& planet : bodies)
    if (planet.lights.enabled) {
      luminance_->setLightsGain(planet.lights.gain);
      break;
    }
  tonemap_ = std::make_unique<TonemapPass>(context, kColorFormat, settings.sky.exposure, luminance_->exposure());
  tonemap_->setAdapting(settings.autoExposure);
  createTargets();
  if (context.timestampValidBits) {
    for (vk::GpuTimer& timer : timers_) timer.create(context, timingScopes());
    timerCreated_ = true;
  }
}

uint32_t Renderer::Body::timingScopes() const {
  return SkyTables::kTimingScopes + TerrainPass::kTimingScopes + SkyPass::kTimingScopes +
         (rings ? RingPass::kTimingScopes : 0);
}

uint32_t Renderer::timingScopes() const {
  uint32_t scopes = (stars_ ? StarPass::kTimingScopes : 0) + LuminancePass::kTimingScopes + TonemapPass::kTimingScopes;
  for (const Body& body : bodies_) scopes += body.timingScopes();
  return scopes;
}

void Renderer::createBodies(const std::vector<PlanetDescription>& planets,
                            const std::vector<std::optional<RingDescription>>& rings) {
  for (size_t i = 0; i < planets.size(); ++i) {
    Body body;
    body.planet = planets[i];
    body.refracted = refractedIntoShadow(body.planet);
    // Only the camera's own body gets the patch textures (prepareScene moves them); the others
    // are seen from afar, where the vertex normals are finer than a pixel.
    TerrainSettings terrain = settings_.terrain;
    if (i > 0) terrain.patches = false;
    // One body: nothing can eclipse it, and its shaders leave that code out.
    terrain.eclipses = planets.size() > 1;
    body.skyTables = std::make_unique<SkyTables>(context_, body.planet);
    body.terrain =
        std::make_unique<TerrainPass>(context_, body.planet, terrain, kHdrFormat, kDepthFormat, *body.skyTables);
    body.sky = std::make_unique<SkyPass>(context_, body.planet, *body.skyTables, settings_.sky, terrain.eclipses);
    // The sea mirrors the sky around it from the sky pass's sky-view table (recorded before the draws).
    body.terrain->setSkyView(body.sky->skyViewTable(), body.skyTables->sampler());
    if (rings[i]) {
      body.rings = std::make_unique<RingPass>(context_, *rings[i], kHdrFormat, kDepthFormat, body.skyTables.get());
      const gpu::RingParams shadow = ringGpuParams(*rings[i], body.planet.radiusM, kSunAngularRadiusRad);
      body.terrain->setRingShadow(&shadow);
    }
    bodies_.push_back(std::move(body));
  }
  composeOrder_ = {ComposeStep{0, false}};
}

Renderer::~Renderer() = default;

void Renderer::createTargets() {
  const VkExtent2D extent{settings_.width, settings_.height};
  vk::requireFormatFeatures(context_, kHdrFormat,
                            VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT |
                                VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT,
                            "the HDR frame (drawn with blending, composed in place)");
  hdr_ = {context_, vk::createImage2D(context_, extent, kHdrFormat,
                                      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT)};
  color_ = {context_, vk::createImage2D(context_, extent, kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT)};
  depth_ = {context_, vk::createImage2D(context_, extent, kDepthFormat,
                                        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT)};
  if (settings_.terrain.deferredShading) {
    for (uint32_t i = 0; i < TerrainPass::kGBufferTargets; ++i)
      gbuffer_.emplace_back(context_,
                            vk::createImage2D(context_, extent, TerrainPass::kGBufferFormat,
                                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT));
    std::vector<const vk::Image*> gbuffer;  // once the vector holds them all (it moves them as it grows)
    for (const vk::Owned<vk::Image>& image : gbuffer_) gbuffer.push_back(&*image);
    for (Body& body : bodies_) body.terrain->setShadingTargets(gbuffer, *hdr_);
  }
  for (Body& body : bodies_) body.sky->setTargets(*hdr_, *depth_);
  luminance_->setSource(*hdr_);
  tonemap_->setSource(*hdr_);
}

void Renderer::resize(uint32_t width, uint32_t height) {
  RenderSettings next = settings_;
  next.width = width;
  next.height = height;
  validateRenderSettings(next);
  if (width == settings_.width && height == settings_.height) return;
  // The old targets go before the new ones are made.
  gbuffer_.clear();
  depth_.reset();
  color_.reset();
  hdr_.reset();
  settings_ = next;
  createTargets();
}

void Renderer::setSkySettings(const SkySettings& sky) {
  settings_.sky = sky;
  for (Body& body : bodies_) body.sky->setSettings(sky);
  tonemap_->setExposure(sky.exposure);
}

void Renderer::setAutoExposure(bool enabled) {
  if (enabled && !settings_.autoExposure) exposureReset_ = true;
  settings_.autoExposure = enabled;
  tonemap_->setAdapting(enabled);
}

void Renderer::adaptExposureOver(double seconds) {
  if (!(seconds >= 0.0 && std::isfinite(seconds)))
    throw Error(fmt::format("exposure adaptation time {} s must be a finite number >= 0", seconds));
  exposureStepS_ = seconds;
}

std::optional<ExposureReport> Renderer::lastExposure(uint32_t slot) const {
  vk::checkFrameSlot(slot);
  if (!settings_.autoExposure) return std::nullopt;
  return luminance_->report(slot);
}

std::vector<vk::GpuTiming> Renderer::lastTimings(uint32_t slot) const {
  vk::checkFrameSlot(slot);
  return timerCreated_ ? timers_[slot].results(context_) : std::vector<vk::GpuTiming>{};
}

double Renderer::lastFrameEndMs(uint32_t slot) const {
  vk::checkFrameSlot(slot);
  return timerCreated_ ? timers_[slot].lastStampMs(context_) : 0.0;
}

CameraPose Renderer::clampToGround(const CameraPose& camera, bool* raised) const {
  return raisedAboveGround(bodies_[0].planet, camera, raised);
}

CameraPose Renderer::raisedAboveGround(const PlanetDescription& planet, const CameraPose& camera, bool* raised) {
  const double surface = surfaceHeightM(planet, directionFromLatLon(camera.latitudeDeg, camera.longitudeDeg));
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

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Between two passes over the frame's targets: the later one loads what the earlier one stored.
void attachmentsBarrier(VkCommandBuffer cmd) {
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                        VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
}

void beginRendering(VkCommandBuffer cmd, VkExtent2D extent, const VkRenderingAttachmentInfo* color, uint32_t colorCount,
                    const VkRenderingAttachmentInfo* depth) {
  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = {{0, 0}, extent};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = colorCount;
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
  checkOnePlanet("prepare", "prepareScene");
  bool raised = false;
  const CameraPose camera = clampToGround(requested, &raised);
  return prepareFrame(onePlanetView(camera, sunPlanet, timeS), 0, camera, raised, slot);
}

void Renderer::checkOnePlanet(const char* call, const char* sceneCall) const {
  if (bodies_.size() != 1)
    throw Error(fmt::format("Renderer::{} places the camera on one planet; this renderer draws {} bodies (use {})",
                            call, bodies_.size(), sceneCall));
}

SceneView Renderer::onePlanetView(const CameraPose& camera, const glm::dvec3& sunPlanet, double timeS) const {
  // The planet frame is the scene frame: the body at the origin, unturned.
  SceneView view;
  view.camera = cameraBasis(camera, bodies_[0].planet.radiusM);
  view.bodies = {SceneBodyView{glm::dvec3(0.0), glm::dmat3(1.0), sunPlanet}};
  view.timeS = timeS;
  return view;
}

Renderer::Prepared Renderer::prepareScene(const SceneView& requested, uint32_t slot) {
  if (requested.bodies.size() != bodies_.size())
    throw Error(fmt::format("scene view has {} bodies, the renderer {}", requested.bodies.size(), bodies_.size()));
  // The camera's own body: the one whose surface is nearest relative to its size.
  std::vector<double> radii;
  std::vector<glm::dvec3> centres;
  for (size_t i = 0; i < bodies_.size(); ++i) {
    radii.push_back(bodies_[i].planet.radiusM);
    centres.push_back(requested.bodies[i].positionM);
  }
  const size_t primary = relativelyNearestBody(radii, centres, requested.camera.position);
  // The eye-height rule on that body, in its frame: a camera below its ground is raised along
  // the vertical, its view direction kept.
  const SceneBodyView& body = requested.bodies[primary];
  const CameraBasis local = cameraToBody(body.positionM, body.bodyToScene, requested.camera);
  const double radius = bodies_[primary].planet.radiusM;
  bool raised = false;
  const CameraPose pose = raisedAboveGround(bodies_[primary].planet, cameraPoseFromBasis(local, radius), &raised);
  SceneView view = requested;
  if (raised)
    view.camera.position =
        body.positionM + body.bodyToScene * (glm::normalize(local.position) * (radius + pose.altitudeM));
  return prepareFrame(view, primary, pose, raised, slot);
}

Renderer::Prepared Renderer::prepareFrame(const SceneView& view, size_t primary, const CameraPose& primaryPose,
                                          bool raised, uint32_t slot) {
  vk::checkFrameSlot(slot);
  preparedSlot_ = UINT32_MAX;  // until this prepare() completed
  if (primary != primary_) {
    bodies_[primary_].terrain->setPatchesEnabled(false);
    bodies_[primary].terrain->setPatchesEnabled(settings_.terrain.patches);
    primary_ = primary;
  }
  Prepared prepared;
  prepared.camera = primaryPose;
  prepared.cameraRaised = raised;

  // Each body sees the camera and the sun in its own frame.
  std::vector<TerrainView> views(bodies_.size());
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const SceneBodyView& body = view.bodies[i];
    TerrainView& t = views[i];
    t.camera = cameraToBody(body.positionM, body.bodyToScene, view.camera);
    t.fovYRad = settings_.fovYDeg * std::numbers::pi / 180.0;
    t.width = settings_.width;
    t.height = settings_.height;
    t.sunDirection = glm::transpose(body.bodyToScene) * body.sunDirection;
    const Sunlight sun = sunlightAtDistance(body.sunDistanceM);
    t.sunIrradianceScale = sun.irradianceScale;
    t.sunAngularRadiusRad = sun.angularRadiusRad;
    t.timeS = view.timeS;
    t.clouds = settings_.sky.clouds;
    // The scene's other bodies, which may hide the sun from this one (eclipses).
    const glm::dmat3 sceneToBody = glm::transpose(body.bodyToScene);
    for (size_t j = 0; j < bodies_.size(); ++j)
      if (j != i)
        t.occluders.push_back({sceneToBody * (view.bodies[j].positionM - view.camera.position),
                               bodies_[j].planet.radiusM, bodies_[j].refracted});
  }
  // One depth buffer: every body takes the nearest near plane. The primary body's own rule
  // (a quarter of the height above its ground) is capped by the others' clearance.
  double maxNear = 5.0e4;
  for (size_t i = 0; i < bodies_.size(); ++i) {
    if (i == primary) continue;
    const double clearance = glm::length(views[i].camera.position) - bodies_[i].planet.radiusM -
                             bodies_[i].terrain->maxTerrainHeightM();
    maxNear = std::min(maxNear, std::max(0.25 * clearance, 0.01));
  }
  views[primary].maxNearPlaneM = maxNear;
  const TerrainFrameInfo& frame = bodies_[primary].terrain->prepare(views[primary], slot);
  prepared.terrain = frame;
  const double nearPlane = frame.nearPlaneM;
  std::vector<std::pair<double, size_t>> farther;  // (distance, body) of the other bodies with air or rings
  for (size_t i = 0; i < bodies_.size(); ++i) {
    if (i == primary) continue;
    views[i].maxNearPlaneM = nearPlane;
    bodies_[i].terrain->prepare(views[i], slot);
    if (bodies_[i].planet.atmosphere.enabled || bodies_[i].rings)
      farther.emplace_back(glm::length(views[i].camera.position), i);
  }
  std::sort(farther.begin(), farther.end(), std::greater<>());
  // Every body's view shares the camera's projection (the frames differ by rotations only).
  const glm::dmat4 projection =
      reversedZPerspective(views[primary].fovYRad, double(settings_.width) / double(settings_.height), nearPlane);
  // Far to near by the bodies' centres, each body's rings right after its atmosphere: a ring is
  // then drawn over every atmosphere behind it and under every nearer one, and applies its own
  // body's air in front of it itself (shaders/ring.frag). The camera's own body comes last
  // (its compose draws the sun and fades the stars). A ring that reaches past a nearer body
  // (a moon inside it) is ordered as its body's centre is: the whole ring behind that body's air.
  composeOrder_.clear();
  for (const auto& [distance, i] : farther) {
    if (bodies_[i].planet.atmosphere.enabled) composeOrder_.push_back({i, false});
    if (bodies_[i].rings) composeOrder_.push_back({i, true});
  }
  composeOrder_.push_back({primary, false});
  if (bodies_[primary].rings) composeOrder_.push_back({primary, true});

  for (size_t i = 0; i < bodies_.size(); ++i) {
    if (!bodies_[i].rings) continue;
    const TerrainView& t = views[i];
    RingView ring;
    ring.viewProjection = projection * viewMatrix(t.camera.forward, t.camera.up);
    ring.cameraBody = t.camera.position;
    ring.sunBody = t.sunDirection;
    ring.planetRadiusM = bodies_[i].planet.radiusM;
    ring.nearPlaneM = nearPlane;
    ring.width = t.width;
    ring.height = t.height;
    ring.sunIrradiance = gpu::kSunIrradiance * bodies_[i].terrain->settings().sunIntensity * t.sunIrradianceScale;
    ring.sunAngularRadiusRad = t.sunAngularRadiusRad;
    ring.ambient = bodies_[i].terrain->settings().ambient;
    ring.occluders = t.occluders;
    ring.sunIrradianceScale = t.sunIrradianceScale;
    // As the sky pass's ground sphere (SkyPass::prepare): the radius sphere under a sea, else
    // the deepest terrain when that is below it.
    const PlanetDescription& planet = bodies_[i].planet;
    ring.groundSphereM = planet.hasOcean ? 0.0 : std::min(bodies_[i].terrain->lowestSurfaceM(), 0.0);
    bodies_[i].rings->prepare(ring, slot);
  }
  // The sky is drawn around the camera: each body's frame, also while the terrain's LOD is frozen.
  glm::dmat4 primaryViewProjection(1.0);
  glm::dmat3 primaryPlanetToLocal(1.0);
  for (const ComposeStep& step : composeOrder_) {
    if (step.rings) continue;
    const size_t i = step.body;
    const TerrainFrameInfo& bodyFrame = bodies_[i].terrain->frame();
    const TerrainView& t = views[i];
    const glm::dmat3 planetToLocal = glm::transpose(bodyFrame.viewOrientation.localToPlanet);
    SkyView skyView;
    skyView.lowestSurfaceM = bodies_[i].terrain->lowestSurfaceM();
    skyView.highestSurfaceM = bodies_[i].terrain->maxTerrainHeightM();
    skyView.ownSurfacesOnly =
        bodies_.size() == 1 && !bodies_[i].rings && skyView.highestSurfaceM < bodies_[i].planet.atmosphere.heightM;
    skyView.viewProjection = projection * viewMatrix(planetToLocal * t.camera.forward, planetToLocal * t.camera.up);
    skyView.localToPlanet = bodyFrame.viewOrientation.localToPlanet;
    skyView.forward = planetToLocal * t.camera.forward;
    skyView.sunLocal = planetToLocal * t.sunDirection;
    skyView.sunIrradianceScale = t.sunIrradianceScale;
    skyView.sunAngularRadiusRad = t.sunAngularRadiusRad;
    skyView.cameraPlanet = t.camera.position;
    skyView.altitudeM = bodyFrame.viewOrientation.altitudeM;
    skyView.nearPlaneM = nearPlane;
    skyView.timeS = view.timeS;
    skyView.pixelAngleRad = t.fovYRad / double(t.height);
    skyView.drawSun = i == primary;
    skyView.occluders = t.occluders;
    bodies_[i].sky->prepare(skyView, settings_.width, settings_.height, slot);
    if (i == primary) {
      primaryViewProjection = skyView.viewProjection;
      primaryPlanetToLocal = planetToLocal;
    }
  }
  // Stars are fixed in the scene frame: scene direction → the primary body's frame → local → clip
  // (a push constant).
  const glm::dmat3 sceneToPrimary = glm::transpose(view.bodies[primary].bodyToScene);
  starsToClip_ = glm::mat4(primaryViewProjection * glm::dmat4(primaryPlanetToLocal * sceneToPrimary));
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
  for (Body& body : bodies_) body.skyTables->recordBuild(cmd, timer);
  if (stars_) stars_->recordGenerate(cmd, timer);
  for (Body& body : bodies_) body.terrain->recordCompute(cmd, timer);
  // The sky-view tables before the draws: the sea mirrors them.
  for (Body& body : bodies_) body.sky->recordSkyView(cmd, timer);
  // Earlier contents are discarded: the frame clears the HDR target and the depth. The source
  // scope covers every earlier command on the queue (a previous frame still reading them).
  vk::Image& hdr = *hdr_;
  vk::Image& depth = *depth_;
  vk::Image& color = *color_;
  hdr.layout = VK_IMAGE_LAYOUT_UNDEFINED;
  depth.layout = VK_IMAGE_LAYOUT_UNDEFINED;
  color.layout = VK_IMAGE_LAYOUT_UNDEFINED;
  vk::transitionImage(cmd, hdr, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  vk::transitionImage(cmd, depth, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
  // The stars, the ground and the sea each in a render pass of their own over the
  // same targets, so that each has a timing scope of its own. Lavapipe shades a draw's vertices
  // when it executes the draw command but its fragments when the render pass's tiles are
  // flushed, and writes a timestamp when its rasterizer reaches it in the tiles of the pass it
  // was recorded in; so one pass's scope ends, and the next one's begins, at the end of that
  // pass (GpuTimer::next), and each scope holds its draws' vertex and fragment work. The barrier
  // between two passes (the later one loads what the earlier one stored) flushes the tiles. On a
  // GPU the few extra passes over a frame's targets, and their barriers, are cheap.
  // With deferred shading (TerrainSettings::deferredShading, one body) the ground's pass draws
  // into the G-buffer instead, and a compute pass after it shades the ground into the HDR
  // target, in a scope of its own ("ground shading"), before the sea's pass.
  struct Section {
    const char* name;
    std::function<void()> draw;
    TerrainPass* deferred = nullptr;  // the pass whose ground this section draws into the G-buffer
  };
  std::vector<Section> sections;
  if (stars_)
    sections.push_back({"stars", [&] { stars_->recordDraw(cmd, starsToClip_, float(settings_.height), nullptr); }});
  TerrainPass* deferred =
      !gbuffer_.empty() && bodies_[0].terrain->shadesDeferred() ? bodies_[0].terrain.get() : nullptr;
  sections.push_back({"terrain",
                      [&] {
                        for (Body& body : bodies_) body.terrain->recordDraw(cmd, nullptr);
                      },
                      deferred});
  if (std::any_of(bodies_.begin(), bodies_.end(), [](const Body& body) { return body.terrain->waterDrawn(); }))
    sections.push_back({"water", [&] {
                          for (Body& body : bodies_) body.terrain->recordWaterDraw(cmd, nullptr);
                        }});
  // The rings come later, between the compose passes (composeOrder_).
  if (deferred) {
    for (vk::Owned<vk::Image>& image : gbuffer_) {
      image->layout = VK_IMAGE_LAYOUT_UNDEFINED;
      vk::transitionImage(cmd, *image, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                          0, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    }
    // The G-buffer's draw has no HDR attachment to clear: a pass of its own clears it when the
    // ground's is the frame's first.
    if (sections.front().deferred) {
      const VkRenderingAttachmentInfo hdrAttachment = clearedAttachment(hdr, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
      const VkRenderingAttachmentInfo depthAttachment =
          clearedAttachment(depth, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
      beginRendering(cmd, extent, &hdrAttachment, 1, &depthAttachment);
      vkCmdEndRendering(cmd);
      attachmentsBarrier(cmd);
    }
  }
  if (timer) timer->begin(cmd, sections.front().name);
  for (size_t k = 0; k < sections.size(); ++k) {
    const Section& section = sections[k];
    const bool first = k == 0 && !section.deferred;  // clears the targets
    VkRenderingAttachmentInfo depthAttachment = clearedAttachment(depth, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
    if (!first) depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    if (section.deferred) {
      VkRenderingAttachmentInfo gbuffer[TerrainPass::kGBufferTargets];
      for (uint32_t i = 0; i < TerrainPass::kGBufferTargets; ++i)
        gbuffer[i] = clearedAttachment(*gbuffer_[i], VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
      gbuffer[TerrainPass::kGBufferTargets - 1].clearValue.color.float32[1] = TerrainPass::kGBufferEmpty;
      beginRendering(cmd, extent, gbuffer, TerrainPass::kGBufferTargets, &depthAttachment);
    } else {
      VkRenderingAttachmentInfo hdrAttachment = clearedAttachment(hdr, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
      if (!first) hdrAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
      beginRendering(cmd, extent, &hdrAttachment, 1, &depthAttachment);
    }
    section.draw();
    const char* next = k + 1 < sections.size() ? sections[k + 1].name : nullptr;
    // The section's scope ends (and the next one's begins) inside its pass, or after its shading.
    const auto endScope = [&](const char* following) {
      if (!timer) return;
      if (following)
        timer->next(cmd, following);
      else
        timer->end(cmd);
    };
    endScope(section.deferred ? "ground shading" : next);
    vkCmdEndRendering(cmd);
    if (section.deferred) {
      // The G-buffer's writes to the compute pass's reads, the HDR target's (the stars') to its
      // writes; then back to a colour attachment for the passes after it.
      for (vk::Owned<vk::Image>& image : gbuffer_)
        vk::transitionImage(cmd, *image, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                            VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
      vk::transitionImage(cmd, hdr, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
      section.deferred->recordShade(cmd, settings_.width, settings_.height);
      vk::transitionImage(cmd, hdr, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
      endScope(next);
    }
    if (next) attachmentsBarrier(cmd);
  }
  // The compose pass reads and writes the HDR colour and samples the depth.
  toComposeLayouts(cmd);
  // The atmospheres and the rings, far to near (prepareFrame's order).
  bool composed = false;  // the last step was a compose pass
  for (const ComposeStep& step : composeOrder_) {
    if (step.rings) {
      recordRings(cmd, *bodies_[step.body].rings, timer);
      composed = false;
      continue;
    }
    // Each compose reads the colour the previous one wrote (a nearer atmosphere over a farther one's).
    if (composed)
      vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    bodies_[step.body].sky->recordCompose(cmd, timer);
    composed = true;
  }
  // Eye adaptation measures the composed frame, before the tonemap applies what it found.
  const double exposureStep = exposureReset_ ? -1.0 : exposureStepS_;
  exposureStepS_ = -1.0;
  if (settings_.autoExposure) {
    luminance_->record(cmd, slot, exposureStep, timer);
    exposureReset_ = false;
  }
  // The tonemap's fragments read what the compose pass wrote.
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
  vk::transitionImage(cmd, color, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  const VkRenderingAttachmentInfo colorAttachment = clearedAttachment(color, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  beginRendering(cmd, extent, &colorAttachment, 1, nullptr);
  tonemap_->recordDraw(cmd, timer);
  vkCmdEndRendering(cmd);
}

void Renderer::prepareAllPipelines() {
  for (Body& body : bodies_) {
    body.terrain->prepareShadingPipelines();
    if (body.sky) body.sky->prepareAllPipelines();
  }
}

void Renderer::toComposeLayouts(VkCommandBuffer cmd) {
  // After drawing into the targets: the compose pass reads and writes the HDR colour and samples
  // the depth.
  vk::transitionImage(cmd, *hdr_, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vk::transitionImage(cmd, *depth_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

void Renderer::recordRings(VkCommandBuffer cmd, RingPass& rings, vk::GpuTimer* timer) {
  vk::Image& hdr = *hdr_;
  vk::Image& depth = *depth_;
  // Between compose passes: the draw blends over what the composes wrote, and tests and writes
  // the depth they sampled.
  vk::transitionImage(cmd, hdr, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  vk::transitionImage(cmd, depth, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 0,
                      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = hdr.view;
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  VkRenderingAttachmentInfo depthAttachment = color;
  depthAttachment.imageView = depth.view;
  depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  beginRendering(cmd, {settings_.width, settings_.height}, &color, 1, &depthAttachment);
  rings.recordDraw(cmd, timer);
  vkCmdEndRendering(cmd);
  // Back for the next compose pass (or the luminance and tonemap passes, through the barrier
  // after the last step): it reads and writes the colour and samples the depth the draw wrote.
  toComposeLayouts(cmd);
}

RenderResult Renderer::render(const CameraPose& requested, const SunPose& sun, double timeS, bool readHdr) {
  checkOnePlanet("render", "renderScene");
  // The sun is placed from the camera's ground point as rendered (after the eye-height rule,
  // applied once here).
  bool raised = false;
  const auto start = std::chrono::steady_clock::now();
  const CameraPose camera = clampToGround(requested, &raised);
  const Prepared prepared = prepareFrame(onePlanetView(camera, sunDirection(sun, camera), timeS), 0, camera, raised, 0);
  return finishFrame(prepared, readHdr, millisecondsSince(start));
}

RenderResult Renderer::renderScene(const SceneView& view, bool readHdr) {
  const auto start = std::chrono::steady_clock::now();
  const Prepared prepared = prepareScene(view, 0);
  return finishFrame(prepared, readHdr, millisecondsSince(start));
}

RenderResult Renderer::finishFrame(const Prepared& prepared, bool readHdr, double prepareMs) {
  // One frame at a time (the submission is waited for): slot 0 always.
  RenderResult result;
  result.prepareMs = prepareMs;
  result.camera = prepared.camera;
  result.cameraRaised = prepared.cameraRaised;
  vk::submitAndWait(context_, [&](VkCommandBuffer cmd) { record(cmd, 0); });
  result.timings = lastTimings(0);
  result.exposure = lastExposure(0);
  result.terrain = bodies_[primary_].terrain->frame();
  if (readImage_) {
    result.image.width = settings_.width;
    result.image.height = settings_.height;
    result.image.pixels = vk::readbackImage(context_, *color_);
  }
  if (readHdr) result.hdr = readHdrImage();
  return result;
}

std::vector<glm::vec4> Renderer::readHdrImage() { return vk::readbackRgbaFloat(context_, *hdr_); }

}  // namespace planet
