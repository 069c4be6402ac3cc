#include "render/vertex.h"

#include "render/kernels.h"

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
  for (PoolVector<float>* v : {&clip_x, &clip_y, &clip_z, &clip_w}) v->resize(count);
  normal.resize(count);
  lit.resize(count);
  outcode.resize(count);
  screen.resize(count);
}

void transformVertices(const Mesh& mesh, const ObjectTransforms& transforms,
                       const ViewportTransform& viewport, size_t first, size_t count,
                       VertexBuffer& out) {
  kernelsFor(detectIsa())
      .transform_vertices(mesh, transforms, viewport, nullptr, first, count, out);
}

}  // namespace tessera::render
