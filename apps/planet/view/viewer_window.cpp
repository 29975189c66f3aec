#include "view/viewer_window.h"

#include <algorithm>
#include <csignal>

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <X11/Xlib.h>
#undef None  // X11 macros that collide with C++ names
#undef Status
#undef Bool
#undef Always

#include "core/error.h"

namespace planet::view {
namespace {

std::string glfwErrorText;

void onGlfwError(int code, const char* description) {
  glfwErrorText = fmt::format("{} (GLFW error {})", description, code);
}

volatile std::sig_atomic_t stopRequested = 0;
void onStopSignal(int) { stopRequested = 1; }

ViewerWindow& windowOf(GLFWwindow* window) { return *static_cast<ViewerWindow*>(glfwGetWindowUserPointer(window)); }

}  // namespace

ViewerWindow::ViewerWindow(uint32_t width, uint32_t height, const std::string& title)
    : keyPressed_(GLFW_KEY_LAST + 1, false) {
  glfwSetErrorCallback(onGlfwError);
  // Xlib must be made thread-safe before GLFW opens its display: a Vulkan driver or layer that
  // calls XInitThreads later leaves the display's context table without its lock, and GLFW's
  // event loop crashes in XFindContext (seen with lavapipe and the validation layer).
  XInitThreads();
  if (!glfwInit())
    throw Error(fmt::format("cannot open a window: {}; without a display, 'planet render' draws to a PNG",
                            glfwErrorText.empty() ? "GLFW failed to start" : glfwErrorText));
  glfw_ = ShutdownGuard(glfwTerminate);
  if (!glfwVulkanSupported())
    throw Error(fmt::format("cannot open a window: GLFW finds no usable Vulkan loader{}",
                            glfwErrorText.empty() ? "" : " (" + glfwErrorText + ")"));
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_.reset(glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr));
  if (!window_) throw Error(fmt::format("cannot open a window: {}", glfwErrorText));
  GLFWwindow* window = window_.get();
  glfwSetWindowUserPointer(window, this);
  // Installed before Dear ImGui's, which chain to them.
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) { windowOf(w).scroll_ += dy; });
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
    if (key >= 0 && key <= GLFW_KEY_LAST && action == GLFW_PRESS) windowOf(w).keyPressed_[key] = true;
  });
  glfwSetFramebufferSizeCallback(window, [](GLFWwindow* w, int, int) { windowOf(w).resized_ = true; });
}

void ViewerWindow::DestroyWindow::operator()(GLFWwindow* window) const { glfwDestroyWindow(window); }

std::vector<const char*> ViewerWindow::instanceExtensions() const {
  uint32_t count = 0;
  const char** extensions = glfwGetRequiredInstanceExtensions(&count);
  if (!extensions) throw Error(fmt::format("cannot open a window: {}", glfwErrorText));
  return std::vector<const char*>(extensions, extensions + count);
}

void ViewerWindow::watchStopSignals() {
  std::signal(SIGINT, onStopSignal);
  std::signal(SIGTERM, onStopSignal);
}

bool ViewerWindow::shouldClose() const { return glfwWindowShouldClose(window_.get()) || stopRequested; }

void ViewerWindow::close() { glfwSetWindowShouldClose(window_.get(), GLFW_TRUE); }

void ViewerWindow::pollEvents() { glfwPollEvents(); }

void ViewerWindow::waitEvents(double timeoutS) { glfwWaitEventsTimeout(timeoutS); }

VkExtent2D ViewerWindow::framebufferSize() const {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_.get(), &width, &height);
  return VkExtent2D{uint32_t(width), uint32_t(height)};
}

bool ViewerWindow::takeResized() {
  const bool resized = resized_;
  resized_ = false;
  return resized;
}

bool ViewerWindow::takePress(int key) {
  const bool pressed = keyPressed_[key];
  keyPressed_[key] = false;
  return pressed && !ImGui::GetIO().WantTextInput;
}

FlightInput ViewerWindow::readInput(double dtS, bool orbit, uint32_t viewHeightPx) {
  FlightInput input;
  input.dtS = dtS;
  const ImGuiIO& io = ImGui::GetIO();
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window_.get(), &x, &y);
  const double dx = cursorKnown_ ? x - lastCursorX_ : 0.0;
  const double dy = cursorKnown_ ? y - lastCursorY_ : 0.0;
  lastCursorX_ = x;
  lastCursorY_ = y;
  cursorKnown_ = true;
  if (!io.WantCaptureKeyboard) {
    auto key = [&](int k) { return glfwGetKey(window_.get(), k) == GLFW_PRESS ? 1.0 : 0.0; };
    input.forward = key(GLFW_KEY_W) - key(GLFW_KEY_S);
    input.right = key(GLFW_KEY_D) - key(GLFW_KEY_A);
    input.up = std::max(key(GLFW_KEY_E), key(GLFW_KEY_SPACE)) - std::max(key(GLFW_KEY_Q), key(GLFW_KEY_C));
    if (key(GLFW_KEY_LEFT_SHIFT) || key(GLFW_KEY_RIGHT_SHIFT)) input.speedFactor = 4.0;
    if (key(GLFW_KEY_LEFT_ALT) || key(GLFW_KEY_RIGHT_ALT)) input.speedFactor = 0.25;
  }
  if (!io.WantCaptureMouse) {
    if (glfwGetMouseButton(window_.get(), GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS) {
      input.lookX = dx;
      input.lookY = dy;
    } else if (glfwGetMouseButton(window_.get(), GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS && orbit) {
      // Dragging the ground: a drag across the window moves about one view height.
      const double perPixel = 2.0 / std::max(1.0, double(viewHeightPx)) / std::max(dtS, 1e-3);
      input.forward += dy * perPixel;
      input.right -= dx * perPixel;
    }
    input.zoom = scroll_;
  }
  scroll_ = 0.0;
  return input;
}

}  // namespace planet::view
