// 2D images: creation with a view, layout transitions, staged upload and readback.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "vk/allocator.h"

namespace planet::vk {

class Context;

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  Allocation allocation;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{0, 0};
  VkImageView cubeView = VK_NULL_HANDLE;             // createImageCube only: the six layers as a cube
  uint32_t layers = 1;                               // array layers
  uint32_t mipLevels = 1;                            // `view` shows level 0 only; `cubeView` every level
  uint32_t depth = 1;                                // slices (createImage3D only)
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // as left by the helpers below
};

// Throws, naming the device, the format and `purpose`, unless the device supports `needed` for
// `format` in optimal tiling.
void requireFormatFeatures(const Context& context, VkFormat format, VkFormatFeatureFlags needed, const char* purpose);

// Bytes per texel of the colour formats the engine uses; throws for others.
uint32_t formatTexelSize(VkFormat format);

Image createImage2D(Context& context, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage);
// An array of `layers` 2D images with one VK_IMAGE_VIEW_TYPE_2D_ARRAY view over all of them (also for 1).
Image createImage2DArray(Context& context, VkExtent2D extent, uint32_t layers, VkFormat format,
                         VkImageUsageFlags usage);
// A 3D image of `depth` slices with a VK_IMAGE_VIEW_TYPE_3D view (sampled with filtering across slices).
Image createImage3D(Context& context, VkExtent2D extent, uint32_t depth, VkFormat format, VkImageUsageFlags usage);
// Six square layers (+x, −x, +y, −y, +z, −z) that can be sampled as a cube map: `view` is the
// 2D-array view of mip level 0 (for storage writes), `cubeView` the cube view of all
// `mipLevels` levels (for samplerCube; the caller fills the smaller levels).
Image createImageCube(Context& context, uint32_t size, VkFormat format, VkImageUsageFlags usage,
                      uint32_t mipLevels = 1);
void destroyImage(Context& context, Image& image);
// A sampler (vk::Owned<VkSampler> destroys it).
VkSampler createSampler(Context& context, const VkSamplerCreateInfo& info);

// Records a layout transition of the whole image (every layer and level) with a full barrier
// between the given stages.
void transitionImage(VkCommandBuffer cmd, Image& image, VkImageLayout newLayout, VkPipelineStageFlags2 srcStage,
                     VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// Records a layout transition of mip levels [firstLevel, firstLevel + levelCount) of every layer
// (the image's `layout` is not updated: it names the whole image's).
void transitionLevels(VkCommandBuffer cmd, const Image& image, uint32_t firstLevel, uint32_t levelCount,
                      VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                      VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// Records the mip chain of a colour image whose level 0 was just written by (srcStage, srcAccess)
// in layout `level0`: each level the linear (box) blit of the one before, every level of every
// layer. Leaves all levels in SHADER_READ_ONLY_OPTIMAL for `readers` (and says so in `layout`).
void recordMipChain(VkCommandBuffer cmd, Image& image, VkImageLayout level0, VkPipelineStageFlags2 srcStage,
                    VkAccessFlags2 srcAccess, VkPipelineStageFlags2 readers);

// Upload and readback cover every layer (or slice), tightly packed, layer after layer.
// Fills the image with tightly packed texels and leaves it in `finalLayout` (blocking).
void uploadImage(Context& context, Image& image, const void* texels, size_t bytes, VkImageLayout finalLayout);

// Reads every texel back, tightly packed, and leaves the image in TRANSFER_SRC_OPTIMAL (blocking).
std::vector<uint8_t> readbackImage(Context& context, Image& image);
// The texels of an RGBA float image (R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT), row by row;
// throws for other formats.
std::vector<glm::vec4> readbackRgbaFloat(Context& context, Image& image);

}  // namespace planet::vk
