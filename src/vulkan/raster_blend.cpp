#include "vulkan/raster_blend.h"

namespace tessera::vulkan {

namespace {

// Every blended triangle of the scene (whether the CPU's setup keeps it or not) becomes
// degenerate in the scene's own index range: the opaque draws must not draw it.
void degenerateBlended(const Scene& scene, PackedScene& packed) {
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& object = scene.objects[i];
    if (!object.mesh) continue;
    const GpuObject& gpu = packed.objects[i];
    const Mesh& mesh = *object.mesh;
    const bool per_triangle = mesh.triangle_materials.size() == mesh.triangleCount();
    for (uint32_t t = 0; t < gpu.triangle_count; ++t) {
      const size_t m = per_triangle ? mesh.triangle_materials[t] : 0;
      const Material& material = object.materials[m < object.materials.size() ? m : 0];
      if (!render::isBlended(material)) continue;
      uint32_t* idx = &packed.indices[(static_cast<size_t>(gpu.triangle_base) + t) * 3];
      idx[1] = idx[2] = idx[0];
    }
  }
}

}  // namespace

bool RasterBlendDraws::prepare(const Scene& scene, const RenderOptions& options,
                               PackedScene& packed) {
  runs_.clear();
  order_.build(scene, options, packed.view_projection);
  if (order_.empty()) return false;
  const uint32_t scene_triangles = static_cast<uint32_t>(packed.triangle_count);
  drawn_.assign(scene_triangles, 0);
  uint32_t next = scene_triangles;  // the appended range's first triangle
  for (const BlendedRecord& r : order_.records()) {
    const uint32_t t = r.key >> 3;
    // The hardware draws a clipped triangle whole: once, where its first piece falls in the order.
    if (drawn_[t]) continue;
    drawn_[t] = 1;
    for (int k = 0; k < 3; ++k) packed.indices.push_back(packed.indices[size_t{t} * 3 + k]);
    packed.triangle_materials.push_back(packed.triangle_materials[t]);
    if (runs_.empty() || runs_.back().object != r.object) runs_.push_back({r.object, next, 0});
    ++runs_.back().count;
    ++next;
  }
  degenerateBlended(scene, packed);
  return true;
}

}  // namespace tessera::vulkan
