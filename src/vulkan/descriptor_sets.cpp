#include "vulkan/descriptor_sets.h"

#include <vector>

namespace tessera::vulkan {

Expected<void> createStorageLayouts(Context& c, uint32_t count, VkShaderStageFlags stages,
                                    uint32_t push_bytes, VkDescriptorSetLayout& set_layout,
                                    VkPipelineLayout& pipeline_layout) {
  std::vector<uint32_t> numbers(count);
  for (uint32_t i = 0; i < count; ++i) numbers[i] = i;
  return createStorageLayouts(c, numbers, stages, push_bytes, set_layout, pipeline_layout);
}

Expected<void> createStorageLayouts(Context& c, std::span<const uint32_t> numbers,
                                    VkShaderStageFlags stages, uint32_t push_bytes,
                                    VkDescriptorSetLayout& set_layout,
                                    VkPipelineLayout& pipeline_layout) {
  const uint32_t count = static_cast<uint32_t>(numbers.size());
  std::vector<VkDescriptorSetLayoutBinding> bindings(count);
  for (uint32_t i = 0; i < count; ++i)
    bindings[i] = {numbers[i], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stages, nullptr};
  VkDescriptorSetLayoutCreateInfo layout_info{};
  layout_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  layout_info.bindingCount = count;
  layout_info.pBindings = bindings.data();
  TESSERA_VK_CHECK(c.vk.vkCreateDescriptorSetLayout(c.device, &layout_info, nullptr, &set_layout));
  const VkPushConstantRange push{stages, 0, push_bytes};
  VkPipelineLayoutCreateInfo pipeline_layout_info{};
  pipeline_layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  pipeline_layout_info.setLayoutCount = 1;
  pipeline_layout_info.pSetLayouts = &set_layout;
  pipeline_layout_info.pushConstantRangeCount = 1;
  pipeline_layout_info.pPushConstantRanges = &push;
  TESSERA_VK_CHECK(
      c.vk.vkCreatePipelineLayout(c.device, &pipeline_layout_info, nullptr, &pipeline_layout));
  return {};
}

Expected<void> allocateStorageSet(Context& c, uint32_t bindings, VkDescriptorSetLayout set_layout,
                                  VkDescriptorPool& pool, VkDescriptorSet& set) {
  VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, bindings};
  VkDescriptorPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = &pool_size;
  TESSERA_VK_CHECK(c.vk.vkCreateDescriptorPool(c.device, &pool_info, nullptr, &pool));
  VkDescriptorSetAllocateInfo allocate{};
  allocate.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  allocate.descriptorPool = pool;
  allocate.descriptorSetCount = 1;
  allocate.pSetLayouts = &set_layout;
  TESSERA_VK_CHECK(c.vk.vkAllocateDescriptorSets(c.device, &allocate, &set));
  return {};
}

Expected<VkPipeline> createComputePipeline(Context& c, VkPipelineLayout layout,
                                           std::span<const uint32_t> spirv,
                                           const VkSpecializationInfo* specialization) {
  Expected<VkShaderModule> module = c.createShaderModule(spirv);
  if (!module) return module.error();
  VkComputePipelineCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  create.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  create.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  create.stage.module = *module;
  create.stage.pName = "main";
  create.stage.pSpecializationInfo = specialization;
  create.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  const VkResult created =
      c.vk.vkCreateComputePipelines(c.device, VK_NULL_HANDLE, 1, &create, nullptr, &pipeline);
  c.vk.vkDestroyShaderModule(c.device, *module, nullptr);
  TESSERA_VK_CHECK(created);
  return pipeline;
}

}  // namespace tessera::vulkan
