// The Vulkan instance, the chosen physical device, the logical device with its queues, and the
// memory allocator: everything a pass needs to create resources and submit work.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/allocator.h"

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
};

// Options from the environment: PLANET_VALIDATION=1 turns validation (and sync validation) on.
ContextOptions contextOptionsFromEnvironment();

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
  bool validation = false;

  // Validation warnings and errors seen so far (each is also printed to stderr).
  uint64_t validationMessageCount() const { return validationMessages_.load(); }
  void countValidationMessage() { ++validationMessages_; }

 private:
  std::atomic<uint64_t> validationMessages_{0};
};

// Creates instance, device, queues and allocator. Throws planet::Error with a one-line
// explanation when no usable device exists or the requested one is not found.
std::unique_ptr<Context> createContext(const ContextOptions& options);

// Frees the allocator (throws if allocations leaked), the device and the instance.
// The destructor does this too, but silently logs instead of throwing.
void destroyContext(Context& context);

// Names of every Vulkan device the loader sees (for error messages and `--device` help).
std::vector<std::string> listDeviceNames();

}  // namespace planet::vk
