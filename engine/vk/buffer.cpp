#include "vk/buffer.h"

#include <cstring>
#include <string>

#include "core/error.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/owned.h"

namespace planet::vk {
namespace {

void checkRange(const Buffer& buffer, VkDeviceSize bytes, VkDeviceSize offset, const char* what) {
  if (offset > buffer.size || bytes > buffer.size - offset)
    throw Error(std::string(what) + " of " + std::to_string(bytes) + " bytes at offset " + std::to_string(offset) +
                " exceeds the buffer's " + std::to_string(buffer.size) + " bytes");
}

}  // namespace

void checkFrameSlot(uint32_t slot) {
  if (slot >= kFramesInFlight)
    throw Error("frame slot " + std::to_string(slot) + " is outside 0.." + std::to_string(kFramesInFlight - 1));
}

VkBufferView createBufferView(Context& context, const Buffer& buffer, VkFormat format) {
  VkBufferViewCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
  info.buffer = buffer.buffer;
  info.format = format;
  info.offset = 0;
  info.range = VK_WHOLE_SIZE;
  VkBufferView view = VK_NULL_HANDLE;
  VK_CHECK(vkCreateBufferView(context.device, &info, nullptr, &view));
  return view;
}

Buffer createBuffer(Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory) {
  if (size == 0) throw Error("cannot create a buffer of 0 bytes");
  // Owned until complete: a failed allocation destroys the VkBuffer.
  Owned<Buffer> buffer(context, Buffer{});
  buffer->size = size;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  // Transfer usage always: any buffer can be uploaded to or read back through staging.
  info.usage = usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VK_CHECK(vkCreateBuffer(context.device, &info, nullptr, &buffer->buffer));
  buffer->allocation = context.allocator.allocateForBuffer(buffer->buffer, memory);
  return buffer.release();
}

void destroyBuffer(Context& context, Buffer& buffer) {
  if (buffer.buffer) vkDestroyBuffer(context.device, buffer.buffer, nullptr);
  context.allocator.free(buffer.allocation);
  buffer = Buffer{};
}

void uploadBuffer(Context& context, Buffer& buffer, const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  checkRange(buffer, bytes, offset, "upload");
  if (bytes == 0) return;
  if (buffer.mapped()) {
    std::memcpy(static_cast<char*>(buffer.mapped()) + offset, data, bytes);
    context.allocator.flush(buffer.allocation);
    return;
  }
  const Owned<Buffer> staging(context, createBuffer(context, bytes, 0, MemoryUsage::Upload));
  std::memcpy(staging->mapped(), data, bytes);
  context.allocator.flush(staging->allocation);
  submitAndWait(context, [&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, offset, bytes};
    vkCmdCopyBuffer(cmd, staging->buffer, buffer.buffer, 1, &region);
    // Later submissions may read the data in any stage; the fence wait orders the rest.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
  });
}

void readbackBuffer(Context& context, const Buffer& buffer, void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  checkRange(buffer, bytes, offset, "readback");
  if (bytes == 0) return;
  if (buffer.mapped()) {
    context.allocator.invalidate(buffer.allocation);
    std::memcpy(data, static_cast<const char*>(buffer.mapped()) + offset, bytes);
    return;
  }
  const Owned<Buffer> staging(context, createBuffer(context, bytes, 0, MemoryUsage::Readback));
  submitAndWait(context, [&](VkCommandBuffer cmd) {
    // Earlier submissions' writes must be visible to the copy.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferCopy region{offset, 0, bytes};
    vkCmdCopyBuffer(cmd, buffer.buffer, staging->buffer, 1, &region);
    // Make the copy visible to the host read below.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                  VK_ACCESS_2_HOST_READ_BIT);
  });
  context.allocator.invalidate(staging->allocation);
  std::memcpy(data, staging->mapped(), bytes);
}

}  // namespace planet::vk
