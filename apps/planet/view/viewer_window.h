// The viewer's window (issue 5): GLFW on X11, one window without a client API, the keys and
// mouse read from it each frame, and Ctrl-C or SIGTERM taken as closing it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "camera/flight_camera.h"
#include "view/shutdown_guard.h"

struct GLFWwindow;

namespace planet::view {

class ViewerWindow {
 public:
  // Throws planet::Error with one line when no window can be opened (no display, no Vulkan
  // loader for GLFW). Destroy it after every Vulkan object made for the window.
  ViewerWindow(uint32_t width, uint32_t height, const std::string& title);
  ViewerWindow(const ViewerWindow&) = delete;
  ViewerWindow& operator=(const ViewerWindow&) = delete;

  GLFWwindow* handle() const { return window_.get(); }
  // The instance extensions a Vulkan surface on this window needs.
  std::vector<const char*> instanceExtensions() const;

  // From here on, Ctrl-C (SIGINT) and SIGTERM make shouldClose() true, as closing the window
  // does: the frame loop finishes, the screenshot is saved and everything is released.
  void watchStopSignals();
  bool shouldClose() const;
  void close();
  void pollEvents();
  void waitEvents(double timeoutS);
  VkExtent2D framebufferSize() const;  // pixels; 0×0 while minimised
  // Whether the framebuffer changed size since the last call.
  bool takeResized();

  // Whether `key` (GLFW_KEY_*) was pressed since it was last taken; a press typed into a text
  // field of the panel does not count.
  bool takePress(int key);
  // This frame's flight input from the keys and mouse the panel does not capture. A left drag
  // (orbit mode only) moves about one view height per view of `viewHeightPx` pixels.
  FlightInput readInput(double dtS, bool orbit, uint32_t viewHeightPx);

 private:
  struct DestroyWindow {
    void operator()(GLFWwindow* window) const;
  };

  // Input state (the window's callbacks write resized_, scroll_ and keyPressed_).
  bool resized_ = false;
  double lastCursorX_ = 0.0, lastCursorY_ = 0.0;
  bool cursorKnown_ = false;
  double scroll_ = 0.0;
  std::vector<bool> keyPressed_;  // by GLFW key code
  // In the order of creation (destroyed in reverse, before the state above): GLFW, its window.
  ShutdownGuard glfw_;
  std::unique_ptr<GLFWwindow, DestroyWindow> window_;
};

}  // namespace planet::view
