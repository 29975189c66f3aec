#include "view/viewer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <deque>
#include <memory>
#include <numbers>
#include <vector>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <fmt/chrono.h>
#include <fmt/format.h>
#include <imgui.h>
#include <unistd.h>

#include <X11/Xlib.h>
#undef None  // X11 macros that collide with C++ names
#undef Status
#undef Bool
#undef Always

#include "core/error.h"
#include "core/image_file.h"
#include "core/log.h"
#include "core/process_memory.h"
#include "core/statistics.h"
#include "planet/preset_writer.h"
#include "planet/terrain_height.h"
#include "camera/flight_camera.h"
#include "camera/scene_flight.h"
#include "render/renderer.h"
#include "view/viewer_ui.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/image.h"
#include "vk/swapchain.h"

namespace planet::view {
namespace {

constexpr uint32_t kFramesInFlight = Renderer::kFramesInFlight;  // one frame slot of the Renderer each
constexpr size_t kFrameGraphLength = 240;
constexpr uint32_t kWarmupFrames = 10;  // allocator and RSS figures are compared after these

std::string glfwErrorText;

// Ctrl-C (SIGINT) or SIGTERM ends the viewer as closing its window would: the frame loop
// finishes, the screenshot is saved and everything is released.
volatile std::sig_atomic_t stopRequested = 0;
void onStopSignal(int) { stopRequested = 1; }

void onGlfwError(int code, const char* description) {
  glfwErrorText = fmt::format("{} (GLFW error {})", description, code);
}

double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

// Unit direction toward the sun from its subsolar point.
glm::dvec3 sunFromSubsolar(double latitudeDeg, double longitudeDeg) {
  return directionFromLatLon(std::clamp(latitudeDeg, -90.0, 90.0), longitudeDeg);
}

struct FrameSlot {
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;         // signalled when the slot's last submission completed
  VkSemaphore acquired = VK_NULL_HANDLE;  // the swapchain image is ready to be written
  bool submitted = false;
};

class Viewer {
 public:
  explicit Viewer(const ViewOptions& options);
  ~Viewer();
  int run();

 private:
  void construct();
  void release();  // everything the destructor frees; safe on a partly constructed viewer
  void createWindowAndContext();
  void createSwapchainResources();
  void destroySwapchainResources();
  void recreateSwapchain();
  void createUi();
  void buildRenderer();
  RenderSettings currentRenderSettings() const;
  void applyTerrainToggles();
  void waitForFrame(FrameSlot& slot);
  void waitIdle();
  FlightInput readInput(double dtS);
  void handleRequests(UiRequests& requests);
  void saveScreenshot(const std::string& path);
  bool drawFrame(uint32_t frameIndex);

  ViewOptions options_;
  ViewerSettings settings_;
  GLFWwindow* window_ = nullptr;
  bool glfwStarted_ = false;
  std::unique_ptr<vk::Context> context_;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  vk::Swapchain swapchain_;
  std::vector<VkSemaphore> presented_;  // per swapchain image: rendering done, may present
  VkRenderPass uiPass_ = VK_NULL_HANDLE;
  std::vector<VkFramebuffer> framebuffers_;
  FrameSlot slots_[kFramesInFlight];
  VkDescriptorPool uiPool_ = VK_NULL_HANDLE;
  bool imguiGlfw_ = false, imguiVulkan_ = false;
  std::unique_ptr<Renderer> renderer_;
  std::unique_ptr<FlightCamera> camera_;  // one planet
  std::unique_ptr<SceneFlight> flight_;   // a scene (its camera is that of the body it flies at)
  double sceneTimeS_ = 0.0;
  FlightCamera& camera() { return flight_ ? flight_->camera() : *camera_; }
  ViewerUi ui_;
  ViewerSettings built_;  // what the current renderer was built from (planet, quality, mesh, view)
  bool swapchainStale_ = false;
  uint32_t swapchainRecreations_ = 0;
  int lastSubmittedSlot_ = -1;

  // Input state between frames.
  double lastCursorX_ = 0.0, lastCursorY_ = 0.0;
  bool cursorKnown_ = false;
  double scroll_ = 0.0;
  bool keyPressed_[GLFW_KEY_LAST + 1] = {};

  // HUD.
  std::deque<float> frameTimesMs_;
  std::vector<vk::GpuTiming> passes_;
  TerrainFrameInfo lastFrame_;
  std::string status_;
  std::string pendingScreenshot_;
};

Viewer::Viewer(const ViewOptions& options) : options_(options) {
  // A constructor that throws runs no destructor: release what was made so far, so that a
  // failure here (out of device memory, a lost device) destroys every Vulkan object before the
  // device, as a normal exit does.
  try {
    construct();
  } catch (...) {
    release();
    throw;
  }
}

void Viewer::construct() {
  const ViewOptions& options = options_;
  settings_.planet = options.planet;
  settings_.fovDeg = options.fovDeg;
  createWindowAndContext();
  settings_.quality = options.quality.value_or(defaultViewQuality(context_->info.isCpu()));
  settings_.mesh = qualityPreset(settings_.quality).mesh;
  if (!options.quality && context_->info.isCpu())
    logInfo("{} is a CPU Vulkan device: starting at quality '{}' ({}); raise it in the panel", context_->info.name,
            viewQualityName(settings_.quality), describeQuality(settings_.quality));
  settings_.clouds = settings_.planet.clouds.enabled;
  settings_.water = settings_.planet.hasOcean;

  if (options.scene) {
    // The panel shows options.planet, the body the camera starts on; the scene's presets are
    // not edited from it.
    sceneTimeS_ = options.sceneTimeS;
    flight_ = std::make_unique<SceneFlight>(*options.scene, options.sceneBody, options.camera.value_or(CameraPose{}),
                                            sceneTimeS_);
    if (options.travelTo) flight_->travelTo(*options.travelTo);
  } else {
    const PlanetDescription& planet = settings_.planet;
    camera_ = std::make_unique<FlightCamera>(
        planet.radiusM, [planet](const glm::dvec3& direction) { return surfaceHeightM(planet, direction); });
    CameraPose start = options.camera.value_or(CameraPose{});
    if (options.path) start = cameraPoseAt(sampleCameraPath(*options.path, options.path->startS()), planet);
    // A view toward the horizon is free flight; a view down at the planet is orbit.
    if (options.path || start.pitchDeg > camera().settings().orbitMaxPitchDeg) camera().setMode(FlightMode::Free);
    camera().setPose(start);
    // The sun stays where --sun puts it for the starting camera: fixed in the planet frame.
    const glm::dvec3 sun = sunDirection(options.sun, camera().pose());
    settings_.sunLatitudeDeg = degrees(std::asin(std::clamp(sun.z, -1.0, 1.0)));
    settings_.sunLongitudeDeg = degrees(std::atan2(sun.y, sun.x));
  }

  createSwapchainResources();
  createUi();
  buildRenderer();
  if (options.hideUi) ui_.togglePanel();
}

void Viewer::createWindowAndContext() {
  glfwSetErrorCallback(onGlfwError);
  // Xlib must be made thread-safe before GLFW opens its display: a Vulkan driver or layer that
  // calls XInitThreads later leaves the display's context table without its lock, and GLFW's
  // event loop crashes in XFindContext (seen with lavapipe and the validation layer).
  XInitThreads();
  if (!glfwInit())
    throw Error(fmt::format("cannot open a window: {}; without a display, 'planet render' draws to a PNG",
                            glfwErrorText.empty() ? "GLFW failed to start" : glfwErrorText));
  glfwStarted_ = true;
  if (!glfwVulkanSupported())
    throw Error(fmt::format("cannot open a window: GLFW finds no usable Vulkan loader{}",
                            glfwErrorText.empty() ? "" : " (" + glfwErrorText + ")"));
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(int(options_.width), int(options_.height),
                             fmt::format("planet: {}", settings_.planet.name).c_str(), nullptr, nullptr);
  if (!window_) throw Error(fmt::format("cannot open a window: {}", glfwErrorText));
  glfwSetWindowUserPointer(window_, this);
  // Installed before ImGui's, which chain to them.
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) {
    static_cast<Viewer*>(glfwGetWindowUserPointer(w))->scroll_ += dy;
  });
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
    if (key >= 0 && key <= GLFW_KEY_LAST && action == GLFW_PRESS)
      static_cast<Viewer*>(glfwGetWindowUserPointer(w))->keyPressed_[key] = true;
  });
  glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int, int) {
    static_cast<Viewer*>(glfwGetWindowUserPointer(w))->swapchainStale_ = true;
  });

  vk::ContextOptions contextOptions = vk::contextOptionsFromEnvironment();
  if (options_.validation) contextOptions.validation = contextOptions.synchronizationValidation = true;
  contextOptions.deviceName = options_.device;
  uint32_t count = 0;
  const char** extensions = glfwGetRequiredInstanceExtensions(&count);
  if (!extensions) throw Error(fmt::format("cannot open a window: {}", glfwErrorText));
  contextOptions.instanceExtensions.assign(extensions, extensions + count);
  contextOptions.deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  context_ = vk::createContext(contextOptions);
  VkResult result = glfwCreateWindowSurface(context_->instance, window_, nullptr, &surface_);
  if (result != VK_SUCCESS)
    throw Error(fmt::format("cannot create a Vulkan surface for the window: {}", vkResultName(result)));
  if (!vk::canPresent(*context_, surface_))
    throw Error(fmt::format("{} cannot present to this window; choose another with --device", context_->info.name));

  for (FrameSlot& slot : slots_) {
    VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = context_->universalFamily;
    VK_CHECK(vkCreateCommandPool(context_->device, &pool, nullptr, &slot.pool));
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = slot.pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VK_CHECK(vkAllocateCommandBuffers(context_->device, &alloc, &slot.cmd));
    VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fence.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    VK_CHECK(vkCreateFence(context_->device, &fence, nullptr, &slot.fence));
    VkSemaphoreCreateInfo semaphore{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VK_CHECK(vkCreateSemaphore(context_->device, &semaphore, nullptr, &slot.acquired));
  }
}

void Viewer::createSwapchainResources() {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  swapchain_ = vk::createSwapchain(*context_, surface_, VkExtent2D{uint32_t(width), uint32_t(height)}, options_.vsync,
                                   swapchain_.swapchain ? &swapchain_ : nullptr);
  if (swapchain_.images.empty()) return;  // minimised
  if (!uiPass_) {
    // The panel is drawn over the blitted frame: load what the blit wrote, leave it for present.
    VkAttachmentDescription attachment{};
    attachment.format = swapchain_.format;
    attachment.samples = VK_SAMPLE_COUNT_1_BIT;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachment.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    attachment.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &reference;
    // The UI blends over the blit's writes.
    VkSubpassDependency dependency{};
    dependency.srcSubpass = VK_SUBPASS_EXTERNAL;
    dependency.dstSubpass = 0;
    dependency.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependency.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    dependency.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependency.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = 1;
    info.pAttachments = &attachment;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 1;
    info.pDependencies = &dependency;
    VK_CHECK(vkCreateRenderPass(context_->device, &info, nullptr, &uiPass_));
  }
  for (VkImageView view : swapchain_.views) {
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = uiPass_;
    info.attachmentCount = 1;
    info.pAttachments = &view;
    info.width = swapchain_.extent.width;
    info.height = swapchain_.extent.height;
    info.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    VK_CHECK(vkCreateFramebuffer(context_->device, &info, nullptr, &framebuffer));
    framebuffers_.push_back(framebuffer);
  }
  while (presented_.size() < swapchain_.images.size()) {
    VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore semaphore = VK_NULL_HANDLE;
    VK_CHECK(vkCreateSemaphore(context_->device, &info, nullptr, &semaphore));
    presented_.push_back(semaphore);
  }
}

void Viewer::destroySwapchainResources() {
  for (VkFramebuffer framebuffer : framebuffers_) vkDestroyFramebuffer(context_->device, framebuffer, nullptr);
  framebuffers_.clear();
}

void Viewer::recreateSwapchain() {
  waitIdle();
  destroySwapchainResources();
  createSwapchainResources();  // replaces the old swapchain (or leaves none while minimised)
  swapchainStale_ = false;
  ++swapchainRecreations_;
  if (!swapchain_.images.empty() && renderer_) {
    const RenderSettings wanted = currentRenderSettings();
    renderer_->resize(wanted.width, wanted.height);
  }
  if (imguiVulkan_ && !swapchain_.images.empty()) ImGui_ImplVulkan_SetMinImageCount(uint32_t(swapchain_.images.size()));
}

void Viewer::createUi() {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini next to wherever the viewer was started
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 4.0f;
  if (!ImGui_ImplGlfw_InitForVulkan(window_, true)) throw Error("Dear ImGui could not attach to the window");
  imguiGlfw_ = true;

  // Room for the font texture's descriptor set (the only one the backend allocates).
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4};
  VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pool.maxSets = 4;
  pool.poolSizeCount = 1;
  pool.pPoolSizes = &size;
  VK_CHECK(vkCreateDescriptorPool(context_->device, &pool, nullptr, &uiPool_));

  if (!uiPass_) throw Error("the window is minimised at start; nothing to draw into");
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = context_->instance;
  info.PhysicalDevice = context_->physicalDevice;
  info.Device = context_->device;
  info.QueueFamily = context_->universalFamily;
  info.Queue = context_->graphicsQueue;
  info.DescriptorPool = uiPool_;
  info.MinImageCount = std::max<uint32_t>(2, uint32_t(swapchain_.images.size()));
  info.ImageCount = info.MinImageCount;
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = [](VkResult result) {
    if (result != VK_SUCCESS) throwVulkanError(result, "Dear ImGui Vulkan backend", __FILE__, __LINE__);
  };
  if (!ImGui_ImplVulkan_Init(&info, uiPass_)) throw Error("Dear ImGui's Vulkan backend failed to start");
  imguiVulkan_ = true;
  vk::submitAndWait(*context_, [](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

RenderSettings Viewer::currentRenderSettings() const {
  RenderSettings base;
  base.fovYDeg = settings_.fovDeg;
  base.terrain.patches = settings_.patches;
  base.terrain.water = settings_.water;
  base.sky.clouds = settings_.clouds;
  base.sky.exposure = settings_.exposure;
  const VkExtent2D window = swapchain_.images.empty() ? VkExtent2D{options_.width, options_.height} : swapchain_.extent;
  RenderSettings render = viewRenderSettings(base, settings_.quality, window.width, window.height);
  render.terrain.mesh = settings_.mesh;
  return render;
}

void Viewer::buildRenderer() {
  waitIdle();
  renderer_.reset();  // free its memory before the new one takes its own
  const auto start = std::chrono::steady_clock::now();
  if (flight_) {
    SceneDescription scene = flight_->scene();
    for (BodyDescription& body : scene.bodies) body.planet = viewPlanet(body.planet, settings_.quality);
    renderer_ = std::make_unique<Renderer>(*context_, scene, currentRenderSettings());
  } else {
    renderer_ =
        std::make_unique<Renderer>(*context_, viewPlanet(settings_.planet, settings_.quality), currentRenderSettings());
  }
  applyTerrainToggles();
  built_ = settings_;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  logInfo("renderer for {} at {}x{} ({} quality) built in {:.2f} s", settings_.planet.name, renderer_->settings().width,
          renderer_->settings().height, viewQualityName(settings_.quality), seconds);
}

void Viewer::applyTerrainToggles() {
  for (size_t body = 0; body < renderer_->bodyCount(); ++body) {
    TerrainPass& terrain = renderer_->terrain(body);
    terrain.setWireframe(settings_.wireframe);
    terrain.setWaterEnabled(settings_.water);
    terrain.setFreezeLod(settings_.freezeLod);
  }
}

void Viewer::waitForFrame(FrameSlot& slot) {
  if (!slot.submitted) return;
  VK_CHECK(vkWaitForFences(context_->device, 1, &slot.fence, VK_TRUE, vk::kSubmitTimeoutNs));
  slot.submitted = false;
}

void Viewer::waitIdle() {
  for (FrameSlot& slot : slots_) waitForFrame(slot);
  if (context_ && context_->device) VK_CHECK(vkDeviceWaitIdle(context_->device));
}

Viewer::~Viewer() { release(); }

void Viewer::release() {
  if (context_ && context_->device) vkDeviceWaitIdle(context_->device);
  renderer_.reset();
  if (imguiVulkan_) ImGui_ImplVulkan_Shutdown();
  if (imguiGlfw_) ImGui_ImplGlfw_Shutdown();
  if (ImGui::GetCurrentContext()) ImGui::DestroyContext();
  if (context_ && context_->device) {
    VkDevice device = context_->device;
    if (uiPool_) vkDestroyDescriptorPool(device, uiPool_, nullptr);
    destroySwapchainResources();
    if (uiPass_) vkDestroyRenderPass(device, uiPass_, nullptr);
    for (VkSemaphore semaphore : presented_) vkDestroySemaphore(device, semaphore, nullptr);
    for (FrameSlot& slot : slots_) {
      if (slot.acquired) vkDestroySemaphore(device, slot.acquired, nullptr);
      if (slot.fence) vkDestroyFence(device, slot.fence, nullptr);
      if (slot.pool) vkDestroyCommandPool(device, slot.pool, nullptr);
    }
    vk::destroySwapchain(*context_, swapchain_);
  }
  if (surface_) vkDestroySurfaceKHR(context_->instance, surface_, nullptr);
  if (context_) {
    try {
      vk::destroyContext(*context_);
    } catch (const std::exception& e) {
      logError("{}", e.what());
    }
  }
  context_.reset();
  if (window_) glfwDestroyWindow(window_);
  window_ = nullptr;
  if (glfwStarted_) glfwTerminate();
  glfwStarted_ = false;
}

FlightInput Viewer::readInput(double dtS) {
  FlightInput input;
  input.dtS = dtS;
  const ImGuiIO& io = ImGui::GetIO();
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window_, &x, &y);
  const double dx = cursorKnown_ ? x - lastCursorX_ : 0.0;
  const double dy = cursorKnown_ ? y - lastCursorY_ : 0.0;
  lastCursorX_ = x;
  lastCursorY_ = y;
  cursorKnown_ = true;
  if (!io.WantCaptureKeyboard) {
    auto key = [&](int k) { return glfwGetKey(window_, k) == GLFW_PRESS ? 1.0 : 0.0; };
    input.forward = key(GLFW_KEY_W) - key(GLFW_KEY_S);
    input.right = key(GLFW_KEY_D) - key(GLFW_KEY_A);
    input.up = std::max(key(GLFW_KEY_E), key(GLFW_KEY_SPACE)) - std::max(key(GLFW_KEY_Q), key(GLFW_KEY_C));
    if (key(GLFW_KEY_LEFT_SHIFT) || key(GLFW_KEY_RIGHT_SHIFT)) input.speedFactor = 4.0;
    if (key(GLFW_KEY_LEFT_ALT) || key(GLFW_KEY_RIGHT_ALT)) input.speedFactor = 0.25;
  }
  if (!io.WantCaptureMouse) {
    if (glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS) {
      input.lookX = dx;
      input.lookY = dy;
    } else if (glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS &&
               camera().mode() == FlightMode::Orbit) {
      // Dragging the ground: a drag across the window moves about one view height.
      const double perPixel = 2.0 / std::max(1.0, double(swapchain_.extent.height)) / std::max(dtS, 1e-3);
      input.forward += dy * perPixel;
      input.right -= dx * perPixel;
    }
    input.zoom = scroll_;
  }
  scroll_ = 0.0;
  return input;
}

void Viewer::saveScreenshot(const std::string& path) {
  Rgba8Image image;
  image.width = renderer_->settings().width;
  image.height = renderer_->settings().height;
  image.pixels = vk::readbackImage(*context_, renderer_->output());
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
  if (r.rebuild) {
    try {
      buildRenderer();
    } catch (const Error& e) {
      // A combination the renderer refuses (the panel's ranges are wider than some
      // combinations allow, e.g. clouds above the top of the air): say so, go back to the
      // settings that last built, and keep flying (a failure there too ends the viewer).
      status_ = fmt::format("not applied: {}", e.what());
      logWarning("{}", status_);
      settings_.planet = built_.planet;
      settings_.quality = built_.quality;
      settings_.mesh = built_.mesh;
      settings_.fovDeg = built_.fovDeg;
      settings_.patches = built_.patches;
      buildRenderer();
    }
  } else {
    if (r.skyChanged) {
      SkySettings sky = renderer_->settings().sky;
      sky.clouds = settings_.clouds;
      sky.exposure = settings_.exposure;
      renderer_->setSkySettings(sky);
    }
    if (r.terrainToggles) applyTerrainToggles();
  }
  if (r.screenshot) pendingScreenshot_ = fmt::format("planet-{:%Y%m%d-%H%M%S}.png", fmt::localtime(std::time(nullptr)));
}

bool Viewer::drawFrame(uint32_t frameIndex) {
  const uint32_t slotIndex = frameIndex % kFramesInFlight;
  FrameSlot& slot = slots_[slotIndex];
  // The Renderer keeps the data the CPU writes in prepare() per slot: only this slot's last
  // frame must be done with it; the other slot's frame may still execute.
  const bool reused = slot.submitted;
  waitForFrame(slot);
  if (reused) passes_ = renderer_->lastTimings(slotIndex);  // the HUD shows the slot's last frame
  if (lastSubmittedSlot_ >= 0 && !pendingScreenshot_.empty()) {
    // The output image is shared by the slots: read it with no frame in flight.
    waitIdle();
    saveScreenshot(pendingScreenshot_);
    pendingScreenshot_.clear();
  }

  uint32_t imageIndex = 0;
  VkResult acquired = vkAcquireNextImageKHR(context_->device, swapchain_.swapchain, UINT64_MAX, slot.acquired,
                                            VK_NULL_HANDLE, &imageIndex);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    recreateSwapchain();
    return false;
  }
  if (acquired != VK_SUCCESS && acquired != VK_SUBOPTIMAL_KHR)
    throwVulkanError(acquired, "vkAcquireNextImageKHR", __FILE__, __LINE__);
  if (acquired == VK_SUBOPTIMAL_KHR) swapchainStale_ = true;

  const double timeS = settings_.timeS;
  const glm::dvec3 sun = sunFromSubsolar(settings_.sunLatitudeDeg, settings_.sunLongitudeDeg);
  const Renderer::Prepared prepared = flight_ ? renderer_->prepareScene(flight_->view(), slotIndex)
                                             : renderer_->prepare(camera().pose(), sun, timeS, slotIndex);
  lastFrame_ = prepared.terrain;

  VK_CHECK(vkResetFences(context_->device, 1, &slot.fence));
  VK_CHECK(vkResetCommandBuffer(slot.cmd, 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(slot.cmd, &begin));
  renderer_->record(slot.cmd, slotIndex);
  vk::Image& output = renderer_->output();
  // The blit reads what the tonemap wrote.
  vk::transitionImage(slot.cmd, output, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  // The swapchain image's old contents are discarded; its acquire semaphore is waited on at
  // the transfer stage, which this barrier's source scope chains to.
  VkImageMemoryBarrier2 toTransfer{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  toTransfer.srcStageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
  toTransfer.dstStageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
  toTransfer.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  toTransfer.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  toTransfer.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  toTransfer.srcQueueFamilyIndex = toTransfer.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  toTransfer.image = swapchain_.images[imageIndex];
  toTransfer.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &toTransfer;
  vkCmdPipelineBarrier2(slot.cmd, &dependency);
  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {int32_t(output.extent.width), int32_t(output.extent.height), 1};
  blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.dstOffsets[1] = {int32_t(swapchain_.extent.width), int32_t(swapchain_.extent.height), 1};
  const bool sameSize =
      output.extent.width == swapchain_.extent.width && output.extent.height == swapchain_.extent.height;
  vkCmdBlitImage(slot.cmd, output.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, swapchain_.images[imageIndex],
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, sameSize ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);

  VkRenderPassBeginInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  pass.renderPass = uiPass_;
  pass.framebuffer = framebuffers_[imageIndex];
  pass.renderArea = {{0, 0}, swapchain_.extent};
  vkCmdBeginRenderPass(slot.cmd, &pass, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), slot.cmd);
  vkCmdEndRenderPass(slot.cmd);
  VK_CHECK(vkEndCommandBuffer(slot.cmd));

  VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  wait.semaphore = slot.acquired;
  wait.stageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
  VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  signal.semaphore = presented_[imageIndex];
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmdInfo.commandBuffer = slot.cmd;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.waitSemaphoreInfoCount = 1;
  submit.pWaitSemaphoreInfos = &wait;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmdInfo;
  submit.signalSemaphoreInfoCount = 1;
  submit.pSignalSemaphoreInfos = &signal;
  VK_CHECK(vk::queueSubmit(*context_, context_->graphicsQueue, submit, slot.fence));
  slot.submitted = true;
  lastSubmittedSlot_ = int(slotIndex);

  VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &presented_[imageIndex];
  present.swapchainCount = 1;
  present.pSwapchains = &swapchain_.swapchain;
  present.pImageIndices = &imageIndex;
  const VkResult presented = vkQueuePresentKHR(context_->graphicsQueue, &present);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR)
    swapchainStale_ = true;
  else if (presented != VK_SUCCESS)
    throwVulkanError(presented, "vkQueuePresentKHR", __FILE__, __LINE__);
  return true;
}

int Viewer::run() {
  uint32_t frame = 0;
  double previous = glfwGetTime();
  const double startS = previous;
  vk::AllocatorStats warm{};
  int64_t warmRss = 0;
  std::vector<double> frameMs;
  std::signal(SIGINT, onStopSignal);
  std::signal(SIGTERM, onStopSignal);
  while (!glfwWindowShouldClose(window_) && !stopRequested) {
    glfwPollEvents();
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    if (width == 0 || height == 0) {  // minimised: draw nothing until it comes back
      glfwWaitEventsTimeout(0.1);
      swapchainStale_ = true;
      continue;
    }
    if (swapchainStale_ || swapchain_.images.empty() || swapchain_.extent.width != uint32_t(width) ||
        swapchain_.extent.height != uint32_t(height)) {
      recreateSwapchain();
      if (swapchain_.images.empty()) continue;
    }
    const double now = glfwGetTime();
    const double dt = now - previous;
    previous = now;

    // Keys that act once per press.
    UiRequests requests;
    const ImGuiIO& io = ImGui::GetIO();
    auto pressed = [&](int key) {
      const bool p = keyPressed_[key];
      keyPressed_[key] = false;
      return p && !io.WantTextInput;
    };
    if (pressed(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(window_, GLFW_TRUE);
    if (pressed(GLFW_KEY_F1)) ui_.toggleHelp();
    if (pressed(GLFW_KEY_F2)) ui_.togglePanel();
    if (pressed(GLFW_KEY_TAB)) requests.toggleMode = true;
    const bool goKey = pressed(GLFW_KEY_G);
    if (pressed(GLFW_KEY_F12) || pressed(GLFW_KEY_P)) requests.screenshot = true;

    // Camera: the path while it plays, else the user's input.
    // With --frames (a scripted run) every frame steps 1/60 s, so that the run is the same on
    // any machine; otherwise the wall clock's.
    const FlightInput input = readInput(options_.frames > 0 ? 1.0 / 60.0 : dt);
    bool pathPlaying = false;
    if (options_.path) {
      const CameraPath& path = *options_.path;
      const double t = options_.frames > 0 ? frameTimeS(path, frame, options_.frames) : path.startS() + (now - startS);
      pathPlaying = t <= path.endS();
      if (pathPlaying) camera().setPose(cameraPoseAt(sampleCameraPath(path, t), settings_.planet));
    }
    if (flight_) {
      const size_t before = flight_->referenceBody();
      if (pressed(GLFW_KEY_T)) {
        // The next body after the one flown to last (or after the camera's own).
        const size_t count = flight_->scene().bodies.size();
        size_t next = (flight_->travelTarget().value_or(before) + 1) % count;
        if (next == before) next = (next + 1) % count;
        if (count > 1) flight_->travelTo(next);
      }
      sceneTimeS_ += (options_.frames > 0 ? 1.0 / 60.0 : dt) * options_.timeScale;
      flight_->update(input, sceneTimeS_);
      const SceneDescription& scene = flight_->scene();
      if (flight_->referenceBody() != before) {
        settings_.planet = scene.bodies[flight_->referenceBody()].planet;
        logInfo("now flying at {} (from {})", scene.bodies[flight_->referenceBody()].name, scene.bodies[before].name);
      }
      status_ = flight_->travelTarget()
                    ? fmt::format("{}: travelling to {} (T: next body)", scene.bodies[flight_->referenceBody()].name,
                                  scene.bodies[*flight_->travelTarget()].name)
                    : fmt::format("{} (T: travel to the next body)", scene.bodies[flight_->referenceBody()].name);
    } else if (!pathPlaying) {
      camera().update(input);
    }
    if (settings_.animate) settings_.timeS += options_.frames > 0 ? 1.0 / 60.0 : dt;
    if (settings_.sunMoves) {
      settings_.sunLongitudeDeg -= 360.0 * (options_.frames > 0 ? 1.0 / 60.0 : dt) / settings_.dayLengthS;
      settings_.sunLongitudeDeg = std::remainder(settings_.sunLongitudeDeg, 360.0);
    }

    // The panel and HUD for this frame.
    frameTimesMs_.push_back(float(dt * 1000.0));
    while (frameTimesMs_.size() > kFrameGraphLength) frameTimesMs_.pop_front();
    HudData hud;
    settings_.cameraLongitudeDeg = camera().pose().longitudeDeg;
    hud.device = context_->info.name;
    std::vector<double> recent(frameTimesMs_.begin(), frameTimesMs_.end());
    const double medianMs = recent.empty() ? 0.0 : percentile(recent, 50.0);
    hud.fps = medianMs > 0.0 ? 1000.0 / medianMs : 0.0;
    hud.frameTimesMs = &frameTimesMs_;
    hud.passes = passes_;
    const CameraPose& pose = camera().pose();
    hud.altitudeM = pose.altitudeM;
    hud.heightAboveGroundM = camera().heightAboveGroundM();
    hud.latitudeDeg = pose.latitudeDeg;
    hud.longitudeDeg = pose.longitudeDeg;
    hud.metresPerVertex = lastFrame_.metresPerVertexAtNadir;
    hud.triangles = lastFrame_.triangles;
    hud.renderWidth = renderer_->settings().width;
    hud.renderHeight = renderer_->settings().height;
    hud.mode = camera().mode();
    hud.speedMps = camera().speedMps();
    hud.pathPlaying = pathPlaying;
    hud.status = status_;
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    ui_.draw(settings_, hud, requests);
    if (goKey) ui_.requestGoTo(requests);
    ImGui::Render();
    handleRequests(requests);

    if (!drawFrame(frame)) continue;
    if (frame > 0) frameMs.push_back(dt * 1000.0);
    ++frame;
    if (frame == kWarmupFrames) {
      warm = context_->allocator.stats();
      warmRss = residentKiB();
    }
    if (options_.frames > 0 && frame >= options_.frames) break;
  }
  waitIdle();
  if (!options_.screenshot.empty() && frame > 0) saveScreenshot(options_.screenshot);

  // What a soak or leak check reads: frame times and memory after warm-up against the end.
  const vk::AllocatorStats end = context_->allocator.stats();
  if (!frameMs.empty())
    fmt::print("frames: {} on {}, median {:.1f} ms ({:.1f} fps), p95 {:.1f} ms, max {:.1f} ms\n", frame,
               context_->info.name, percentile(frameMs, 50.0), 1000.0 / percentile(frameMs, 50.0),
               percentile(frameMs, 95.0), percentile(frameMs, 100.0));
  fmt::print("swapchain recreated {} times (resize, minimise, out of date)\n", swapchainRecreations_);
  if (flight_)
    fmt::print("scene: at {} ({:.1f} m above its ground) after {} change(s) of body, scene time {:.1f} s\n",
               flight_->scene().bodies[flight_->referenceBody()].name, flight_->camera().heightAboveGroundM(),
               flight_->switches(), sceneTimeS_);
  if (frame >= kWarmupFrames)
    fmt::print(
        "memory after frame {}: {} allocations, {} bytes used, {} blocks, RSS {} KiB; after frame {}: {} allocations, "
        "{} bytes used, {} blocks, RSS {} KiB\n",
        kWarmupFrames, warm.liveAllocations, warm.bytesUsed, warm.blocks, warmRss, frame, end.liveAllocations,
        end.bytesUsed, end.blocks, residentKiB());
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
