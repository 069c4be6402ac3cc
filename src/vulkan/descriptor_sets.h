// The one descriptor set both Vulkan backends use: every binding a storage buffer; and a compute
// pipeline on such a layout.
#pragma once

#include <cstdint>
#include <span>

#include <tessera/base/expected.h>

#include "vulkan/context.h"

namespace tessera::vulkan {

// A descriptor set layout of `bindings` storage buffers (bindings 0..bindings-1) seen by
// `stages`, and a pipeline layout of that one set and `push_bytes` of push constants.
Expected<void> createStorageLayouts(Context& context, uint32_t bindings, VkShaderStageFlags stages,
                                    uint32_t push_bytes, VkDescriptorSetLayout& set_layout,
                                    VkPipelineLayout& pipeline_layout);
// The same with the storage buffers at the given binding numbers (not necessarily 0..n-1).
Expected<void> createStorageLayouts(Context& context, std::span<const uint32_t> bindings,
                                    VkShaderStageFlags stages, uint32_t push_bytes,
                                    VkDescriptorSetLayout& set_layout,
                                    VkPipelineLayout& pipeline_layout);
// A pool for one such set of `bindings` storage buffers, and the set.
Expected<void> allocateStorageSet(Context& context, uint32_t bindings,
                                  VkDescriptorSetLayout set_layout, VkDescriptorPool& pool,
                                  VkDescriptorSet& set);

// A compute pipeline of `spirv` (entry point "main") on `layout`, specialized when given.
Expected<VkPipeline> createComputePipeline(Context& context, VkPipelineLayout layout,
                                           std::span<const uint32_t> spirv,
                                           const VkSpecializationInfo* specialization = nullptr);

}  // namespace tessera::vulkan
