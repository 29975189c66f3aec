// Dear ImGui in the viewer (issue 5): the context, its GLFW and Vulkan backends, the font upload,
// and the render pass that draws the panel and HUD over the frame blitted onto a swapchain image.
// What the panel shows is viewer_ui's.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

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
  // is minimised (no images) or a backend does not start.
  ImGuiLayer(vk::Context& context, GLFWwindow* window, const vk::Swapchain& swapchain);
  ~ImGuiLayer();  // nothing may still use its objects
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
  void start(GLFWwindow* window, const vk::Swapchain& swapchain);
  void createFramebuffers(const vk::Swapchain& swapchain);
  void release();

  vk::Context& context_;
  VkRenderPass pass_ = VK_NULL_HANDLE;  // made for the first swapchain's format
  std::vector<VkFramebuffer> framebuffers_;
  VkExtent2D extent_{0, 0};
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  bool glfwBackend_ = false, vulkanBackend_ = false;
};

}  // namespace planet::view
