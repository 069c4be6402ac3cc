#include "vulkan/mesh_pack.h"

#include <algorithm>

#include <tessera/math/vec.h>

namespace tessera::vulkan {

namespace {

// Which of a mesh's optional attributes are packed: each only when it is whole.
struct MeshAttributes {
  bool normals, uv, uv1, color, materials, tangents;
};

// The attributes the object's mesh has, per vertex (or per triangle, for its materials).
MeshAttributes meshAttributes(const Object& object) {
  const Mesh& mesh = *object.mesh;
  const size_t count = mesh.vertexCount();
  MeshAttributes has{};
  has.normals = mesh.normals.size() == count;
  has.uv = mesh.uvs.size() == count;
  has.uv1 = mesh.uvs1.size() == count;  // else set 0 in its place
  has.color = mesh.colors.size() == count;
  has.materials = mesh.triangle_materials.size() == mesh.triangleCount();
  // The CPU's SetupContext::tangents (render/setup.h: objectSetupContext).
  has.tangents = object.shading == Shading::kPbr && has.uv && has.normals &&
                 mesh.tangents.size() == count &&
                 std::any_of(object.materials.begin(), object.materials.end(),
                             [](const Material& m) { return m.normal.texture != nullptr; });
  return has;
}

// Appends the mesh's vertices: an attribute it lacks is zero, but its colour is white and its set
// 1 is set 0.
void appendVertices(const Mesh& mesh, const MeshAttributes& has, PackedScene& out) {
  const size_t count = mesh.vertexCount();
  for (size_t v = 0; v < count; ++v) {
    GpuVertex gv{};
    gv.position[0] = mesh.positions[v].x;
    gv.position[1] = mesh.positions[v].y;
    gv.position[2] = mesh.positions[v].z;
    if (has.normals) {
      gv.normal[0] = mesh.normals[v].x;
      gv.normal[1] = mesh.normals[v].y;
      gv.normal[2] = mesh.normals[v].z;
    }
    if (has.uv) {
      gv.uv[0] = mesh.uvs[v].x;
      gv.uv[1] = mesh.uvs[v].y;
      const float2 uv1 = has.uv1 ? mesh.uvs1[v] : mesh.uvs[v];
      gv.uv1[0] = uv1.x;
      gv.uv1[1] = uv1.y;
    }
    const float4 color = has.color ? mesh.colors[v] : float4{1, 1, 1, 1};
    for (int c = 0; c < 4; ++c) gv.color[c] = color[c];
    if (has.tangents)
      for (int c = 0; c < 4; ++c) gv.tangent[c] = mesh.tangents[v][c];
    out.vertices.push_back(gv);
  }
}

// Appends the mesh's triangles' indices as the policy says (IndexPolicy).
void appendIndices(const Mesh& mesh, IndexPolicy policy, PackedScene& out) {
  const size_t count = mesh.vertexCount(), triangles = mesh.triangleCount();
  if (policy == IndexPolicy::kAsGiven) {
    out.indices.insert(out.indices.end(), mesh.indices.begin(),
                       mesh.indices.begin() + static_cast<ptrdiff_t>(triangles * 3));
    return;
  }
  // A vertex that is safe to repeat three times: a zero-area triangle draws nothing.
  uint32_t safe = 0;
  while (safe < count && !isFinite(mesh.positions[safe])) ++safe;
  for (size_t t = 0; t < triangles; ++t) {
    const uint32_t* idx = &mesh.indices[t * 3];
    bool drawn = idx[0] < count && idx[1] < count && idx[2] < count;
    for (int k = 0; drawn && k < 3; ++k) drawn = isFinite(mesh.positions[idx[k]]);
    if (drawn) {
      out.indices.insert(out.indices.end(), idx, idx + 3);
    } else {
      out.indices.insert(out.indices.end(), {safe, safe, safe});
    }
  }
}

}  // namespace

void packMesh(const Object& object, IndexPolicy policy, GpuObject& gpu, PackedScene& out) {
  const Mesh& mesh = *object.mesh;
  const size_t count = mesh.vertexCount(), triangles = mesh.triangleCount();
  const MeshAttributes has = meshAttributes(object);
  gpu.vertex_count = static_cast<uint32_t>(count);
  gpu.triangle_count = static_cast<uint32_t>(triangles);
  gpu.flags = (has.uv ? kObjectHasUv : 0u) | (has.color ? kObjectHasColor : 0u) |
              (has.normals ? kObjectHasNormals : 0u) |
              (has.materials ? kObjectHasTriangleMaterials : 0u) |
              (has.tangents ? kObjectHasTangents : 0u);
  appendVertices(mesh, has, out);
  appendIndices(mesh, policy, out);
  for (size_t t = 0; t < triangles; ++t)
    out.triangle_materials.push_back(has.materials ? mesh.triangle_materials[t] : 0u);
}

}  // namespace tessera::vulkan
