// Vertex stage: object-space positions to clip space and normals to world space, for every
// vertex of every object, into structure-of-arrays buffers.
#pragma once

#include <algorithm>
#include <vector>

#include <cstddef>
#include <span>
#include <vector>

#include <tessera/math/math.h>
#include <tessera/scene/scene.h>

#include "render/clip.h"
#include "render/page_pool.h"
#include "render/setup.h"

namespace tessera::render {

// Per-object constants of one frame.
struct ObjectTransforms {
  float4x4 model;
  float4x4 model_view_projection;
  float3x3 normal_matrix;  // inverse transpose of the model's upper 3x3
  float winding_sign;      // sign of det(model): a mirrored object flips face normals
  size_t vertex_base;      // first vertex in the VertexBuffer
  size_t triangle_base;    // first triangle in the scene's triangle list (the id base)
};

ObjectTransforms makeObjectTransforms(const Object& object, const float4x4& view_projection);

// The index of the object holding scene triangle `triangle`: the last whose triangle_base is at
// most `triangle` (objects are in triangle order).
inline size_t objectHolding(const std::vector<ObjectTransforms>& objects, size_t triangle) {
  return static_cast<size_t>(
      std::upper_bound(objects.begin(), objects.end(), triangle,
                       [](size_t t, const ObjectTransforms& o) { return t < o.triangle_base; }) -
      objects.begin() - 1);
}

// Gouraud objects with vertex normals are lit per vertex in the vertex stage (VertexBuffer::lit).
// With a point or spot light setup lights every corner itself (it needs world positions).
inline bool litPerVertex(const Object& object, const LightRig& lights) {
  return !lights.local && object.shading == Shading::kGouraud && object.mesh &&
         object.mesh->normals.size() == object.mesh->vertexCount();
}

// Transformed vertices of the whole scene, objects one after another.
struct VertexBuffer {
  PoolVector<float> clip_x, clip_y, clip_z, clip_w;
  // World space, unit (zero if the mesh has none). One array of float3: setup fetches normals by
  // index, and one cache line beats three.
  PoolVector<float3> normal;
  // Gouraud objects with normals only: irradiance(scene, normal), so that setup lights each vertex
  // once instead of once per triangle corner (about six). NaN where the normal is zero: setup
  // then lights that corner itself (with the face normal), as for vertices it cannot take from
  // here (clipped ones, drawn back faces).
  PoolVector<float3> lit;
  PoolVector<uint16_t> outcode;     // clip planes the vertex is outside of (clip.h)
  PoolVector<ScreenVertex> screen;  // valid only where outcode has no kCutPlanes bit

  void resize(size_t count);
  float4 clip(size_t i) const { return {clip_x[i], clip_y[i], clip_z[i], clip_w[i]}; }
};

struct ViewportTransform {
  float width = 0, height = 0;
  GuardBand guard;
};

// The scene's lights, for objects lit in the vertex stage (VertexBuffer::lit): directional only.
struct VertexLighting {
  float3 ambient;
  std::span<const ShadeLight> lights;
};

// Transforms mesh vertices [first, first + count) into the buffer at transforms.vertex_base:
// clip position, outcode, and (inside the guard band and the depth range) the snapped screen
// position; world normals; with lighting, out.lit. The exact operations are specified in
// vertex_kernel.h; each instruction set has its variant (kernels.h).
using TransformVerticesFn = void (*)(const Mesh& mesh, const ObjectTransforms& transforms,
                                     const ViewportTransform& viewport,
                                     const VertexLighting* lighting, size_t first, size_t count,
                                     VertexBuffer& out);

// The same with the best variant this CPU runs and no lighting (for benchmarks and tools; the
// renderer calls the variant it chose).
void transformVertices(const Mesh& mesh, const ObjectTransforms& transforms,
                       const ViewportTransform& viewport, size_t first, size_t count,
                       VertexBuffer& out);

}  // namespace tessera::render
