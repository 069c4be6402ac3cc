#include "vulkan/compute_pipelines.h"

#include <vector>

#include <tessera/base/check.h>

#include "shaders/Bin.spv.h"
#include "shaders/BinArgs.spv.h"
#include "shaders/Clear.spv.h"
#include "shaders/DiagOccupancy.spv.h"
#include "shaders/DiagTests.spv.h"
#include "shaders/RasterAtomic64.spv.h"
#include "shaders/RasterDepth32.spv.h"
#include "shaders/RasterId32.spv.h"
#include "shaders/RayBin.spv.h"
#include "shaders/RayRasterAtomic64Fp32.spv.h"
#include "shaders/RayRasterAtomic64Fp64.spv.h"
#include "shaders/RayRasterDepth32Fp32.spv.h"
#include "shaders/RayRasterDepth32Fp64.spv.h"
#include "shaders/RayRasterId32Fp32.spv.h"
#include "shaders/RayRasterId32Fp64.spv.h"
#include "shaders/RaySetup.spv.h"
#include "shaders/RayShade.spv.h"
#include "shaders/Scan.spv.h"
#include "shaders/SetupDiagnosticsFp32.spv.h"
#include "shaders/SetupDiagnosticsFp64.spv.h"
#include "shaders/SetupFp32.spv.h"
#include "shaders/SetupFp64.spv.h"
#include "shaders/Shade.spv.h"
#include "shaders/TransformFp32.spv.h"
#include "shaders/TransformFp64.spv.h"
#include "vulkan/descriptor_sets.h"

namespace tessera::vulkan {

namespace {

using Spirv = std::span<const uint32_t>;

// The fine raster's shaders: the commit (64-bit atomics, or the 32-bit path's two passes) and,
// for the ray passes, the depth's division (double or float).
struct RasterShaders {
  Spirv first, second;  // second: the 32-bit path's key pass, empty with 64-bit atomics
};

RasterShaders rasterShaders(bool ray, bool atomic64, bool fp64) {
  if (!ray) {
    if (atomic64) return {spirv::kRasterAtomic64, {}};
    return {spirv::kRasterDepth32, spirv::kRasterId32};
  }
  if (atomic64)
    return {fp64 ? Spirv(spirv::kRayRasterAtomic64Fp64) : spirv::kRayRasterAtomic64Fp32, {}};
  if (fp64) return {spirv::kRayRasterDepth32Fp64, spirv::kRayRasterId32Fp64};
  return {spirv::kRayRasterDepth32Fp32, spirv::kRayRasterId32Fp32};
}

}  // namespace

Expected<void> ComputePipelines::create(Context& c, bool with_atomic64, bool with_fp64) {
  atomic64 = with_atomic64;
  fp64 = with_fp64;
  if (Expected<void> r = createStorageLayouts(c, kComputeBindingCount, VK_SHADER_STAGE_COMPUTE_BIT,
                                              sizeof(GpuPassConstants), set_layout, layout);
      !r)
    return r;

  struct Entry {
    VkPipeline* pipeline;
    Spirv spirv;
  };
  const Entry entries[] = {
      {&clear, spirv::kClear},
      {&transform, fp64 ? Spirv(spirv::kTransformFp64) : Spirv(spirv::kTransformFp32)},
      {&bin_args, spirv::kBinArgs},
      {&scan, spirv::kScan},
  };
  for (const Entry& e : entries) {
    Expected<VkPipeline> pipeline = createComputePipeline(c, layout, e.spirv);
    if (!pipeline) return pipeline.error();
    *e.pipeline = *pipeline;
  }
  return {};
}

Expected<void> ComputePipelines::ensureProjection(Context& c, bool ray_passes) {
  ProjectionPasses& passes = ray_passes ? ray : perspective;
  struct Entry {
    VkPipeline* pipeline;
    Spirv spirv;
  };
  const Spirv setup = ray_passes ? Spirv(spirv::kRaySetup)
                      : fp64     ? Spirv(spirv::kSetupFp64)
                                 : Spirv(spirv::kSetupFp32);
  const Entry entries[] = {
      {&passes.setup, setup},
      {&passes.bin, ray_passes ? Spirv(spirv::kRayBin) : Spirv(spirv::kBin)},
      {&passes.shade, ray_passes ? Spirv(spirv::kRayShade) : Spirv(spirv::kShade)},
  };
  for (const Entry& e : entries) {
    if (*e.pipeline) continue;
    Expected<VkPipeline> pipeline = createComputePipeline(c, layout, e.spirv);
    if (!pipeline) return pipeline.error();
    *e.pipeline = *pipeline;
  }
  return {};
}

Expected<void> ComputePipelines::ensureRaster(Context& c, uint32_t layers, bool ray_passes) {
  TESSERA_CHECK(layers >= 1 && layers <= kMaxVisibilityLayers) << layers << " layers";
  ProjectionPasses& passes = ray_passes ? ray : perspective;
  if (passes.raster[layers]) return {};
  // raster.comp's shared memory for a batch of B records: edge coefficients, thresholds per
  // layer, depth plane and key, 32 half-row buckets; B = 64 unless that does not fit. (The ray
  // passes stage less per record: 48 bytes, and no thresholds.)
  auto shared_bytes = [&](uint32_t batch) { return batch * (176 + 12 * layers) + 128; };
  const uint32_t batch =
      shared_bytes(64) <= c.caps.properties.limits.maxComputeSharedMemorySize ? 64 : 32;
  const uint32_t constants[2] = {layers, batch};
  const VkSpecializationMapEntry map[2] = {{0, 0, sizeof(uint32_t)},
                                           {1, sizeof(uint32_t), sizeof(uint32_t)}};
  const VkSpecializationInfo specialization{2, map, sizeof(constants), constants};
  const RasterShaders shaders = rasterShaders(ray_passes, atomic64, fp64);
  Expected<VkPipeline> first = createComputePipeline(c, layout, shaders.first, &specialization);
  if (!first) return first.error();
  passes.raster[layers] = *first;
  if (!shaders.second.empty()) {
    Expected<VkPipeline> second = createComputePipeline(c, layout, shaders.second, &specialization);
    if (!second) return second.error();
    passes.raster_id[layers] = *second;
  }
  return {};
}

Expected<void> ComputePipelines::ensureDiagnostics(Context& c) {
  if (diag_tests) return {};
  struct Entry {
    VkPipeline* pipeline;
    Spirv spirv;
  };
  const Entry entries[] = {
      {&setup_diagnostics,
       fp64 ? Spirv(spirv::kSetupDiagnosticsFp64) : Spirv(spirv::kSetupDiagnosticsFp32)},
      {&diag_occupancy, spirv::kDiagOccupancy},
      {&diag_tests, spirv::kDiagTests},
  };
  for (const Entry& e : entries) {
    if (*e.pipeline) continue;
    Expected<VkPipeline> pipeline = createComputePipeline(c, layout, e.spirv);
    if (!pipeline) return pipeline.error();
    *e.pipeline = *pipeline;
  }
  return {};
}

void ComputePipelines::destroy(Context& c) {
  VkDevice device = c.device;
  for (VkPipeline p :
       {clear, transform, bin_args, scan, setup_diagnostics, diag_occupancy, diag_tests}) {
    if (p) c.vk.vkDestroyPipeline(device, p, nullptr);
  }
  for (ProjectionPasses* passes : {&perspective, &ray}) {
    for (VkPipeline p : {passes->setup, passes->bin, passes->shade})
      if (p) c.vk.vkDestroyPipeline(device, p, nullptr);
    for (int l = 0; l <= kMaxVisibilityLayers; ++l) {
      if (passes->raster[l]) c.vk.vkDestroyPipeline(device, passes->raster[l], nullptr);
      if (passes->raster_id[l]) c.vk.vkDestroyPipeline(device, passes->raster_id[l], nullptr);
    }
  }
  if (layout) c.vk.vkDestroyPipelineLayout(device, layout, nullptr);
  if (set_layout) c.vk.vkDestroyDescriptorSetLayout(device, set_layout, nullptr);
}

}  // namespace tessera::vulkan
