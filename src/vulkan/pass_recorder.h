// The compute backend's recording of one frame's passes (compute_backend.cpp).
#pragma once

#include "vulkan/context.h"
#include "vulkan/gpu_types.h"

namespace tessera::vulkan {

// One frame's command buffer as it is recorded: binds, pushes and dispatches, the barriers
// between passes and the timestamps.
struct PassRecorder {
  const VulkanFunctions& vk;
  VkCommandBuffer cmd;
  VkPipelineLayout layout;
  VkBuffer counters;
  VkQueryPool timestamps;

  void timestamp(uint32_t index) const {
    if (timestamps)
      vk.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps, index);
  }
  void bind(VkPipeline pipeline, uint32_t mode) const {
    vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    const GpuPassConstants constants{mode, 0, 0, 0};
    vk.vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants),
                          &constants);
  }
  void dispatch(VkPipeline pipeline, uint64_t groups, uint32_t mode = 0) const {
    bind(pipeline, mode);
    const DispatchGrid grid = dispatchGrid(groups);
    if (grid.x) vk.vkCmdDispatch(cmd, grid.x, grid.y, 1);
  }
  void dispatchIndirect(VkPipeline pipeline, VkDeviceSize offset, uint32_t mode = 0) const {
    bind(pipeline, mode);
    vk.vkCmdDispatchIndirect(cmd, counters, offset);
  }
  // Shader writes of one pass made visible to the shader reads and writes of the next.
  void computeToCompute() const {
    memoryBarrier(vk, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  }
  // Shader writes of dispatch sizes made visible to the indirect dispatch that reads them (and
  // to the shaders that read the counters).
  void computeToIndirect() const {
    memoryBarrier(vk, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT |
                      VK_ACCESS_SHADER_WRITE_BIT);
  }
  // Shader writes made visible to the host's reads after the fence.
  void computeToHost() const {
    memoryBarrier(vk, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  }
};

}  // namespace tessera::vulkan
