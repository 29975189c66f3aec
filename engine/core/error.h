// Errors: one exception type for everything a user can cause or a device can report, and
// VK_CHECK, which is on in every build type (a release build must not silently continue).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include <vulkan/vulkan.h>

namespace planet {

// A failure worth one clear line to the user (bad input, missing device, failed Vulkan call).
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// User text (a path, a name) as it may appear inside a one-line message: every control byte
// (a newline, a tab, an escape) becomes '?', so a message stays one line and cannot move the
// terminal's cursor whatever the user passed.
std::string printable(std::string_view text);

// "'path'" with printable() applied: how messages name a file.
std::string quotedPath(std::string_view path);

// A Vulkan call returned an error code; result() lets callers react to specific codes
// (VK_ERROR_DEVICE_LOST, VK_ERROR_OUT_OF_DEVICE_MEMORY, ...).
class VulkanError : public Error {
 public:
  VulkanError(VkResult result, const std::string& message) : Error(message), result_(result) {}
  VkResult result() const { return result_; }

 private:
  VkResult result_;
};

// The enumerator's name, e.g. "VK_ERROR_DEVICE_LOST".
const char* vkResultName(VkResult result);

[[noreturn]] void throwVulkanError(VkResult result, const char* call, const char* file, int line);

}  // namespace planet

// Throws planet::VulkanError naming the call, file, line and result if `call` does not return
// VK_SUCCESS. Use for calls whose only good outcome is VK_SUCCESS.
#define VK_CHECK(call)                                                                                       \
  do {                                                                                                       \
    VkResult vkCheckResult_ = (call);                                                                        \
    if (vkCheckResult_ != VK_SUCCESS) ::planet::throwVulkanError(vkCheckResult_, #call, __FILE__, __LINE__); \
  } while (0)
