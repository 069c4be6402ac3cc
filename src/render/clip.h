// Assembly-time clipping: trivial reject against the view frustum, and Sutherland-Hodgman
// clipping against the near and far planes (always exactly) and against the guard band (only
// where a triangle leaves it, so almost no triangle is ever cut at the screen edges).
#pragma once

#include <cstdint>

#include <tessera/math/vec.h>

namespace tessera::render {

// A vertex as the clipper sees it: clip-space position plus every interpolated attribute.
// Attributes are linear in clip space, so the cut interpolates them with the same t.
struct ClipVertex {
  float4 position;
  float3 normal;
  float2 uv;
  float4 color;
  float3 world;      // world position: point and spot lights, kPbr
  float4 tangent{};  // world tangent: kPbr with a normal map
  float2 uv1{};      // TEXCOORD_1: materials that read it (SetupContext::uv1)
};

enum ClipPlaneBit : uint32_t {
  kClipNear = 1u << 0,
  kClipFar = 1u << 1,
  kClipLeft = 1u << 2,  // the viewport's planes (x = -w ...): for trivial reject only
  kClipRight = 1u << 3,
  kClipBottom = 1u << 4,
  kClipTop = 1u << 5,
  kGuardLeft = 1u << 6,  // the guard band's planes: clipped against when crossed
  kGuardRight = 1u << 7,
  kGuardBottom = 1u << 8,
  kGuardTop = 1u << 9,
  kNonFinite = 1u << 10,  // a NaN or infinite coordinate: the triangle is dropped
};
constexpr uint32_t kRejectPlanes =
    kClipNear | kClipFar | kClipLeft | kClipRight | kClipBottom | kClipTop;
constexpr uint32_t kCutPlanes =
    kClipNear | kClipFar | kGuardLeft | kGuardRight | kGuardBottom | kGuardTop;

// The guard band as clip-space factors: a vertex is inside when |x| <= x_factor * w and
// |y| <= y_factor * w.
struct GuardBand {
  float x_factor = 1.0f;
  float y_factor = 1.0f;
};
GuardBand makeGuardBand(int width, int height);

// A vertex's outcode (the planes it is outside of) is computed in the vertex stage, eight at a
// time: see vertex_kernel.h.

// The most vertices a triangle cut by the six cut planes can have.
constexpr int kMaxClippedVertices = 3 + 6;

// Clips the triangle (in[0], in[1], in[2]) against the planes in `planes` (a subset of
// kCutPlanes). Writes the convex polygon to `out` and returns its vertex count (0 if nothing is
// left). Each intersection is computed from the inside vertex towards the outside one, so an edge
// shared by two triangles is cut at bit-identical points in both.
int clipTriangle(const ClipVertex in[3], uint32_t planes, const GuardBand& guard,
                 ClipVertex out[kMaxClippedVertices]);

}  // namespace tessera::render
