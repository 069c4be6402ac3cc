#include "vulkan/loader.h"

#include <cstdlib>
#include <map>
#include <mutex>
#include <string>

#if defined(_WIN32)
#include <windows.h>
#else
#include <dlfcn.h>
#endif

namespace tessera::vulkan {

namespace {

#if defined(_WIN32)
constexpr const char* kLoaderName = "vulkan-1.dll";
#elif defined(__APPLE__)
constexpr const char* kLoaderName = "libvulkan.1.dylib";
#else
constexpr const char* kLoaderName = "libvulkan.so.1";
#endif

struct LoaderLibrary {
  PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;
  std::string error;
};

// Each library is opened once per process and never closed: instances made from it may outlive
// any one backend. Keyed by name, so that TESSERA_VULKAN_LOADER is honoured whenever it is read.
LoaderLibrary openLoader(const std::string& name) {
  LoaderLibrary result;
#if defined(_WIN32)
  HMODULE handle = LoadLibraryA(name.c_str());
  if (!handle) {
    result.error = "cannot open the Vulkan loader " + name + " (is a Vulkan driver installed?)";
    return result;
  }
  result.get_instance_proc_addr = reinterpret_cast<PFN_vkGetInstanceProcAddr>(
      reinterpret_cast<void*>(GetProcAddress(handle, "vkGetInstanceProcAddr")));
#else
  void* handle = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    result.error = "cannot open the Vulkan loader " + name + " (" + (why ? why : "unknown") +
                   "); install a Vulkan loader and driver (Debian: libvulkan1 and "
                   "mesa-vulkan-drivers)";
    return result;
  }
  result.get_instance_proc_addr =
      reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(handle, "vkGetInstanceProcAddr"));
#endif
  if (!result.get_instance_proc_addr)
    result.error = "the Vulkan loader " + name + " has no vkGetInstanceProcAddr";
  return result;
}

LoaderLibrary loaderLibrary() {
  static std::mutex mutex;
  static std::map<std::string, LoaderLibrary> opened;
  const char* override_name = std::getenv("TESSERA_VULKAN_LOADER");
  const std::string name = override_name && *override_name ? override_name : kLoaderName;
  std::lock_guard<std::mutex> lock(mutex);
  auto found = opened.find(name);
  if (found == opened.end()) found = opened.emplace(name, openLoader(name)).first;
  return found->second;
}

}  // namespace

Expected<void> loadGlobalFunctions(VulkanFunctions& vk) {
  const LoaderLibrary library = loaderLibrary();
  if (!library.get_instance_proc_addr) return makeError(library.error);
  vk.vkGetInstanceProcAddr = library.get_instance_proc_addr;
#define TESSERA_VK_LOAD(name)                                                              \
  vk.name = reinterpret_cast<PFN_##name>(vk.vkGetInstanceProcAddr(VK_NULL_HANDLE, #name)); \
  if (!vk.name) return makeError("the Vulkan loader does not provide " #name);
  TESSERA_VK_GLOBAL_FUNCTIONS(TESSERA_VK_LOAD)
#undef TESSERA_VK_LOAD
  vk.vkEnumerateInstanceVersion = reinterpret_cast<PFN_vkEnumerateInstanceVersion>(
      vk.vkGetInstanceProcAddr(VK_NULL_HANDLE, "vkEnumerateInstanceVersion"));
  return {};
}

Expected<void> loadInstanceFunctions(VulkanFunctions& vk, VkInstance instance, bool debug_utils) {
#define TESSERA_VK_LOAD(name)                                                        \
  vk.name = reinterpret_cast<PFN_##name>(vk.vkGetInstanceProcAddr(instance, #name)); \
  if (!vk.name) return makeError("the Vulkan instance does not provide " #name);
  TESSERA_VK_INSTANCE_FUNCTIONS(TESSERA_VK_LOAD)
  if (debug_utils) {
    TESSERA_VK_DEBUG_FUNCTIONS(TESSERA_VK_LOAD)
  }
#undef TESSERA_VK_LOAD
  return {};
}

Expected<void> loadDeviceFunctions(VulkanFunctions& vk, VkDevice device) {
#define TESSERA_VK_LOAD(name)                                                    \
  vk.name = reinterpret_cast<PFN_##name>(vk.vkGetDeviceProcAddr(device, #name)); \
  if (!vk.name) return makeError("the Vulkan device does not provide " #name);
  TESSERA_VK_DEVICE_FUNCTIONS(TESSERA_VK_LOAD)
#undef TESSERA_VK_LOAD
  return {};
}

const char* resultName(VkResult result) {
  switch (result) {
#define TESSERA_VK_RESULT(name) \
  case name:                    \
    return #name;
    TESSERA_VK_RESULT(VK_SUCCESS)
    TESSERA_VK_RESULT(VK_NOT_READY)
    TESSERA_VK_RESULT(VK_TIMEOUT)
    TESSERA_VK_RESULT(VK_EVENT_SET)
    TESSERA_VK_RESULT(VK_EVENT_RESET)
    TESSERA_VK_RESULT(VK_INCOMPLETE)
    TESSERA_VK_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
    TESSERA_VK_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    TESSERA_VK_RESULT(VK_ERROR_INITIALIZATION_FAILED)
    TESSERA_VK_RESULT(VK_ERROR_DEVICE_LOST)
    TESSERA_VK_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
    TESSERA_VK_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
    TESSERA_VK_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
    TESSERA_VK_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
    TESSERA_VK_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
    TESSERA_VK_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
    TESSERA_VK_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
    TESSERA_VK_RESULT(VK_ERROR_FRAGMENTED_POOL)
    TESSERA_VK_RESULT(VK_ERROR_UNKNOWN)
    TESSERA_VK_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
    TESSERA_VK_RESULT(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    TESSERA_VK_RESULT(VK_ERROR_FRAGMENTATION)
    TESSERA_VK_RESULT(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
#undef TESSERA_VK_RESULT
    default:
      return "VkResult(unknown)";
  }
}

Error vulkanError(const char* call, VkResult result) {
  std::string message = std::string(call);
  // Keep the function name, not the whole argument list.
  if (size_t paren = message.find('('); paren != std::string::npos) message.resize(paren);
  if (message.rfind("vk.", 0) == 0) message.erase(0, 3);
  message += " failed: ";
  message += resultName(result);
  if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
    message += " (the scene or the image is too large for this device's memory)";
  if (result == VK_ERROR_DEVICE_LOST) message += " (the GPU stopped responding)";
  return makeError(message);
}

}  // namespace tessera::vulkan
