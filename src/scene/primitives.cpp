#include <tessera/scene/primitives.h>

#include <cmath>

namespace tessera {

Mesh makeCube() {
  Mesh mesh;
  // Each face: outward normal and two in-plane axes (u, v) with cross(u, v) == normal, so the
  // corners listed as -u-v, +u-v, +u+v, -u+v run counter-clockwise seen from outside.
  struct Face {
    float3 n, u, v;
  };
  const Face faces[6] = {
      {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
      {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
      {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
  };
  const float2 corner_uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const float sign_u[4] = {-1, 1, 1, -1};
  const float sign_v[4] = {-1, -1, 1, 1};
  for (const Face& f : faces) {
    uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    for (int c = 0; c < 4; ++c) {
      mesh.positions.push_back((f.n + f.u * sign_u[c] + f.v * sign_v[c]) * 0.5f);
      mesh.normals.push_back(f.n);
      mesh.uvs.push_back(corner_uv[c]);
    }
    for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + i);
  }
  return mesh;
}

Mesh makeUvSphere(int segments, int rings) {
  segments = std::max(segments, 3);
  rings = std::max(rings, 2);
  Mesh mesh;
  for (int r = 0; r <= rings; ++r) {
    float v = static_cast<float>(r) / rings;
    float theta = v * kPi;  // 0 at the north pole (+Y)
    for (int s = 0; s <= segments; ++s) {
      float u = static_cast<float>(s) / segments;
      float phi = u * 2.0f * kPi;
      float3 n{std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi)};
      mesh.positions.push_back(n);
      mesh.normals.push_back(n);
      mesh.uvs.push_back({u, 1.0f - v});
    }
  }
  const uint32_t stride = static_cast<uint32_t>(segments + 1);
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      uint32_t a = r * stride + s, b = a + 1, c = a + stride, d = c + 1;
      // Counter-clockwise seen from outside; skip the degenerate triangles at the poles.
      if (r != 0) mesh.indices.insert(mesh.indices.end(), {a, c, b});
      if (r != rings - 1) mesh.indices.insert(mesh.indices.end(), {b, c, d});
    }
  }
  return mesh;
}

}  // namespace tessera
