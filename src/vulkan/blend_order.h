// alphaMode BLEND on the Vulkan backends: the CPU's back-to-front order of the blended triangles
// (render/blend.h), found on the host with the CPU's own stages so that the order is the CPU's:
// the vertex stage (transformVertices: the same snapped window positions and outcodes), the
// clipper and projectToScreen for triangles that cross the near or far plane or leave the guard
// band, setupRaster (the same pixel box and depth plane, with the CPU's sample reach under MSAA)
// and blendRecordDepth, then the CPU's sort (sortBlendEntries). Only the blended objects' vertices
// are transformed, so a frame without blended materials pays one look at each object's materials.
#pragma once

#include <cstdint>
#include <vector>

#include <tessera/math/math.h>
#include <tessera/render/options.h>
#include <tessera/scene/scene.h>

#include "render/blend.h"
#include "render/setup.h"
#include "render/vertex.h"

namespace tessera::vulkan {

// One record of a blended triangle, in drawing order.
struct BlendedRecord {
  uint32_t key;          // scene triangle << 3 | fan piece: the compute backend's record key
  uint32_t object;       // index into Scene::objects
  render::PixelBox box;  // the CPU's pixel box (with MSAA: grown by the samples' reach)
};

class BlendDrawOrder {
 public:
  // Orders the blended records of `scene` as the CPU renderer would draw them with `options`;
  // `view_projection` is the CPU's (PackedScene::view_projection, jitter included). With
  // AlphaMode::kMask: the masked records instead, in submission order (the compute backend's
  // MASK pass, whose depth commits do not depend on the order).
  void build(const Scene& scene, const RenderOptions& options, const float4x4& view_projection,
             AlphaMode mode = AlphaMode::kBlend);
  bool empty() const { return records_.empty(); }
  // In drawing order: objects farthest first, then their triangles farthest first.
  const std::vector<BlendedRecord>& records() const { return records_; }

 private:
  void addObject(const Scene& scene, size_t object_index, const render::ObjectTransforms& xf,
                 const RenderOptions& options);

  AlphaMode mode_ = AlphaMode::kBlend;

  render::VertexBuffer vertices_;
  std::vector<render::BlendEntry> entries_;
  std::vector<BlendedRecord> found_;  // submission order; entries_' keys index it
  std::vector<BlendedRecord> records_;
  std::vector<double> object_sum_;
  std::vector<uint32_t> object_entries_;
};

}  // namespace tessera::vulkan
