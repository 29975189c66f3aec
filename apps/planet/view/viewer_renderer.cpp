#include "view/viewer_renderer.h"

#include <chrono>

#include <fmt/format.h>

#include "core/error.h"
#include "core/log.h"
#include "render/view_quality.h"
#include "vk/context.h"
#include "vk/frame_ring.h"

namespace planet::view {

ViewerRenderer::ViewerRenderer(vk::Context& context, vk::FrameRing& slots, const SceneDescription* scene)
    : context_(context), slots_(slots), scene_(scene) {}

RenderSettings ViewerRenderer::renderSettings(const ViewerSettings& settings, VkExtent2D window) const {
  RenderSettings base;
  base.fovYDeg = settings.fovDeg;
  base.terrain.patches = settings.patches;
  base.terrain.water = settings.water;
  base.terrain.lights = settings.lights;
  base.sky.clouds = settings.clouds;
  base.sky.exposure = settings.exposure;
  base.autoExposure = settings.autoExposure;
  base.sky.mode = settings.skyMode;
  base.terrain.deferredShading = settings.deferredShading;
  RenderSettings render = viewRenderSettings(base, settings.quality, window.width, window.height);
  render.terrain.mesh = settings.mesh;
  return render;
}

void ViewerRenderer::waitIdle() {
  slots_.waitAll();
  VK_CHECK(vkDeviceWaitIdle(context_.device));
}

void ViewerRenderer::build(const ViewerSettings& settings, VkExtent2D window) {
  waitIdle();
  renderer_.reset();  // free its memory before the new one takes its own
  const auto start = std::chrono::steady_clock::now();
  if (scene_) {
    SceneDescription scene = *scene_;
    for (BodyDescription& body : scene.bodies) body.planet = viewPlanet(body.planet, settings.quality);
    renderer_ = std::make_unique<Renderer>(context_, scene, renderSettings(settings, window));
  } else {
    renderer_ = std::make_unique<Renderer>(context_, viewPlanet(settings.planet, settings.quality),
                                           renderSettings(settings, window));
  }
  // Every variant a frame may pick, now: a compile in flight would stall a frame.
  renderer_->prepareAllPipelines();
  applyTerrainToggles(settings);
  built_ = settings;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  logInfo("renderer for {} at {}x{} ({} quality) built in {:.2f} s", settings.planet.name, renderer_->settings().width,
          renderer_->settings().height, viewQualityName(settings.quality), seconds);
}

void ViewerRenderer::apply(const UiRequests& r, ViewerSettings& settings, VkExtent2D window, std::string& status) {
  if (r.rebuild) {
    try {
      build(settings, window);
    } catch (const Error& e) {
      // A combination the renderer refuses (the panel's ranges are wider than some
      // combinations allow, e.g. clouds above the top of the air): say so, go back to the
      // settings that last built, and keep flying (a failure there too ends the viewer).
      status = fmt::format("not applied: {}", e.what());
      logWarning("{}", status);
      settings.planet = built_.planet;
      settings.quality = built_.quality;
      settings.mesh = built_.mesh;
      settings.fovDeg = built_.fovDeg;
      settings.patches = built_.patches;
      build(settings, window);
    }
  } else {
    if (r.skyChanged) {
      SkySettings sky = renderer_->settings().sky;
      sky.clouds = settings.clouds;
      sky.exposure = settings.exposure;
      sky.mode = settings.skyMode;
      renderer_->setSkySettings(sky);
      renderer_->setAutoExposure(settings.autoExposure);
    }
    if (r.terrainToggles) applyTerrainToggles(settings);
  }
}

void ViewerRenderer::resize(const ViewerSettings& settings, VkExtent2D window) {
  const RenderSettings wanted = renderSettings(settings, window);
  renderer_->resize(wanted.width, wanted.height);
}

void ViewerRenderer::applyTerrainToggles(const ViewerSettings& settings) {
  for (size_t body = 0; body < renderer_->bodyCount(); ++body) {
    TerrainPass& terrain = renderer_->terrain(body);
    terrain.setWireframe(settings.wireframe);
    terrain.setWaterEnabled(settings.water);
    terrain.setLightsEnabled(settings.lights);
    terrain.setFreezeLod(settings.freezeLod);
  }
}

}  // namespace planet::view
