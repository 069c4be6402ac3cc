#include "vulkan/compute_blend.h"

#include <algorithm>
#include <cstring>

#include "shaders/ShadeBlend.spv.h"
#include "shaders/ShadeMask.spv.h"
#include "vulkan/descriptor_sets.h"
#include "vulkan/gpu_types.h"

namespace tessera::vulkan {

Expected<void> ComputeBlendPass::create(Context& c, VkDescriptorSetLayout scene_set_layout,
                                        uint32_t push_bytes, std::span<const uint32_t> spirv,
                                        AlphaMode mode) {
  mode_ = mode;
  VkPipelineLayout single = VK_NULL_HANDLE;
  if (Expected<void> r =
          createStorageLayouts(c, 1, VK_SHADER_STAGE_COMPUTE_BIT, push_bytes, set_layout_, single);
      !r)
    return r;
  c.vk.vkDestroyPipelineLayout(c.device, single, nullptr);
  if (Expected<void> r = allocateStorageSet(c, 1, set_layout_, pool_, set_); !r) return r;
  // Set 0 as every other pass has it (the same set layout and push range: compatible), set 1 the
  // list.
  const VkDescriptorSetLayout sets[2] = {scene_set_layout, set_layout_};
  const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes};
  VkPipelineLayoutCreateInfo layout_info{};
  layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  layout_info.setLayoutCount = 2;
  layout_info.pSetLayouts = sets;
  layout_info.pushConstantRangeCount = 1;
  layout_info.pPushConstantRanges = &push;
  TESSERA_VK_CHECK(c.vk.vkCreatePipelineLayout(c.device, &layout_info, nullptr, &layout_));
  spirv_ = spirv;
  return {};
}

void ComputeBlendPass::destroy(Context& c) {
  if (pipeline_) c.vk.vkDestroyPipeline(c.device, pipeline_, nullptr);
  if (layout_) c.vk.vkDestroyPipelineLayout(c.device, layout_, nullptr);
  if (pool_) c.vk.vkDestroyDescriptorPool(c.device, pool_, nullptr);
  if (set_layout_) c.vk.vkDestroyDescriptorSetLayout(c.device, set_layout_, nullptr);
  c.destroyBuffer(list_);
  pipeline_ = VK_NULL_HANDLE;
  layout_ = VK_NULL_HANDLE;
  pool_ = VK_NULL_HANDLE;
  set_layout_ = VK_NULL_HANDLE;
}

Expected<bool> ComputeBlendPass::prepare(Context& c, const Scene& scene,
                                         const RenderOptions& options, const PackedScene& packed) {
  if (options.projection != Projection::kPerspective) return false;
  order_.build(scene, options, packed.view_projection, mode_);
  if (order_.empty()) return false;
  if (!pipeline_) {
    Expected<VkPipeline> pipeline = createComputePipeline(c, layout_, spirv_);
    if (!pipeline) return pipeline.error();
    pipeline_ = *pipeline;
  }
  // The list: per tile an offset (tiles + 1 of them, from the start of the buffer), then the keys
  // of each tile's records in drawing order. Counted, then filled.
  const uint32_t columns = packed.frame.tile_columns, rows = packed.frame.tile_rows;
  const size_t tiles = static_cast<size_t>(columns) * rows;
  words_.assign(tiles + 1, 0);
  auto tileRange = [](int lo, int hi) {
    return std::pair{lo >> kGpuTileSizeLog2, hi >> kGpuTileSizeLog2};
  };
  for (const BlendedRecord& r : order_.records()) {
    const auto [x0, x1] = tileRange(r.box.min_x, r.box.max_x);
    const auto [y0, y1] = tileRange(r.box.min_y, r.box.max_y);
    for (int ty = y0; ty <= y1; ++ty)
      for (int tx = x0; tx <= x1; ++tx) ++words_[static_cast<size_t>(ty) * columns + tx];
  }
  uint32_t offset = static_cast<uint32_t>(tiles + 1);
  for (size_t t = 0; t <= tiles; ++t) {
    const uint32_t count = t < tiles ? words_[t] : 0;
    words_[t] = offset;
    offset += count;
  }
  words_.resize(offset);
  std::vector<uint32_t> cursor(words_.begin(), words_.begin() + static_cast<ptrdiff_t>(tiles));
  for (const BlendedRecord& r : order_.records()) {
    const auto [x0, x1] = tileRange(r.box.min_x, r.box.max_x);
    const auto [y0, y1] = tileRange(r.box.min_y, r.box.max_y);
    for (int ty = y0; ty <= y1; ++ty)
      for (int tx = x0; tx <= x1; ++tx)
        words_[cursor[static_cast<size_t>(ty) * columns + tx]++] = r.key;
  }
  if (Expected<void> r = c.ensureBuffer(list_, words_.size() * sizeof(uint32_t),
                                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryKind::kHost,
                                        "transparent pass list");
      !r)
    return r.error();
  std::memcpy(list_.mapped, words_.data(), words_.size() * sizeof(uint32_t));
  if (written_ != list_.buffer) {
    const VkDescriptorBufferInfo info{list_.buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet write{};
    write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    write.dstSet = set_;
    write.dstBinding = 0;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    write.pBufferInfo = &info;
    c.vk.vkUpdateDescriptorSets(c.device, 1, &write, 0, nullptr);
    written_ = list_.buffer;
  }
  return true;
}

void ComputeBlendPass::record(const VulkanFunctions& vk, VkCommandBuffer cmd,
                              VkDescriptorSet scene_set, VkPipelineLayout rebind_layout, int width,
                              int height) const {
  const VkDescriptorSet sets[2] = {scene_set, set_};
  vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 2, sets, 0, nullptr);
  vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vk.vkCmdDispatch(cmd, (static_cast<uint32_t>(width) + 7) / 8,
                   (static_cast<uint32_t>(height) + 7) / 8, 1);
  vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, rebind_layout, 0, 1, &scene_set,
                             0, nullptr);
}

Expected<void> AlphaPasses::create(Context& c, VkDescriptorSetLayout scene_set_layout,
                                   uint32_t push_bytes, bool atomic64) {
  if (Expected<void> r = blend.create(c, scene_set_layout, push_bytes, spirv::kShadeBlend); !r)
    return r;
  if (!atomic64) return {};
  return mask.create(c, scene_set_layout, push_bytes, spirv::kShadeMask, AlphaMode::kMask);
}

void AlphaPasses::destroy(Context& c) {
  blend.destroy(c);
  mask.destroy(c);
}

Expected<void> AlphaPasses::prepare(Context& c, const Scene& scene, const RenderOptions& options,
                                    bool atomic64, PackedScene& packed) {
  Expected<bool> blending = blend.prepare(c, scene, options, packed);
  if (!blending) return blending.error();
  blend_active = *blending;
  mask_active = false;
  if (!atomic64)
    return {};  // the 32-bit path draws masked materials opaque (docs/vulkan-features.md)
  Expected<bool> masking = mask.prepare(c, scene, options, packed);
  if (!masking) return masking.error();
  mask_active = *masking;
  if (mask_active) packed.frame.flags |= kFrameMaskPass;
  return {};
}

}  // namespace tessera::vulkan
