#include <tessera/scene/mesh.h>

namespace tessera {

Bounds Mesh::bounds() const {
  Bounds b;
  for (const float3& p : positions)
    if (isFinite(p)) b.add(p);
  return b;
}

void generateSmoothNormals(Mesh& mesh) {
  mesh.normals.assign(mesh.positions.size(), float3{});
  const size_t vertex_count = mesh.positions.size();
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    if (i0 >= vertex_count || i1 >= vertex_count || i2 >= vertex_count) continue;
    float3 p0 = mesh.positions[i0], p1 = mesh.positions[i1], p2 = mesh.positions[i2];
    // The unnormalized cross product is twice the area: larger faces weigh more.
    float3 n = cross(p1 - p0, p2 - p0);
    if (!isFinite(n)) continue;
    mesh.normals[i0] += n;
    mesh.normals[i1] += n;
    mesh.normals[i2] += n;
  }
  for (float3& n : mesh.normals) {
    float3 unit = normalize(n);
    n = (length(unit) > 0.0f && isFinite(unit)) ? unit : float3{0, 0, 1};
  }
}

}  // namespace tessera
