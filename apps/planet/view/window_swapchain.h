// The viewer window's swapchain (issue 5): the window's surface, a swapchain recreated when the
// window changes size or the surface reports it out of date, a present semaphore per image, and
// the blit of the Renderer's output onto the image a frame acquired.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/owned.h"
#include "vk/swapchain.h"

struct GLFWwindow;

namespace planet::vk {
class Context;
struct Image;
}  // namespace planet::vk

namespace planet::view {

class WindowSwapchain {
 public:
  // Creates the window's surface (no swapchain yet: create() makes it). Throws planet::Error with
  // one line when no surface can be made or the device cannot present to it. Destroy it only
  // when nothing uses the images any more.
  WindowSwapchain(vk::Context& context, GLFWwindow* window, bool vsync);
  WindowSwapchain(const WindowSwapchain&) = delete;
  WindowSwapchain& operator=(const WindowSwapchain&) = delete;

  // Makes the swapchain for the window's size in pixels, replacing the current one (nothing may
  // still use its images); none while the window is minimised.
  void create();
  // create() for a window that changed: counts the recreation and clears the stale mark.
  void recreate();
  // Resized, suboptimal or out of date: recreate before the next frame.
  void markStale() { stale_ = true; }
  // Whether a frame for a window of width × height pixels needs recreate() first.
  bool needsRecreate(uint32_t width, uint32_t height) const;
  uint32_t recreations() const { return recreations_; }

  bool empty() const { return swapchain_->images.empty(); }  // minimised
  const vk::Swapchain& swapchain() const { return *swapchain_; }
  VkExtent2D extent() const { return swapchain_->extent; }

  // Acquires the next image into `imageIndex`, signalling `acquired` once it may be written.
  // False when the swapchain is out of date (recreate it and skip the frame); a suboptimal one
  // is drawn into and marked stale.
  bool acquire(VkSemaphore acquired, uint32_t& imageIndex);
  // Records the blit of `source` (as the tonemap left it, a colour attachment) onto image
  // `imageIndex`, scaled to the swapchain's extent, which it leaves as a transfer destination.
  // The frame's submission waits for the acquire semaphore at the transfer stage.
  void recordBlit(VkCommandBuffer cmd, vk::Image& source, uint32_t imageIndex) const;
  // Signalled by the submission that draws image `imageIndex`; the present waits for it.
  VkSemaphore renderedSemaphore(uint32_t imageIndex) const { return rendered_[imageIndex].get(); }
  // Presents image `imageIndex` on `queue`; an out-of-date or suboptimal swapchain is marked stale.
  void present(VkQueue queue, uint32_t imageIndex);

 private:
  vk::Context& context_;
  GLFWwindow* window_;
  bool vsync_;
  // In the order of creation (destroyed in reverse).
  vk::Owned<VkSurfaceKHR> surface_;
  vk::Owned<vk::Swapchain> swapchain_;
  // Per image, not per frame slot: a semaphore may be signalled again only once the present that
  // waited on it is done, which reacquiring its image guarantees. Kept across recreations.
  std::vector<vk::Owned<VkSemaphore>> rendered_;
  bool stale_ = false;
  uint32_t recreations_ = 0;
};

}  // namespace planet::view
