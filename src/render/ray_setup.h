// Triangle setup for the nonlinear projections (tessera/render/projection.h): a pixel is covered
// when its view ray passes through the triangle, tested with three planes through the eye.
//
// Every ray starts at the eye, the origin of camera space. With the corners q0, q1, q2 ordered so
// that det = q0 . (q1 x q2) > 0, the rays through the triangle are exactly the positive
// combinations a q0 + b q1 + c q2, and for a ray d:
//   E_k(d) = d . n_k, n_k = q_{k+1} x q_{k+2} (edge k is opposite corner k), all >= 0 inside;
//   the barycentrics of the hit are E_k / (E_0 + E_1 + E_2) (perspective-correct by construction);
//   the distance along a unit ray is det / (E_0 + E_1 + E_2).
// Two triangles sharing an edge (corners from the same camera-space vertices, both ordered as
// above) compute exactly opposite normals for it (a x b = -(b x a) in floating point too), hence
// exactly opposite E values: a ray exactly on the edge (E = 0) is given to the triangle whose n
// is positive in the first non-zero of x, y, z (`owner`), so it is covered once, never twice or
// not at all, as the top-left rule does for pixel centres.
//
// The arithmetic, in float with no fused multiply-add, in exactly this order (every backend):
//   cross(a, b) = (a.y*b.z - a.z*b.y, a.z*b.x - a.x*b.z, a.x*b.y - a.y*b.x)
//   dot(a, b)   = (a.x*b.x + a.y*b.y) + a.z*b.z
//   det = dot(q0, n0); S = (E0 + E1) + E2; t = det / S; z = (t - near) * inv_range
//   covered: every E_k > 0 or (E_k == 0 and owner bit k), and S > 0, and 0 <= z <= 1
// (z: the distance mapped linearly from near (0) to far (1), with inv_range = 1 / (far - near)).
//
// Which pixels to test: the triangle's directions as the mode's angles (latitude and longitude, or
// the angle from the view axis and the azimuth about it), exact at the corners, at the arcs'
// nearest approaches to the poles and for triangles holding a pole; mapped to up to two pixel boxes
// (two where the triangle crosses the seam of a 360-degree image), widened by the samples' reach.
#pragma once

#include <cstdint>

#include <tessera/math/vec.h>
#include <tessera/render/projection.h>
#include <tessera/scene/scene.h>

#include "render/setup.h"

namespace tessera::render {

struct alignas(64) RayTriangle {
  float n[3][3];  // edge normals n_k, see above
  float det;      // q0 . (q1 x q2) > 0
  // Up to two inclusive pixel boxes, clipped to the image; the second is empty (min_x > max_x)
  // unless the triangle crosses the seam of a 360-degree image.
  int16_t box[2][4];  // min_x, min_y, max_x, max_y
  uint8_t owner;      // bit k: rays exactly on edge k (E_k == 0) are covered
};
static_assert(sizeof(RayTriangle) == 64);

// How a hit's distance t along its unit ray becomes depth: (t - near) * inv_range, kept in [0, 1].
struct RayDepth {
  float near = 0.1f;
  float inv_range = 1.0f;
};

struct RaySetupContext {
  Projection projection = Projection::kSpherical;
  int width = 0, height = 0;
  double fov_y_radians = 0;
  CullMode cull = CullMode::kBack;
  // How far (pixels) a pixel's rays lie from its centre: 0 with one sample and no jitter; up to
  // a pixel with MSAA and jitter (kRayReach).
  double sample_reach = 0;
};
// Samples lie within the pixel, and jitter moves them by at most half a pixel.
constexpr double kRayReach = 1.0;

// Corners p[3] in camera space, in input order. False when the triangle is culled (its plane
// passes through the eye, it faces away per ctx.cull, or no pixel can see it); otherwise the
// record and the orientation (order, back_facing) that setupShadeCorners reads.
bool setupRayTriangle(const RaySetupContext& ctx, const float3 p[3], RayTriangle& out,
                      TriangleOrientation& orientation);

inline float3 crossRay(float3 a, float3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float dotRay(float3 a, float3 b) {
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}

// The barycentrics of ray d's hit (E_k / S), as the shading kernels form them.
inline void rayBarycentrics(const RayTriangle& t, float3 d, float& b0, float& b1, float& b2) {
  const float e0 = dotRay(d, {t.n[0][0], t.n[0][1], t.n[0][2]});
  const float e1 = dotRay(d, {t.n[1][0], t.n[1][1], t.n[1][2]});
  const float e2 = dotRay(d, {t.n[2][0], t.n[2][1], t.n[2][2]});
  const float inv_s = 1.0f / ((e0 + e1) + e2);
  b1 = e1 * inv_s;
  b2 = e2 * inv_s;
  b0 = 1.0f - b1 - b2;
}

}  // namespace tessera::render
