#include "vulkan/context.h"

#include <algorithm>
#include <cstring>
#include <iostream>
#include <sstream>

#include "vulkan/gpu_types.h"

namespace tessera::vulkan {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr uint32_t kRequiredApi = VK_API_VERSION_1_2;

std::string versionString(uint32_t version) {
  return std::to_string(VK_API_VERSION_MAJOR(version)) + "." +
         std::to_string(VK_API_VERSION_MINOR(version)) + "." +
         std::to_string(VK_API_VERSION_PATCH(version));
}

bool pretends(const std::vector<std::string>& missing, const char* feature) {
  return std::find(missing.begin(), missing.end(), feature) != missing.end();
}

// Discrete GPUs first, the CPU last: the order in which -1 picks a device.
int typeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 3;
    default:
      return 4;
  }
}

// The validation layer and the extensions it provides that the instance enables: debug utils
// (its messages), and validation features (synchronization validation) where the layer has them,
// which `sync_validation` says. An error where the layer is not installed.
Expected<void> validationLayer(const VulkanFunctions& vk, std::vector<const char*>& layers,
                               std::vector<const char*>& extensions, bool& sync_validation) {
  uint32_t count = 0;
  TESSERA_VK_CHECK(vk.vkEnumerateInstanceLayerProperties(&count, nullptr));
  std::vector<VkLayerProperties> available(count);
  TESSERA_VK_CHECK(vk.vkEnumerateInstanceLayerProperties(&count, available.data()));
  const bool found = std::any_of(available.begin(), available.end(), [](const auto& layer) {
    return std::strcmp(layer.layerName, kValidationLayer) == 0;
  });
  if (!found)
    return makeError(std::string("validation was requested but ") + kValidationLayer +
                     " is not installed (Debian: vulkan-validationlayers)");
  layers.push_back(kValidationLayer);
  // The layer provides the debug-utils and validation-features extensions.
  uint32_t extension_count = 0;
  TESSERA_VK_CHECK(
      vk.vkEnumerateInstanceExtensionProperties(kValidationLayer, &extension_count, nullptr));
  std::vector<VkExtensionProperties> layer_extensions(extension_count);
  TESSERA_VK_CHECK(vk.vkEnumerateInstanceExtensionProperties(kValidationLayer, &extension_count,
                                                             layer_extensions.data()));
  auto provides = [&](const char* name) {
    return std::any_of(layer_extensions.begin(), layer_extensions.end(),
                       [&](const auto& e) { return std::strcmp(e.extensionName, name) == 0; });
  };
  if (!provides(VK_EXT_DEBUG_UTILS_EXTENSION_NAME))
    return makeError(std::string(kValidationLayer) + " does not provide " +
                     VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  sync_validation = provides(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  if (sync_validation) extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  return {};
}

}  // namespace

bool validationRequestedByEnvironment() {
  const char* value = std::getenv("TESSERA_VULKAN_VALIDATION");
  return value && std::strcmp(value, "1") == 0;
}

DeviceCapabilities queryDevice(const VulkanFunctions& vk, VkPhysicalDevice physical,
                               const std::vector<std::string>& pretend_missing,
                               int pretend_max_samples) {
  DeviceCapabilities caps;
  caps.physical = physical;
  vk.vkGetPhysicalDeviceProperties(physical, &caps.properties);
  caps.api_version = caps.properties.apiVersion;

  uint32_t family_count = 0;
  vk.vkGetPhysicalDeviceQueueFamilyProperties(physical, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vk.vkGetPhysicalDeviceQueueFamilyProperties(physical, &family_count, families.data());
  for (uint32_t i = 0; i < family_count; ++i) {
    const VkQueueFlags flags = families[i].queueFlags;
    const bool compute = flags & VK_QUEUE_COMPUTE_BIT, graphics = flags & VK_QUEUE_GRAPHICS_BIT;
    if (compute && graphics && caps.graphics_queue_family < 0)
      caps.graphics_queue_family = static_cast<int>(i);
    if (compute && caps.compute_queue_family < 0) caps.compute_queue_family = static_cast<int>(i);
  }
  if (caps.graphics_queue_family >= 0) caps.compute_queue_family = caps.graphics_queue_family;
  if (caps.compute_queue_family >= 0)
    caps.timestamp_valid_bits =
        families[static_cast<size_t>(caps.compute_queue_family)].timestampValidBits;

  caps.driver = "driver version " + std::to_string(caps.properties.driverVersion);
  if (caps.api_version >= kRequiredApi) {
    VkPhysicalDeviceDriverProperties driver{};
    driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
    VkPhysicalDeviceProperties2 properties{};
    properties.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
    properties.pNext = &driver;
    vk.vkGetPhysicalDeviceProperties2(physical, &properties);
    caps.driver = std::string(driver.driverName) + ", " + driver.driverInfo;

    VkPhysicalDeviceVulkan12Features features12{};
    features12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
    VkPhysicalDeviceFeatures2 features{};
    features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    features.pNext = &features12;
    vk.vkGetPhysicalDeviceFeatures2(physical, &features);
    caps.shader_int64 = features.features.shaderInt64;
    caps.shader_float64 = features.features.shaderFloat64;
    caps.geometry_shader = features.features.geometryShader;
    caps.int64_atomics = features12.shaderBufferInt64Atomics;
  }
  if (pretends(pretend_missing, "shaderInt64")) caps.shader_int64 = false;
  if (pretends(pretend_missing, "shaderFloat64")) caps.shader_float64 = false;
  if (pretends(pretend_missing, "shaderBufferInt64Atomics")) caps.int64_atomics = false;
  if (pretends(pretend_missing, "geometryShader")) caps.geometry_shader = false;
  const VkPhysicalDeviceLimits& limits = caps.properties.limits;
  caps.framebuffer_sample_counts =
      limits.framebufferColorSampleCounts & limits.framebufferDepthSampleCounts;
  caps.standard_sample_locations = limits.standardSampleLocations == VK_TRUE &&
                                   !pretends(pretend_missing, "standardSampleLocations");
  if (pretend_max_samples > 0)
    caps.framebuffer_sample_counts &= static_cast<VkSampleCountFlags>(2 * pretend_max_samples - 1);
  // 64-bit atomics on int64 values need int64 arithmetic in the same shader.
  caps.int64_atomics = caps.int64_atomics && caps.shader_int64;

  VkFormatProperties depth{};
  vk.vkGetPhysicalDeviceFormatProperties(physical, VK_FORMAT_D32_SFLOAT, &depth);
  caps.depth32_attachment =
      depth.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT;
  return caps;
}

std::string missingRequirements(const DeviceCapabilities& caps, BackendKind kind) {
  std::vector<std::string> missing;
  if (caps.api_version < kRequiredApi)
    missing.push_back("Vulkan 1.2 (the device has " + versionString(caps.api_version) + ")");
  const VkPhysicalDeviceLimits& limits = caps.properties.limits;
  if (kind == BackendKind::kCompute) {
    if (caps.compute_queue_family < 0) missing.push_back("a compute queue");
    if (!caps.shader_int64) missing.push_back("shaderInt64 (64-bit fixed-point edge functions)");
    if (limits.maxComputeWorkGroupInvocations < 256 || limits.maxComputeWorkGroupSize[0] < 256)
      missing.push_back("256-invocation workgroups (maxComputeWorkGroupInvocations is " +
                        std::to_string(limits.maxComputeWorkGroupInvocations) + ")");
    if (limits.maxComputeSharedMemorySize < 16384)
      missing.push_back("16 KiB of workgroup shared memory");
    if (limits.maxPerStageDescriptorStorageBuffers < kComputeBindingCount)
      missing.push_back(std::to_string(kComputeBindingCount) +
                        " storage buffers per stage (maxPerStageDescriptorStorageBuffers is " +
                        std::to_string(limits.maxPerStageDescriptorStorageBuffers) + ")");
  } else {
    if (caps.graphics_queue_family < 0) missing.push_back("a graphics queue");
    if (!caps.geometry_shader)
      missing.push_back("geometryShader (gl_PrimitiveID in the fragment shader)");
    if (!caps.depth32_attachment) missing.push_back("a D32_SFLOAT depth attachment");
    // The scene inputs and the shadow maps (kBindingShadows).
    if (limits.maxPerStageDescriptorStorageBuffers < kSceneBindingCount + 1)
      missing.push_back(std::to_string(kSceneBindingCount + 1) + " storage buffers per stage");
    if (limits.maxColorAttachments < 3) missing.push_back("3 colour attachments");
  }
  std::string text;
  for (size_t i = 0; i < missing.size(); ++i) text += (i ? ", " : "") + missing[i];
  return text;
}

DeviceInfo describeDevice(const DeviceCapabilities& caps, int index) {
  DeviceInfo info;
  info.index = index;
  info.name = caps.properties.deviceName;
  switch (caps.properties.deviceType) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      info.type = "discrete GPU";
      break;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      info.type = "integrated GPU";
      break;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      info.type = "virtual GPU";
      break;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      info.type = "CPU";
      break;
    default:
      info.type = "other";
      break;
  }
  info.api_version = versionString(caps.api_version);
  info.driver = caps.driver;
  info.int64_atomics = caps.int64_atomics;
  info.float64 = caps.shader_float64;
  const std::string compute_missing = missingRequirements(caps, BackendKind::kCompute);
  info.compute_usable = compute_missing.empty();
  if (info.compute_usable) {
    info.compute_note = caps.int64_atomics ? "64-bit atomic visibility commits"
                                           : "no shaderBufferInt64Atomics: two-pass 32-bit commits";
    info.compute_note +=
        caps.shader_float64 ? ", double-precision setup" : ", no shaderFloat64: float depth planes";
  } else {
    info.compute_note = "missing " + compute_missing;
  }
  const std::string raster_missing = missingRequirements(caps, BackendKind::kRaster);
  info.raster_usable = raster_missing.empty();
  info.raster_sample_counts = {1};
  for (int n : {2, 4, 8})
    if (rasterSampleCountProblem(caps, n).empty()) info.raster_sample_counts.push_back(n);
  if (info.raster_usable) {
    info.raster_note = "graphics pipeline, MSAA";
    for (size_t i = 0; i < info.raster_sample_counts.size(); ++i) {
      info.raster_note += i ? '/' : ' ';
      info.raster_note += std::to_string(info.raster_sample_counts[i]);
    }
  } else {
    info.raster_note = "missing " + raster_missing;
  }
  return info;
}

Expected<std::unique_ptr<Context>> Context::create(const VulkanOptions& options, BackendKind kind) {
  std::unique_ptr<Context> context(new Context());
  context->fence_timeout_ms = options.fence_timeout_ms;
  if (Expected<void> r = loadGlobalFunctions(context->vk); !r) return r.error();
  if (Expected<void> r = context->createInstance(options); !r) return r.error();
  if (Expected<void> r = context->pickDevice(options, kind); !r) return r.error();
  if (Expected<void> r = context->createDevice(kind); !r) return r.error();
  context->max_buffer_bytes = context->caps.properties.limits.maxStorageBufferRange;
  if (options.pretend_max_buffer_bytes > 0)
    context->max_buffer_bytes =
        std::min(context->max_buffer_bytes, options.pretend_max_buffer_bytes);
  return context;
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::onDebugMessage(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT /*types*/,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  Context* context = static_cast<Context*>(user);
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    std::lock_guard<std::mutex> lock(context->messages_mutex_);
    context->validation_errors_.push_back(data && data->pMessage ? data->pMessage : "(no text)");
    std::cerr << "tessera: vulkan validation: " << context->validation_errors_.back() << "\n";
  }
  return VK_FALSE;
}

std::vector<std::string> Context::validationErrors() const {
  std::lock_guard<std::mutex> lock(messages_mutex_);
  return validation_errors_;
}

Expected<void> Context::createInstance(const VulkanOptions& options) {
  uint32_t loader_version = VK_API_VERSION_1_0;
  if (vk.vkEnumerateInstanceVersion)
    TESSERA_VK_CHECK(vk.vkEnumerateInstanceVersion(&loader_version));
  if (loader_version < kRequiredApi)
    return makeError("the Vulkan loader supports Vulkan " + versionString(loader_version) +
                     "; tessera needs 1.2");

  std::vector<const char*> layers, extensions;
  bool sync_validation = false;
  if (options.validation) {
    if (Expected<void> r = validationLayer(vk, layers, extensions, sync_validation); !r) return r;
  }

  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "tessera";
  app.pEngineName = "tessera";
  app.apiVersion = kRequiredApi;

  // Chained into the instance's create info so that messages about creating the instance itself
  // are caught too.
  VkDebugUtilsMessengerCreateInfoEXT messenger_info{};
  messenger_info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                   VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger_info.pfnUserCallback = &Context::onDebugMessage;
  messenger_info.pUserData = this;

  // Synchronization validation too: it checks every barrier against the accesses it orders.
  const VkValidationFeatureEnableEXT enables[] = {
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{};
  features.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
  features.pNext = &messenger_info;
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;

  VkInstanceCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  create.pNext = !options.validation ? nullptr
                 : sync_validation   ? static_cast<const void*>(&features)
                                     : static_cast<const void*>(&messenger_info);
  create.pApplicationInfo = &app;
  create.enabledLayerCount = static_cast<uint32_t>(layers.size());
  create.ppEnabledLayerNames = layers.data();
  create.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  create.ppEnabledExtensionNames = extensions.data();
  const VkResult created = vk.vkCreateInstance(&create, nullptr, &instance);
  if (created == VK_ERROR_INCOMPATIBLE_DRIVER)
    return makeError(
        "no Vulkan driver found (vkCreateInstance: VK_ERROR_INCOMPATIBLE_DRIVER); "
        "install one (Debian: mesa-vulkan-drivers provides lavapipe)");
  TESSERA_VK_CHECK(created);
  if (Expected<void> r = loadInstanceFunctions(vk, instance, options.validation); !r) return r;
  if (options.validation)
    TESSERA_VK_CHECK(
        vk.vkCreateDebugUtilsMessengerEXT(instance, &messenger_info, nullptr, &messenger));
  return {};
}

Expected<void> Context::pickDevice(const VulkanOptions& options, BackendKind kind) {
  uint32_t count = 0;
  TESSERA_VK_CHECK(vk.vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> physical(count);
  TESSERA_VK_CHECK(vk.vkEnumeratePhysicalDevices(instance, &count, physical.data()));
  if (count == 0)
    return makeError(
        "no Vulkan device found (the loader found no driver with a device; "
        "Debian: mesa-vulkan-drivers provides lavapipe)");
  const char* backend = kind == BackendKind::kCompute ? "vulkan" : "vulkan-raster";

  if (options.device >= 0) {
    if (static_cast<uint32_t>(options.device) >= count)
      return makeError("Vulkan device " + std::to_string(options.device) + " does not exist (" +
                       std::to_string(count) + " device" + (count == 1 ? "" : "s") +
                       "; see 'tessera devices')");
    caps = queryDevice(vk, physical[static_cast<size_t>(options.device)],
                       options.pretend_missing_features);
    const std::string missing = missingRequirements(caps, kind);
    if (!missing.empty())
      return makeError("Vulkan device " + std::to_string(options.device) + " (" +
                       caps.properties.deviceName + ") cannot run the " + backend +
                       " backend: missing " + missing);
    info = describeDevice(caps, options.device);
    return {};
  }

  int best = -1, best_rank = 1000;
  std::string reasons;
  for (uint32_t i = 0; i < count; ++i) {
    DeviceCapabilities candidate =
        queryDevice(vk, physical[i], options.pretend_missing_features, options.pretend_max_samples);
    const std::string missing = missingRequirements(candidate, kind);
    if (!missing.empty()) {
      reasons += std::string(reasons.empty() ? "" : "; ") + std::to_string(i) + " (" +
                 candidate.properties.deviceName + "): missing " + missing;
      continue;
    }
    const int rank = typeRank(candidate.properties.deviceType);
    if (rank < best_rank) {
      best = static_cast<int>(i);
      best_rank = rank;
      caps = candidate;
    }
  }
  if (best < 0)
    return makeError(std::string("no Vulkan device can run the ") + backend +
                     " backend: " + reasons);
  info = describeDevice(caps, best);
  return {};
}

Expected<void> Context::createDevice(BackendKind kind) {
  queue_family = static_cast<uint32_t>(kind == BackendKind::kCompute ? caps.compute_queue_family
                                                                     : caps.graphics_queue_family);
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{};
  queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue_info.queueFamilyIndex = queue_family;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;

  // Only what the chosen paths use (and never a feature the options pretend is missing).
  VkPhysicalDeviceVulkan12Features features12{};
  features12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
  VkPhysicalDeviceFeatures2 features{};
  features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  features.pNext = &features12;
  if (kind == BackendKind::kCompute) {
    features.features.shaderInt64 = VK_TRUE;
    features.features.shaderFloat64 = caps.shader_float64;
    features12.shaderBufferInt64Atomics = caps.int64_atomics;
  } else {
    features.features.geometryShader = VK_TRUE;
  }

  VkDeviceCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  create.pNext = &features;
  create.queueCreateInfoCount = 1;
  create.pQueueCreateInfos = &queue_info;
  TESSERA_VK_CHECK(vk.vkCreateDevice(caps.physical, &create, nullptr, &device));
  if (Expected<void> r = loadDeviceFunctions(vk, device); !r) return r;
  vk.vkGetDeviceQueue(device, queue_family, 0, &queue);
  vk.vkGetPhysicalDeviceMemoryProperties(caps.physical, &memory_properties);

  VkCommandPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool_info.queueFamilyIndex = queue_family;
  TESSERA_VK_CHECK(vk.vkCreateCommandPool(device, &pool_info, nullptr, &command_pool));
  VkCommandBufferAllocateInfo allocate{};
  allocate.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  allocate.commandPool = command_pool;
  allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocate.commandBufferCount = 1;
  TESSERA_VK_CHECK(vk.vkAllocateCommandBuffers(device, &allocate, &commands));
  VkFenceCreateInfo fence_info{};
  fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  TESSERA_VK_CHECK(vk.vkCreateFence(device, &fence_info, nullptr, &fence));
  return {};
}

Context::~Context() {
  if (device) {
    // Never destroy what the GPU may still use; and never wait without bound. A device that
    // does not finish within the timeout leaks its objects rather than hanging the program.
    fence_timeout_ms = std::max<uint32_t>(fence_timeout_ms, 5000);
    if (pending_ && !waitForPending()) {
      std::cerr << "tessera: vulkan: the GPU is still busy; leaking its resources\n";
      return;
    }
    if (fence) vk.vkDestroyFence(device, fence, nullptr);
    if (command_pool) vk.vkDestroyCommandPool(device, command_pool, nullptr);
    vk.vkDestroyDevice(device, nullptr);
  }
  if (messenger) vk.vkDestroyDebugUtilsMessengerEXT(instance, messenger, nullptr);
  if (instance) vk.vkDestroyInstance(instance, nullptr);
}

Expected<uint32_t> Context::findMemoryType(uint32_t type_bits, VkMemoryPropertyFlags required,
                                           VkMemoryPropertyFlags preferred) const {
  int fallback = -1;
  for (uint32_t i = 0; i < memory_properties.memoryTypeCount; ++i) {
    if (!(type_bits & (1u << i))) continue;
    const VkMemoryPropertyFlags flags = memory_properties.memoryTypes[i].propertyFlags;
    if ((flags & required) != required) continue;
    if ((flags & preferred) == preferred) return i;
    if (fallback < 0) fallback = static_cast<int>(i);
  }
  if (fallback < 0) return makeError("the Vulkan device has no suitable memory type");
  return static_cast<uint32_t>(fallback);
}

Expected<void> Context::ensureBuffer(Buffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage,
                                     MemoryKind kind, const char* what) {
  bytes = std::max<VkDeviceSize>(bytes, 256);
  if (buffer.buffer && buffer.size >= bytes) return {};
  // Grow by half again, so a scene that grows a little each frame does not reallocate each frame.
  VkDeviceSize size = buffer.buffer ? std::max(bytes, buffer.size + buffer.size / 2) : bytes;
  size = (size + 255) & ~VkDeviceSize{255};
  const VkDeviceSize limit = max_buffer_bytes;
  if (usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) {
    if (bytes > limit) {
      std::ostringstream message;
      message << "the scene is too large for this device: the " << what << " buffer needs "
              << (bytes + (1 << 20) - 1) / (1 << 20) << " MiB but the device allows at most "
              << limit / (1 << 20) << " MiB per storage buffer (maxStorageBufferRange)";
      return makeError(message.str());
    }
    size = std::min(size, limit);
  }
  destroyBuffer(buffer);

  VkBufferCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  create.size = size;
  create.usage = usage;
  create.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  TESSERA_VK_CHECK(vk.vkCreateBuffer(device, &create, nullptr, &buffer.buffer));
  VkMemoryRequirements requirements{};
  vk.vkGetBufferMemoryRequirements(device, buffer.buffer, &requirements);
  Expected<uint32_t> type =
      kind == MemoryKind::kHost
          ? findMemoryType(
                requirements.memoryTypeBits,
                VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                VK_MEMORY_PROPERTY_HOST_CACHED_BIT)
          : findMemoryType(requirements.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (!type) return type.error();
  VkMemoryAllocateInfo allocate{};
  allocate.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  allocate.allocationSize = requirements.size;
  allocate.memoryTypeIndex = *type;
  TESSERA_VK_CHECK(vk.vkAllocateMemory(device, &allocate, nullptr, &buffer.memory));
  TESSERA_VK_CHECK(vk.vkBindBufferMemory(device, buffer.buffer, buffer.memory, 0));
  if (kind == MemoryKind::kHost)
    TESSERA_VK_CHECK(vk.vkMapMemory(device, buffer.memory, 0, VK_WHOLE_SIZE, 0, &buffer.mapped));
  buffer.size = size;
  return {};
}

void Context::destroyBuffer(Buffer& buffer) {
  if (buffer.buffer) vk.vkDestroyBuffer(device, buffer.buffer, nullptr);
  if (buffer.memory) vk.vkFreeMemory(device, buffer.memory, nullptr);  // unmaps too
  buffer = Buffer{};
}

Expected<VkShaderModule> Context::createShaderModule(std::span<const uint32_t> spirv) {
  VkShaderModuleCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  create.codeSize = spirv.size_bytes();
  create.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  TESSERA_VK_CHECK(vk.vkCreateShaderModule(device, &create, nullptr, &module));
  return module;
}

Expected<void> Context::waitForPending() {
  if (!pending_) return {};
  const uint64_t timeout_ns = static_cast<uint64_t>(fence_timeout_ms) * 1000000ull;
  const VkResult waited = vk.vkWaitForFences(device, 1, &fence, VK_TRUE, timeout_ns);
  if (waited == VK_TIMEOUT)
    return makeError("the GPU did not finish within " + std::to_string(fence_timeout_ms) +
                     " ms (vkWaitForFences: VK_TIMEOUT); the frame was abandoned");
  TESSERA_VK_CHECK(waited);
  pending_ = false;
  TESSERA_VK_CHECK(vk.vkResetFences(device, 1, &fence));
  return {};
}

Expected<VkCommandBuffer> Context::beginCommands() {
  if (Expected<void> r = waitForPending(); !r)
    return makeError("an earlier frame is still running: " + r.error().message);
  TESSERA_VK_CHECK(vk.vkResetCommandBuffer(commands, 0));
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  TESSERA_VK_CHECK(vk.vkBeginCommandBuffer(commands, &begin));
  return commands;
}

Expected<void> Context::submitAndWait() {
  TESSERA_VK_CHECK(vk.vkEndCommandBuffer(commands));
  // Host writes to the mapped, coherent input buffers happened before this call: a queue
  // submission makes them visible to the device (the implicit host-write ordering of
  // vkQueueSubmit), so no host-to-device barrier is recorded.
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands;
  TESSERA_VK_CHECK(vk.vkQueueSubmit(queue, 1, &submit, fence));
  pending_ = true;
  return waitForPending();
}

DispatchGrid dispatchGrid(uint64_t groups) {
  if (groups == 0) return {0, 0};
  constexpr uint64_t kMaxX = 32768;
  const uint64_t x = std::min(groups, kMaxX);
  return {static_cast<uint32_t>(x), static_cast<uint32_t>((groups + x - 1) / x)};
}

void memoryBarrier(const VulkanFunctions& vk, VkCommandBuffer commands,
                   VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                   VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
  VkMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  barrier.srcAccessMask = src_access;
  barrier.dstAccessMask = dst_access;
  vk.vkCmdPipelineBarrier(commands, src_stage, dst_stage, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace tessera::vulkan
