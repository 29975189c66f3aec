#include "vk/allocator.h"

#include <algorithm>
#include <cstdio>
#include <iterator>

#include "core/error.h"

namespace planet::vk {

namespace {

// Every failing Vulkan call goes through here: a planet::VulkanError naming the call and result.
void check(VkResult result, const char* call) {
  if (result != VK_SUCCESS) throwVulkanError(result, call, __FILE__, __LINE__);
}

bool isPowerOfTwo(VkDeviceSize value) { return value != 0 && (value & (value - 1)) == 0; }

// alignment must be a power of two.
VkDeviceSize alignUp(VkDeviceSize value, VkDeviceSize alignment) { return (value + alignment - 1) & ~(alignment - 1); }

VkDeviceSize alignDown(VkDeviceSize value, VkDeviceSize alignment) { return value & ~(alignment - 1); }

bool samePage(VkDeviceSize a, VkDeviceSize b, VkDeviceSize granularity) {
  return alignDown(a, granularity) == alignDown(b, granularity);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// BlockAllocator

BlockAllocator::BlockAllocator(VkDeviceSize size) : size_(size) {
  if (size == 0) throw std::invalid_argument("BlockAllocator: size must be non-zero");
  addFree(0, size);
}

void BlockAllocator::addFree(VkDeviceSize offset, VkDeviceSize size) {
  ranges_[offset] = Range{size, true, ResourceKind::Linear};
  freeBySize_.insert({size, offset});
}

void BlockAllocator::removeFree(VkDeviceSize offset, VkDeviceSize size) {
  freeBySize_.erase({size, offset});
  ranges_.erase(offset);
}

std::optional<VkDeviceSize> BlockAllocator::allocate(VkDeviceSize size, VkDeviceSize alignment, ResourceKind kind,
                                                     VkDeviceSize granularity) {
  if (size == 0) throw std::invalid_argument("BlockAllocator::allocate: size must be non-zero");
  alignment = std::max<VkDeviceSize>(alignment, 1);
  granularity = std::max<VkDeviceSize>(granularity, 1);
  if (!isPowerOfTwo(alignment) || !isPowerOfTwo(granularity))
    throw std::invalid_argument(
        "BlockAllocator::allocate: alignment and granularity must be "
        "powers of two");

  // Free ranges are visited smallest first, so the first one that fits is the best fit.
  // Free ranges never touch each other, so their neighbours are always live allocations,
  // and checking only the immediate neighbours keeps Linear and Optimal pages apart.
  for (auto it = freeBySize_.lower_bound({size, 0}); it != freeBySize_.end(); ++it) {
    const auto [rangeSize, rangeOffset] = *it;
    const VkDeviceSize rangeEnd = rangeOffset + rangeSize;
    const auto range = ranges_.find(rangeOffset);

    VkDeviceSize offset = alignUp(rangeOffset, alignment);
    if (granularity > 1 && range != ranges_.begin()) {
      const auto prev = std::prev(range);
      const VkDeviceSize prevLast = prev->first + prev->second.size - 1;
      // Both are powers of two, so the page boundary is also aligned.
      if (prev->second.kind != kind && samePage(prevLast, offset, granularity)) offset = alignUp(offset, granularity);
    }
    if (offset > rangeEnd || size > rangeEnd - offset) continue;
    const VkDeviceSize end = offset + size;
    if (granularity > 1) {
      const auto next = std::next(range);
      if (next != ranges_.end() && next->second.kind != kind && samePage(end - 1, next->first, granularity)) continue;
    }

    removeFree(rangeOffset, rangeSize);  // invalidates it; we return below
    if (offset > rangeOffset) addFree(rangeOffset, offset - rangeOffset);
    if (end < rangeEnd) addFree(end, rangeEnd - end);
    ranges_[offset] = Range{size, false, kind};
    usedBytes_ += size;
    ++allocationCount_;
    return offset;
  }
  return std::nullopt;
}

void BlockAllocator::free(VkDeviceSize offset) {
  const auto it = ranges_.find(offset);
  if (it == ranges_.end() || it->second.free)
    throw std::logic_error("BlockAllocator::free: no allocation at offset " + std::to_string(offset));
  usedBytes_ -= it->second.size;
  --allocationCount_;

  VkDeviceSize start = offset;
  VkDeviceSize length = it->second.size;
  const auto next = std::next(it);
  if (next != ranges_.end() && next->second.free) {
    length += next->second.size;
    removeFree(next->first, next->second.size);
  }
  if (it != ranges_.begin()) {
    const auto prev = std::prev(it);
    if (prev->second.free) {
      start = prev->first;
      length += prev->second.size;
      removeFree(prev->first, prev->second.size);
    }
  }
  ranges_.erase(offset);
  addFree(start, length);
}

VkDeviceSize BlockAllocator::largestFreeRange() const { return freeBySize_.empty() ? 0 : freeBySize_.rbegin()->first; }

// ---------------------------------------------------------------------------------------------
// Allocator

const char* memoryUsageName(MemoryUsage usage) {
  switch (usage) {
    case MemoryUsage::DeviceLocal: return "DeviceLocal";
    case MemoryUsage::Upload: return "Upload";
    case MemoryUsage::Readback: return "Readback";
  }
  return "Unknown";
}

Allocator::~Allocator() {
  // No throwing or freeing here: the device may already be gone. Teardown is explicit.
  if (device_ != VK_NULL_HANDLE) std::fprintf(stderr, "planet::vk::Allocator: destructed without destroy()\n");
}

void Allocator::init(VkPhysicalDevice physicalDevice, VkDevice device, const AllocatorOptions& options) {
  std::lock_guard lock(mutex_);
  if (device_ != VK_NULL_HANDLE) throw std::logic_error("Allocator::init: already initialized");
  if (physicalDevice == VK_NULL_HANDLE || device == VK_NULL_HANDLE)
    throw std::invalid_argument("Allocator::init: null device");
  if (options.blockSize == 0) throw std::invalid_argument("Allocator::init: blockSize must be non-zero");

  VkPhysicalDeviceProperties properties = {};
  vkGetPhysicalDeviceProperties(physicalDevice, &properties);
  vkGetPhysicalDeviceMemoryProperties(physicalDevice, &memoryProperties_);
  bufferImageGranularity_ = std::max<VkDeviceSize>(properties.limits.bufferImageGranularity, 1);
  nonCoherentAtomSize_ = std::max<VkDeviceSize>(properties.limits.nonCoherentAtomSize, 1);
  options_ = options;
  device_ = device;
}

void Allocator::destroy() {
  std::lock_guard lock(mutex_);
  if (device_ == VK_NULL_HANDLE) return;

  uint32_t leaked = 0;
  for (uint32_t type = 0; type < VK_MAX_MEMORY_TYPES; ++type) {
    if (liveCount_[type] == 0) continue;
    std::fprintf(stderr,
                 "planet::vk::Allocator: %u live allocations (%llu bytes) leaked in memory "
                 "type %u\n",
                 liveCount_[type], static_cast<unsigned long long>(liveBytes_[type]), type);
    leaked += liveCount_[type];
  }

  // Release everything even when leaking, so the device itself can still be torn down.
  for (auto& block : blocks_)
    if (block) vkFreeMemory(device_, block->memory, nullptr);
  for (const auto& [memory, size] : dedicated_) vkFreeMemory(device_, memory, nullptr);
  blocks_.clear();
  dedicated_.clear();
  std::fill(std::begin(liveCount_), std::end(liveCount_), 0u);
  std::fill(std::begin(liveBytes_), std::end(liveBytes_), VkDeviceSize(0));
  device_ = VK_NULL_HANDLE;

  if (leaked != 0) throw std::logic_error("allocator destroyed with " + std::to_string(leaked) + " live allocations");
}

void Allocator::checkInitialized() const {
  if (device_ == VK_NULL_HANDLE) throw std::logic_error("Allocator used before init() or after destroy()");
}

// Runs a vkGet*MemoryRequirements2 query (under the lock) that also asks whether the
// resource wants a dedicated allocation, and records both in `request`.
template <typename Query>
void Allocator::queryRequirements(Request& request, Query query) {
  VkMemoryDedicatedRequirements dedicated = {};
  dedicated.sType = VK_STRUCTURE_TYPE_MEMORY_DEDICATED_REQUIREMENTS;
  VkMemoryRequirements2 requirements = {};
  requirements.sType = VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2;
  requirements.pNext = &dedicated;
  {
    std::lock_guard lock(mutex_);
    checkInitialized();
    query(requirements);
  }
  request.requirements = requirements.memoryRequirements;
  request.wantsDedicated = dedicated.prefersDedicatedAllocation || dedicated.requiresDedicatedAllocation;
}

Allocation Allocator::allocateForBuffer(VkBuffer buffer, MemoryUsage usage) {
  Request request;
  request.usage = usage;
  request.kind = ResourceKind::Linear;
  request.buffer = buffer;
  queryRequirements(request, [&](VkMemoryRequirements2& requirements) {
    VkBufferMemoryRequirementsInfo2 info = {};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_REQUIREMENTS_INFO_2;
    info.buffer = buffer;
    vkGetBufferMemoryRequirements2(device_, &info, &requirements);
  });

  Allocation allocation = allocate(request);
  // Binding touches only the buffer (externally synchronized by the caller), not our state.
  const VkResult result = vkBindBufferMemory(device_, buffer, allocation.memory, allocation.offset);
  if (result != VK_SUCCESS) free(allocation);
  check(result, "vkBindBufferMemory");
  return allocation;
}

Allocation Allocator::allocateForImage(VkImage image, MemoryUsage usage, ResourceKind kind) {
  Request request;
  request.usage = usage;
  request.kind = kind;
  request.image = image;
  queryRequirements(request, [&](VkMemoryRequirements2& requirements) {
    VkImageMemoryRequirementsInfo2 info = {};
    info.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_REQUIREMENTS_INFO_2;
    info.image = image;
    vkGetImageMemoryRequirements2(device_, &info, &requirements);
  });

  Allocation allocation = allocate(request);
  const VkResult result = vkBindImageMemory(device_, image, allocation.memory, allocation.offset);
  if (result != VK_SUCCESS) free(allocation);
  check(result, "vkBindImageMemory");
  return allocation;
}

std::vector<uint32_t> Allocator::candidateTypes(uint32_t memoryTypeBits, MemoryUsage usage) const {
  // Types we never hand out: protected and lazily allocated memory need special resources,
  // and the AMD coherence flags are only valid with a device feature we do not enable.
  constexpr VkMemoryPropertyFlags kExcluded =
      VK_MEMORY_PROPERTY_PROTECTED_BIT | VK_MEMORY_PROPERTY_LAZILY_ALLOCATED_BIT |
      VK_MEMORY_PROPERTY_DEVICE_COHERENT_BIT_AMD | VK_MEMORY_PROPERTY_DEVICE_UNCACHED_BIT_AMD;

  VkMemoryPropertyFlags required = 0;
  if (usage == MemoryUsage::Upload)
    required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  if (usage == MemoryUsage::Readback) required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;

  std::vector<std::pair<int, uint32_t>> scored;  // (score, type)
  for (uint32_t type = 0; type < memoryProperties_.memoryTypeCount; ++type) {
    const VkMemoryPropertyFlags flags = memoryProperties_.memoryTypes[type].propertyFlags;
    if (!(memoryTypeBits & (1u << type)) || (flags & required) != required || (flags & kExcluded)) continue;
    const bool deviceLocal = flags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    const bool hostVisible = flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
    const bool cached = flags & VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
    const bool coherent = flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    int score = 0;
    switch (usage) {
      case MemoryUsage::DeviceLocal:
        // Leave host-visible device memory (often a small BAR heap) to uploads.
        score = (deviceLocal ? 4 : 0) + (hostVisible ? 0 : 1);
        break;
      case MemoryUsage::Upload:
        // CPU writes sequentially, so write-combined (uncached) memory is fastest.
        score = cached ? 0 : 1;
        break;
      case MemoryUsage::Readback:
        // CPU reads from uncached memory are very slow; coherent saves invalidate calls.
        score = (cached ? 4 : 0) + (coherent ? 1 : 0);
        break;
    }
    scored.push_back({score, type});
  }
  // Equal scores keep the driver's order, which the spec sorts roughly by preference.
  std::stable_sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<uint32_t> types;
  for (const auto& entry : scored) types.push_back(entry.second);
  return types;
}

Allocation Allocator::allocate(const Request& request) {
  std::lock_guard lock(mutex_);
  checkInitialized();
  const VkDeviceSize size = request.requirements.size;
  const std::vector<uint32_t> types = candidateTypes(request.requirements.memoryTypeBits, request.usage);
  if (types.empty())
    throw std::runtime_error(std::string("no memory type supports ") + memoryUsageName(request.usage) +
                             " for memoryTypeBits " + std::to_string(request.requirements.memoryTypeBits));

  const bool dedicated = request.wantsDedicated || size > std::min(options_.dedicatedThreshold, options_.blockSize);
  for (const uint32_t type : types) {
    std::optional<Allocation> allocation;
    if (!dedicated) allocation = allocateFromBlocks(request, type);
    // A fresh block may not fit in the heap while the exact size still does.
    if (!allocation) allocation = allocateDedicated(request, type);
    if (allocation) {
      ++liveCount_[type];
      liveBytes_[type] += size;
      return *allocation;
    }
  }
  const auto mib = [](VkDeviceSize bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1 << 20));
    return std::string(text);
  };
  std::string message = "out of device memory: cannot allocate " + std::to_string(size) + " bytes (" +
                        memoryUsageName(request.usage) + ") with " + mib(reservedBytes()) + " already held";
  if (options_.memoryLimit != 0) message += " of the " + mib(options_.memoryLimit) + " limit";
  throw OutOfMemoryError(message);
}

std::optional<Allocation> Allocator::allocateFromBlocks(const Request& request, uint32_t type) {
  const VkMemoryPropertyFlags flags = memoryProperties_.memoryTypes[type].propertyFlags;
  VkDeviceSize alignment = request.requirements.alignment;
  // On non-coherent memory, give each allocation whole atoms, so that flushing or
  // invalidating one allocation never touches a neighbour's bytes.
  if ((flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) && !(flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT))
    alignment = std::max(alignment, nonCoherentAtomSize_);

  auto tryBlock = [&](int32_t index) -> std::optional<Allocation> {
    Block& block = *blocks_[index];
    const std::optional<VkDeviceSize> offset =
        block.suballocator.allocate(request.requirements.size, alignment, request.kind, bufferImageGranularity_);
    if (!offset) return std::nullopt;
    Allocation allocation;
    allocation.memory = block.memory;
    allocation.offset = *offset;
    allocation.size = request.requirements.size;
    allocation.mapped = block.mapped ? static_cast<char*>(block.mapped) + *offset : nullptr;
    allocation.memoryType = type;
    allocation.block = index;
    return allocation;
  };

  for (size_t i = 0; i < blocks_.size(); ++i)
    if (blocks_[i] && blocks_[i]->memoryType == type)
      if (auto allocation = tryBlock(int32_t(i))) return allocation;

  const VkDeviceMemory memory = allocateMemory(options_.blockSize, type, nullptr);
  if (memory == VK_NULL_HANDLE) return std::nullopt;
  auto block = std::make_unique<Block>(Block{memory, nullptr, type, BlockAllocator(options_.blockSize)});
  block->mapped = mapIfHostVisible(memory, type);

  auto slot = std::find(blocks_.begin(), blocks_.end(), nullptr);
  if (slot == blocks_.end()) slot = blocks_.insert(blocks_.end(), nullptr);
  *slot = std::move(block);
  // Cannot fail: size <= blockSize, and offset 0 satisfies any alignment.
  return tryBlock(int32_t(slot - blocks_.begin()));
}

std::optional<Allocation> Allocator::allocateDedicated(const Request& request, uint32_t type) {
  const VkDeviceMemory memory = allocateMemory(request.requirements.size, type, &request);
  if (memory == VK_NULL_HANDLE) return std::nullopt;
  Allocation allocation;
  allocation.memory = memory;
  allocation.size = request.requirements.size;
  allocation.mapped = mapIfHostVisible(memory, type);
  allocation.memoryType = type;
  allocation.block = -1;
  dedicated_[memory] = request.requirements.size;
  return allocation;
}

VkDeviceMemory Allocator::allocateMemory(VkDeviceSize size, uint32_t type, const Request* dedicated) {
  // Asking for more than the whole heap is invalid usage (VUID-vkAllocateMemory-pAllocateInfo-01713),
  // not an out-of-memory result, so answer it here the way the driver would.
  const uint32_t heap = memoryProperties_.memoryTypes[type].heapIndex;
  if (size > memoryProperties_.memoryHeaps[heap].size) return VK_NULL_HANDLE;
  if (options_.memoryLimit != 0 && reservedBytes() + size > options_.memoryLimit) return VK_NULL_HANDLE;

  VkMemoryAllocateInfo info = {};
  info.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  info.allocationSize = size;
  info.memoryTypeIndex = type;
  VkMemoryDedicatedAllocateInfo dedicatedInfo = {};
  dedicatedInfo.sType = VK_STRUCTURE_TYPE_MEMORY_DEDICATED_ALLOCATE_INFO;
  if (dedicated && (dedicated->buffer != VK_NULL_HANDLE || dedicated->image != VK_NULL_HANDLE)) {
    dedicatedInfo.buffer = dedicated->buffer;
    dedicatedInfo.image = dedicated->image;
    info.pNext = &dedicatedInfo;
  }

  VkDeviceMemory memory = VK_NULL_HANDLE;
  const VkResult result = vkAllocateMemory(device_, &info, nullptr, &memory);
  // Out of memory in this heap is not fatal: the caller tries the next acceptable type.
  if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY) return VK_NULL_HANDLE;
  check(result, "vkAllocateMemory");
  return memory;
}

void* Allocator::mapIfHostVisible(VkDeviceMemory memory, uint32_t type) {
  if (!(memoryProperties_.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)) return nullptr;
  void* mapped = nullptr;
  const VkResult result = vkMapMemory(device_, memory, 0, VK_WHOLE_SIZE, 0, &mapped);
  if (result != VK_SUCCESS) vkFreeMemory(device_, memory, nullptr);
  check(result, "vkMapMemory");
  return mapped;
}

void Allocator::releaseBlock(int32_t index) {
  vkFreeMemory(device_, blocks_[index]->memory, nullptr);  // implicitly unmaps
  blocks_[index].reset();
}

void Allocator::free(Allocation& allocation) {
  if (allocation.memory == VK_NULL_HANDLE) return;
  std::lock_guard lock(mutex_);
  checkInitialized();
  if (allocation.memoryType >= memoryProperties_.memoryTypeCount)
    throw std::logic_error("Allocator::free: invalid memory type");

  if (allocation.block < 0) {
    const auto it = dedicated_.find(allocation.memory);
    if (it == dedicated_.end()) throw std::logic_error("Allocator::free: unknown dedicated allocation");
    vkFreeMemory(device_, allocation.memory, nullptr);
    dedicated_.erase(it);
  } else {
    const size_t index = size_t(allocation.block);
    if (index >= blocks_.size() || !blocks_[index] || blocks_[index]->memory != allocation.memory)
      throw std::logic_error("Allocator::free: allocation does not belong to this allocator");
    Block& block = *blocks_[index];
    block.suballocator.free(allocation.offset);
    if (block.suballocator.empty()) {
      // Keep the last block of each type, so alloc/free cycles do not churn vkAllocateMemory.
      const bool hasOther = std::any_of(blocks_.begin(), blocks_.end(), [&](const auto& b) {
        return b && b.get() != &block && b->memoryType == block.memoryType;
      });
      if (hasOther) releaseBlock(allocation.block);
    }
  }
  --liveCount_[allocation.memoryType];
  liveBytes_[allocation.memoryType] -= allocation.size;
  allocation = Allocation{};
}

void Allocator::syncRange(const Allocation& allocation, bool invalidateRange) const {
  if (allocation.memory == VK_NULL_HANDLE) return;
  checkInitialized();
  const VkMemoryPropertyFlags flags = memoryProperties_.memoryTypes[allocation.memoryType].propertyFlags;
  if (!(flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) || (flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)) return;

  VkMappedMemoryRange range = {};
  range.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE;
  range.memory = allocation.memory;
  if (allocation.block < 0) {
    range.offset = 0;
    range.size = VK_WHOLE_SIZE;
  } else {
    // The spec wants atom-multiple ranges, or ones that end at the end of the memory.
    range.offset = alignDown(allocation.offset, nonCoherentAtomSize_);
    const VkDeviceSize end =
        std::min(alignUp(allocation.offset + allocation.size, nonCoherentAtomSize_), options_.blockSize);
    range.size = end - range.offset;
  }
  if (invalidateRange)
    check(vkInvalidateMappedMemoryRanges(device_, 1, &range), "vkInvalidateMappedMemoryRanges");
  else
    check(vkFlushMappedMemoryRanges(device_, 1, &range), "vkFlushMappedMemoryRanges");
}

void Allocator::invalidate(const Allocation& allocation) const { syncRange(allocation, true); }

void Allocator::flush(const Allocation& allocation) const { syncRange(allocation, false); }

VkDeviceSize Allocator::reservedBytes() const {
  VkDeviceSize bytes = 0;
  for (const auto& block : blocks_)
    if (block) bytes += block->suballocator.size();
  for (const auto& [memory, size] : dedicated_) bytes += size;
  return bytes;
}

AllocatorStats Allocator::stats() const {
  std::lock_guard lock(mutex_);
  AllocatorStats stats;
  for (const auto& block : blocks_)
    if (block) ++stats.blocks;
  stats.bytesReserved = reservedBytes();
  stats.dedicatedAllocations = uint32_t(dedicated_.size());
  for (uint32_t type = 0; type < VK_MAX_MEMORY_TYPES; ++type) {
    stats.liveAllocations += liveCount_[type];
    stats.bytesUsed += liveBytes_[type];
  }
  return stats;
}

}  // namespace planet::vk
