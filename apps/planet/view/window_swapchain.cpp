#include "view/window_swapchain.h"

#include <utility>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include "core/error.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/image.h"

namespace planet::view {

WindowSwapchain::WindowSwapchain(vk::Context& context, GLFWwindow* window, bool vsync)
    : context_(context), window_(window), vsync_(vsync) {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  VkResult result = glfwCreateWindowSurface(context.instance, window, nullptr, &surface);
  if (result != VK_SUCCESS)
    throw Error(fmt::format("cannot create a Vulkan surface for the window: {}", vkResultName(result)));
  surface_ = {context, surface};
  if (!vk::canPresent(context, surface))
    throw Error(fmt::format("{} cannot present to this window; choose another with --device", context.info.name));
}

void WindowSwapchain::create() {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  // The old swapchain (if any) is handed over to its replacement, which destroys it.
  vk::Swapchain created = vk::createSwapchain(context_, surface_.get(), VkExtent2D{uint32_t(width), uint32_t(height)},
                                              vsync_, swapchain_->swapchain ? &*swapchain_ : nullptr);
  swapchain_ = {context_, std::move(created)};
  if (swapchain_->images.empty()) return;  // minimised
  while (rendered_.size() < swapchain_->images.size()) {
    vk::Owned<VkSemaphore> semaphore(context_, vk::createSemaphore(context_));
    rendered_.push_back(std::move(semaphore));
  }
}

void WindowSwapchain::recreate() {
  create();
  stale_ = false;
  ++recreations_;
}

bool WindowSwapchain::needsRecreate(uint32_t width, uint32_t height) const {
  return stale_ || swapchain_->images.empty() || swapchain_->extent.width != width ||
         swapchain_->extent.height != height;
}

bool WindowSwapchain::acquire(VkSemaphore acquired, uint32_t& imageIndex) {
  const VkResult result =
      vkAcquireNextImageKHR(context_.device, swapchain_->swapchain, UINT64_MAX, acquired, VK_NULL_HANDLE, &imageIndex);
  if (result == VK_ERROR_OUT_OF_DATE_KHR) return false;
  if (result != VK_SUCCESS && result != VK_SUBOPTIMAL_KHR)
    throwVulkanError(result, "vkAcquireNextImageKHR", __FILE__, __LINE__);
  if (result == VK_SUBOPTIMAL_KHR) stale_ = true;
  return true;
}

void WindowSwapchain::recordBlit(VkCommandBuffer cmd, vk::Image& source, uint32_t imageIndex) const {
  // The blit reads what the tonemap wrote.
  vk::transitionImage(cmd, source, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
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
  toTransfer.image = swapchain_->images[imageIndex];
  toTransfer.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &toTransfer;
  vkCmdPipelineBarrier2(cmd, &dependency);
  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {int32_t(source.extent.width), int32_t(source.extent.height), 1};
  blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.dstOffsets[1] = {int32_t(swapchain_->extent.width), int32_t(swapchain_->extent.height), 1};
  const bool sameSize =
      source.extent.width == swapchain_->extent.width && source.extent.height == swapchain_->extent.height;
  vkCmdBlitImage(cmd, source.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, swapchain_->images[imageIndex],
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, sameSize ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
}

void WindowSwapchain::present(VkQueue queue, uint32_t imageIndex) {
  VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &rendered_[imageIndex].get();
  present.swapchainCount = 1;
  present.pSwapchains = &swapchain_->swapchain;
  present.pImageIndices = &imageIndex;
  const VkResult result = vkQueuePresentKHR(queue, &present);
  if (result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR)
    stale_ = true;
  else if (result != VK_SUCCESS)
    throwVulkanError(result, "vkQueuePresentKHR", __FILE__, __LINE__);
}

}  // namespace planet::view
