// The compute backend's transparent pass (alphaMode BLEND): the host orders the blended records
// as the CPU does (blend_order.h) and bins them, in that order, to the 16x16 tiles; after shading,
// one invocation per pixel walks its tile's list and composites them over the shaded colour
// (shaders/blend_pass.glsl). Its list lives in a descriptor set of its own (set 1), so the
// backend's set 0 and every other pass are unchanged.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/render/options.h>
#include <tessera/scene/scene.h>

#include "vulkan/blend_order.h"
#include "vulkan/context.h"
#include "vulkan/scene_upload.h"

namespace tessera::vulkan {

// With AlphaMode::kMask the same machinery runs the MASK pass (shaders/mask_pass.glsl): the masked
// records, binned in submission order, commit their depth and key where the alpha test passes,
// between the fine raster and shading.
class ComputeBlendPass {
 public:
  // The pass's layouts over the backend's set 0 (`scene_set_layout`) and `push_bytes` of push
  // constants, as the other passes' layout has them; its pipeline (`spirv`: shade.comp's blend or
  // mask variant, which lavapipe takes half a second to compile) on the first frame that has
  // records for it.
  Expected<void> create(Context& context, VkDescriptorSetLayout scene_set_layout,
                        uint32_t push_bytes, std::span<const uint32_t> spirv,
                        AlphaMode mode = AlphaMode::kBlend);
  void destroy(Context& context);
  // Orders and bins this frame's blended records. False when there are none (or the projection is
  // a nonlinear one, where blended materials are drawn opaque): record() is then not called.
  Expected<bool> prepare(Context& context, const Scene& scene, const RenderOptions& options,
                         const PackedScene& packed);
  // The pass, after shading (the caller orders the shaded output before it and the host's read
  // after it). Binds set 0 (`scene_set`) with its own layout, and `rebind_layout` afterwards.
  void record(const VulkanFunctions& vk, VkCommandBuffer cmd, VkDescriptorSet scene_set,
              VkPipelineLayout rebind_layout, int width, int height) const;
  size_t recordCount() const { return order_.records().size(); }

 private:
  AlphaMode mode_ = AlphaMode::kBlend;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  std::span<const uint32_t> spirv_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  Buffer list_;
  VkBuffer written_ = VK_NULL_HANDLE;  // the buffer set 1 names
  BlendDrawOrder order_;
  std::vector<uint32_t> words_;
};

// The compute backend's two alpha passes and whether this frame runs them.
struct AlphaPasses {
  ComputeBlendPass blend;  // alphaMode BLEND: the transparent pass after shading
  ComputeBlendPass mask;   // alphaMode MASK: after the fine raster (64-bit commits only)
  bool blend_active = false, mask_active = false;

  Expected<void> create(Context& context, VkDescriptorSetLayout scene_set_layout,
                        uint32_t push_bytes, bool atomic64);
  void destroy(Context& context);
  // This frame's lists; with a MASK pass, sets kFrameMaskPass in `packed` (setup then leaves the
  // masked records to it). Without 64-bit commits masked materials are drawn opaque.
  Expected<void> prepare(Context& context, const Scene& scene, const RenderOptions& options,
                         bool atomic64, PackedScene& packed);
};

}  // namespace tessera::vulkan
