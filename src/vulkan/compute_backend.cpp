// The "vulkan" backend: a tiled rasterizer in compute shaders. One command buffer per frame:
//
//   clear -> transform -> setup -> bin args -> bin count -> scan -> bin fill -> fine raster
//   -> shade/resolve -> (host) lines
//
// Every pass reads what the previous ones wrote, so a global memory barrier separates each pair;
// each says what it orders. When setup asks for more clip records, or binning for more entries,
// than the buffers hold, the frame is recorded again with larger buffers (a second round): no
// triangle is ever dropped.
//
// The nonlinear projections (RenderOptions::projection other than perspective) take the same
// passes with other shaders for setup, binning, the fine raster and shading (the ray passes,
// shaders/rays.glsl): each pixel's ray, from the CPU's own RayTable, is tested against the
// triangle's planes through the eye, as the CPU does; the transform pass then runs with the view
// matrix in place of view-projection, giving camera-space positions.
#include <tessera/vulkan/vulkan_backend.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <limits>
#include <string>

#include <tessera/base/check.h>
#include <tessera/render/composite.h>

#include "render/fixed_point.h"
#include "vulkan/backend_diagnostics.h"
#include "vulkan/compute_blend.h"
#include "vulkan/compute_pipelines.h"
#include "vulkan/context.h"
#include "vulkan/descriptor_sets.h"
#include "vulkan/gpu_types.h"
#include "vulkan/pass_recorder.h"
#include "vulkan/scene_upload.h"
#include "vulkan/shadow_upload.h"

namespace tessera::vulkan {

namespace {

// Before clear, then after each of the six passes and (with diagnostics) the diagnostics passes.
constexpr uint32_t kTimestampCount = 8;
constexpr int kMaxRounds = 4;

}  // namespace

struct ComputeBackend::State {
  std::unique_ptr<Context> context;
  SceneOverlay overlay;  // points and lines on the read-back frame
  VulkanOptions vulkan_options;
  bool atomic64 = false;
  bool fp64 = false;

  ComputePipelines pipelines;
  AlphaPasses alpha;  // alphaMode MASK and BLEND (compute_blend.h)
  VkDescriptorPool descriptor_pool = VK_NULL_HANDLE;
  VkDescriptorSet descriptor_set = VK_NULL_HANDLE;
  VkQueryPool timestamps = VK_NULL_HANDLE;

  PackedScene packed;
  SceneBuffers scene_buffers;
  Buffer transformed, raster_records, shade_records, extra_base, counters, visible_list, tiles,
      bin_entries, segments, visibility, output;
  // RenderOptions::diagnostics: the diagnostics passes' counts (GpuDiagnosticsLayout); a
  // placeholder of one header otherwise, since binding 20 must hold a buffer.
  Buffer diagnostics;
  ShadowUpload shadows;  // binding 21: RenderOptions::shadows' maps, or a header naming no light
  std::vector<size_t> triangle_bases;  // fillComputeDiagnostics' scratch
  // The nonlinear projections' rays: the RayTable's layers as the shaders read them (rays.glsl),
  // rewritten only when the table is rebuilt (or the buffer was reallocated).
  RayTable ray_table;
  Buffer rays;
  bool rays_current = false;
  uint32_t bin_capacity = 0;
  uint32_t extra_capacity = 0;

  ComputeStats stats;
  TileOccupancy occupancy;
  Expected<void> last_result;

  ~State();
  Expected<void> createPipelines();
  Expected<void> ensureWorkingBuffers(const RenderOptions& options);
  Expected<void> uploadRays(const Scene& scene, const RenderOptions& options);
  void writeDescriptors();
  Expected<void> recordAndRun(const RenderOptions& options);
  // The fine raster, shading and (`diagnostic_passes`) the diagnostics passes.
  void recordTilePasses(const PassRecorder& recorder, const RenderOptions& options,
                        const ProjectionPasses& passes, bool diagnostic_passes);
  // Records and runs the frame until its bins and clip records fit (growing them), adding the
  // bin entries that did not fit to `entries_dropped`.
  Expected<void> runRounds(const RenderOptions& options, uint64_t& entries_dropped);
  void fillDiagnostics(const Scene& scene, bool diagnostic_passes, uint64_t entries_dropped,
                       double lines_ms, Frame& frame);
  Expected<void> renderFrame(const Scene& scene, const RenderOptions& options, Frame& frame);
  void readTimings(bool diagnostic_passes);
};

ComputeBackend::State::~State() {
  if (!context) return;
  Context& c = *context;
  // Teardown waits at least 5 s (still bounded) for a frame a short timeout abandoned; past that
  // the Context leaks everything rather than hang.
  c.fence_timeout_ms = std::max<uint32_t>(c.fence_timeout_ms, 5000);
  if (!c.waitForPending()) return;
  VkDevice device = c.device;
  if (descriptor_pool) c.vk.vkDestroyDescriptorPool(device, descriptor_pool, nullptr);
  pipelines.destroy(c);
  alpha.destroy(c);
  if (timestamps) c.vk.vkDestroyQueryPool(device, timestamps, nullptr);
  destroySceneBuffers(c, scene_buffers);
  for (Buffer* b :
       {&transformed, &raster_records, &shade_records, &extra_base, &counters, &visible_list,
        &tiles, &bin_entries, &segments, &visibility, &output, &rays, &diagnostics})
    c.destroyBuffer(*b);
  destroyShadowUpload(c, shadows);
}

Expected<void> ComputeBackend::State::createPipelines() {
  Context& c = *context;
  if (Expected<void> r = pipelines.create(c, atomic64, fp64); !r) return r;
  if (Expected<void> r = alpha.create(c, pipelines.set_layout, sizeof(GpuPassConstants), atomic64);
      !r)
    return r;
  if (Expected<void> r = allocateStorageSet(c, kComputeBindingCount, pipelines.set_layout,
                                            descriptor_pool, descriptor_set);
      !r)
    return r;

  if (c.caps.timestamp_valid_bits > 0) {
    VkQueryPoolCreateInfo query_info{};
    query_info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
    query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    query_info.queryCount = kTimestampCount;
    TESSERA_VK_CHECK(c.vk.vkCreateQueryPool(c.device, &query_info, nullptr, &timestamps));
  }
  return {};
}

Expected<void> ComputeBackend::State::ensureWorkingBuffers(const RenderOptions& options) {
  Context& c = *context;
  constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  const size_t pixels = static_cast<size_t>(options.width) * options.height;
  const size_t tiles_count =
      static_cast<size_t>(packed.frame.tile_columns) * static_cast<size_t>(packed.frame.tile_rows);
  const size_t records = packed.triangle_count + extra_capacity;
  const size_t segment_capacity = tiles_count + bin_capacity / kEntriesPerSegment + 1;
  if (records > 0xffffffffull || segment_capacity > 0xffffffffull)
    return makeError("the scene is too large for the vulkan backend's 32-bit record indices");
  packed.frame.extra_capacity = extra_capacity;
  packed.frame.bin_capacity = bin_capacity;
  packed.frame.segment_capacity = static_cast<uint32_t>(segment_capacity);
  const size_t output_words_per_pixel = 3 + (options.normals ? 3 : 0) + (options.coverage ? 1 : 0);

  struct Need {
    Buffer* buffer;
    size_t bytes;
    VkBufferUsageFlags usage;
    MemoryKind kind;
    const char* what;
  };
  const Need needs[] = {
      {&transformed, packed.vertex_count * sizeof(GpuTransformedVertex), kStorage,
       MemoryKind::kDevice, "transformed vertex"},
      {&raster_records, records * sizeof(GpuRasterRecord), kStorage, MemoryKind::kDevice,
       "raster record"},
      {&shade_records, records * sizeof(GpuShadeRecord), kStorage, MemoryKind::kDevice,
       "shade record"},
      {&extra_base, packed.triangle_count * sizeof(uint32_t), kStorage, MemoryKind::kDevice,
       "clip record index"},
      {&counters, sizeof(GpuCounters), kStorage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
       MemoryKind::kHost, "counter"},
      {&visible_list, records * sizeof(uint32_t), kStorage, MemoryKind::kDevice, "visible list"},
      {&tiles, tiles_count * sizeof(GpuTileBin), kStorage, MemoryKind::kHost, "tile bin"},
      {&bin_entries, static_cast<size_t>(bin_capacity) * sizeof(uint32_t), kStorage,
       MemoryKind::kDevice, "bin entry"},
      {&segments, segment_capacity * 4 * sizeof(uint32_t), kStorage, MemoryKind::kDevice,
       "raster segment"},
      {&visibility, pixels * packed.frame.layers * sizeof(uint64_t), kStorage, MemoryKind::kDevice,
       "visibility"},
      {&output, pixels * output_words_per_pixel * sizeof(uint32_t), kStorage, MemoryKind::kHost,
       "output image"},
      {&diagnostics,
       (options.diagnostics ? GpuDiagnosticsLayout::of(options.width, options.height).words
                            : size_t{kDiagHeaderWords}) *
           sizeof(uint32_t),
       kStorage, MemoryKind::kHost, "diagnostics"},
  };
  for (const Need& need : needs)
    if (Expected<void> r =
            c.ensureBuffer(*need.buffer, need.bytes, need.usage, need.kind, need.what);
        !r)
      return r;
  return {};
}

Expected<void> ComputeBackend::State::uploadRays(const Scene& scene, const RenderOptions& options) {
  constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  // The perspective passes do not read binding 19, but it must hold a buffer.
  if (options.projection == Projection::kPerspective)
    return context->ensureBuffer(rays, 0, kStorage, MemoryKind::kHost, "ray");
  const bool rebuilt = ray_table.update(options.projection, options.width, options.height,
                                        scene.camera.fov_y_degrees, options.msaa, options.jitter);
  // Layer 0 the pixel centres, then the samples; with one sample the centre is the sample.
  const int layers = options.msaa == 1 ? 1 : options.msaa + 1;
  const size_t pixels = static_cast<size_t>(options.width) * options.height;
  const size_t bytes = layers * pixels * 3 * sizeof(float);
  if (!rays.buffer || rays.size < bytes) rays_current = false;  // a new buffer holds nothing yet
  if (Expected<void> r = context->ensureBuffer(rays, bytes, kStorage, MemoryKind::kHost, "ray"); !r)
    return r;
  if (!rebuilt && rays_current) return {};
  float* out = static_cast<float*>(rays.mapped);
  for (int l = 0; l < layers; ++l) {
    const RayLayer& layer = l == 0 ? ray_table.centre() : ray_table.sample(l - 1);
    for (size_t p = 0; p < pixels; ++p, out += 3) {
      out[0] = layer.x[p];
      out[1] = layer.y[p];
      out[2] = layer.z[p];
    }
  }
  rays_current = true;
  return {};
}

void ComputeBackend::State::writeDescriptors() {
  Context& c = *context;
  std::vector<VkDescriptorBufferInfo> infos;
  appendSceneDescriptors(scene_buffers, infos);
  for (const Buffer* b : {&transformed, &raster_records, &shade_records, &extra_base, &counters,
                          &visible_list, &tiles, &bin_entries, &segments, &visibility, &output,
                          &rays, &diagnostics, &shadows.buffer})
    infos.push_back(VkDescriptorBufferInfo{b->buffer, 0, VK_WHOLE_SIZE});
  TESSERA_CHECK(infos.size() == kComputeBindingCount);
  std::vector<VkWriteDescriptorSet> writes(infos.size());
  for (size_t i = 0; i < infos.size(); ++i) {
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = descriptor_set;
    writes[i].dstBinding = static_cast<uint32_t>(i);
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  c.vk.vkUpdateDescriptorSets(c.device, static_cast<uint32_t>(writes.size()), writes.data(), 0,
                              nullptr);
}

Expected<void> ComputeBackend::State::recordAndRun(const RenderOptions& options) {
  Context& c = *context;
  const VulkanFunctions& vk = c.vk;
  // The frame constants carry this round's capacities.
  std::memcpy(scene_buffers.frame.mapped, &packed.frame, sizeof(GpuFrameConstants));
  writeDescriptors();

  Expected<VkCommandBuffer> begun = c.beginCommands();
  if (!begun) return begun.error();
  VkCommandBuffer cmd = *begun;
  const PassRecorder r{vk, cmd, pipelines.layout, counters.buffer, timestamps};

  if (timestamps) vk.vkCmdResetQueryPool(cmd, timestamps, 0, kTimestampCount);
  vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines.layout, 0, 1,
                             &descriptor_set, 0, nullptr);
  const uint64_t pixels = static_cast<uint64_t>(options.width) * options.height;
  const bool perspective = options.projection == Projection::kPerspective;
  const ProjectionPasses& passes = perspective ? pipelines.perspective : pipelines.ray;
  // Diagnostics take setup's variant that counts the cull reasons, and passes of their own
  // after shading; the frame is the same.
  const bool diagnostic_passes = options.diagnostics && perspective;
  r.timestamp(0);

  // 1. Clear.
  r.dispatch(pipelines.clear, (pixels * packed.frame.layers + 255) / 256);
  // Orders the cleared visibility buffer, tile bins and counters before setup's counter
  // atomics, binning and the fine raster's commits.
  r.computeToCompute();
  r.timestamp(1);

  // 2. Transform.
  r.dispatch(pipelines.transform, (packed.vertex_count + 255) / 256);
  // Orders the clip-space vertices before setup reads them.
  r.computeToCompute();
  r.timestamp(2);

  // 3. Setup and cull.
  r.dispatch(diagnostic_passes ? pipelines.setup_diagnostics : passes.setup,
             (packed.triangle_count + 63) / 64);
  // Orders setup's records, visible list and counters before the bin-args pass reads the count.
  r.computeToCompute();
  r.dispatch(pipelines.bin_args, 1);
  // Orders the bin passes' dispatch size before the indirect dispatch reads it.
  r.computeToIndirect();
  r.timestamp(3);

  // 4. Bin: count, scan, fill.
  r.dispatchIndirect(passes.bin, kBinDispatchOffset, 0);
  // Orders the per-tile counts before the scan reads them.
  r.computeToCompute();
  r.dispatch(pipelines.scan, 1);
  // Orders the tile offsets, the segments and the raster's dispatch size before the fill reads
  // the offsets and the raster's indirect dispatch reads its size.
  r.computeToIndirect();
  r.dispatchIndirect(passes.bin, kBinDispatchOffset, 1);
  // Orders the filled bins before the fine raster (and the diagnostics passes) read them.
  r.computeToCompute();
  r.timestamp(4);
  recordTilePasses(r, options, passes, diagnostic_passes);
  return c.submitAndWait();
}

void ComputeBackend::State::recordTilePasses(const PassRecorder& r, const RenderOptions& options,
                                             const ProjectionPasses& passes,
                                             bool diagnostic_passes) {
  const VulkanFunctions& vk = r.vk;
  VkCommandBuffer cmd = r.cmd;
  // 5. Fine raster.
  r.dispatchIndirect(passes.raster[packed.frame.layers], kRasterDispatchOffset);
  if (!atomic64) {
    // Orders the committed depths (pass 1 of the 32-bit path) before pass 2 compares with them.
    r.computeToCompute();
    r.dispatchIndirect(passes.raster_id[packed.frame.layers], kRasterDispatchOffset);
  }
  if (alpha.mask_active) {
    // 5b. The MASK pass. Orders the fine raster's commits before its own (atomics on the same
    // words: the barrier only keeps the passes from overlapping).
    r.computeToCompute();
    alpha.mask.record(vk, cmd, descriptor_set, pipelines.layout, options.width, options.height);
  }
  // Orders the visibility buffer's commits before the shade pass reads it.
  r.computeToCompute();
  r.timestamp(5);

  // 6. Shade and resolve.
  vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, passes.shade);
  vk.vkCmdDispatch(cmd, (static_cast<uint32_t>(options.width) + 7) / 8,
                   (static_cast<uint32_t>(options.height) + 7) / 8, 1);
  if (alpha.blend_active) {
    // 6b. The transparent pass. Orders the shaded output before it reads and rewrites it.
    r.computeToCompute();
    alpha.blend.record(vk, cmd, descriptor_set, pipelines.layout, options.width, options.height);
  }
  // Orders the output image, the counters and the tile counts before the host reads them
  // (after the fence).
  r.computeToHost();
  r.timestamp(6);

  if (diagnostic_passes) {
    // 7. Diagnostics: they read the records, visible list and bins the barriers above made
    // visible to every later compute pass, and write only the diagnostics buffer.
    r.dispatchIndirect(pipelines.diag_occupancy, kBinDispatchOffset);
    // Orders the occupancy's atomics before the depth-test pass writes the same buffer (other
    // words of it, but one binding: the passes must not overlap on it).
    r.computeToCompute();
    r.dispatch(pipelines.diag_tests,
               static_cast<uint64_t>(packed.frame.tile_columns) * packed.frame.tile_rows);
    // Orders the diagnostics buffer's counts before the host reads them (after the fence).
    r.computeToHost();
    r.timestamp(7);
  }
}

void ComputeBackend::State::readTimings(bool diagnostic_passes) {
  PassTimings& t = stats.timings;
  t = PassTimings{};
  if (!timestamps) return;
  Context& c = *context;
  uint64_t ticks[kTimestampCount] = {};
  const uint32_t written = diagnostic_passes ? kTimestampCount : kTimestampCount - 1;
  const VkResult got = c.vk.vkGetQueryPoolResults(
      c.device, timestamps, 0, written, sizeof(ticks), ticks, sizeof(uint64_t),
      VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
  if (got != VK_SUCCESS) return;  // timings are diagnostics: a frame never fails over them
  const uint32_t bits = c.caps.timestamp_valid_bits;
  const uint64_t mask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
  const double ms_per_tick = c.caps.properties.limits.timestampPeriod * 1e-6;
  auto span = [&](int a, int b) {
    return static_cast<double>((ticks[b] - ticks[a]) & mask) * ms_per_tick;
  };
  t.clear = span(0, 1);
  t.transform = span(1, 2);
  t.setup = span(2, 3);
  t.bin = span(3, 4);
  t.raster = span(4, 5);
  t.shade = span(5, 6);
  t.total = span(0, 6);
  if (diagnostic_passes) t.diagnostics = span(6, 7);
  t.valid = true;
}

Expected<void> ComputeBackend::State::runRounds(const RenderOptions& options,
                                                uint64_t& entries_dropped) {
  for (int round = 0;; ++round) {
    if (Expected<void> r = ensureWorkingBuffers(options); !r) return r;
    // The diagnostics passes add into a zeroed buffer (host-coherent: the submit makes the
    // zeros visible to the device).
    if (options.diagnostics) std::memset(diagnostics.mapped, 0, diagnostics.size);
    if (Expected<void> r = recordAndRun(options); !r) return r;
    const GpuCounters* counted = static_cast<const GpuCounters*>(counters.mapped);
    const bool extra_overflow = counted->extra > extra_capacity;
    const bool bin_overflow = counted->bin_entries > bin_capacity;
    if (!extra_overflow && !bin_overflow) return {};
    ++stats.bin_overflows;
    if (bin_overflow) entries_dropped += counted->bin_entries - bin_capacity;
    if (round + 1 >= kMaxRounds)
      return makeError("the vulkan backend's bins kept overflowing after " +
                       std::to_string(kMaxRounds) + " rounds");
    // Grow to what was asked for, with headroom for the next frames.
    auto grown = [](uint64_t asked) {
      return static_cast<uint32_t>(std::min<uint64_t>(asked + asked / 4 + 64, 0xffffffffull));
    };
    if (extra_overflow) extra_capacity = grown(counted->extra);
    if (bin_overflow) bin_capacity = grown(counted->bin_entries);
  }
}

void ComputeBackend::State::fillDiagnostics(const Scene& scene, bool diagnostic_passes,
                                            uint64_t entries_dropped, double lines_ms,
                                            Frame& frame) {
  const PassTimings& t = stats.timings;
  ComputeDiagnosticsInput in;
  in.words = static_cast<const uint32_t*>(diagnostics.mapped);
  in.counters = static_cast<const GpuCounters*>(counters.mapped);
  in.gpu_tile_columns = packed.frame.tile_columns;
  in.gpu_tile_rows = packed.frame.tile_rows;
  in.pixel_tests = diagnostic_passes;
  in.triangles_in = packed.triangle_count;
  in.bin_overflow = entries_dropped;
  // The CPU's stages: setup includes binning; the tile stage clears, rasterizes and shades.
  in.times = {t.transform, t.setup + t.bin, t.clear + t.raster + t.shade, lines_ms, t.diagnostics};
  fillComputeDiagnostics(scene, in, triangle_bases, frame);
}

Expected<void> ComputeBackend::State::renderFrame(const Scene& scene, const RenderOptions& options,
                                                  Frame& frame) {
  // Nothing the GPU may still read (an earlier frame abandoned after a timeout) is touched
  // before that frame has finished: buffers, descriptors and mapped inputs alike.
  if (Expected<void> r = context->waitForPending(); !r)
    return makeError("an earlier frame is still running: " + r.error().message);
  if (options.projection != Projection::kPerspective) {
    const float aspect = static_cast<float>(options.width) / static_cast<float>(options.height);
    if (std::string problem =
            checkViewAngle(options.projection, scene.camera.fov_y_degrees, aspect);
        !problem.empty())
      return makeError(problem);
    if (!(scene.camera.far_z > scene.camera.near_z && scene.camera.near_z >= 0.0f))
      return makeError("the " + std::string(projectionName(options.projection)) +
                       " projection needs 0 <= near < far");
  }
  if (Expected<void> r = packScene(scene, options, IndexPolicy::kAsGiven, packed); !r) return r;
  if (Expected<void> r = uploadScene(*context, packed, scene_buffers); !r) return r;
  if (Expected<void> r = alpha.prepare(*context, scene, options, atomic64, packed); !r) return r;
  const bool ray_passes = options.projection != Projection::kPerspective;
  if (Expected<void> r = pipelines.ensureProjection(*context, ray_passes); !r) return r;
  if (Expected<void> r = pipelines.ensureRaster(*context, packed.frame.layers, ray_passes); !r)
    return r;
  if (Expected<void> r = uploadRays(scene, options); !r) return r;
  if (Expected<void> r = uploadShadows(*context, scene, options, shadows); !r) return r;
  const bool diagnostic_passes = options.diagnostics && !ray_passes;
  if (diagnostic_passes)
    if (Expected<void> r = pipelines.ensureDiagnostics(*context); !r) return r;

  // First-frame capacities: every visible triangle in a few tiles, a few clipped triangles.
  if (bin_capacity == 0)
    bin_capacity = vulkan_options.initial_bin_capacity
                       ? vulkan_options.initial_bin_capacity
                       : static_cast<uint32_t>(std::min<size_t>(
                             std::max<size_t>(65536, packed.triangle_count * 4), 1u << 28));
  if (extra_capacity == 0) extra_capacity = 1024;

  stats = ComputeStats{};
  uint64_t entries_dropped = 0;  // bin entries that did not fit, over the rounds
  if (Expected<void> r = runRounds(options, entries_dropped); !r) return r;
  const GpuCounters* counted = static_cast<const GpuCounters*>(counters.mapped);

  // Results.
  const size_t n = frame.pixelCount();
  const uint32_t* words = static_cast<const uint32_t*>(output.mapped);
  copyResults(words, words + n, words + 2 * n,
              options.normals ? reinterpret_cast<const float*>(words + 3 * n) : nullptr, 3, frame);
  if (options.coverage) {
    const uint32_t* coverage = words + (options.normals ? 6 : 3) * n;
    for (size_t p = 0; p < n; ++p) frame.coverage[p] = static_cast<uint8_t>(coverage[p]);
  }
  const auto lines_start = std::chrono::steady_clock::now();
  drawSceneOverlay(scene, options, packed, overlay, frame);
  const double lines_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - lines_start)
          .count();

  stats.triangles_in = packed.triangle_count;
  stats.triangles_culled = counted->culled;
  stats.triangles_clipped = counted->clipped;
  stats.triangles_setup = counted->visible;
  stats.triangles_binned = counted->binned_records;
  stats.bin_entries = counted->bin_entries;
  stats.bin_capacity = bin_capacity;
  stats.tiles = static_cast<size_t>(packed.frame.tile_columns) * packed.frame.tile_rows;
  stats.tiles_occupied = counted->occupied_tiles;
  stats.max_tile_entries = counted->max_tile_entries;
  stats.raster_workgroups = counted->segments;
  stats.int64_atomics = atomic64;
  stats.fp64_setup = fp64;
  readTimings(diagnostic_passes);
  if (options.diagnostics)
    fillDiagnostics(scene, diagnostic_passes, entries_dropped, lines_ms, frame);

  occupancy.columns = packed.frame.tile_columns;
  occupancy.rows = packed.frame.tile_rows;
  occupancy.tile_size = kGpuTileSize;
  occupancy.entries.resize(stats.tiles);
  const GpuTileBin* bins = static_cast<const GpuTileBin*>(tiles.mapped);
  for (size_t i = 0; i < stats.tiles; ++i) occupancy.entries[i] = bins[i].count;
  return {};
}

// ---- the public class ----

Expected<std::unique_ptr<ComputeBackend>> ComputeBackend::create(const VulkanOptions& options) {
  Expected<std::unique_ptr<Context>> context = Context::create(options, BackendKind::kCompute);
  if (!context) return context.error();
  auto state = std::make_unique<State>();
  state->context = std::move(*context);
  state->vulkan_options = options;
  state->atomic64 = state->context->caps.int64_atomics && !options.force_32bit_atomics;
  state->fp64 = state->context->caps.shader_float64 && !options.force_fp32_setup;
  if (Expected<void> r = state->createPipelines(); !r) return r.error();
  return std::unique_ptr<ComputeBackend>(new ComputeBackend(std::move(state)));
}

ComputeBackend::ComputeBackend(std::unique_ptr<State> state) : state_(std::move(state)) {}
ComputeBackend::~ComputeBackend() = default;

void ComputeBackend::render(const Scene& scene, const RenderOptions& requested, Frame& frame) {
  const RenderOptions options = withCompositeInputs(scene, withDiagnosticInputs(requested));
  frame.diagnostics.valid = false;
  state_->last_result = renderIntoFrame(scene, options, frame,
                                        [&] { return state_->renderFrame(scene, options, frame); });
}

Expected<void> ComputeBackend::lastResult() const {
  return state_->last_result;
}
const ComputeStats& ComputeBackend::lastStats() const {
  return state_->stats;
}
const TileOccupancy& ComputeBackend::lastTileOccupancy() const {
  return state_->occupancy;
}
const DeviceInfo& ComputeBackend::device() const {
  return state_->context->info;
}
std::vector<std::string> ComputeBackend::validationErrors() const {
  return state_->context->validationErrors();
}
void ComputeBackend::setFenceTimeout(uint32_t milliseconds) {
  state_->context->fence_timeout_ms = milliseconds;
}
bool ComputeBackend::uses64BitCommits() const {
  return state_->atomic64;
}
Expected<void> ComputeBackend::setForce32BitAtomics(bool force) {
  if (force == state_->vulkan_options.force_32bit_atomics) return {};
  VulkanOptions options = state_->vulkan_options;
  options.device = state_->context->info.index;
  options.force_32bit_atomics = force;
  options.fence_timeout_ms = state_->context->fence_timeout_ms;
  // A new context and pipelines, made before the old ones go: a failure keeps the working state.
  Expected<std::unique_ptr<ComputeBackend>> fresh = create(options);
  if (!fresh) return fresh.error();
  state_ = std::move((*fresh)->state_);
  return {};
}

Expected<std::unique_ptr<Backend>> makeComputeBackend(const VulkanOptions& options) {
  Expected<std::unique_ptr<ComputeBackend>> backend = ComputeBackend::create(options);
  if (!backend) return backend.error();
  return std::unique_ptr<Backend>(std::move(*backend));
}

}  // namespace tessera::vulkan
