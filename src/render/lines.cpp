#include "render/lines.h"

#include <algorithm>
#include <cmath>

#include <tessera/scene/color.h>

namespace tessera::render {

uint32_t blendOver(uint32_t under, float3 color, float a) {
  // Alpha too, for a transparent background (composite.h).
  const float under_alpha = static_cast<float>(under >> 24);
  uint32_t mixed = static_cast<uint32_t>(std::lround(under_alpha + (255.0f - under_alpha) * a))
                   << 24;
  for (int k = 0; k < 3; ++k) {
    const float below = decodeSrgb8(static_cast<uint8_t>(under >> (8 * k)));
    mixed |= static_cast<uint32_t>(encodeSrgb8(below + (color[k] - below) * a)) << (8 * k);
  }
  return mixed;
}

void appendAxes(LineList& lines, const float4x4& m, float length) {
  const float3 origin = (m * float4{0, 0, 0, 1}).xyz();
  const float3 colors[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int axis = 0; axis < 3; ++axis) {
    float3 end{0, 0, 0};
    end[axis] = length;
    lines.add(origin, (m * float4{end, 1}).xyz(), colors[axis]);
  }
}

namespace {

// Clips the segment a-b (clip space) to the view frustum; false if nothing is left.
bool clipSegment(float4& a, float4& b) {
  float t0 = 0.0f, t1 = 1.0f;
  // Plane distances (inside >= 0) for x, y, z against +-w.
  auto distances = [](float4 p, float d[6]) {
    d[0] = p.w + p.x, d[1] = p.w - p.x, d[2] = p.w + p.y;
    d[3] = p.w - p.y, d[4] = p.w + p.z, d[5] = p.w - p.z;
  };
  float da[6], db[6];
  distances(a, da);
  distances(b, db);
  for (int i = 0; i < 6; ++i) {
    if (da[i] < 0 && db[i] < 0) return false;
    if (da[i] < 0)
      t0 = std::max(t0, da[i] / (da[i] - db[i]));
    else if (db[i] < 0)
      t1 = std::min(t1, da[i] / (da[i] - db[i]));
  }
  if (t0 > t1) return false;
  const float4 a0 = a;
  a = lerp(a0, b, t0);
  b = lerp(a0, b, t1);
  return true;
}

}  // namespace

namespace {

// Mixes `color` (linear) into pixel (x, y) with weight `a`, where z is nearer than the depth.
void blendPixel(Frame& frame, int x, int y, float z, float3 color, float a) {
  if (x < 0 || y < 0 || x >= frame.width || y >= frame.height || a <= 0.0f) return;
  const size_t index = static_cast<size_t>(y) * frame.width + x;
  if (!(z < frame.depth[index])) return;
  frame.color[index] = blendOver(frame.color[index], color, a);
}

}  // namespace

namespace {

// The pixels across a wide line at a step: those whose row (or column) overlaps the line's
// `width` about `across`, with that overlap as their weight when anti-aliased.
void drawAcross(Frame& frame, bool x_major, int along, float across, float z, float3 linear,
                uint32_t color, bool antialiased, float width) {
  const float low = across - 0.5f * width, high = across + 0.5f * width;
  auto put = [&](int k, float weight) {
    const int x = x_major ? along : k, y = x_major ? k : along;
    if (antialiased) {
      blendPixel(frame, x, y, z, linear, weight);
      return;
    }
    if (x < 0 || y < 0 || x >= frame.width || y >= frame.height) return;
    const size_t index = static_cast<size_t>(y) * frame.width + x;
    if (z < frame.depth[index]) frame.color[index] = color;
  };
  if (!antialiased) {
    // The pixels whose centres are within the width (one pixel wide: the one holding `across`).
    const int first = static_cast<int>(std::floor(across - 0.5f * (width - 1.0f)));
    const int last = static_cast<int>(std::floor(across + 0.5f * (width - 1.0f)));
    for (int k = first; k <= last; ++k) put(k, 1.0f);
    return;
  }
  const int first = static_cast<int>(std::floor(low)), last = static_cast<int>(std::floor(high));
  for (int k = first; k <= last; ++k) {
    const float kf = static_cast<float>(k);
    put(k, std::min(high, kf + 1.0f) - std::max(low, kf));
  }
}

// Steps along the window-space segment sa-sb (z: window depth) a pixel at a time.
void drawWindowSegment(Frame& frame, float3 sa, float3 sb, float3 linear, bool antialiased,
                       float width = 1.0f) {
  const float w = static_cast<float>(frame.width), h = static_cast<float>(frame.height);
  const uint32_t color = packSrgba8(float4{linear, 1.0f});
  const bool x_major = std::fabs(sb.x - sa.x) >= std::fabs(sb.y - sa.y);
  const float steps = std::ceil(std::max(std::fabs(sb.x - sa.x), std::fabs(sb.y - sa.y)));
  const int n = static_cast<int>(std::min(steps, 4.0f * (w + h)));
  for (int s = 0; s <= n; ++s) {
    const float t = n > 0 ? static_cast<float>(s) / n : 0.0f;
    const float3 p = lerp(sa, sb, t);
    if (width != 1.0f) {
      const int along = static_cast<int>(std::floor(x_major ? p.x : p.y));
      drawAcross(frame, x_major, along, x_major ? p.y : p.x, p.z, linear, color, antialiased,
                 width);
      continue;
    }
    if (antialiased) {
      // The two pixel centres across the line nearest p, by their distance from it.
      const float across = (x_major ? p.y : p.x) - 0.5f;
      const float low = std::floor(across), f = across - low;
      const int along = static_cast<int>(std::floor(x_major ? p.x : p.y));
      const int first = static_cast<int>(low);
      if (x_major) {
        blendPixel(frame, along, first, p.z, linear, 1.0f - f);
        blendPixel(frame, along, first + 1, p.z, linear, f);
      } else {
        blendPixel(frame, first, along, p.z, linear, 1.0f - f);
        blendPixel(frame, first + 1, along, p.z, linear, f);
      }
      continue;
    }
    const int x = static_cast<int>(std::floor(p.x)), y = static_cast<int>(std::floor(p.y));
    if (x < 0 || y < 0 || x >= frame.width || y >= frame.height) continue;
    const size_t index = static_cast<size_t>(y) * frame.width + x;
    if (p.z < frame.depth[index]) frame.color[index] = color;
  }
}

}  // namespace

void drawLines(const LineList& lines, const float4x4& view_projection, Frame& frame,
               bool antialiased, const LineStyle& style) {
  const float w = static_cast<float>(frame.width), h = static_cast<float>(frame.height);
  // Pulled towards the eye in clip space: the clip position is linear in the world position.
  const float4 eye = view_projection * float4{style.eye, 1.0f};
  for (size_t i = 0; i + 1 < lines.points.size(); i += 2) {
    float4 a = view_projection * float4{lines.points[i], 1.0f};
    float4 b = view_projection * float4{lines.points[i + 1], 1.0f};
    if (style.pull != 0.0f) {
      a = lerp(a, eye, style.pull);
      b = lerp(b, eye, style.pull);
    }
    if (!clipSegment(a, b)) continue;
    auto window = [&](float4 p) {
      return float3{(p.x / p.w * 0.5f + 0.5f) * w, (0.5f - p.y / p.w * 0.5f) * h,
                    p.z / p.w * 0.5f + 0.5f};
    };
    const float3 sa = window(a), sb = window(b);
    if (!isFinite(sa) || !isFinite(sb)) continue;
    drawWindowSegment(frame, sa, sb, lines.colors[i / 2], antialiased, style.width);
  }
}

void drawRayLines(const LineList& lines, const float4x4& view, const RayLines& mode, Frame& frame,
                  bool antialiased, float width) {
  // Pieces short enough that the curve between their ends is within a fraction of a pixel of the
  // chord at the image sizes in use; a piece whose ends land on both sides of a seam is skipped.
  constexpr int kPieces = 256;
  const double seam = 0.5 * frame.width;
  for (size_t i = 0; i + 1 < lines.points.size(); i += 2) {
    const float3 a = (view * float4{lines.points[i], 1.0f}).xyz();
    const float3 b = (view * float4{lines.points[i + 1], 1.0f}).xyz();
    bool have_last = false;
    float3 last{};
    for (int k = 0; k <= kPieces; ++k) {
      const float3 p = lerp(a, b, static_cast<float>(k) / kPieces);
      const double d[3] = {p.x, p.y, p.z};
      const double distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      double sx, sy;
      const bool seen = distance >= mode.near && distance <= mode.far &&
                        projectDirection(mode.projection, d, frame.width, frame.height,
                                         mode.fov_y_radians, sx, sy);
      if (!seen) {
        have_last = false;
        continue;
      }
      const float3 q{static_cast<float>(sx), static_cast<float>(sy),
                     static_cast<float>((distance - mode.near) / (mode.far - mode.near))};
      if (have_last && std::fabs(q.x - last.x) < seam)
        drawWindowSegment(frame, last, q, lines.colors[i / 2], antialiased, width);
      last = q;
      have_last = true;
    }
  }
}

}  // namespace tessera::render
