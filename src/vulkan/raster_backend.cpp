// The "vulkan-raster" backend: the scene through Vulkan's graphics pipeline. One indexed draw per
// object in each pass of src/vulkan/raster_passes.h:
//   - the AOV pass (one sample): packed sRGB colour, triangle id, world normal and depth, copied
//     into a mapped buffer; with MSAA it still gives the id, depth and normal AOVs (and the
//     depth the lines are tested against), which are the pixel centre's at any sample count;
//   - with options.msaa > 1, the multisample pass: the pipeline's own multisampling at the
//     standard sample positions, resolved to linear colour and coverage, encoded on the host;
//   - with blended materials (alphaMode BLEND; raster_blend.h) the same pass (at one sample too)
//     draws them after the opaque ones, back to front, blended in its linear colour; the AOV pass
//     then gives the AOVs only.
// Then the CPU's line pass draws the axes on the host.
//
// Window coordinates match the CPU's: the zero-to-one projection gives the same window z, and a
// negative-height viewport puts pixel (0, 0) at the top left with Y up in NDC, so the OpenGL
// winding rule (counter-clockwise in NDC is front-facing) holds unchanged.
#include <tessera/vulkan/vulkan_backend.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>

#include <tessera/base/check.h>
#include <tessera/render/composite.h>
#include <tessera/scene/color.h>

#include "shaders/MeshFrag.spv.h"
#include "shaders/MeshFragBlend.spv.h"
#include "shaders/MeshFragMsaa.spv.h"
#include "vulkan/backend_diagnostics.h"
#include "vulkan/context.h"
#include "vulkan/descriptor_sets.h"
#include "vulkan/gpu_types.h"
#include "vulkan/raster_blend.h"
#include "vulkan/raster_passes.h"
#include "vulkan/scene_upload.h"
#include "vulkan/shadow_upload.h"

namespace tessera::vulkan {

namespace {

// The readback buffer, per pixel: normal (16 bytes), resolved linear colour (8), packed colour,
// id and depth (4 each). Each region starts at a multiple of its texel size.
struct ReadbackLayout {
  VkDeviceSize normal, resolved, color, id, depth, total;
};
ReadbackLayout readbackLayout(size_t pixels) {
  return {0, pixels * 16, pixels * 24, pixels * 28, pixels * 32, pixels * 36};
}

// IEEE half to float (the resolved RGBA16F colour).
float halfToFloat(uint16_t h) {
  const uint32_t sign = static_cast<uint32_t>(h & 0x8000u) << 16;
  const uint32_t exponent = (h >> 10) & 0x1fu, mantissa = h & 0x3ffu;
  if (exponent == 0) {  // zero or subnormal: mantissa * 2^-24
    const float value = std::ldexp(static_cast<float>(mantissa), -24);
    return sign ? -value : value;
  }
  uint32_t bits = sign | (exponent == 31 ? 0x7f800000u | (mantissa << 13)
                                         : ((exponent + 112) << 23) | (mantissa << 13));
  float value;
  std::memcpy(&value, &bits, sizeof(value));
  return value;
}

}  // namespace

struct RasterBackend::State {
  std::unique_ptr<Context> context;
  SceneOverlay overlay;  // points and lines on the read-back frame
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
  VkDescriptorPool descriptor_pool = VK_NULL_HANDLE;
  VkDescriptorSet descriptor_set = VK_NULL_HANDLE;
  VkRenderPass aov_pass = VK_NULL_HANDLE;
  VkPipeline aov_pipelines[3] = {};  // by CullMode: back, front, none
  // The multisample pass of the last sample count used (made on first use), and its pipelines.
  int ms_samples = 0;
  VkRenderPass ms_pass = VK_NULL_HANDLE;
  VkPipeline ms_pipelines[3] = {};
  VkPipeline ms_blend_pipelines[3] = {};  // the transparent pass's, in the same pass
  RasterBlendDraws blend;                 // this frame's blended triangles
  bool blending = false;
  VkQueryPool timestamps = VK_NULL_HANDLE;

  PassTargets aov_targets, ms_targets;
  Buffer readback;
  std::vector<uint32_t> resolved_colors;  // the multisample pass's colour, encoded
  std::vector<size_t> triangle_bases;     // fillRasterDiagnostics' scratch

  PackedScene packed;
  SceneBuffers scene_buffers;
  ShadowUpload shadows;  // binding 21: RenderOptions::shadows' maps, or a header naming no light
  RasterStats stats;
  Expected<void> last_result;

  ~State();
  Expected<void> createPipelines();
  Expected<void> ensureMultisamplePass(int samples);
  // The mesh pipelines this frame's draws use (`samples`: the linear pass's, 0 without it).
  Expected<void> ensureMeshPipelines(int samples, bool aov_pass_needed);
  Expected<void> ensureTargets(int w, int h, int samples, bool aov_pass_needed);
  void destroyMultisamplePass();
  void writeDescriptors();
  void recordPass(VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer framebuffer,
                  const VkPipeline pipelines[3], const VkClearValue* clears, uint32_t clear_count,
                  const VkPipeline* blend_pipelines = nullptr);
  void recordBlendDraws(VkCommandBuffer cmd, const VkPipeline blend_pipelines[3]);
  void recordPasses(VkCommandBuffer cmd, int samples, int linear_samples, bool aov_pass_needed,
                    const ReadbackLayout& layout);
  void recordCopy(VkCommandBuffer cmd, const Image& image, bool depth, VkDeviceSize offset);
  void resolveOnHost(int samples, Frame& frame);
  void readResults(int samples, bool aov_pass_ran, Frame& frame);
  Expected<void> renderFrame(const Scene& scene, const RenderOptions& options, Frame& frame);
  void readTimings();
};

RasterBackend::State::~State() {
  if (!context) return;
  Context& c = *context;
  // Teardown waits at least 5 s (still bounded) for a frame a short timeout abandoned; past that
  // the Context leaks everything rather than hang.
  c.fence_timeout_ms = std::max<uint32_t>(c.fence_timeout_ms, 5000);
  if (!c.waitForPending()) return;
  destroyPassTargets(c, aov_targets);
  destroyPassTargets(c, ms_targets);
  destroyMultisamplePass();
  for (VkPipeline p : aov_pipelines)
    if (p) c.vk.vkDestroyPipeline(c.device, p, nullptr);
  if (aov_pass) c.vk.vkDestroyRenderPass(c.device, aov_pass, nullptr);
  if (pipeline_layout) c.vk.vkDestroyPipelineLayout(c.device, pipeline_layout, nullptr);
  if (descriptor_pool) c.vk.vkDestroyDescriptorPool(c.device, descriptor_pool, nullptr);
  if (set_layout) c.vk.vkDestroyDescriptorSetLayout(c.device, set_layout, nullptr);
  if (timestamps) c.vk.vkDestroyQueryPool(c.device, timestamps, nullptr);
  destroySceneBuffers(c, scene_buffers);
  destroyShadowUpload(c, shadows);
  c.destroyBuffer(readback);
}

Expected<void> RasterBackend::State::createPipelines() {
  Context& c = *context;
  const VulkanFunctions& vk = c.vk;
  constexpr VkShaderStageFlags kStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

  // The scene inputs (0..7) and the shadow maps (21, read by mesh.frag). Push constants: the
  // object; the transparent pass's first triangle (mesh.frag).
  constexpr uint32_t kBindings[] = {0, 1, 2, 3, 4, 5, 6, 7, kBindingShadows};
  static_assert(std::size(kBindings) == kSceneBindingCount + 1);
  if (Expected<void> r = createStorageLayouts(c, kBindings, kStages, 2 * sizeof(uint32_t),
                                              set_layout, pipeline_layout);
      !r)
    return r;
  if (Expected<void> r =
          allocateStorageSet(c, std::size(kBindings), set_layout, descriptor_pool, descriptor_set);
      !r)
    return r;

  Expected<VkRenderPass> pass = createAovPass(c);
  if (!pass) return pass.error();
  aov_pass = *pass;

  if (c.caps.timestamp_valid_bits > 0) {
    VkQueryPoolCreateInfo query_info{};
    query_info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
    query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    query_info.queryCount = 2;
    TESSERA_VK_CHECK(vk.vkCreateQueryPool(c.device, &query_info, nullptr, &timestamps));
  }
  return {};
}

void RasterBackend::State::destroyMultisamplePass() {
  Context& c = *context;
  for (VkPipeline* list : {ms_pipelines, ms_blend_pipelines})
    for (int i = 0; i < 3; ++i) {
      if (list[i]) c.vk.vkDestroyPipeline(c.device, list[i], nullptr);
      list[i] = VK_NULL_HANDLE;
    }
  if (ms_pass) c.vk.vkDestroyRenderPass(c.device, ms_pass, nullptr);
  ms_pass = VK_NULL_HANDLE;
  ms_samples = 0;
}

Expected<void> RasterBackend::State::ensureMultisamplePass(int samples) {
  if (ms_samples == samples) return {};
  Context& c = *context;
  destroyPassTargets(c, ms_targets);
  destroyMultisamplePass();
  Expected<VkRenderPass> pass = createMultisamplePass(c, samples);
  if (!pass) return pass.error();
  ms_pass = *pass;
  ms_samples = samples;
  return {};
}

Expected<void> RasterBackend::State::ensureMeshPipelines(int samples, bool aov_pass_needed) {
  Context& c = *context;
  // The cull modes the frame's draws use, opaque and blended (bit i for CullMode i).
  uint32_t opaque = 0, blended = 0;
  for (const GpuObject& object : packed.objects)
    if (object.triangle_count > 0) opaque |= 1u << std::min(object.cull, 2u);
  if (blending)
    for (const RasterBlendRun& run : blend.runs())
      blended |= 1u << std::min(packed.objects[run.object].cull, 2u);
  if (aov_pass_needed)
    if (Expected<void> r = createMeshPipelines(c, pipeline_layout, aov_pass, 1, 3, spirv::kMeshFrag,
                                               aov_pipelines, opaque);
        !r)
      return r;
  if (samples == 0) return {};
  if (Expected<void> r = createMeshPipelines(c, pipeline_layout, ms_pass, samples, 1,
                                             spirv::kMeshFragMsaa, ms_pipelines, opaque);
      !r)
    return r;
  return createMeshPipelines(c, pipeline_layout, ms_pass, samples, 1, spirv::kMeshFragBlend,
                             ms_blend_pipelines, blended, true);
}

Expected<void> RasterBackend::State::ensureTargets(int w, int h, int samples,
                                                   bool aov_pass_needed) {
  Context& c = *context;
  if (aov_pass_needed && (aov_targets.width != w || aov_targets.height != h))
    if (Expected<void> r = createPassTargets(c, aov_pass, w, h, 1, aov_targets); !r) return r;
  if (samples > 0) {  // the linear pass: MSAA, or blended materials at one sample
    if (Expected<void> r = ensureMultisamplePass(samples); !r) return r;
    if (ms_targets.width != w || ms_targets.height != h || ms_targets.samples != samples)
      if (Expected<void> r = createPassTargets(c, ms_pass, w, h, samples, ms_targets, true); !r)
        return r;
  }
  const size_t pixels = static_cast<size_t>(w) * h;
  return c.ensureBuffer(readback, readbackLayout(pixels).total, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        MemoryKind::kHost, "readback");
}

void RasterBackend::State::writeDescriptors() {
  std::vector<VkDescriptorBufferInfo> infos;
  appendSceneDescriptors(scene_buffers, infos);
  VkWriteDescriptorSet writes[kSceneBindingCount]{};
  for (uint32_t i = 0; i < kSceneBindingCount; ++i) {
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = descriptor_set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  context->vk.vkUpdateDescriptorSets(context->device, kSceneBindingCount, writes, 0, nullptr);
  writeShadowDescriptor(*context, descriptor_set, shadows);
}

void RasterBackend::State::recordPass(VkCommandBuffer cmd, VkRenderPass pass,
                                      VkFramebuffer framebuffer, const VkPipeline pipelines[3],
                                      const VkClearValue* clears, uint32_t clear_count,
                                      const VkPipeline* blend_pipelines) {
  const VulkanFunctions& vk = context->vk;
  const int width = packed.frame.width, height = packed.frame.height;
  VkRenderPassBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  begin.renderPass = pass;
  begin.framebuffer = framebuffer;
  begin.renderArea = {{0, 0}, {static_cast<uint32_t>(width), static_cast<uint32_t>(height)}};
  begin.clearValueCount = clear_count;
  begin.pClearValues = clears;
  vk.vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  // Negative height: y = 0 of the framebuffer is NDC y = +1, the top row, as the CPU's viewport.
  VkViewport viewport{};
  viewport.y = static_cast<float>(height);
  viewport.width = static_cast<float>(width);
  viewport.height = -static_cast<float>(height);
  viewport.maxDepth = 1.0f;
  vk.vkCmdSetViewport(cmd, 0, 1, &viewport);
  const VkRect2D scissor{{0, 0}, {static_cast<uint32_t>(width), static_cast<uint32_t>(height)}};
  vk.vkCmdSetScissor(cmd, 0, 1, &scissor);
  vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout, 0, 1,
                             &descriptor_set, 0, nullptr);
  const VkDeviceSize zero = 0;
  vk.vkCmdBindVertexBuffers(cmd, 0, 1, &scene_buffers.vertices.buffer, &zero);
  vk.vkCmdBindIndexBuffer(cmd, scene_buffers.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
  stats.draws = 0;
  for (uint32_t i = 0; i < packed.objects.size(); ++i) {
    const GpuObject& object = packed.objects[i];
    if (object.triangle_count == 0) continue;
    vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                         pipelines[std::min(object.cull, 2u)]);
    vk.vkCmdPushConstants(cmd, pipeline_layout,
                          VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                          sizeof(uint32_t), &i);
    vk.vkCmdDrawIndexed(cmd, object.triangle_count * 3, 1, object.triangle_base * 3,
                        static_cast<int32_t>(object.vertex_base), 0);
    ++stats.draws;
  }
  if (blend_pipelines) recordBlendDraws(cmd, blend_pipelines);
  vk.vkCmdEndRenderPass(cmd);
}

// After the opaque draws, in the same pass: the blended triangles' runs in drawing order.
void RasterBackend::State::recordBlendDraws(VkCommandBuffer cmd,
                                            const VkPipeline blend_pipelines[3]) {
  const VulkanFunctions& vk = context->vk;
  for (const RasterBlendRun& run : blend.runs()) {
    const GpuObject& object = packed.objects[run.object];
    vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                         blend_pipelines[std::min(object.cull, 2u)]);
    const uint32_t push[2] = {run.object, run.first};
    vk.vkCmdPushConstants(cmd, pipeline_layout,
                          VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                          sizeof(push), push);
    vk.vkCmdDrawIndexed(cmd, run.count * 3, 1, run.first * 3,
                        static_cast<int32_t>(object.vertex_base), 0);
    ++stats.draws;
  }
}

// The AOV pass (with its copies) when needed, then the linear pass when `linear_samples` > 0.
void RasterBackend::State::recordPasses(VkCommandBuffer cmd, int samples, int linear_samples,
                                        bool aov_pass_needed, const ReadbackLayout& layout) {
  if (aov_pass_needed) {
    VkClearValue clears[kAovAttachmentCount]{};
    clears[kAovColor].color.uint32[0] = packed.frame.background;
    clears[kAovDepth].depthStencil = {1.0f, 0};
    recordPass(cmd, aov_pass, aov_targets.framebuffer, aov_pipelines, clears, kAovAttachmentCount);
    if (linear_samples == 0) recordCopy(cmd, aov_targets.images[kAovColor], false, layout.color);
    recordCopy(cmd, aov_targets.images[kAovId], false, layout.id);
    recordCopy(cmd, aov_targets.images[kAovNormal], false, layout.normal);
    recordCopy(cmd, aov_targets.images[kAovDepth], true, layout.depth);
  }
  if (linear_samples > 0) {
    // Samples no triangle covers keep the background, in linear light, with alpha 0.
    VkClearValue clears[kMsAttachmentCount]{};
    const float* decode = srgbDecodeTable();
    for (int k = 0; k < 3; ++k)
      clears[kMsColor].color.float32[k] = decode[(packed.frame.background >> (8 * k)) & 255u];
    clears[kMsDepth].depthStencil = {1.0f, 0};
    recordPass(cmd, ms_pass, ms_targets.framebuffer, ms_pipelines, clears,
               samples > 1 ? kMsAttachmentCount : kMsResolve,
               blending ? ms_blend_pipelines : nullptr);
    recordCopy(cmd, ms_targets.images[samples > 1 ? kMsResolve : kMsColor], false, layout.resolved);
  }
}

// The render pass's outgoing dependency orders its attachment writes (and resolve) before this.
void RasterBackend::State::recordCopy(VkCommandBuffer cmd, const Image& image, bool depth,
                                      VkDeviceSize offset) {
  VkBufferImageCopy region{};
  region.bufferOffset = offset;
  region.imageSubresource = {static_cast<VkImageAspectFlags>(depth ? VK_IMAGE_ASPECT_DEPTH_BIT
                                                                   : VK_IMAGE_ASPECT_COLOR_BIT),
                             0, 0, 1};
  region.imageExtent = {static_cast<uint32_t>(packed.frame.width),
                        static_cast<uint32_t>(packed.frame.height), 1};
  context->vk.vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                     readback.buffer, 1, &region);
}

// The resolved linear colour to sRGB (the CPU's encode, once) and its alpha, the share of
// covered samples, to the coverage AOV (when the frame has one): (covered * 255 + S / 2) / S.
void RasterBackend::State::resolveOnHost(int samples, Frame& frame) {
  const size_t pixels = frame.pixelCount();
  const uint16_t* halves = reinterpret_cast<const uint16_t*>(
      static_cast<const char*>(readback.mapped) + readbackLayout(pixels).resolved);
  resolved_colors.resize(pixels);
  const bool with_coverage = !frame.coverage.empty();
  for (size_t p = 0; p < pixels; ++p) {
    const uint16_t* h = halves + 4 * p;
    resolved_colors[p] = encodeSrgb8(halfToFloat(h[0])) |
                         static_cast<uint32_t>(encodeSrgb8(halfToFloat(h[1]))) << 8 |
                         static_cast<uint32_t>(encodeSrgb8(halfToFloat(h[2]))) << 16 | 255u << 24;
    if (with_coverage && blending) {
      // A + c (1 - A) per sample, averaged, as the CPU's transparent pass leaves the coverage
      // (equal to the count's rounding below wherever nothing blended).
      const float alpha = std::clamp(halfToFloat(h[3]), 0.0f, 1.0f);
      frame.coverage[p] = static_cast<uint8_t>(std::lround(alpha * 255.0f));
    } else if (with_coverage) {
      const long covered = std::lround(halfToFloat(h[3]) * static_cast<float>(samples));
      const int n = static_cast<int>(std::clamp<long>(covered, 0, samples));
      frame.coverage[p] = static_cast<uint8_t>((n * 255 + samples / 2) / samples);
    }
  }
}

Expected<void> RasterBackend::State::renderFrame(const Scene& scene, const RenderOptions& options,
                                                 Frame& frame) {
  Context& c = *context;
  const VulkanFunctions& vk = c.vk;
  const int samples = options.msaa;
  // The fixed-function rasterizer draws straight edges: under a nonlinear projection an edge is a
  // curve, which only the compute backend's per-pixel rays give.
  if (options.projection != Projection::kPerspective)
    return makeError(
        "vulkan-raster draws the perspective projection only; use --backend cpu or "
        "vulkan");
  if (const std::string problem = rasterSampleCountProblem(c.caps, samples); !problem.empty())
    return makeError("vulkan-raster cannot render " + std::to_string(samples) +
                     "x MSAA on device " + std::to_string(c.info.index) + " (" + c.info.name +
                     "): " + problem);
  // Nothing the GPU may still read (an earlier frame abandoned after a timeout) is touched
  // before that frame has finished: buffers, descriptors and mapped inputs alike.
  if (Expected<void> r = c.waitForPending(); !r)
    return makeError("an earlier frame is still running: " + r.error().message);
  if (Expected<void> r = packScene(scene, options, IndexPolicy::kDegenerateDropped, packed); !r)
    return r;
  blending = blend.prepare(scene, options, packed);
  if (Expected<void> r = uploadScene(c, packed, scene_buffers); !r) return r;
  if (Expected<void> r = uploadShadows(c, scene, options, shadows); !r) return r;
  // The AOV pass gives the colour at one sample (unless the linear pass blends), and the pixel
  // centres' AOVs at any count.
  const bool aov_pass_needed = (samples == 1 && !blending) || !frame.depth.empty() ||
                               !frame.triangle_id.empty() || !frame.normal.empty();
  const int linear_samples = samples > 1 || blending ? samples : 0;
  if (Expected<void> r =
          ensureTargets(options.width, options.height, linear_samples, aov_pass_needed);
      !r)
    return r;
  if (Expected<void> r = ensureMeshPipelines(linear_samples, aov_pass_needed); !r) return r;
  writeDescriptors();

  Expected<VkCommandBuffer> begun = c.beginCommands();
  if (!begun) return begun.error();
  VkCommandBuffer cmd = *begun;
  if (timestamps) {
    vk.vkCmdResetQueryPool(cmd, timestamps, 0, 2);
    vk.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps, 0);
  }
  stats = RasterStats{};
  stats.triangles_in = packed.triangle_count;
  stats.samples = samples;
  const size_t pixels = static_cast<size_t>(options.width) * options.height;
  const ReadbackLayout layout = readbackLayout(pixels);
  recordPasses(cmd, samples, linear_samples, aov_pass_needed, layout);
  // Orders the copies' writes into the readback buffer before the host reads it (after the
  // fence).
  memoryBarrier(vk, cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  if (timestamps) vk.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps, 1);
  if (Expected<void> r = c.submitAndWait(); !r) return r;

  readResults(samples, aov_pass_needed, frame);
  const auto lines_start = std::chrono::steady_clock::now();
  drawSceneOverlay(scene, options, packed, overlay, frame);
  const double lines_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - lines_start)
          .count();
  readTimings();
  if (options.diagnostics) {
    // The render pass (vertex, raster, fragment) and its copies are one span: the tile stage's.
    const StageTimes times{0, 0, stats.gpu_ms, lines_ms, 0};
    fillRasterDiagnostics(scene, packed.triangle_count, times, triangle_bases, frame);
  }
  return {};
}

void RasterBackend::State::readResults(int samples, bool aov_pass_ran, Frame& frame) {
  const size_t pixels = frame.pixelCount();
  const ReadbackLayout layout = readbackLayout(pixels);
  char* bytes = static_cast<char*>(readback.mapped);
  uint32_t* ids = reinterpret_cast<uint32_t*>(bytes + layout.id);
  float* depths = reinterpret_cast<float*>(bytes + layout.depth);
  // The CPU's empty pixels are +inf deep; the depth attachment clears to 1.
  if (aov_pass_ran)
    for (size_t p = 0; p < pixels; ++p)
      if (ids[p] == kNoTriangle) depths[p] = std::numeric_limits<float>::infinity();
  const uint32_t* colors = reinterpret_cast<const uint32_t*>(bytes + layout.color);
  if (samples > 1 || blending) {
    resolveOnHost(samples, frame);
    colors = resolved_colors.data();
  } else if (!frame.coverage.empty()) {
    for (size_t p = 0; p < pixels; ++p) frame.coverage[p] = ids[p] == kNoTriangle ? 0 : 255;
  }
  copyResults(colors, reinterpret_cast<const uint32_t*>(depths), ids,
              reinterpret_cast<const float*>(bytes + layout.normal), 4, frame);
}

void RasterBackend::State::readTimings() {
  if (!timestamps) return;
  Context& c = *context;
  uint64_t ticks[2] = {};
  if (c.vk.vkGetQueryPoolResults(c.device, timestamps, 0, 2, sizeof(ticks), ticks, sizeof(uint64_t),
                                 VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT) != VK_SUCCESS)
    return;  // timings are diagnostics: a frame never fails over them
  const uint32_t bits = c.caps.timestamp_valid_bits;
  const uint64_t mask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
  stats.gpu_ms = static_cast<double>((ticks[1] - ticks[0]) & mask) *
                 c.caps.properties.limits.timestampPeriod * 1e-6;
  stats.timings_valid = true;
}

Expected<std::unique_ptr<RasterBackend>> RasterBackend::create(const VulkanOptions& options) {
  Expected<std::unique_ptr<Context>> context = Context::create(options, BackendKind::kRaster);
  if (!context) return context.error();
  auto state = std::make_unique<State>();
  state->context = std::move(*context);
  if (Expected<void> r = state->createPipelines(); !r) return r.error();
  return std::unique_ptr<RasterBackend>(new RasterBackend(std::move(state)));
}

RasterBackend::RasterBackend(std::unique_ptr<State> state) : state_(std::move(state)) {}
RasterBackend::~RasterBackend() = default;

void RasterBackend::render(const Scene& scene, const RenderOptions& requested, Frame& frame) {
  const RenderOptions options = withCompositeInputs(scene, withDiagnosticInputs(requested));
  frame.diagnostics.valid = false;
  state_->last_result = renderIntoFrame(scene, options, frame,
                                        [&] { return state_->renderFrame(scene, options, frame); });
}

Expected<void> RasterBackend::lastResult() const {
  return state_->last_result;
}
const RasterStats& RasterBackend::lastStats() const {
  return state_->stats;
}
const DeviceInfo& RasterBackend::device() const {
  return state_->context->info;
}
std::vector<std::string> RasterBackend::validationErrors() const {
  return state_->context->validationErrors();
}
void RasterBackend::setFenceTimeout(uint32_t milliseconds) {
  state_->context->fence_timeout_ms = milliseconds;
}

Expected<std::unique_ptr<Backend>> makeRasterBackend(const VulkanOptions& options) {
  Expected<std::unique_ptr<RasterBackend>> backend = RasterBackend::create(options);
  if (!backend) return backend.error();
  return std::unique_ptr<Backend>(std::move(*backend));
}

}  // namespace tessera::vulkan
