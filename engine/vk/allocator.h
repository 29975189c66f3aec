#pragma once

// Our small VMA-style device-memory allocator: a few large VkDeviceMemory blocks per memory
// type, each carved up by a BlockAllocator; big or dedicated-preferring resources get their
// own VkDeviceMemory. Host-visible memory is mapped once, persistently.

#include <vulkan/vulkan.h>

#include "core/error.h"

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace planet::vk {

// Buffers and linear-tiling images are Linear, optimal-tiling images are Optimal. The two must
// not share a bufferImageGranularity page (Vulkan spec, "Buffer-Image Granularity").
enum class ResourceKind : uint8_t { Linear, Optimal };

// Sub-allocation bookkeeping over one range [0, size). Pure logic, no Vulkan calls, so it can
// be unit-tested without a GPU. Best fit over a size-ordered index of free ranges; freed ranges
// merge with free neighbours, so there are never two adjacent free ranges and
// freeRangeCount() <= allocationCount() + 1.
class BlockAllocator {
 public:
  explicit BlockAllocator(VkDeviceSize size);

  // Returns the offset of a new allocation, or nullopt when no free range can hold it.
  // alignment and granularity must be powers of two (0 is treated as 1).
  std::optional<VkDeviceSize> allocate(VkDeviceSize size, VkDeviceSize alignment, ResourceKind kind,
                                       VkDeviceSize granularity);
  // Throws std::logic_error when offset is not the start of a live allocation.
  void free(VkDeviceSize offset);

  VkDeviceSize size() const { return size_; }
  VkDeviceSize usedBytes() const { return usedBytes_; }
  uint32_t allocationCount() const { return allocationCount_; }
  uint32_t freeRangeCount() const { return uint32_t(freeBySize_.size()); }
  VkDeviceSize largestFreeRange() const;
  bool empty() const { return allocationCount_ == 0; }

 private:
  struct Range {
    VkDeviceSize size = 0;
    bool free = true;
    ResourceKind kind = ResourceKind::Linear;
  };

  void addFree(VkDeviceSize offset, VkDeviceSize size);
  void removeFree(VkDeviceSize offset, VkDeviceSize size);

  VkDeviceSize size_ = 0;
  VkDeviceSize usedBytes_ = 0;
  uint32_t allocationCount_ = 0;
  std::map<VkDeviceSize, Range> ranges_;                        // every range, by offset
  std::set<std::pair<VkDeviceSize, VkDeviceSize>> freeBySize_;  // (size, offset) of free ones
};

struct Allocation {
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // first byte of the allocation when host-visible, else null
  uint32_t memoryType = 0;
  int32_t block = -1;  // -1 = dedicated VkDeviceMemory
};

// DeviceLocal: GPU-only resources. Upload: CPU writes, GPU reads (host-visible and coherent).
// Readback: GPU writes, CPU reads (host-visible, cached if possible; call invalidate()).
enum class MemoryUsage { DeviceLocal, Upload, Readback };

const char* memoryUsageName(MemoryUsage usage);

// Thrown when no acceptable memory type has room; the message names the size and usage.
class OutOfMemoryError : public Error {
 public:
  using Error::Error;
};

struct AllocatorOptions {
  VkDeviceSize blockSize = 64ull << 20;           // size of each shared VkDeviceMemory block
  VkDeviceSize dedicatedThreshold = 32ull << 20;  // larger requests get their own memory
  // The most VkDeviceMemory (blocks plus dedicated) held at once; 0 = no limit. A request
  // beyond it is answered like VK_ERROR_OUT_OF_DEVICE_MEMORY from the driver.
  VkDeviceSize memoryLimit = 0;
};

struct AllocatorStats {
  uint32_t blocks = 0;
  uint32_t dedicatedAllocations = 0;
  uint32_t liveAllocations = 0;    // block sub-allocations plus dedicated allocations
  VkDeviceSize bytesReserved = 0;  // VkDeviceMemory held: blocks plus dedicated
  VkDeviceSize bytesUsed = 0;      // sum of live allocation sizes
};

// Thread-safe: every public member locks one mutex. Binding happens outside the lock.
class Allocator {
 public:
  Allocator() = default;
  Allocator(const Allocator&) = delete;
  Allocator& operator=(const Allocator&) = delete;
  ~Allocator();

  void init(VkPhysicalDevice physicalDevice, VkDevice device, const AllocatorOptions& options = {});
  // Frees all blocks. Throws std::logic_error if allocations are still live (after freeing
  // the memory anyway), so callers must free everything first.
  void destroy();

  // Allocate memory for the resource and bind it. Throws OutOfMemoryError when no
  // acceptable memory type has room.
  Allocation allocateForBuffer(VkBuffer buffer, MemoryUsage usage);
  Allocation allocateForImage(VkImage image, MemoryUsage usage, ResourceKind kind);
  // Resets allocation to empty; freeing an empty Allocation does nothing.
  void free(Allocation& allocation);

  // Needed only for non-coherent memory (Readback may land there); no-ops on coherent memory.
  void invalidate(const Allocation& allocation) const;
  void flush(const Allocation& allocation) const;

  AllocatorStats stats() const;
  const VkPhysicalDeviceMemoryProperties& memoryProperties() const { return memoryProperties_; }

 private:
  struct Block {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
    uint32_t memoryType = 0;
    BlockAllocator suballocator;
  };
  struct Request {
    VkMemoryRequirements requirements = {};
    bool wantsDedicated = false;
    MemoryUsage usage = MemoryUsage::DeviceLocal;
    ResourceKind kind = ResourceKind::Linear;
    VkBuffer buffer = VK_NULL_HANDLE;  // at most one of buffer/image is set, for
    VkImage image = VK_NULL_HANDLE;    // VkMemoryDedicatedAllocateInfo
  };

  template <typename Query>
  void queryRequirements(Request& request, Query query);
  Allocation allocate(const Request& request);
  std::vector<uint32_t> candidateTypes(uint32_t memoryTypeBits, MemoryUsage usage) const;
  std::optional<Allocation> allocateFromBlocks(const Request& request, uint32_t type);
  std::optional<Allocation> allocateDedicated(const Request& request, uint32_t type);
  VkDeviceMemory allocateMemory(VkDeviceSize size, uint32_t type, const Request* dedicated);
  void* mapIfHostVisible(VkDeviceMemory memory, uint32_t type);
  void releaseBlock(int32_t index);
  void syncRange(const Allocation& allocation, bool invalidateRange) const;
  void checkInitialized() const;
  VkDeviceSize reservedBytes() const;  // caller holds mutex_

  mutable std::mutex mutex_;
  VkDevice device_ = VK_NULL_HANDLE;
  AllocatorOptions options_;
  VkPhysicalDeviceMemoryProperties memoryProperties_ = {};
  VkDeviceSize bufferImageGranularity_ = 1;
  VkDeviceSize nonCoherentAtomSize_ = 1;

  std::vector<std::unique_ptr<Block>> blocks_;                  // null slots are reused; index = Allocation::block
  std::unordered_map<VkDeviceMemory, VkDeviceSize> dedicated_;  // memory -> size
  uint32_t liveCount_[VK_MAX_MEMORY_TYPES] = {};
  VkDeviceSize liveBytes_[VK_MAX_MEMORY_TYPES] = {};
};

}  // namespace planet::vk
