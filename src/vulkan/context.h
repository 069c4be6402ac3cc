// The Vulkan objects a backend owns: instance (with the validation messenger when asked), the
// chosen physical device and its capabilities, the logical device, one queue, one command buffer
// and its fence, and the buffers. Shared by the compute and raster backends; each backend owns
// its own Context.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/vulkan/vulkan_backend.h>

#include "vulkan/loader.h"

namespace tessera::vulkan {

enum class BackendKind { kCompute, kRaster };

// What a physical device offers, after VulkanOptions::pretend_missing_features is applied.
struct DeviceCapabilities {
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties{};
  uint32_t api_version = 0;
  std::string driver;              // driver name and version, e.g. "llvmpipe, Mesa 22.3.6 (...)"
  int compute_queue_family = -1;   // a family with COMPUTE (graphics and compute preferred)
  int graphics_queue_family = -1;  // a family with GRAPHICS and COMPUTE
  bool shader_int64 = false;
  bool shader_float64 = false;
  bool int64_atomics = false;  // shaderBufferInt64Atomics
  bool geometry_shader = false;
  bool depth32_attachment = false;
  // Sample counts a colour and a depth attachment both take (framebufferColorSampleCounts &
  // framebufferDepthSampleCounts), and whether they sit at the standard positions: what
  // vulkan-raster's MSAA needs.
  VkSampleCountFlags framebuffer_sample_counts = VK_SAMPLE_COUNT_1_BIT;
  bool standard_sample_locations = false;
  uint32_t timestamp_valid_bits = 0;  // of the chosen queue family (0: no timestamps)
};

// pretend_max_samples > 0 treats every sample count above it as unsupported.
DeviceCapabilities queryDevice(const VulkanFunctions& vk, VkPhysicalDevice physical,
                               const std::vector<std::string>& pretend_missing,
                               int pretend_max_samples = 0);
// Why a backend cannot run on the device ("" when it can).
std::string missingRequirements(const DeviceCapabilities& caps, BackendKind kind);
DeviceInfo describeDevice(const DeviceCapabilities& caps, int index);
// Why vulkan-raster cannot render with `samples` per pixel on the device ("" when it can).
std::string rasterSampleCountProblem(const DeviceCapabilities& caps, int samples);

enum class MemoryKind {
  kDevice,  // written and read by the GPU only: device-local where the device has it
  kHost,    // mapped: written by the host (inputs) or read by it (results); host-coherent
};

struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // for MemoryKind::kHost
};

class Context {
 public:
  static Expected<std::unique_ptr<Context>> create(const VulkanOptions& options, BackendKind kind);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // Makes `buffer` at least `bytes` large (keeping it when it already is); `what` names it in
  // the Error when the device's limits or memory cannot hold it. Invalidates descriptor sets.
  Expected<void> ensureBuffer(Buffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage,
                              MemoryKind kind, const char* what);
  void destroyBuffer(Buffer& buffer);
  Expected<uint32_t> findMemoryType(uint32_t type_bits, VkMemoryPropertyFlags required,
                                    VkMemoryPropertyFlags preferred) const;
  Expected<VkShaderModule> createShaderModule(std::span<const uint32_t> spirv);

  // Begins recording the frame's command buffer (waiting first for any earlier submission).
  Expected<VkCommandBuffer> beginCommands();
  // Ends, submits and waits for the command buffer, for at most fence_timeout_ms.
  Expected<void> submitAndWait();
  // Waits (bounded) for a submission that an earlier timeout left running.
  Expected<void> waitForPending();

  std::vector<std::string> validationErrors() const;

  VulkanFunctions vk;
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queue_family = 0;
  VkCommandPool command_pool = VK_NULL_HANDLE;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  DeviceCapabilities caps;
  DeviceInfo info;
  VkPhysicalDeviceMemoryProperties memory_properties{};
  uint32_t fence_timeout_ms = 20000;
  uint64_t max_buffer_bytes = 0;  // maxStorageBufferRange, or less when the options pretend

 private:
  Context() = default;
  static VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(
      VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
      const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);
  Expected<void> createInstance(const VulkanOptions& options);
  Expected<void> pickDevice(const VulkanOptions& options, BackendKind kind);
  Expected<void> createDevice(BackendKind kind);

  bool pending_ = false;  // submitted, fence not yet seen signalled
  mutable std::mutex messages_mutex_;
  std::vector<std::string> validation_errors_;
};

// Splits a count of workgroups into a grid every device accepts (x at most 32768); shaders
// flatten it back with gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x.
struct DispatchGrid {
  uint32_t x = 0, y = 0;
};
DispatchGrid dispatchGrid(uint64_t groups);

// Global memory barrier between two stages: every barrier in the backends goes through this
// and says at the call what it orders.
void memoryBarrier(const VulkanFunctions& vk, VkCommandBuffer commands,
                   VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                   VkPipelineStageFlags dst_stage, VkAccessFlags dst_access);

}  // namespace tessera::vulkan
