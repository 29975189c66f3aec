// Buffers: a VkBuffer with its sub-allocation, plus staged upload and readback.
#pragma once

#include <cstddef>
#include <cstdint>

#include <vulkan/vulkan.h>

#include "vk/allocator.h"

namespace planet::vk {

class Context;

// Frames a renderer may have in flight: its passes keep this many copies (frame slots) of the
// data the CPU writes per frame, so that one slot is written while the GPU reads the other.
inline constexpr uint32_t kFramesInFlight = 2;
// Throws planet::Error naming a slot outside 0 .. kFramesInFlight − 1.
void checkFrameSlot(uint32_t slot);

struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  Allocation allocation;
  VkDeviceSize size = 0;
  // Persistently mapped pointer for Upload/Readback buffers, nullptr for DeviceLocal ones
  // (unless the device-local memory happens to be host-visible, as on CPU devices).
  void* mapped() const { return allocation.mapped; }
};

Buffer createBuffer(Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory);
void destroyBuffer(Context& context, Buffer& buffer);

// A view of the whole buffer as texels of `format`, for a uniform or storage texel buffer
// descriptor (the buffer made with the matching usage bit).
VkBufferView createBufferView(Context& context, const Buffer& buffer, VkFormat format);

// Copies `bytes` from host memory into the buffer at `offset`: directly when the buffer is
// mapped, else through a temporary staging buffer and a transfer (blocking).
void uploadBuffer(Context& context, Buffer& buffer, const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);

// Copies `bytes` at `offset` of the buffer back to host memory (blocking, staged if needed).
void readbackBuffer(Context& context, const Buffer& buffer, void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);

}  // namespace planet::vk
