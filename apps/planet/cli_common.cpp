#include "cli_common.h"

#include <charconv>

#include "core/log.h"
#include "render/renderer.h"

namespace planet::cli {

std::unique_ptr<vk::Context> openContext(const GlobalOptions& options) {
  vk::ContextOptions contextOptions = vk::contextOptionsFromEnvironment();
  if (options.validation) {
    contextOptions.validation = true;
    contextOptions.synchronizationValidation = true;
  }
  contextOptions.deviceName = options.device;
  return vk::createContext(contextOptions);
}

void parseSize(const std::string& text, uint32_t& width, uint32_t& height) {
  const size_t x = text.find('x');
  auto number = [&](std::string_view part, uint32_t& value) {
    auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
    return !part.empty() && ec == std::errc() && ptr == part.data() + part.size();
  };
  if (x == std::string::npos || !number(std::string_view(text).substr(0, x), width) ||
      !number(std::string_view(text).substr(x + 1), height))
    throw UsageError("--size expects WIDTHxHEIGHT in pixels, got '" + text + "'");
  if (width == 0 || height == 0 || width > kRenderMaxSize || height > kRenderMaxSize)
    throw UsageError(fmt::format("--size {} is outside 1x1 .. {}x{}", text, kRenderMaxSize, kRenderMaxSize));
}

void checkFieldOfView(double degrees) {
  if (!(degrees > 0.0 && degrees <= kRenderMaxFovDeg))
    throw UsageError(fmt::format("--fov must be in (0, {}] degrees, got {}", kRenderMaxFovDeg, degrees));
}

int finishWithValidation(const vk::Context& context, int exitCode) {
  if (context.validation && context.validationMessageCount() > 0) {
    logError("{} Vulkan validation message(s) were reported (see above)", context.validationMessageCount());
    return kExitFailure;
  }
  return exitCode;
}

}  // namespace planet::cli
