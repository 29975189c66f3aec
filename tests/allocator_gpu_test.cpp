// The allocator with real device memory: sub-allocation into shared blocks, mapping,
// dedicated allocations, statistics, out-of-memory reporting and leak detection.
#include <cstring>
#include <map>

#include <gtest/gtest.h>

#include "gpu_fixture.h"
#include "vk/buffer.h"
#include "vk/image.h"

namespace planet::test {
namespace {

using AllocatorGpu = GpuTest;

TEST_F(AllocatorGpu, SmallBuffersShareBlocksWithoutOverlapping) {
  vk::AllocatorStats before = context().allocator.stats();
  std::vector<vk::Buffer> buffers;
  VkDeviceSize requested = 0;
  for (int i = 0; i < 200; ++i) {
    VkDeviceSize size = 256 + VkDeviceSize(i) * 1000;
    requested += size;
    buffers.push_back(vk::createBuffer(context(), size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       i % 2 ? vk::MemoryUsage::DeviceLocal : vk::MemoryUsage::Upload));
  }
  vk::AllocatorStats during = context().allocator.stats();
  EXPECT_EQ(during.liveAllocations, before.liveAllocations + 200);
  EXPECT_GE(during.bytesUsed - before.bytesUsed, requested);
  EXPECT_LE(during.blocks, before.blocks + 4) << "200 small buffers should fit in a few blocks";
  // No two allocations in the same VkDeviceMemory overlap.
  std::map<VkDeviceMemory, std::vector<std::pair<VkDeviceSize, VkDeviceSize>>> ranges;
  for (const vk::Buffer& b : buffers) ranges[b.allocation.memory].push_back({b.allocation.offset, b.allocation.size});
  for (auto& [memory, list] : ranges) {
    std::sort(list.begin(), list.end());
    for (size_t i = 1; i < list.size(); ++i) EXPECT_LE(list[i - 1].first + list[i - 1].second, list[i].first);
  }
  for (vk::Buffer& b : buffers) vk::destroyBuffer(context(), b);
  vk::AllocatorStats after = context().allocator.stats();
  EXPECT_EQ(after.liveAllocations, before.liveAllocations);
  EXPECT_EQ(after.bytesUsed, before.bytesUsed);
}

TEST_F(AllocatorGpu, HostVisibleMemoryStaysMappedAndWritable) {
  vk::Buffer buffer = vk::createBuffer(context(), 4096, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::Upload);
  ASSERT_NE(buffer.mapped(), nullptr);
  std::memset(buffer.mapped(), 0xab, 4096);
  std::vector<uint8_t> back(4096);
  vk::readbackBuffer(context(), buffer, back.data(), back.size());
  EXPECT_EQ(back, std::vector<uint8_t>(4096, 0xab));
  vk::destroyBuffer(context(), buffer);
}

TEST_F(AllocatorGpu, LargeImagesGetDedicatedMemory) {
  vk::AllocatorStats before = context().allocator.stats();
  vk::Image image = vk::createImage2D(context(), {4096, 4096}, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT);
  EXPECT_EQ(image.allocation.block, -1) << "a 64 MiB image should not be sub-allocated";
  EXPECT_EQ(context().allocator.stats().dedicatedAllocations, before.dedicatedAllocations + 1);
  vk::destroyImage(context(), image);
  EXPECT_EQ(context().allocator.stats().dedicatedAllocations, before.dedicatedAllocations);
}

TEST_F(AllocatorGpu, ImpossibleAllocationIsAClearOutOfMemoryError) {
  const VkDeviceSize huge = VkDeviceSize(1) << 50;  // 1 PiB
  try {
    vk::Buffer b = vk::createBuffer(context(), huge, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::DeviceLocal);
    vk::destroyBuffer(context(), b);
    FAIL() << "a 1 PiB buffer was allocated";
  } catch (const vk::OutOfMemoryError& e) {
    EXPECT_NE(std::string(e.what()).find("1125899906842624"), std::string::npos) << e.what();
  } catch (const VulkanError& e) {
    // Some drivers refuse the VkBuffer itself (maxBufferSize); that is also a clear error.
    EXPECT_EQ(e.result(), VK_ERROR_OUT_OF_DEVICE_MEMORY) << e.what();
  }
  EXPECT_EQ(context().allocator.stats().liveAllocations, 0u);
}

TEST(AllocatorLimit, AllocationsBeyondTheLimitFailAndFreeingMakesRoomAgain) {
  vk::ContextOptions options;
  options.deviceMemoryLimit = 8ull << 20;
  std::unique_ptr<vk::Context> context = createTestContext(options);
  if (!context) GTEST_SKIP() << "no Vulkan device on this machine";
  // 8 MiB allows three 2.5 MiB buffers (each dedicated: a 64 MiB block does not fit), not four.
  const VkDeviceSize size = 5ull << 19;
  std::vector<vk::Buffer> held;
  for (int i = 0; i < 3; ++i)
    held.push_back(vk::createBuffer(*context, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::DeviceLocal));
  try {
    vk::Buffer extra = vk::createBuffer(*context, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::DeviceLocal);
    vk::destroyBuffer(*context, extra);
    FAIL() << "a fourth buffer fitted under the limit";
  } catch (const vk::OutOfMemoryError& e) {
    EXPECT_NE(std::string(e.what()).find("7.5 MiB already held of the 8.0 MiB limit"), std::string::npos) << e.what();
  }
  EXPECT_EQ(context->allocator.stats().liveAllocations, 3u) << "the failed request left something behind";
  vk::destroyBuffer(*context, held.back());
  held.pop_back();
  held.push_back(vk::createBuffer(*context, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::DeviceLocal));
  EXPECT_LE(context->allocator.stats().bytesReserved, options.deviceMemoryLimit);
  for (vk::Buffer& b : held) vk::destroyBuffer(*context, b);
  EXPECT_EQ(context->validationMessageCount(), 0u);
}

TEST(AllocatorLeaks, DestroyingTheContextWithALiveAllocationFails) {
  std::unique_ptr<vk::Context> context = createTestContext();
  if (!context) GTEST_SKIP() << "no Vulkan device on this machine";
  vk::Buffer leaked = vk::createBuffer(*context, 1024, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::Upload);
  vkDestroyBuffer(context->device, leaked.buffer, nullptr);  // the memory itself is never freed
  EXPECT_THROW(vk::destroyContext(*context), std::logic_error);
}

}  // namespace
}  // namespace planet::test
