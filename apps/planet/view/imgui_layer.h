// Dear ImGui in the viewer (issue 5): the context, its GLFW and Vulkan backends, the font upload,
// and the render pass that draws the panel and HUD over the frame blitted onto a swapchain image.
// What the panel shows is viewer_ui's.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "view/shutdown_guard.h"
#include "vk/owned.h"
#include "vk/swapchain.h"

struct GLFWwindow;

namespace planet::vk {
class Context;
}

namespace planet::view {

class ImGuiLayer {
 public:
  // Starts Dear ImGui on `window` (its GLFW backend chains to the callbacks installed before)
  // drawing into `swapchain`'s images, and uploads the font. Throws planet::Error when the window
  // is minimised (no images) or a backend does not start. Destroy it only when nothing uses its
  // objects any more.
  ImGuiLayer(vk::Context& context, GLFWwindow* window, const vk::Swapchain& swapchain);
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

  // Around a swapchain's replacement: detach() before (the framebuffers hold the old images'
  // views), attach() after, which tells the backend the new image count.
  void detach();
  void attach(const vk::Swapchain& swapchain);

  // Around the ImGui:: calls that build this frame's windows; record() draws what endFrame() left.
  void beginFrame();
  void endFrame();
  // Records the frame's windows over swapchain image `imageIndex`, which the blit left as a
  // transfer destination; leaves it ready to present.
  void record(VkCommandBuffer cmd, uint32_t imageIndex) const;

 private:
  void createFramebuffers(const vk::Swapchain& swapchain);

  vk::Context& context_;
  VkExtent2D extent_{0, 0};
  // In the order of creation (destroyed in reverse): the Vulkan objects, then Dear ImGui's
  // context and its backends, each set once it started.
  vk::Owned<VkRenderPass> pass_;  // made for the first swapchain's format
  std::vector<vk::Owned<VkFramebuffer>> framebuffers_;
  vk::Owned<VkDescriptorPool> pool_;
  ShutdownGuard imguiContext_;
  ShutdownGuard glfwBackend_;
  ShutdownGuard vulkanBackend_;
};

}  // namespace planet::view
