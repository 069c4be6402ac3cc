#include "render/clip.h"

#include "render/fixed_point.h"

namespace tessera::render {

GuardBand makeGuardBand(int width, int height) {
  // Window x = (x/w * 0.5 + 0.5) * width lies in [-G, width + G] exactly when
  // |x/w| <= 1 + 2G/width.
  return {1.0f + 2.0f * kGuardBandPixels / static_cast<float>(width),
          1.0f + 2.0f * kGuardBandPixels / static_cast<float>(height)};
}

namespace {

// Signed distance to a plane; inside when >= 0.
float planeDistance(uint32_t plane, float4 p, const GuardBand& guard) {
  switch (plane) {
    case kClipNear:
      return p.z + p.w;
    case kClipFar:
      return p.w - p.z;
    case kGuardLeft:
      return p.x + guard.x_factor * p.w;
    case kGuardRight:
      return guard.x_factor * p.w - p.x;
    case kGuardBottom:
      return p.y + guard.y_factor * p.w;
    default:
      return guard.y_factor * p.w - p.y;  // kGuardTop
  }
}

ClipVertex interpolate(const ClipVertex& inside, const ClipVertex& outside, float t) {
  ClipVertex v;
  v.position = lerp(inside.position, outside.position, t);
  v.normal = lerp(inside.normal, outside.normal, t);
  v.uv = inside.uv + (outside.uv - inside.uv) * t;
  v.color = lerp(inside.color, outside.color, t);
  v.world = lerp(inside.world, outside.world, t);
  v.tangent = lerp(inside.tangent, outside.tangent, t);
  v.uv1 = inside.uv1 + (outside.uv1 - inside.uv1) * t;
  return v;
}

}  // namespace

int clipTriangle(const ClipVertex in[3], uint32_t planes, const GuardBand& guard,
                 ClipVertex out[kMaxClippedVertices]) {
  ClipVertex buffer_a[kMaxClippedVertices], buffer_b[kMaxClippedVertices];
  ClipVertex* src = buffer_a;
  ClipVertex* dst = buffer_b;
  int count = 3;
  for (int i = 0; i < 3; ++i) src[i] = in[i];

  for (uint32_t plane : {kClipNear, kClipFar, kGuardLeft, kGuardRight, kGuardBottom, kGuardTop}) {
    if (!(planes & plane)) continue;
    int out_count = 0;
    for (int i = 0; i < count; ++i) {
      const ClipVertex& a = src[i];
      const ClipVertex& b = src[(i + 1) % count];
      float da = planeDistance(plane, a.position, guard);
      float db = planeDistance(plane, b.position, guard);
      bool a_in = da >= 0.0f, b_in = db >= 0.0f;
      if (a_in) dst[out_count++] = a;
      if (a_in != b_in) {
        // Always from the inside vertex towards the outside one (see the header).
        dst[out_count++] =
            a_in ? interpolate(a, b, da / (da - db)) : interpolate(b, a, db / (db - da));
      }
    }
    count = out_count;
    std::swap(src, dst);
    if (count < 3) return 0;
  }
  for (int i = 0; i < count; ++i) out[i] = src[i];
  return count;
}

}  // namespace tessera::render
