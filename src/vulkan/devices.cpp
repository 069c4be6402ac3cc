// listDevices(): a short-lived instance that enumerates the physical devices; and what a
// device's multisampling limits allow vulkan-raster.
#include <tessera/vulkan/vulkan_backend.h>

#include "vulkan/context.h"

namespace tessera::vulkan {

namespace {

// The instance is destroyed on every path out of listDevices().
struct InstanceGuard {
  const VulkanFunctions& vk;
  VkInstance instance = VK_NULL_HANDLE;
  ~InstanceGuard() {
    if (instance) vk.vkDestroyInstance(instance, nullptr);
  }
};

Expected<std::vector<DeviceInfo>> enumerate(VulkanFunctions& vk, InstanceGuard& guard) {
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "tessera";
  app.apiVersion = VK_API_VERSION_1_2;
  VkInstanceCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  create.pApplicationInfo = &app;
  const VkResult created = vk.vkCreateInstance(&create, nullptr, &guard.instance);
  if (created == VK_ERROR_INCOMPATIBLE_DRIVER)
    return makeError(
        "no Vulkan driver found (vkCreateInstance: VK_ERROR_INCOMPATIBLE_DRIVER); "
        "install one (Debian: mesa-vulkan-drivers provides lavapipe)");
  TESSERA_VK_CHECK(created);
  if (Expected<void> r = loadInstanceFunctions(vk, guard.instance, false); !r) return r.error();
  uint32_t count = 0;
  TESSERA_VK_CHECK(vk.vkEnumeratePhysicalDevices(guard.instance, &count, nullptr));
  std::vector<VkPhysicalDevice> physical(count);
  TESSERA_VK_CHECK(vk.vkEnumeratePhysicalDevices(guard.instance, &count, physical.data()));
  std::vector<DeviceInfo> devices;
  for (uint32_t i = 0; i < count; ++i)
    devices.push_back(describeDevice(queryDevice(vk, physical[i], {}), static_cast<int>(i)));
  return devices;
}

}  // namespace

Expected<std::vector<DeviceInfo>> listDevices() {
  VulkanFunctions vk;
  if (Expected<void> r = loadGlobalFunctions(vk); !r) return r.error();
  InstanceGuard guard{vk};
  return enumerate(vk, guard);
}

std::string rasterSampleCountProblem(const DeviceCapabilities& caps, int samples) {
  if (samples == 1) return {};
  std::string problem;
  if (!(caps.framebuffer_sample_counts & static_cast<VkSampleCountFlags>(samples))) {
    problem = "the device does not take " + std::to_string(samples) +
              " samples per pixel (framebufferColorSampleCounts & framebufferDepthSampleCounts "
              "allow";
    for (int n = 1; n <= 64; n *= 2) {
      if (!(caps.framebuffer_sample_counts & static_cast<VkSampleCountFlags>(n))) continue;
      problem += ' ';
      problem += std::to_string(n);
    }
    problem += ")";
  } else if (!caps.standard_sample_locations) {
    problem =
        "the device does not place its samples at the standard positions "
        "(standardSampleLocations is false), so its coverage would not be tessera's";
  }
  return problem;
}

}  // namespace tessera::vulkan
