// The viewer's swapchain: images to present on a window surface, recreated when the window
// changes size or the surface reports it out of date.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace planet::vk {

class Context;

struct Swapchain {
  VkSwapchainKHR swapchain = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkColorSpaceKHR colorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  VkPresentModeKHR presentMode = VK_PRESENT_MODE_FIFO_KHR;
  VkExtent2D extent{0, 0};
  std::vector<VkImage> images;
  std::vector<VkImageView> views;
};

// Whether the universal queue family can present to `surface`; the viewer needs it.
bool canPresent(const Context& context, VkSurfaceKHR surface);

// Creates (or, given `old`, replaces) a swapchain of at least 3 images with an sRGB format
// (B8G8R8A8 or R8G8B8A8, written as sRGB by blits), usable as a transfer destination and a
// colour attachment. `vsync` picks FIFO; otherwise MAILBOX, else IMMEDIATE, else FIFO.
// `framebufferExtent` is the window's size in pixels; the surface's current extent wins where
// it is defined. Returns a swapchain with extent 0×0 (and no images) while the window is
// minimised. `old` is destroyed (after the new one is created from it).
Swapchain createSwapchain(Context& context, VkSurfaceKHR surface, VkExtent2D framebufferExtent, bool vsync,
                          Swapchain* old = nullptr);
void destroySwapchain(Context& context, Swapchain& swapchain);

}  // namespace planet::vk
