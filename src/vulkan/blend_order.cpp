#include "vulkan/blend_order.h"

#include <algorithm>

#include "render/clip.h"

namespace tessera::vulkan {

using namespace render;

namespace {

bool objectHas(const Object& object, AlphaMode mode) {
  return object.mesh && std::any_of(object.materials.begin(), object.materials.end(),
                                    [&](const Material& m) { return m.alpha_mode == mode; });
}

// The material of local triangle `local`, as setup picks it (an index past the list: the first).
const Material& triangleMaterial(const Object& object, size_t local) {
  const Mesh& mesh = *object.mesh;
  const size_t m =
      mesh.triangle_materials.size() == mesh.triangleCount() ? mesh.triangle_materials[local] : 0;
  return object.materials[m < object.materials.size() ? m : 0];
}

}  // namespace

void BlendDrawOrder::build(const Scene& scene, const RenderOptions& options,
                           const float4x4& view_projection, AlphaMode mode) {
  mode_ = mode;
  entries_.clear();
  found_.clear();
  records_.clear();
  if (std::none_of(scene.objects.begin(), scene.objects.end(),
                   [&](const Object& o) { return objectHas(o, mode); }))
    return;
  size_t triangle_base = 0;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& object = scene.objects[i];
    ObjectTransforms xf = makeObjectTransforms(object, view_projection);
    xf.vertex_base = 0;
    xf.triangle_base = triangle_base;
    if (objectHas(object, mode)) addObject(scene, i, xf, options);
    if (object.mesh) triangle_base += object.mesh->triangleCount();
  }
  if (mode != AlphaMode::kBlend) {
    records_ = found_;
    return;
  }
  sortBlendEntries(entries_, scene.objects.size(), object_sum_, object_entries_);
  records_.reserve(entries_.size());
  for (const BlendEntry& e : entries_) records_.push_back(found_[e.key]);
}

// The object's blended records, through the CPU's stages (chunk_setup.cpp's per-triangle path).
void BlendDrawOrder::addObject(const Scene& scene, size_t object_index, const ObjectTransforms& xf,
                               const RenderOptions& options) {
  const Object& object = scene.objects[object_index];
  const Mesh& mesh = *object.mesh;
  const size_t vertex_count = mesh.vertexCount();
  const float width = static_cast<float>(options.width),
              height = static_cast<float>(options.height);
  const GuardBand guard = makeGuardBand(options.width, options.height);
  vertices_.resize(vertex_count);
  transformVertices(mesh, xf, ViewportTransform{width, height, guard}, 0, vertex_count, vertices_);
  SetupContext ctx;
  ctx.width = options.width;
  ctx.height = options.height;
  ctx.cull = object.cull;
  ctx.sample_reach = sampleReach(options.msaa);

  auto add = [&](size_t local, uint32_t piece, const ScreenVertex sv[3]) {
    RasterTriangle raster;
    RasterWide wide;
    TriangleOrientation orientation;
    if (!setupRaster(ctx, sv, raster, wide, orientation)) return;
    const uint32_t triangle = static_cast<uint32_t>(xf.triangle_base + local);
    entries_.push_back({0.0f, blendRecordDepth(raster), static_cast<uint32_t>(object_index),
                        static_cast<uint32_t>(found_.size())});
    found_.push_back({triangle << 3 | piece, static_cast<uint32_t>(object_index),
                      PixelBox{raster.min_x, raster.min_y, raster.max_x, raster.maxY()}});
  };
  for (size_t local = 0; local < mesh.triangleCount(); ++local) {
    if (triangleMaterial(object, local).alpha_mode != mode_) continue;
    const uint32_t idx[3] = {mesh.indices[local * 3], mesh.indices[local * 3 + 1],
                             mesh.indices[local * 3 + 2]};
    if (idx[0] >= vertex_count || idx[1] >= vertex_count || idx[2] >= vertex_count) continue;
    const uint32_t c0 = vertices_.outcode[idx[0]], c1 = vertices_.outcode[idx[1]],
                   c2 = vertices_.outcode[idx[2]];
    if (((c0 | c1 | c2) & kNonFinite) || (c0 & c1 & c2 & kRejectPlanes)) continue;
    const uint32_t cut = (c0 | c1 | c2) & kCutPlanes;
    if (!cut) {
      const ScreenVertex sv[3] = {vertices_.screen[idx[0]], vertices_.screen[idx[1]],
                                  vertices_.screen[idx[2]]};
      add(local, 0, sv);
      continue;
    }
    ClipVertex in[3]{};
    for (int k = 0; k < 3; ++k) in[k].position = vertices_.clip(idx[k]);
    ClipVertex polygon[kMaxClippedVertices];
    const int n = clipTriangle(in, cut, guard, polygon);
    for (int k = 1; k + 1 < n; ++k) {
      const ScreenVertex sv[3] = {projectToScreen(polygon[0].position, width, height),
                                  projectToScreen(polygon[k].position, width, height),
                                  projectToScreen(polygon[k + 1].position, width, height)};
      add(local, static_cast<uint32_t>(k - 1), sv);
    }
  }
}

}  // namespace tessera::vulkan
