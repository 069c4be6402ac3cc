// The scene as the shaders read it: per-frame constants and lights, objects (with the CPU's
// matrices, computed by the CPU's own makeObjectTransforms so clip positions match bit for bit),
// materials, every object's vertices and indices one after another, textures and the sRGB
// tables. Packed on the host into reusable vectors, then copied into mapped buffers.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <unordered_map>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/math/math.h>
#include <tessera/render/options.h>
#include <tessera/scene/scene.h>

#include "render/point_pass.h"
#include "render/worker_pool.h"
#include "vulkan/context.h"
#include "vulkan/gpu_types.h"

namespace tessera::vulkan {

struct PackedScene {
  GpuFrameConstants frame{};
  std::vector<GpuLight> lights;
  std::vector<GpuObject> objects;
  std::vector<float4x4> models;  // each object's model matrix (for the axes)
  std::vector<GpuMaterial> materials;
  std::vector<GpuVertex> vertices;
  std::vector<uint32_t> indices;
  std::vector<uint32_t> triangle_materials;
  std::vector<uint32_t> texels;
  std::unordered_map<const Texture*, uint32_t> texture_offsets;
  float4x4 view_projection;  // OpenGL clip space, exactly as the CPU renderer builds it
  size_t triangle_count = 0;
  size_t vertex_count = 0;
};

enum class IndexPolicy {
  kAsGiven,            // the compute backend checks indices and finiteness itself, as the CPU
  kDegenerateDropped,  // the raster backend: triangles the CPU drops (an index past the end, a
                       // non-finite vertex) become degenerate, so the rasterizer draws nothing
};

// Fills `out` (reusing its memory). An Error for a scene beyond what the shaders can address.
Expected<void> packScene(const Scene& scene, const RenderOptions& options, IndexPolicy policy,
                         PackedScene& out);

// The scene inputs on the device: one buffer per binding 0..7.
struct SceneBuffers {
  Buffer frame, objects, materials, vertices, indices, triangle_materials, texels, color_tables;
  bool color_tables_written = false;
};

// Copies the packed scene into the mapped buffers, growing them as needed.
// The colour-table buffer (common.glsl's color_tables): the CPU's sRGB constants
// (tessera/scene/color.h) as float words, the decode table (256) then the encode's (SrgbEncode:
// scale (10), polynomial (5), end of the linear segment, its factor, the offset), then
// FixedFilter::kScale as a float word and the bilinear filter's 15-bit texel values as integers,
// unorm then sRGB (texelFixedTable, 256 each; shading.glsl's kFixedScale and after).
std::vector<uint32_t> makeColorTables();
constexpr size_t kColorConstantWords = 256 + 10 + 5 + 3;  // the float words before kScale

Expected<void> uploadScene(Context& context, const PackedScene& packed, SceneBuffers& buffers);
void destroySceneBuffers(Context& context, SceneBuffers& buffers);
// Descriptor writes for bindings 0..7.
void appendSceneDescriptors(const SceneBuffers& buffers,
                            std::vector<VkDescriptorBufferInfo>& infos);

// Sizes the frame as the CPU renderer does: colour always; depth when asked for or when lines or
// points are drawn (they are depth-tested); ids, normals and coverage when asked for.
void resizeFrame(const Scene& scene, const RenderOptions& options, Frame& frame);
// Copies the results the frame holds buffers for (words of `pixels` each: colour, depth bits, id;
// then three floats a pixel of normal, when `normals` is given).
void copyResults(const uint32_t* color, const uint32_t* depth, const uint32_t* ids,
                 const float* normals, int normal_stride, Frame& frame);
// Clears a frame whose render failed: empty, never half drawn.
void clearFrame(Frame& frame);
// A backend's render(): checks the viewport (outside 1..kMaxViewport is a caller's bug), sizes
// the frame, then draws with `draw`; a failed draw leaves a cleared frame. Returns what `draw` did.
Expected<void> renderIntoFrame(const Scene& scene, const RenderOptions& options, Frame& frame,
                               const std::function<Expected<void>()>& draw);

// What the CPU's passes draw on a backend's read-back frame; kept by the backend, so that its
// buffers are reused frame to frame.
struct SceneOverlay {
  render::PointPass points;
  std::unique_ptr<render::WorkerPool> pool;  // made for the first frame with points
  LineList axes;
};
// On the finished frame: the composite over the background (composite.h), the CPU's point pass
// (point_pass.h), then its line pass (scene lines at RenderOptions::line_width, world and object
// axes).
void drawSceneOverlay(const Scene& scene, const RenderOptions& options, const PackedScene& packed,
                      SceneOverlay& overlay, Frame& frame);

}  // namespace tessera::vulkan
