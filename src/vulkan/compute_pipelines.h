// The compute backend's pipelines: one descriptor set layout (every binding a storage buffer) and
// push-constant range for all of them, the passes every frame runs (clear, transform, bin args,
// scan), and two sets of the passes that depend on the projection: the classic pipeline's
// (perspective: edge functions on projected vertices) and the ray passes' (the nonlinear
// projections: each pixel's ray tested against the triangle's planes). Only the first are made with
// the backend: a projection's passes on its first frame (their shade shaders are the largest, and
// lavapipe takes most of a second to compile each), the fine raster's per visibility layer count,
// which sizes their shared memory.
#pragma once

#include <cstdint>
#include <span>

#include <tessera/base/expected.h>

#include "vulkan/context.h"
#include "vulkan/gpu_types.h"

namespace tessera::vulkan {

// The passes whose shaders differ between the classic pipeline and the ray passes.
struct ProjectionPasses {
  VkPipeline setup = VK_NULL_HANDLE, bin = VK_NULL_HANDLE, shade = VK_NULL_HANDLE;
  // Fine raster by visibility layers per pixel; raster_id is the 32-bit path's second pass.
  VkPipeline raster[kMaxVisibilityLayers + 1] = {}, raster_id[kMaxVisibilityLayers + 1] = {};
};

struct ComputePipelines {
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline clear = VK_NULL_HANDLE, transform = VK_NULL_HANDLE, bin_args = VK_NULL_HANDLE,
             scan = VK_NULL_HANDLE;
  ProjectionPasses perspective, ray;
  // RenderOptions::diagnostics (perspective frames): setup counting its cull reasons, then the
  // occupancy and depth-test passes. Made on the first frame that asks for diagnostics.
  VkPipeline setup_diagnostics = VK_NULL_HANDLE, diag_occupancy = VK_NULL_HANDLE,
             diag_tests = VK_NULL_HANDLE;
  bool atomic64 = false;  // 64-bit atomic commits, else the two 32-bit passes
  bool fp64 = false;      // divisions in double

  // Makes the layouts and the passes every frame runs.
  Expected<void> create(Context& context, bool with_atomic64, bool with_fp64);
  // The setup, bin and shade passes of the classic pipeline or of the ray passes.
  Expected<void> ensureProjection(Context& context, bool ray);
  // The fine raster's pipelines for `layers` visibility layers, of the ray passes or not.
  Expected<void> ensureRaster(Context& context, uint32_t layers, bool ray);
  Expected<void> ensureDiagnostics(Context& context);
  void destroy(Context& context);
};

}  // namespace tessera::vulkan
