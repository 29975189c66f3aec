#include "vk/image.h"

#include <algorithm>
#include <cstring>
#include <string>

#include <glm/gtc/packing.hpp>

#include "core/error.h"
#include "vk/buffer.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/owned.h"

namespace planet::vk {

void requireFormatFeatures(const Context& context, VkFormat format, VkFormatFeatureFlags needed, const char* purpose) {
  VkFormatProperties properties{};
  vkGetPhysicalDeviceFormatProperties(context.physicalDevice, format, &properties);
  if ((properties.optimalTilingFeatures & needed) != needed)
    throw Error("device '" + context.info.name + "' lacks format features " + std::to_string(needed) + " of format " +
                std::to_string(int(format)) + " (it has " + std::to_string(properties.optimalTilingFeatures) +
                "), which " + purpose + " needs");
}

uint32_t formatTexelSize(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8_UNORM: return 1;
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_D32_SFLOAT: return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT: return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
    default: throw Error("unsupported image format " + std::to_string(int(format)));
  }
}

namespace {

Image createImage(Context& context, VkExtent2D extent, uint32_t layers, VkFormat format, VkImageUsageFlags usage,
                  VkImageViewType viewType, bool cube = false, uint32_t mipLevels = 1, uint32_t slices = 1) {
  if (extent.width == 0 || extent.height == 0 || layers == 0 || slices == 0)
    throw Error("cannot create an image of size 0");
  if (mipLevels == 0 || (std::max(extent.width, extent.height) >> (mipLevels - 1)) == 0)
    throw Error("cannot create " + std::to_string(mipLevels) + " mip levels for an image of " +
                std::to_string(extent.width) + "x" + std::to_string(extent.height));
  // Owned until complete: a throw destroys what was created so far.
  Owned<Image> image(context, Image{});
  image->format = format;
  image->extent = extent;
  image->layers = layers;
  image->mipLevels = mipLevels;
  image->depth = slices;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = viewType == VK_IMAGE_VIEW_TYPE_3D ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {extent.width, extent.height, slices};
  info.mipLevels = mipLevels;
  info.arrayLayers = layers;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  if (cube) info.flags = VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT;
  VK_CHECK(vkCreateImage(context.device, &info, nullptr, &image->image));
  image->allocation = context.allocator.allocateForImage(image->image, MemoryUsage::DeviceLocal, ResourceKind::Optimal);
  VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = image->image;
  viewInfo.viewType = viewType;
  viewInfo.format = format;
  bool depth = format == VK_FORMAT_D32_SFLOAT;
  viewInfo.subresourceRange = {VkImageAspectFlags(depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0, 1,
                               0, layers};
  VK_CHECK(vkCreateImageView(context.device, &viewInfo, nullptr, &image->view));
  if (cube) {
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_CUBE;
    viewInfo.subresourceRange.levelCount = mipLevels;
    VK_CHECK(vkCreateImageView(context.device, &viewInfo, nullptr, &image->cubeView));
  }
  return image.release();
}

}  // namespace

Image createImage2D(Context& context, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage) {
  return createImage(context, extent, 1, format, usage, VK_IMAGE_VIEW_TYPE_2D);
}

Image createImage2DArray(Context& context, VkExtent2D extent, uint32_t layers, VkFormat format,
                         VkImageUsageFlags usage) {
  return createImage(context, extent, layers, format, usage, VK_IMAGE_VIEW_TYPE_2D_ARRAY);
}

Image createImage3D(Context& context, VkExtent2D extent, uint32_t depth, VkFormat format, VkImageUsageFlags usage) {
  return createImage(context, extent, 1, format, usage, VK_IMAGE_VIEW_TYPE_3D, false, 1, depth);
}

Image createImageCube(Context& context, uint32_t size, VkFormat format, VkImageUsageFlags usage,
                      uint32_t mipLevels) {
  return createImage(context, {size, size}, 6, format, usage, VK_IMAGE_VIEW_TYPE_2D_ARRAY, true, mipLevels);
}

void destroyImage(Context& context, Image& image) {
  if (image.cubeView) vkDestroyImageView(context.device, image.cubeView, nullptr);
  if (image.view) vkDestroyImageView(context.device, image.view, nullptr);
  if (image.image) vkDestroyImage(context.device, image.image, nullptr);
  context.allocator.free(image.allocation);
  image = Image{};
}

VkSampler createSampler(Context& context, const VkSamplerCreateInfo& info) {
  VkSampler sampler = VK_NULL_HANDLE;
  VK_CHECK(vkCreateSampler(context.device, &info, nullptr, &sampler));
  return sampler;
}

void transitionImage(VkCommandBuffer cmd, Image& image, VkImageLayout newLayout, VkPipelineStageFlags2 srcStage,
                     VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  barrier.srcStageMask = srcStage;
  barrier.srcAccessMask = srcAccess;
  barrier.dstStageMask = dstStage;
  barrier.dstAccessMask = dstAccess;
  barrier.oldLayout = image.layout;
  barrier.newLayout = newLayout;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image.image;
  bool depth = image.format == VK_FORMAT_D32_SFLOAT;
  barrier.subresourceRange = {VkImageAspectFlags(depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0,
                              image.mipLevels, 0, image.layers};
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dep);
  image.layout = newLayout;
}

void transitionLevels(VkCommandBuffer cmd, const Image& image, uint32_t firstLevel, uint32_t levelCount,
                      VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                      VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  barrier.srcStageMask = srcStage;
  barrier.srcAccessMask = srcAccess;
  barrier.dstStageMask = dstStage;
  barrier.dstAccessMask = dstAccess;
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image.image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, firstLevel, levelCount, 0, image.layers};
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dep);
}

void recordMipChain(VkCommandBuffer cmd, Image& image, VkImageLayout level0, VkPipelineStageFlags2 srcStage,
                    VkAccessFlags2 srcAccess, VkPipelineStageFlags2 readers) {
  const uint32_t levels = image.mipLevels;
  // Level 0 is the first blit's source; the others are written whole, their contents discarded.
  transitionLevels(cmd, image, 0, 1, level0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, srcStage, srcAccess,
                   VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  if (levels > 1)
    transitionLevels(cmd, image, 1, levels - 1, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  for (uint32_t level = 1; level < levels; ++level) {
    const int32_t fromW = int32_t(std::max(image.extent.width >> (level - 1), 1u));
    const int32_t fromH = int32_t(std::max(image.extent.height >> (level - 1), 1u));
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, image.layers};
    blit.srcOffsets[1] = {fromW, fromH, 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, image.layers};
    blit.dstOffsets[1] = {std::max(fromW / 2, 1), std::max(fromH / 2, 1), 1};
    vkCmdBlitImage(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image.image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
    // The level just written is the next blit's source.
    transitionLevels(cmd, image, level, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                     VK_ACCESS_2_TRANSFER_READ_BIT);
  }
  transitionLevels(cmd, image, 0, levels, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                   VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT, readers,
                   VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  image.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
}

static VkBufferImageCopy fullCopy(const Image& image) {
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, image.layers};
  region.imageExtent = {image.extent.width, image.extent.height, image.depth};
  return region;
}

void uploadImage(Context& context, Image& image, const void* texels, size_t bytes, VkImageLayout finalLayout) {
  size_t expected =
      size_t(image.extent.width) * image.extent.height * image.depth * image.layers * formatTexelSize(image.format);
  if (bytes != expected)
    throw Error("image upload of " + std::to_string(bytes) + " bytes, expected " + std::to_string(expected));
  const Owned<Buffer> staging(context, createBuffer(context, bytes, 0, MemoryUsage::Upload));
  std::memcpy(staging->mapped(), texels, bytes);
  context.allocator.flush(staging->allocation);
  submitAndWait(context, [&](VkCommandBuffer cmd) {
    // Previous contents are discarded; the copy waits for nothing but earlier transfers.
    image.layout = VK_IMAGE_LAYOUT_UNDEFINED;
    transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0,
                    VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkBufferImageCopy region = fullCopy(image);
    vkCmdCopyBufferToImage(cmd, staging->buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    // Any later stage may read the image in its final layout.
    transitionImage(cmd, image, finalLayout, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT);
  });
}

std::vector<uint8_t> readbackImage(Context& context, Image& image) {
  size_t bytes =
      size_t(image.extent.width) * image.extent.height * image.depth * image.layers * formatTexelSize(image.format);
  const Owned<Buffer> staging(context, createBuffer(context, bytes, 0, MemoryUsage::Readback));
  std::vector<uint8_t> texels(bytes);
  submitAndWait(context, [&](VkCommandBuffer cmd) {
    // Whatever wrote the image last must finish before the copy reads it.
    transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                    VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region = fullCopy(image);
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging->buffer, 1, &region);
    // The host reads the staging buffer after the fence.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                  VK_ACCESS_2_HOST_READ_BIT);
  });
  context.allocator.invalidate(staging->allocation);
  std::memcpy(texels.data(), staging->mapped(), bytes);
  return texels;
}

std::vector<glm::vec4> readbackRgbaFloat(Context& context, Image& image) {
  if (image.format != VK_FORMAT_R16G16B16A16_SFLOAT && image.format != VK_FORMAT_R32G32B32A32_SFLOAT)
    throw Error("readbackRgbaFloat: image format " + std::to_string(int(image.format)) + " is not RGBA float");
  const std::vector<uint8_t> bytes = readbackImage(context, image);
  std::vector<glm::vec4> texels(bytes.size() / formatTexelSize(image.format));
  if (image.format == VK_FORMAT_R32G32B32A32_SFLOAT) {
    std::memcpy(texels.data(), bytes.data(), bytes.size());
  } else {
    for (size_t i = 0; i < texels.size() * 4; ++i) {
      uint16_t half = 0;
      std::memcpy(&half, bytes.data() + 2 * i, 2);
      texels[i / 4][int(i % 4)] = glm::unpackHalf1x16(half);
    }
  }
  return texels;
}

}  // namespace planet::vk
