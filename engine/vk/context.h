// The Vulkan instance, the chosen physical device, the logical device with its queues, and the
// memory allocator: everything a pass needs to create resources and submit work.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/allocator.h"
#include "vk/pipeline_store.h"

namespace planet::vk {

struct ContextOptions {
  // Khronos validation layer plus a debug messenger that counts every warning and error.
  // Default: on when the environment sets PLANET_VALIDATION=1 (the test suite does).
  bool validation = false;
  // Also enable synchronization validation (slower; used by the tests).
  bool synchronizationValidation = false;
  // Choose the first device whose name contains this (case-insensitive); empty: PLANET_DEVICE
  // from the environment, else the best device (discrete > integrated > virtual > CPU).
  std::string deviceName;
  // Instance extensions the caller needs (e.g. surface extensions for a window).
  std::vector<const char*> instanceExtensions;
  // Device extensions the caller needs (e.g. VK_KHR_swapchain).
  std::vector<const char*> deviceExtensions;
  // The most VkDeviceMemory the allocator may hold (0: whatever the device gives). Beyond it
  // allocations fail exactly as on a device that is out of memory, so a small-memory device and
  // the out-of-memory paths can be tried on any machine.
  VkDeviceSize deviceMemoryLimit = 0;
  // Fault injection for tests: submission number N (1-based, counted over every queue
  // submission of this context) reports VK_ERROR_DEVICE_LOST instead of running. 0: never.
  uint64_t deviceLostAtSubmit = 0;
};

// Options from the environment: PLANET_VALIDATION=1 turns validation (and sync validation) on;
// PLANET_DEVICE_MEMORY_LIMIT=SIZE (bytes, or with a K, M or G suffix) sets deviceMemoryLimit;
// PLANET_FAULT=device-lost@N sets deviceLostAtSubmit. A malformed value is a planet::Error
// naming it.
ContextOptions contextOptionsFromEnvironment();

// Parses a byte count such as "268435456", "256M" or "1.5G" (K, M, G are powers of 1024).
// Throws planet::Error naming `what` and the text.
VkDeviceSize parseByteSize(const std::string& text, const std::string& what);

struct DeviceInfo {
  std::string name;    // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string driver;  // e.g. "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)"
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  VkDriverId driverId = VkDriverId(0);
  uint32_t apiVersion = 0;
  bool isCpu() const { return type == VK_PHYSICAL_DEVICE_TYPE_CPU; }
};

class Context {
 public:
  Context() = default;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  ~Context();

  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties{};
  DeviceInfo info;

  // Queue families: `universal` supports graphics and compute (always present on the devices
  // we accept); `compute` is a compute-only family when the device has one, else universal.
  uint32_t universalFamily = 0;
  uint32_t computeFamily = 0;
  VkQueue graphicsQueue = VK_NULL_HANDLE;
  VkQueue computeQueue = VK_NULL_HANDLE;
  uint32_t timestampValidBits = 0;  // of the universal family; 0 = no timestamps

  Allocator allocator;
  // Pipelines shared by the passes and Renderers made on this context (vk/pipeline_store.h).
  PipelineStore pipelines;
  bool validation = false;
  // Validation messages raised inside vkCreateInstance, held until it is known to have worked
  // (see createInstance in context.cpp); (is error, text).
  bool holdInstanceMessages = false;
  std::vector<std::pair<bool, std::string>> heldInstanceMessages;

  // Validation warnings and errors seen so far (each is also printed to stderr).
  uint64_t validationMessageCount() const { return validationMessages_.load(); }
  void countValidationMessage() { ++validationMessages_; }

  // Every queue submission goes through this first: VK_SUCCESS, or the injected
  // VK_ERROR_DEVICE_LOST when this is the submission ContextOptions::deviceLostAtSubmit names.
  VkResult beforeSubmit();

 private:
  std::atomic<uint64_t> validationMessages_{0};
  std::atomic<uint64_t> submissions_{0};
  uint64_t deviceLostAtSubmit_ = 0;
  friend std::unique_ptr<Context> createContext(const ContextOptions& options);
};

// vkQueueSubmit2 through Context::beforeSubmit; the result as the driver (or the fault) gave it.
VkResult queueSubmit(Context& context, VkQueue queue, const VkSubmitInfo2& submit, VkFence fence);

// Creates instance, device, queues and allocator. Throws planet::Error with a one-line
// explanation when no usable device exists or the requested one is not found.
std::unique_ptr<Context> createContext(const ContextOptions& options);

// Frees the allocator (throws if allocations leaked), the device and the instance.
// The destructor does this too, but silently logs instead of throwing.
void destroyContext(Context& context);

// Names of every Vulkan device the loader sees (for error messages and `--device` help).
std::vector<std::string> listDeviceNames();

}  // namespace planet::vk
