// Scenes for the nonlinear projections' tests, and the independent oracle they are held to: a
// brute-force ray caster (every pixel's ray against every triangle, in double precision, with
// Moller-Trumbore's test), which shares nothing with the renderer but projection.h's formulas.
#pragma once

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include <tessera/render/frame.h>
#include <tessera/render/projection.h>
#include <tessera/scene/scene.h>

namespace tessera::test {

// Quads of an axis-aligned face subdivided n x n, two triangles each, appended to `mesh` with
// material `material`: the face at `axis` = `side` * half of a cube of half-size `half` around
// `centre`.
inline void addCubeFace(Mesh& mesh, float3 centre, float half, int axis, float side, int n,
                        uint16_t material) {
  const int u_axis = (axis + 1) % 3, v_axis = (axis + 2) % 3;
  const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      float3 p = centre;
      p[axis] += side * half;
      p[u_axis] += (2.0f * i / n - 1.0f) * half;
      p[v_axis] += (2.0f * j / n - 1.0f) * half;
      mesh.positions.push_back(p);
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const uint32_t a = base + static_cast<uint32_t>(j * (n + 1) + i), b = a + 1,
                     c = a + static_cast<uint32_t>(n + 1), d = c + 1;
      for (uint32_t index : {a, b, d, a, d, c}) mesh.indices.push_back(index);
      mesh.triangle_materials.push_back(material);
      mesh.triangle_materials.push_back(material);
    }
  }
}

// A closed cube room of half-size `half` around `centre`, each face n x n quads; face f (material
// f) is axis f / 2 on side f % 2 == 0 ? -1 : +1: -X, +X, -Y, +Y, -Z, +Z.
inline Mesh roomMesh(float3 centre, float half, int n) {
  Mesh mesh;
  for (int f = 0; f < 6; ++f)
    addCubeFace(mesh, centre, half, f / 2, f % 2 == 0 ? -1.0f : 1.0f, n, static_cast<uint16_t>(f));
  return mesh;
}

// A strip behind the camera (the eye at the origin looking down -Z), across the seam of a
// 360-degree image: x from -1 to 1 at z = 2, n x 4 quads.
inline Mesh seamMesh(int n) {
  Mesh mesh;
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= n; ++i)
      mesh.positions.push_back({2.0f * i / n - 1.0f, 0.25f * j - 0.5f, 2.0f + 0.3f * i / n});
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = static_cast<uint32_t>(j * (n + 1) + i), b = a + 1,
                     c = a + static_cast<uint32_t>(n + 1), d = c + 1;
      for (uint32_t index : {a, b, d, a, d, c}) mesh.indices.push_back(index);
    }
  return mesh;
}

// A fan around the pole above the eye: a disc at height y = 2 of radius 3, `segments` triangles.
inline Mesh poleMesh(int segments) {
  Mesh mesh;
  mesh.positions.push_back({0.1f, 2.0f, -0.2f});
  for (int i = 0; i < segments; ++i) {
    const float a = 2.0f * 3.14159265f * i / segments;
    mesh.positions.push_back({3.0f * std::cos(a), 2.0f + 0.2f * std::sin(3.0f * a),
                              3.0f * std::sin(a)});
  }
  for (int i = 0; i < segments; ++i) {
    mesh.indices.push_back(0);
    mesh.indices.push_back(1 + static_cast<uint32_t>(i));
    mesh.indices.push_back(1 + static_cast<uint32_t>((i + 1) % segments));
  }
  return mesh;
}

inline Object unlitObject(Mesh mesh, int materials = 1) {
  Object o;
  o.mesh = std::make_shared<Mesh>(std::move(mesh));
  o.materials = std::vector<Material>(static_cast<size_t>(materials), Material{});
  for (int i = 0; i < materials; ++i)
    o.materials[static_cast<size_t>(i)].base_color = {0.1f + 0.15f * i, 0.9f - 0.1f * i, 0.5f, 1};
  o.shading = Shading::kUnlit;
  o.cull = CullMode::kNone;
  return o;
}

// The eye at `eye` looking down -Z (camera space = world space less the eye).
inline Scene eyeScene(float3 eye, float fov_y_degrees, float near_z = 0.01f, float far_z = 50.0f) {
  Scene scene;
  scene.camera.position = eye;
  scene.camera.target = eye + float3{0, 0, -1};
  scene.camera.up = {0, 1, 0};
  scene.camera.fov_y_degrees = fov_y_degrees;
  scene.camera.near_z = near_z;
  scene.camera.far_z = far_z;
  scene.background = {0, 0, 0, 1};
  return scene;
}

struct OracleHit {
  uint32_t id = kNoTriangle;  // scene triangle index + 1
  double distance = std::numeric_limits<double>::infinity();
};

// The nearest hit of pixel (x, y)'s centre ray within [near, far] (camera at scene.camera.position
// looking down -Z with +Y up, as eyeScene makes it).
inline OracleHit castRay(const Scene& scene, Projection p, int x, int y, int width, int height) {
  OracleHit best;
  double d[3];
  const double fov = scene.camera.fov_y_degrees * 3.14159265358979323846 / 180.0;
  if (!rayDirection(p, x + 0.5, y + 0.5, width, height, fov, d)) return best;
  const float3 eye = scene.camera.position;
  uint32_t base = 0;
  for (const Object& object : scene.objects) {
    const Mesh& mesh = *object.mesh;
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      double v[3][3];
      for (int k = 0; k < 3; ++k) {
        const float3 q =
            (object.transform.matrix() * float4{mesh.positions[mesh.indices[t * 3 + k]], 1}).xyz();
        v[k][0] = q.x - eye.x, v[k][1] = q.y - eye.y, v[k][2] = q.z - eye.z;
      }
      const double e1[3] = {v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
      const double e2[3] = {v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]};
      const double pv[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2],
                            d[0] * e2[1] - d[1] * e2[0]};
      const double det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
      if (std::fabs(det) < 1e-15) continue;
      const double tv[3] = {-v[0][0], -v[0][1], -v[0][2]};
      const double u = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) / det;
      if (u < 0 || u > 1) continue;
      const double qv[3] = {tv[1] * e1[2] - tv[2] * e1[1], tv[2] * e1[0] - tv[0] * e1[2],
                            tv[0] * e1[1] - tv[1] * e1[0]};
      const double w = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) / det;
      if (w < 0 || u + w > 1) continue;
      const double dist = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
      if (dist < scene.camera.near_z || dist > scene.camera.far_z || dist >= best.distance)
        continue;
      best = {base + static_cast<uint32_t>(t) + 1, dist};
    }
    base += static_cast<uint32_t>(mesh.triangleCount());
  }
  return best;
}

}  // namespace tessera::test
