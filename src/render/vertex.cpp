#include "render/vertex.h"

#include <cmath>
#include <limits>

namespace tessera::render {

ObjectTransforms makeObjectTransforms(const Object& object, const float4x4& view_projection) {
  ObjectTransforms t;
  t.model = object.transform.matrix();
  t.model_view_projection = view_projection * t.model;
  t.normal_matrix = normalMatrix(t.model);
  t.winding_sign = determinant(upper3x3(t.model)) < 0.0f ? -1.0f : 1.0f;
  t.vertex_base = 0;
  t.triangle_base = 0;
  return t;
}

void VertexBuffer::resize(size_t count) {
  for (std::vector<float>* v : {&clip_x, &clip_y, &clip_z, &clip_w}) v->resize(count);
  normal.resize(count);
  lit.resize(count);
  outcode.resize(count);
  screen.resize(count);
}

void transformVertices(const Mesh& mesh, const ObjectTransforms& transforms,
                       const ViewportTransform& viewport, size_t first, size_t count,
                       VertexBuffer& out) {
  const float4x4& m = transforms.model_view_projection;
  const size_t base = transforms.vertex_base;
  // Written as plain loops over arrays so the compiler vectorizes them.
  for (size_t i = first; i < first + count; ++i) {
    const float3 p = mesh.positions[i];
    const size_t o = base + i;
    out.clip_x[o] = m.col[0].x * p.x + m.col[1].x * p.y + m.col[2].x * p.z + m.col[3].x;
    out.clip_y[o] = m.col[0].y * p.x + m.col[1].y * p.y + m.col[2].y * p.z + m.col[3].y;
    out.clip_z[o] = m.col[0].z * p.x + m.col[1].z * p.y + m.col[2].z * p.z + m.col[3].z;
    out.clip_w[o] = m.col[0].w * p.x + m.col[1].w * p.y + m.col[2].w * p.z + m.col[3].w;
  }
  for (size_t o = base + first; o < base + first + count; ++o) {
    const float4 c = out.clip(o);
    const bool finite =
        std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && std::isfinite(c.w);
    const uint32_t code = finite ? outcode(c, viewport.guard) : kNonFinite;
    out.outcode[o] = static_cast<uint16_t>(code);
    if (!(code & kCutPlanes)) out.screen[o] = projectToScreen(c, viewport.width, viewport.height);
  }
  if (mesh.normals.size() != mesh.positions.size()) {
    for (size_t i = first; i < first + count; ++i) {
      const size_t o = base + i;
      out.normal[o] = float3{};
    }
    return;
  }
  const float3x3& n = transforms.normal_matrix;
  for (size_t i = first; i < first + count; ++i) {
    float3 w = normalize(n * mesh.normals[i]);
    const size_t o = base + i;
    out.normal[o] = w;
  }
}

void lightVertices(const Scene& scene, size_t first, size_t count, VertexBuffer& out) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // Copied out of the scene: the stores to out.lit could alias it and force a reload per vertex.
  const float3 ambient = scene.ambient;
  const std::span<const DirectionalLight> lights = scene.lights;
  const float3* normal = out.normal.data();
  float3* lit = out.lit.data();
  for (size_t o = first; o < first + count; ++o) {
    const float3 n = normal[o];
    // The same test and the same irradiance as setupShade, so the same bits.
    const bool zero = n.x == 0.0f && n.y == 0.0f && n.z == 0.0f;
    lit[o] = zero ? float3{nan, nan, nan} : irradiance(ambient, lights, n);
  }
}

}  // namespace tessera::render
