#include "vk/context.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <exception>

#include "core/error.h"
#include "core/log.h"

namespace planet::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* context = static_cast<Context*>(user);
  const char* kind = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
  logError("vulkan validation {}: {}", kind, data->pMessage ? data->pMessage : "(no message)");
  if (context) context->countValidationMessage();
  return VK_FALSE;  // never abort the call: the test that caused it fails on the count
}

// Messages while vkCreateInstance runs are held back: when it fails (no driver), the one-line
// error says what the user needs and the loader's lines would only repeat it; when it succeeds,
// they are reported and counted like every other message.
VKAPI_ATTR VkBool32 VKAPI_CALL holdCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                            VkDebugUtilsMessageTypeFlagsEXT type,
                                            const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* context = static_cast<Context*>(user);
  if (!context->holdInstanceMessages) return debugCallback(severity, type, data, user);
  context->heldInstanceMessages.emplace_back((severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0,
                                             data->pMessage ? data->pMessage : "(no message)");
  return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messengerInfo(Context* context) {
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = debugCallback;
  info.pUserData = context;
  return info;
}

bool hasInstanceLayer(const char* name) {
  uint32_t count = 0;
  VK_CHECK(vkEnumerateInstanceLayerProperties(&count, nullptr));
  std::vector<VkLayerProperties> layers(count);
  VK_CHECK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
  return std::any_of(layers.begin(), layers.end(),
                     [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

std::string lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

int typeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
  }
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
  uint32_t count = 0;
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  return devices;
}

std::vector<VkQueueFamilyProperties> queueFamilies(VkPhysicalDevice device) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  return families;
}

// The first family with graphics and compute, or -1.
int universalFamilyOf(VkPhysicalDevice device) {
  auto families = queueFamilies(device);
  for (uint32_t i = 0; i < families.size(); ++i) {
    VkQueueFlags flags = families[i].queueFlags;
    if ((flags & VK_QUEUE_GRAPHICS_BIT) && (flags & VK_QUEUE_COMPUTE_BIT)) return int(i);
  }
  return -1;
}

VkInstance createInstance(Context& context, const ContextOptions& options) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "planet";
  app.pEngineName = "planet";
  app.apiVersion = VK_API_VERSION_1_3;

  std::vector<const char*> layers;
  std::vector<const char*> extensions = options.instanceExtensions;
  if (options.validation) {
    if (!hasInstanceLayer(kValidationLayer))
      throw Error(
          "validation was requested but VK_LAYER_KHRONOS_validation is not installed "
          "(apt-get install vulkan-validationlayers)");
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (options.synchronizationValidation) extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  }

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  info.enabledLayerCount = uint32_t(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();

  // Chained so that messages from vkCreateInstance/vkDestroyInstance are caught too.
  // (It also serves vkDestroyInstance, so its user data must outlive this function: the context.)
  VkDebugUtilsMessengerCreateInfoEXT messenger = messengerInfo(&context);
  messenger.pfnUserCallback = holdCallback;
  context.holdInstanceMessages = true;
  VkValidationFeatureEnableEXT syncValidation = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = &syncValidation;
  if (options.validation) {
    info.pNext = &messenger;
    if (options.synchronizationValidation) messenger.pNext = &features;
  }

  VkInstance instance = VK_NULL_HANDLE;
  VkResult result = vkCreateInstance(&info, nullptr, &instance);
  context.holdInstanceMessages = false;
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER)
    throw Error("no Vulkan 1.3 driver found (install mesa-vulkan-drivers for the CPU driver lavapipe)");
  VK_CHECK(result);
  for (const auto& [isError, message] : context.heldInstanceMessages) {
    logError("vulkan validation {}: {}", isError ? "error" : "warning", message);
    context.countValidationMessage();
  }
  context.heldInstanceMessages.clear();
  return instance;
}

VkPhysicalDevice chooseDevice(VkInstance instance, const std::string& wanted) {
  std::vector<VkPhysicalDevice> devices = physicalDevices(instance);
  VkPhysicalDevice best = VK_NULL_HANDLE;
  int bestRank = -1;
  std::string available;
  for (VkPhysicalDevice device : devices) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(device, &props);
    available += (available.empty() ? "" : ", ") + std::string(props.deviceName);
    bool usable = props.apiVersion >= VK_API_VERSION_1_3 && universalFamilyOf(device) >= 0;
    if (!wanted.empty()) {
      if (lowercase(props.deviceName).find(lowercase(wanted)) == std::string::npos) continue;
      if (!usable)
        throw Error("device '" + std::string(props.deviceName) + "' lacks Vulkan 1.3 or a graphics+compute queue");
      return device;
    }
    if (usable && typeRank(props.deviceType) > bestRank) {
      best = device;
      bestRank = typeRank(props.deviceType);
    }
  }
  if (devices.empty()) throw Error("no Vulkan device found (install mesa-vulkan-drivers for the CPU driver lavapipe)");
  if (!wanted.empty()) throw Error("no Vulkan device matches '" + wanted + "' (available: " + available + ")");
  if (!best)
    throw Error("no Vulkan device supports Vulkan 1.3 with a graphics+compute queue (found: " + available + ")");
  return best;
}

void describeDevice(Context& context) {
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props2.pNext = &driver;
  vkGetPhysicalDeviceProperties2(context.physicalDevice, &props2);
  context.properties = props2.properties;
  context.info.name = context.properties.deviceName;
  context.info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
  context.info.type = context.properties.deviceType;
  context.info.driverId = driver.driverID;
  context.info.apiVersion = context.properties.apiVersion;
}

void createDevice(Context& context, const ContextOptions& options) {
  auto families = queueFamilies(context.physicalDevice);
  context.universalFamily = uint32_t(universalFamilyOf(context.physicalDevice));
  context.computeFamily = context.universalFamily;
  for (uint32_t i = 0; i < families.size(); ++i) {
    VkQueueFlags flags = families[i].queueFlags;
    if ((flags & VK_QUEUE_COMPUTE_BIT) && !(flags & VK_QUEUE_GRAPHICS_BIT)) {
      context.computeFamily = i;
      break;
    }
  }
  context.timestampValidBits = families[context.universalFamily].timestampValidBits;

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queues[2] = {};
  for (VkDeviceQueueCreateInfo& q : queues) {
    q.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    q.queueCount = 1;
    q.pQueuePriorities = &priority;
  }
  queues[0].queueFamilyIndex = context.universalFamily;
  queues[1].queueFamilyIndex = context.computeFamily;
  uint32_t queueCount = context.computeFamily == context.universalFamily ? 1 : 2;

  // Enable the Vulkan 1.2/1.3 features the engine relies on, where supported.
  VkPhysicalDeviceVulkan13Features supported13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features supported12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  supported12.pNext = &supported13;
  VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  supported.pNext = &supported12;
  vkGetPhysicalDeviceFeatures2(context.physicalDevice, &supported);
  if (!supported13.synchronization2 || !supported13.dynamicRendering)
    throw Error("device '" + context.info.name + "' lacks synchronization2 or dynamicRendering");
  // The sky passes index an array of uniform buffers (shaders/sky_uniforms.glsl says why).
  if (!supported.features.shaderUniformBufferArrayDynamicIndexing)
    throw Error("device '" + context.info.name + "' lacks shaderUniformBufferArrayDynamicIndexing");

  VkPhysicalDeviceVulkan13Features enable13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  enable13.synchronization2 = VK_TRUE;
  enable13.dynamicRendering = VK_TRUE;
  enable13.maintenance4 = supported13.maintenance4;
  VkPhysicalDeviceVulkan12Features enable12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  enable12.pNext = &enable13;
  enable12.hostQueryReset = supported12.hostQueryReset;
  enable12.timelineSemaphore = supported12.timelineSemaphore;
  enable12.scalarBlockLayout = supported12.scalarBlockLayout;
  VkPhysicalDeviceFeatures2 enable{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  enable.pNext = &enable12;
  enable.features.fillModeNonSolid = supported.features.fillModeNonSolid;  // wireframe debug view
  enable.features.shaderFloat64 = supported.features.shaderFloat64;
  enable.features.samplerAnisotropy = supported.features.samplerAnisotropy;
  enable.features.shaderUniformBufferArrayDynamicIndexing = VK_TRUE;
  enable.features.largePoints = supported.features.largePoints;  // star sprites wider than 1 px (render/star_pass.h)

  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.pNext = &enable;
  info.queueCreateInfoCount = queueCount;
  info.pQueueCreateInfos = queues;
  info.enabledExtensionCount = uint32_t(options.deviceExtensions.size());
  info.ppEnabledExtensionNames = options.deviceExtensions.data();
  VK_CHECK(vkCreateDevice(context.physicalDevice, &info, nullptr, &context.device));
  vkGetDeviceQueue(context.device, context.universalFamily, 0, &context.graphicsQueue);
  vkGetDeviceQueue(context.device, context.computeFamily, 0, &context.computeQueue);
}

}  // namespace

VkDeviceSize parseByteSize(const std::string& text, const std::string& what) {
  const auto bad = [&] {
    return Error(what + " expects a size in bytes with an optional K, M or G suffix, got '" + text + "'");
  };
  if (text.empty() || !(std::isdigit(static_cast<unsigned char>(text[0])) || text[0] == '.')) throw bad();
  size_t end = 0;
  double value = 0;
  try {
    value = std::stod(text, &end);
  } catch (const std::exception&) {
    throw bad();
  }
  double unit = 1;
  if (end < text.size()) {
    switch (text[end]) {
      case 'K': case 'k': unit = 1024.0; break;
      case 'M': case 'm': unit = 1024.0 * 1024.0; break;
      case 'G': case 'g': unit = 1024.0 * 1024.0 * 1024.0; break;
      default: throw bad();
    }
    ++end;
  }
  const double bytes = value * unit;
  // 2^50 bytes (1 PiB) bounds every device this runs on and keeps the conversion exact.
  if (end != text.size() || !std::isfinite(bytes) || bytes < 1 || bytes > 0x1p50) throw bad();
  return VkDeviceSize(bytes);
}

ContextOptions contextOptionsFromEnvironment() {
  ContextOptions options;
  const char* validation = std::getenv("PLANET_VALIDATION");
  options.validation = validation && std::strcmp(validation, "0") != 0 && *validation;
  options.synchronizationValidation = options.validation;
  if (const char* limit = std::getenv("PLANET_DEVICE_MEMORY_LIMIT"); limit && *limit)
    options.deviceMemoryLimit = parseByteSize(limit, "PLANET_DEVICE_MEMORY_LIMIT");
  if (const char* fault = std::getenv("PLANET_FAULT"); fault && *fault) {
    const std::string text = fault;
    const std::string prefix = "device-lost@";
    const std::string count = text.substr(std::min(text.size(), prefix.size()));
    const bool digits = !count.empty() && count.size() <= 9 &&
                        std::all_of(count.begin(), count.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (text.compare(0, prefix.size(), prefix) != 0 || !digits || std::stoull(count) == 0)
      throw Error("PLANET_FAULT must be device-lost@N with N a submission number >= 1, got '" + text + "'");
    options.deviceLostAtSubmit = std::stoull(count);
  }
  return options;
}

VkResult Context::beforeSubmit() {
  const uint64_t number = ++submissions_;
  return number == deviceLostAtSubmit_ ? VK_ERROR_DEVICE_LOST : VK_SUCCESS;
}

VkResult queueSubmit(Context& context, VkQueue queue, const VkSubmitInfo2& submit, VkFence fence) {
  const VkResult fault = context.beforeSubmit();
  if (fault != VK_SUCCESS) return fault;
  return vkQueueSubmit2(queue, 1, &submit, fence);
}

std::unique_ptr<Context> createContext(const ContextOptions& options) {
  auto context = std::make_unique<Context>();
  context->validation = options.validation;
  context->instance = createInstance(*context, options);
  if (options.validation) {
    VkDebugUtilsMessengerCreateInfoEXT info = messengerInfo(context.get());
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(context->instance, "vkCreateDebugUtilsMessengerEXT"));
    VK_CHECK(create(context->instance, &info, nullptr, &context->messenger));
  }
  std::string wanted = options.deviceName;
  if (wanted.empty())
    if (const char* env = std::getenv("PLANET_DEVICE")) wanted = env;
  context->physicalDevice = chooseDevice(context->instance, wanted);
  describeDevice(*context);
  createDevice(*context, options);
  AllocatorOptions allocatorOptions;
  allocatorOptions.memoryLimit = options.deviceMemoryLimit;
  context->allocator.init(context->physicalDevice, context->device, allocatorOptions);
  context->deviceLostAtSubmit_ = options.deviceLostAtSubmit;
  logDebug("vulkan device: {} ({})", context->info.name, context->info.driver);
  return context;
}

void destroyContext(Context& context) {
  // A leak report from the allocator must not stop the rest of the teardown: remember it,
  // release everything, then rethrow.
  std::exception_ptr leak;
  if (context.device) {
    vkDeviceWaitIdle(context.device);
    context.pipelines.destroyAll(context.device);
    try {
      context.allocator.destroy();
    } catch (...) {
      leak = std::current_exception();
    }
    vkDestroyDevice(context.device, nullptr);
    context.device = VK_NULL_HANDLE;
  }
  if (context.messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(context.instance, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(context.instance, context.messenger, nullptr);
    context.messenger = VK_NULL_HANDLE;
  }
  if (context.instance) {
    vkDestroyInstance(context.instance, nullptr);
    context.instance = VK_NULL_HANDLE;
  }
  if (leak) std::rethrow_exception(leak);
}

Context::~Context() {
  try {
    destroyContext(*this);
  } catch (const std::exception& e) {
    logError("{}", e.what());
  }
}

std::vector<std::string> listDeviceNames() {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  VkInstance instance = VK_NULL_HANDLE;
  if (vkCreateInstance(&info, nullptr, &instance) != VK_SUCCESS) return {};
  std::vector<std::string> names;
  for (VkPhysicalDevice device : physicalDevices(instance)) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(device, &props);
    names.emplace_back(props.deviceName);
  }
  vkDestroyInstance(instance, nullptr);
  return names;
}

}  // namespace planet::vk
