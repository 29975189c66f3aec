#include "vk/swapchain.h"

#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "core/error.h"
#include "vk/context.h"
#include "vk/owned.h"

namespace planet::vk {
namespace {

VkSurfaceFormatKHR chooseFormat(const Context& context, VkSurfaceKHR surface) {
  uint32_t count = 0;
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(context.physicalDevice, surface, &count, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(count);
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(context.physicalDevice, surface, &count, formats.data()));
  // The renderer's frame is sRGB-encoded; an sRGB swapchain keeps the blit a plain copy.
  for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB})
    for (const VkSurfaceFormatKHR& f : formats)
      if (f.format == wanted && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return f;
  std::string names;
  for (const VkSurfaceFormatKHR& f : formats) names += fmt::format(" {}", int(f.format));
  throw Error(fmt::format("the window surface offers no sRGB 8-bit format (formats:{})", names));
}

VkPresentModeKHR choosePresentMode(const Context& context, VkSurfaceKHR surface, bool vsync) {
  if (vsync) return VK_PRESENT_MODE_FIFO_KHR;  // always supported
  uint32_t count = 0;
  VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(context.physicalDevice, surface, &count, nullptr));
  std::vector<VkPresentModeKHR> modes(count);
  VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(context.physicalDevice, surface, &count, modes.data()));
  for (VkPresentModeKHR wanted : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
    if (std::find(modes.begin(), modes.end(), wanted) != modes.end()) return wanted;
  return VK_PRESENT_MODE_FIFO_KHR;
}

}  // namespace

bool canPresent(const Context& context, VkSurfaceKHR surface) {
  VkBool32 supported = VK_FALSE;
  VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(context.physicalDevice, context.universalFamily, surface, &supported));
  return supported == VK_TRUE;
}

Swapchain createSwapchain(Context& context, VkSurfaceKHR surface, VkExtent2D framebufferExtent, bool vsync,
                          Swapchain* old) {
  VkSurfaceCapabilitiesKHR caps{};
  VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context.physicalDevice, surface, &caps));
  Swapchain result;
  // 0xFFFFFFFF: the surface takes the swapchain's size; otherwise it dictates it.
  if (caps.currentExtent.width != UINT32_MAX) {
    result.extent = caps.currentExtent;
  } else {
    result.extent.width = std::clamp(framebufferExtent.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    result.extent.height = std::clamp(framebufferExtent.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  if (result.extent.width == 0 || result.extent.height == 0 || framebufferExtent.width == 0 ||
      framebufferExtent.height == 0) {
    result.extent = {0, 0};  // minimised: nothing to present until the window comes back
    if (old) destroySwapchain(context, *old);
    return result;
  }
  const VkSurfaceFormatKHR format = chooseFormat(context, surface);
  result.format = format.format;
  result.colorSpace = format.colorSpace;
  result.presentMode = choosePresentMode(context, surface, vsync);
  uint32_t imageCount = std::max(3u, caps.minImageCount);
  if (caps.maxImageCount) imageCount = std::min(imageCount, caps.maxImageCount);
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  if ((caps.supportedUsageFlags & usage) != usage)
    throw Error("the window surface's images cannot be blit targets and colour attachments");

  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = surface;
  info.minImageCount = imageCount;
  info.imageFormat = format.format;
  info.imageColorSpace = format.colorSpace;
  info.imageExtent = result.extent;
  info.imageArrayLayers = 1;
  info.imageUsage = usage;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = (caps.supportedTransforms & VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR)
                          ? VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR
                          : caps.currentTransform;
  info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                            : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
  info.presentMode = result.presentMode;
  info.clipped = VK_TRUE;
  info.oldSwapchain = old ? old->swapchain : VK_NULL_HANDLE;
  // Owned until complete: a throw below destroys the new swapchain and the views made so far.
  Owned<Swapchain> made(context, std::move(result));
  VK_CHECK(vkCreateSwapchainKHR(context.device, &info, nullptr, &made->swapchain));
  if (old) destroySwapchain(context, *old);

  uint32_t count = 0;
  VK_CHECK(vkGetSwapchainImagesKHR(context.device, made->swapchain, &count, nullptr));
  made->images.resize(count);
  VK_CHECK(vkGetSwapchainImagesKHR(context.device, made->swapchain, &count, made->images.data()));
  made->views.reserve(count);  // no allocation between a view's creation and its push_back
  for (VkImage image : made->images) {
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = made->format;
    view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView handle = VK_NULL_HANDLE;
    VK_CHECK(vkCreateImageView(context.device, &view, nullptr, &handle));
    made->views.push_back(handle);
  }
  return made.release();
}

void destroySwapchain(Context& context, Swapchain& swapchain) {
  for (VkImageView view : swapchain.views) vkDestroyImageView(context.device, view, nullptr);
  if (swapchain.swapchain) vkDestroySwapchainKHR(context.device, swapchain.swapchain, nullptr);
  swapchain = Swapchain{};
}

}  // namespace planet::vk
