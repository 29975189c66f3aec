#include "view/viewer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <numbers>
#include <vector>

#include <GLFW/glfw3.h>
#include <fmt/chrono.h>
#include <fmt/format.h>

#include "core/error.h"
#include "core/image_file.h"
#include "core/log.h"
#include "planet/preset_writer.h"
#include "planet/terrain_height.h"
#include "render/renderer.h"
#include "view/imgui_layer.h"
#include "view/viewer_flight.h"
#include "view/viewer_renderer.h"
#include "view/viewer_stats.h"
#include "view/viewer_ui.h"
#include "view/viewer_window.h"
#include "view/window_swapchain.h"
#include "vk/context.h"
#include "vk/frame_ring.h"
#include "vk/image.h"

namespace planet::view {
namespace {

constexpr uint32_t kFramesInFlight = Renderer::kFramesInFlight;  // one frame slot of the Renderer each

double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

// Unit direction toward the sun from its subsolar point.
glm::dvec3 sunFromSubsolar(double latitudeDeg, double longitudeDeg) {
  return directionFromLatLon(std::clamp(latitudeDeg, -90.0, 90.0), longitudeDeg);
}

class Viewer {
 public:
  explicit Viewer(const ViewOptions& options);
  ~Viewer();
  int run();

 private:
  void createWindowAndContext();
  void recreateSwapchain();
  VkExtent2D windowExtent() const;
  void waitIdle();
  void handleRequests(UiRequests& requests);
  void saveScreenshot(const std::string& path);
  // `stepS`: the time since the previous frame, over which the exposure adapts.
  bool drawFrame(uint32_t frameIndex, double stepS);

  ViewOptions options_;
  ViewerSettings settings_;
  // In the order of creation, so destroyed in reverse (the device before the window, every
  // Vulkan object before the device), also when the constructor throws half-way.
  std::unique_ptr<ViewerWindow> window_;
  std::unique_ptr<vk::Context> context_;  // ~Context logs a leak report instead of throwing
  std::unique_ptr<WindowSwapchain> swapchain_;
  std::unique_ptr<vk::FrameRing> slots_;  // one frame slot of the Renderer each
  std::unique_ptr<ViewerFlight> flight_;
  std::unique_ptr<ImGuiLayer> imgui_;
  std::unique_ptr<ViewerRenderer> renderer_;
  FlightCamera& camera() { return flight_->camera(); }
  ViewerUi ui_;
  bool submittedAny_ = false;

  // HUD.
  ViewerStats stats_;
  std::vector<vk::GpuTiming> passes_;
  std::optional<ExposureReport> exposure_;
  TerrainFrameInfo lastFrame_;
  std::string status_;
  std::string pendingScreenshot_;
};

Viewer::Viewer(const ViewOptions& viewOptions) : options_(viewOptions) {
  const ViewOptions& options = options_;
  settings_.planet = options.planet;
  settings_.fovDeg = options.fovDeg;
  settings_.autoExposure = options.autoExposure;
  settings_.exposure = options.exposure;
  settings_.skyMode = options.skyMode;
  settings_.deferredShading = options.deferredShading;
  settings_.lights = options.lights;
  createWindowAndContext();
  settings_.quality = options.quality.value_or(defaultViewQuality(context_->info.isCpu()));
  settings_.mesh = qualityPreset(settings_.quality).mesh;
  if (!options.quality && context_->info.isCpu())
    logInfo("{} is a CPU Vulkan device: starting at quality '{}' ({}); raise it in the panel", context_->info.name,
            viewQualityName(settings_.quality), describeQuality(settings_.quality));
  settings_.clouds = settings_.planet.clouds.enabled;
  settings_.water = settings_.planet.hasOcean;

  // In a scene the panel shows options.planet, the body the camera starts on; the scene's
  // presets are not edited from it.
  flight_ = std::make_unique<ViewerFlight>(options);
  if (!options.scene) {
    // The sun stays where --sun puts it for the starting camera: fixed in the planet frame.
    const glm::dvec3 sun = sunDirection(options.sun, camera().pose());
    settings_.sunLatitudeDeg = degrees(std::asin(std::clamp(sun.z, -1.0, 1.0)));
    settings_.sunLongitudeDeg = degrees(std::atan2(sun.y, sun.x));
  }

  swapchain_->create();
  imgui_ = std::make_unique<ImGuiLayer>(*context_, window_->handle(), swapchain_->swapchain());
  const SceneFlight* scene = flight_->scene();
  renderer_ = std::make_unique<ViewerRenderer>(*context_, *slots_, scene ? &scene->scene() : nullptr);
  renderer_->build(settings_, windowExtent());
  if (options.hideUi) ui_.togglePanel();
}

void Viewer::createWindowAndContext() {
  window_ =
      std::make_unique<ViewerWindow>(options_.width, options_.height, fmt::format("planet: {}", settings_.planet.name));
  vk::ContextOptions contextOptions = vk::contextOptionsFromEnvironment();
  if (options_.validation) contextOptions.validation = contextOptions.synchronizationValidation = true;
  contextOptions.deviceName = options_.device;
  contextOptions.instanceExtensions = window_->instanceExtensions();
  contextOptions.deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  context_ = vk::createContext(contextOptions);
  swapchain_ = std::make_unique<WindowSwapchain>(*context_, window_->handle(), options_.vsync);
  slots_ = std::make_unique<vk::FrameRing>(*context_);
}

void Viewer::recreateSwapchain() {
  waitIdle();
  imgui_->detach();
  swapchain_->recreate();  // replaces the old swapchain (or leaves none while minimised)
  imgui_->attach(swapchain_->swapchain());
  if (!swapchain_->empty() && renderer_) renderer_->resize(settings_, windowExtent());
}

VkExtent2D Viewer::windowExtent() const {
  return swapchain_->empty() ? VkExtent2D{options_.width, options_.height} : swapchain_->extent();
}

void Viewer::waitIdle() {
  if (slots_) slots_->waitAll();
  if (context_ && context_->device) VK_CHECK(vkDeviceWaitIdle(context_->device));
}

Viewer::~Viewer() {
  // The members go next, in reverse order; no frame may still use what they own. (A constructor
  // that throws leaves nothing in flight: it submits only through submitAndWait.)
  if (context_ && context_->device) vkDeviceWaitIdle(context_->device);
}

void Viewer::saveScreenshot(const std::string& path) {
  Rgba8Image image;
  Renderer& renderer = renderer_->get();
  image.width = renderer.settings().width;
  image.height = renderer.settings().height;
  image.pixels = vk::readbackImage(*context_, renderer.output());
  writePng(path, image);
  status_ = fmt::format("saved {} ({}x{})", path, image.width, image.height);
  logInfo("{}", status_);
}

void Viewer::handleRequests(UiRequests& r) {
  if (r.toggleMode) camera().setMode(camera().mode() == FlightMode::Orbit ? FlightMode::Free : FlightMode::Orbit);
  if (r.goTo) {
    try {
      camera().goTo(r.goToLatDeg, r.goToLonDeg, r.goToAltitudeM);
      status_ = fmt::format("flying to {:.4f}, {:.4f}, {:.0f} m", r.goToLatDeg, r.goToLonDeg, r.goToAltitudeM);
    } catch (const Error& e) {
      status_ = e.what();
    }
  }
  if (!r.savePreset.empty()) {
    try {
      savePlanetDescription(settings_.planet, r.savePreset);
      status_ = fmt::format("saved preset {}", r.savePreset);
    } catch (const Error& e) {
      status_ = e.what();
    }
  }
  if (!r.loadPreset.empty()) {
    try {
      settings_.planet = resolvePreset(r.loadPreset);
      settings_.water = settings_.planet.hasOcean;
      settings_.clouds = settings_.planet.clouds.enabled;
      r.rebuild = true;
      status_ = fmt::format("loaded preset {}", r.loadPreset);
    } catch (const Error& e) {
      status_ = e.what();
    }
  }
  renderer_->apply(r, settings_, windowExtent(), status_);
  if (r.screenshot) pendingScreenshot_ = fmt::format("planet-{:%Y%m%d-%H%M%S}.png", fmt::localtime(std::time(nullptr)));
}

bool Viewer::drawFrame(uint32_t frameIndex, double stepS) {
  const uint32_t slot = frameIndex % kFramesInFlight;
  // The Renderer keeps the data the CPU writes in prepare() per slot: only this slot's last
  // frame must be done with it; the other slot's frame may still execute.
  Renderer& renderer = renderer_->get();
  if (slots_->wait(slot)) {  // the HUD shows the slot's last frame
    passes_ = renderer.lastTimings(slot);
    exposure_ = renderer.lastExposure(slot);
  }
  if (submittedAny_ && !pendingScreenshot_.empty()) {
    // The output image is shared by the slots: read it with no frame in flight.
    waitIdle();
    saveScreenshot(pendingScreenshot_);
    pendingScreenshot_.clear();
  }

  uint32_t imageIndex = 0;
  if (!swapchain_->acquire(slots_->acquireSemaphore(slot), imageIndex)) {
    recreateSwapchain();
    return false;
  }
  const double timeS = settings_.timeS;
  const glm::dvec3 sun = sunFromSubsolar(settings_.sunLatitudeDeg, settings_.sunLongitudeDeg);
  const SceneFlight* scene = flight_->scene();
  const Renderer::Prepared prepared =
      scene ? renderer.prepareScene(scene->view(), slot) : renderer.prepare(camera().pose(), sun, timeS, slot);
  lastFrame_ = prepared.terrain;

  const VkCommandBuffer cmd = slots_->begin(slot);
  renderer.adaptExposureOver(stepS);
  renderer.record(cmd, slot);
  swapchain_->recordBlit(cmd, renderer.output(), imageIndex);
  imgui_->record(cmd, imageIndex);
  // The blit waits for the acquire (see recordBlit).
  slots_->submitForPresent(slot, VK_PIPELINE_STAGE_2_TRANSFER_BIT, swapchain_->renderedSemaphore(imageIndex));
  submittedAny_ = true;
  swapchain_->present(context_->graphicsQueue, imageIndex);
  return true;
}

int Viewer::run() {
  uint32_t frame = 0;
  double previous = glfwGetTime();
  const double startS = previous;
  window_->watchStopSignals();
  while (!window_->shouldClose()) {
    window_->pollEvents();
    if (window_->takeResized()) swapchain_->markStale();
    const VkExtent2D size = window_->framebufferSize();
    if (size.width == 0 || size.height == 0) {  // minimised: draw nothing until it comes back
      window_->waitEvents(0.1);
      swapchain_->markStale();
      continue;
    }
    if (swapchain_->needsRecreate(size.width, size.height)) {
      recreateSwapchain();
      if (swapchain_->empty()) continue;
    }
    const double now = glfwGetTime();
    const double dt = now - previous;
    previous = now;

    // Keys that act once per press.
    UiRequests requests;
    auto pressed = [&](int key) { return window_->takePress(key); };
    if (pressed(GLFW_KEY_ESCAPE)) window_->close();
    if (pressed(GLFW_KEY_F1)) ui_.toggleHelp();
    if (pressed(GLFW_KEY_F2)) ui_.togglePanel();
    if (pressed(GLFW_KEY_TAB)) requests.toggleMode = true;
    const bool goKey = pressed(GLFW_KEY_G);
    if (pressed(GLFW_KEY_F12) || pressed(GLFW_KEY_P)) requests.screenshot = true;

    // Camera: the path while it plays, else the user's input.
    // With --frames (a scripted run) every frame steps 1/60 s, so that the run is the same on
    // any machine; otherwise the wall clock's.
    const double stepS = options_.frames > 0 ? 1.0 / 60.0 : dt;
    const FlightInput input =
        window_->readInput(stepS, camera().mode() == FlightMode::Orbit, swapchain_->extent().height);
    const bool nextBody = flight_->scene() && pressed(GLFW_KEY_T);
    const bool pathPlaying = flight_->update(input, stepS, frame, now - startS, nextBody, settings_.planet);
    if (flight_->scene()) status_ = flight_->sceneStatus();
    if (settings_.animate) settings_.timeS += stepS;
    if (settings_.sunMoves) {
      settings_.sunLongitudeDeg -= 360.0 * stepS / settings_.dayLengthS;
      settings_.sunLongitudeDeg = std::remainder(settings_.sunLongitudeDeg, 360.0);
    }

    // The panel and HUD for this frame.
    stats_.addInterval(dt);
    HudData hud;
    settings_.cameraLongitudeDeg = camera().pose().longitudeDeg;
    hud.device = context_->info.name;
    hud.fps = stats_.fps();
    hud.frameTimesMs = &stats_.recentMs();
    hud.passes = passes_;
    hud.exposure = exposure_;
    const CameraPose& pose = camera().pose();
    hud.altitudeM = pose.altitudeM;
    hud.heightAboveGroundM = camera().heightAboveGroundM();
    hud.latitudeDeg = pose.latitudeDeg;
    hud.longitudeDeg = pose.longitudeDeg;
    hud.metresPerVertex = lastFrame_.metresPerVertexAtNadir;
    hud.triangles = lastFrame_.triangles;
    hud.renderWidth = renderer_->get().settings().width;
    hud.renderHeight = renderer_->get().settings().height;
    hud.mode = camera().mode();
    hud.speedMps = camera().speedMps();
    hud.pathPlaying = pathPlaying;
    hud.status = status_;
    imgui_->beginFrame();
    ui_.draw(settings_, hud, requests);
    if (goKey) ui_.requestGoTo(requests);
    imgui_->endFrame();
    handleRequests(requests);

    if (!drawFrame(frame, stepS)) continue;
    stats_.frameDrawn(frame++, dt, context_->allocator);
    if (options_.frames > 0 && frame >= options_.frames) break;
  }
  waitIdle();
  if (!options_.screenshot.empty() && frame > 0) saveScreenshot(options_.screenshot);

  // What a soak or leak check reads: frame times and memory after warm-up against the end.
  const vk::AllocatorStats end = context_->allocator.stats();
  stats_.printFrameTimes(frame, context_->info.name);
  fmt::print("swapchain recreated {} times (resize, minimise, out of date)\n", swapchain_->recreations());
  if (flight_->scene()) flight_->printSceneSummary();
  stats_.printMemory(frame, end);
  std::fflush(stdout);
  if (context_->validation && context_->validationMessageCount() > 0) {
    logError("{} Vulkan validation message(s) were reported (see above)", context_->validationMessageCount());
    return 1;
  }
  return 0;
}

}  // namespace

int runViewer(const ViewOptions& options) {
  Viewer viewer(options);
  return viewer.run();
}

}  // namespace planet::view
