// The Vulkan entry points tessera uses, loaded at run time from the system's Vulkan loader
// (libvulkan.so.1), and the one checking macro every VkResult goes through.
//
// Opening the loader ourselves (instead of linking it) turns "no Vulkan on this machine" into an
// Error a user can read; TESSERA_VULKAN_LOADER overrides the library name (tests use it to
// simulate a machine without a loader).
#pragma once

#include <string>

#include <vulkan/vulkan.h>

#include <tessera/base/expected.h>

namespace tessera::vulkan {

// Functions obtained from the loader before an instance exists.
#define TESSERA_VK_GLOBAL_FUNCTIONS(X)      \
  X(vkCreateInstance)                       \
  X(vkEnumerateInstanceExtensionProperties) \
  X(vkEnumerateInstanceLayerProperties)

// Functions of an instance.
#define TESSERA_VK_INSTANCE_FUNCTIONS(X)      \
  X(vkDestroyInstance)                        \
  X(vkEnumeratePhysicalDevices)               \
  X(vkGetPhysicalDeviceProperties)            \
  X(vkGetPhysicalDeviceProperties2)           \
  X(vkGetPhysicalDeviceFeatures2)             \
  X(vkGetPhysicalDeviceQueueFamilyProperties) \
  X(vkGetPhysicalDeviceMemoryProperties)      \
  X(vkGetPhysicalDeviceFormatProperties)      \
  X(vkEnumerateDeviceExtensionProperties)     \
  X(vkCreateDevice)                           \
  X(vkGetDeviceProcAddr)

// Functions of the debug-utils extension (present only when validation is on).
#define TESSERA_VK_DEBUG_FUNCTIONS(X) \
  X(vkCreateDebugUtilsMessengerEXT)   \
  X(vkDestroyDebugUtilsMessengerEXT)

// Functions of a device.
#define TESSERA_VK_DEVICE_FUNCTIONS(X) \
  X(vkDestroyDevice)                   \
  X(vkGetDeviceQueue)                  \
  X(vkDeviceWaitIdle)                  \
  X(vkCreateBuffer)                    \
  X(vkDestroyBuffer)                   \
  X(vkGetBufferMemoryRequirements)     \
  X(vkCreateImage)                     \
  X(vkDestroyImage)                    \
  X(vkGetImageMemoryRequirements)      \
  X(vkCreateImageView)                 \
  X(vkDestroyImageView)                \
  X(vkAllocateMemory)                  \
  X(vkFreeMemory)                      \
  X(vkBindBufferMemory)                \
  X(vkBindImageMemory)                 \
  X(vkMapMemory)                       \
  X(vkUnmapMemory)                     \
  X(vkCreateShaderModule)              \
  X(vkDestroyShaderModule)             \
  X(vkCreateDescriptorSetLayout)       \
  X(vkDestroyDescriptorSetLayout)      \
  X(vkCreatePipelineLayout)            \
  X(vkDestroyPipelineLayout)           \
  X(vkCreateComputePipelines)          \
  X(vkCreateGraphicsPipelines)         \
  X(vkDestroyPipeline)                 \
  X(vkCreateDescriptorPool)            \
  X(vkDestroyDescriptorPool)           \
  X(vkAllocateDescriptorSets)          \
  X(vkUpdateDescriptorSets)            \
  X(vkCreateRenderPass)                \
  X(vkDestroyRenderPass)               \
  X(vkCreateFramebuffer)               \
  X(vkDestroyFramebuffer)              \
  X(vkCreateCommandPool)               \
  X(vkDestroyCommandPool)              \
  X(vkAllocateCommandBuffers)          \
  X(vkResetCommandBuffer)              \
  X(vkBeginCommandBuffer)              \
  X(vkEndCommandBuffer)                \
  X(vkCreateFence)                     \
  X(vkDestroyFence)                    \
  X(vkResetFences)                     \
  X(vkWaitForFences)                   \
  X(vkQueueSubmit)                     \
  X(vkCreateQueryPool)                 \
  X(vkDestroyQueryPool)                \
  X(vkGetQueryPoolResults)             \
  X(vkCmdResetQueryPool)               \
  X(vkCmdWriteTimestamp)               \
  X(vkCmdBindPipeline)                 \
  X(vkCmdBindDescriptorSets)           \
  X(vkCmdPushConstants)                \
  X(vkCmdDispatch)                     \
  X(vkCmdDispatchIndirect)             \
  X(vkCmdPipelineBarrier)              \
  X(vkCmdCopyImageToBuffer)            \
  X(vkCmdBeginRenderPass)              \
  X(vkCmdEndRenderPass)                \
  X(vkCmdBindVertexBuffers)            \
  X(vkCmdBindIndexBuffer)              \
  X(vkCmdDrawIndexed)                  \
  X(vkCmdSetViewport)                  \
  X(vkCmdSetScissor)

// The function table. Members are named as the Vulkan functions, so a call reads
// `vk.vkCreateBuffer(...)`.
struct VulkanFunctions {
#define TESSERA_VK_DECLARE(name) PFN_##name name = nullptr;
  PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;
  PFN_vkEnumerateInstanceVersion vkEnumerateInstanceVersion = nullptr;  // null on Vulkan 1.0
  TESSERA_VK_GLOBAL_FUNCTIONS(TESSERA_VK_DECLARE)
  TESSERA_VK_INSTANCE_FUNCTIONS(TESSERA_VK_DECLARE)
  TESSERA_VK_DEBUG_FUNCTIONS(TESSERA_VK_DECLARE)
  TESSERA_VK_DEVICE_FUNCTIONS(TESSERA_VK_DECLARE)
#undef TESSERA_VK_DECLARE
};

// Opens the Vulkan loader (once per process) and fills the global functions. An Error naming
// the library when it cannot be opened.
Expected<void> loadGlobalFunctions(VulkanFunctions& vk);
// Fills the instance functions (and the debug-utils ones when `debug_utils`).
Expected<void> loadInstanceFunctions(VulkanFunctions& vk, VkInstance instance, bool debug_utils);
// Fills the device functions.
Expected<void> loadDeviceFunctions(VulkanFunctions& vk, VkDevice device);

// "VK_ERROR_OUT_OF_DEVICE_MEMORY" and so on.
const char* resultName(VkResult result);
// The Error for a failed call: "<call> failed: <result>".
Error vulkanError(const char* call, VkResult result);

}  // namespace tessera::vulkan

// The one checking macro: evaluates a call returning VkResult and, unless it is VK_SUCCESS,
// returns from the enclosing function (which returns an Expected or an Error) with an Error
// naming the call and the result.
#define TESSERA_VK_CHECK(call)                                          \
  do {                                                                  \
    const VkResult tessera_vk_result_ = (call);                         \
    if (tessera_vk_result_ != VK_SUCCESS)                               \
      return ::tessera::vulkan::vulkanError(#call, tessera_vk_result_); \
  } while (false)
