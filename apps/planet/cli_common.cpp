#include "cli_common.h"

#include "core/log.h"

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

int finishWithValidation(const vk::Context& context, int exitCode) {
  if (context.validation && context.validationMessageCount() > 0) {
    logError("{} Vulkan validation message(s) were reported (see above)", context.validationMessageCount());
    return kExitFailure;
  }
  return exitCode;
}

}  // namespace planet::cli
