#include "core/error.h"

namespace planet {

std::string printable(std::string_view text) {
  std::string out(text);
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return out;
}

std::string quotedPath(std::string_view path) {
  std::string out;
  out.reserve(path.size() + 2);
  out += '\'';
  out += printable(path);
  out += '\'';
  return out;
}

const char* vkResultName(VkResult result) {
  switch (result) {
#define PLANET_RESULT_NAME(r) \
  case r: return #r;
    PLANET_RESULT_NAME(VK_SUCCESS)
    PLANET_RESULT_NAME(VK_NOT_READY)
    PLANET_RESULT_NAME(VK_TIMEOUT)
    PLANET_RESULT_NAME(VK_EVENT_SET)
    PLANET_RESULT_NAME(VK_EVENT_RESET)
    PLANET_RESULT_NAME(VK_INCOMPLETE)
    PLANET_RESULT_NAME(VK_ERROR_OUT_OF_HOST_MEMORY)
    PLANET_RESULT_NAME(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    PLANET_RESULT_NAME(VK_ERROR_INITIALIZATION_FAILED)
    PLANET_RESULT_NAME(VK_ERROR_DEVICE_LOST)
    PLANET_RESULT_NAME(VK_ERROR_MEMORY_MAP_FAILED)
    PLANET_RESULT_NAME(VK_ERROR_LAYER_NOT_PRESENT)
    PLANET_RESULT_NAME(VK_ERROR_EXTENSION_NOT_PRESENT)
    PLANET_RESULT_NAME(VK_ERROR_FEATURE_NOT_PRESENT)
    PLANET_RESULT_NAME(VK_ERROR_INCOMPATIBLE_DRIVER)
    PLANET_RESULT_NAME(VK_ERROR_TOO_MANY_OBJECTS)
    PLANET_RESULT_NAME(VK_ERROR_FORMAT_NOT_SUPPORTED)
    PLANET_RESULT_NAME(VK_ERROR_FRAGMENTED_POOL)
    PLANET_RESULT_NAME(VK_ERROR_UNKNOWN)
    PLANET_RESULT_NAME(VK_ERROR_OUT_OF_POOL_MEMORY)
    PLANET_RESULT_NAME(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    PLANET_RESULT_NAME(VK_ERROR_FRAGMENTATION)
    PLANET_RESULT_NAME(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
    PLANET_RESULT_NAME(VK_PIPELINE_COMPILE_REQUIRED)
    PLANET_RESULT_NAME(VK_ERROR_SURFACE_LOST_KHR)
    PLANET_RESULT_NAME(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
    PLANET_RESULT_NAME(VK_SUBOPTIMAL_KHR)
    PLANET_RESULT_NAME(VK_ERROR_OUT_OF_DATE_KHR)
    PLANET_RESULT_NAME(VK_ERROR_INCOMPATIBLE_DISPLAY_KHR)
    PLANET_RESULT_NAME(VK_ERROR_VALIDATION_FAILED_EXT)
#undef PLANET_RESULT_NAME
    default: return "VK_RESULT_UNKNOWN";
  }
}

void throwVulkanError(VkResult result, const char* call, const char* file, int line) {
  throw VulkanError(result, std::string(file) + ":" + std::to_string(line) + ": " + call + " failed: " +
                                vkResultName(result) + " (" + std::to_string(static_cast<int>(result)) + ")");
}

}  // namespace planet
