#include <tessera/viewer/temporal.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <tessera/base/check.h>
#include <tessera/scene/color.h>

namespace tessera::viewer {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// A history sample belongs to the same surface when its view depth is within 5% of the
// reprojected point's: loose enough for the jitter's sub-pixel moves and a surface seen at a
// grazing angle, tight enough that an occluder in front is never taken for it.
constexpr float kDepthTolerance = 0.05f;

// YCoCg (Malvar and Sullivan): a luma and two chroma axes, in which the box of a neighbourhood's
// colours hugs them more tightly than in RGB (Karis, "High Quality Temporal Supersampling").
float3 toYCoCg(float3 c) {
  return {0.25f * c.x + 0.5f * c.y + 0.25f * c.z, 0.5f * c.x - 0.5f * c.z,
          -0.25f * c.x + 0.5f * c.y - 0.25f * c.z};
}
float3 fromYCoCg(float3 c) {
  return {c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z};
}

float4 ndcOfSample(int x, int y, float depth, Jitter jitter, int width, int height) {
  const float z = std::isfinite(depth) ? depth : 1.0f;
  return {2.0f * (static_cast<float>(x) + 0.5f + jitter.x) / static_cast<float>(width) - 1.0f,
          1.0f - 2.0f * (static_cast<float>(y) + 0.5f + jitter.y) / static_cast<float>(height),
          2.0f * z - 1.0f, 1.0f};
}

// Row 3 of `m` times v: the w of a product without the rest.
float rowW(const float4x4& m, float4 v) {
  return m(3, 0) * v.x + m(3, 1) * v.y + m(3, 2) * v.z + m(3, 3) * v.w;
}

}  // namespace

Reprojected reprojectPixel(const float4x4& reprojection, const float4x4& inverse_current, int x,
                           int y, float depth, Jitter jitter, int width, int height) {
  const float4 ndc = ndcOfSample(x, y, depth, jitter, width, height);
  // The world point is inverse_current * ndc / its w; its clip position in the previous frame
  // is then reprojection * ndc over the same w, which cancels in the divide by clip w.
  const float4 clip = reprojection * ndc;
  const float world_w = rowW(inverse_current, ndc);
  Reprojected r;
  if (!(clip.w > 0.0f) || world_w == 0.0f) {
    r.x = r.y = -kInfinity;  // behind the previous camera: off screen
    return r;
  }
  r.x = (clip.x / clip.w + 1.0f) * 0.5f * static_cast<float>(width);
  r.y = (1.0f - clip.y / clip.w) * 0.5f * static_cast<float>(height);
  r.view_depth = clip.w / world_w;
  return r;
}

void TemporalResolver::decodeCurrent(const Frame& frame) {
  const float* decode = srgbDecodeTable();
  const size_t n = frame.pixelCount();
  current_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const uint32_t c = frame.color[i];
    current_[i] = {decode[c & 0xff], decode[(c >> 8) & 0xff], decode[(c >> 16) & 0xff]};
  }
}

void TemporalResolver::start(const Frame& frame) {
  width_ = frame.width, height_ = frame.height;
  const size_t n = frame.pixelCount();
  history_ = current_;
  still_sum_ = current_;
  next_.resize(n);
  still_base_.resize(n);
  count_.assign(n, 1);
  next_count_.resize(n);
  still_frames_ = 1;
  valid_ = true;
}

void TemporalResolver::resolve(Frame& frame, const float4x4& view_projection, Jitter jitter) {
  TESSERA_CHECK(frame.depth.size() == frame.pixelCount() && frame.color.size() == frame.depth.size())
      << "temporal reprojection needs the frame's colour and depth";
  if (frame.pixelCount() == 0) return;
  decodeCurrent(frame);
  const bool resized = frame.width != width_ || frame.height != height_;
  if (!valid_ || resized) {
    start(frame);
  } else if (std::memcmp(&view_projection, &previous_view_projection_, sizeof view_projection) ==
             0) {
    accumulateStill();
    encodeInto(frame);
  } else {
    blendMoving(frame, view_projection, jitter);
    encodeInto(frame);
  }
  previous_view_projection_ = view_projection;
  keepDepth(frame, view_projection, jitter);
}

void TemporalResolver::accumulateStill() {
  if (still_frames_ >= kJitterCycle) return;  // converged: history_ is the average and stays
  const size_t n = history_.size();
  if (still_frames_ == 1) still_base_ = history_;
  ++still_frames_;
  const float scale = 1.0f / static_cast<float>(kJitterCycle);
  const float base_weight = static_cast<float>(kJitterCycle - still_frames_);
  for (size_t i = 0; i < n; ++i) {
    still_sum_[i] += current_[i];
    // At a whole cycle the base's weight is 0 and this is the sum times 1/cycle exactly, as the
    // Accumulator computes it.
    history_[i] = (still_sum_[i] + still_base_[i] * base_weight) * scale;
    count_[i] = static_cast<uint8_t>(std::min<int>(count_[i] + 1, kMovingHistory));
  }
}

void TemporalResolver::blendMoving(const Frame& frame, const float4x4& view_projection,
                                   Jitter jitter) {
  const int w = width_, h = height_;
  const float4x4 inverse_current = inverse(view_projection);
  const float4x4 reprojection = previous_view_projection_ * inverse_current;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      const float3 current = current_[i];
      const float depth = frame.depth[i];
      const Reprojected p =
          reprojectPixel(reprojection, inverse_current, x, y, depth, jitter, w, h);
      // Off screen in the previous frame: nothing to blend with.
      if (!(p.x >= 0.0f && p.x <= static_cast<float>(w) && p.y >= 0.0f &&
            p.y <= static_cast<float>(h))) {
        next_[i] = current, next_count_[i] = 1;
        continue;
      }
      // The 2x2 history pixels around the point, bilinearly.
      const float sx = p.x - 0.5f, sy = p.y - 0.5f;
      const float fx0 = std::floor(sx), fy0 = std::floor(sy);
      const float fx = sx - fx0, fy = sy - fy0;
      const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
      const int xs[2] = {std::clamp(x0, 0, w - 1), std::clamp(x0 + 1, 0, w - 1)};
      const int ys[2] = {std::clamp(y0, 0, h - 1), std::clamp(y0 + 1, 0, h - 1)};
      // Disocclusion: none of them saw this surface (a nearer one hid it, or this is background
      // where a surface was).
      bool seen = false;
      for (int ty = 0; ty < 2 && !seen; ++ty)
        for (int tx = 0; tx < 2 && !seen; ++tx) {
          const float d = previous_depth_[static_cast<size_t>(ys[ty]) * w + xs[tx]];
          seen = std::isfinite(depth) ? std::fabs(d - p.view_depth) <= kDepthTolerance * p.view_depth
                                      : !std::isfinite(d);
        }
      if (!seen) {
        next_[i] = current, next_count_[i] = 1;
        continue;
      }
      auto at = [&](int tx, int ty) { return history_[static_cast<size_t>(ys[ty]) * w + xs[tx]]; };
      const float3 history = lerp(lerp(at(0, 0), at(1, 0), fx), lerp(at(0, 1), at(1, 1), fx), fy);
      // Stale history (a surface that changed colour, a highlight that moved) is pulled into the
      // box of the colours around the pixel now.
      float3 lo{kInfinity, kInfinity, kInfinity}, hi = -lo;
      for (int ny = std::max(y - 1, 0); ny <= std::min(y + 1, h - 1); ++ny)
        for (int nx = std::max(x - 1, 0); nx <= std::min(x + 1, w - 1); ++nx) {
          const float3 c = toYCoCg(current_[static_cast<size_t>(ny) * w + nx]);
          lo = min(lo, c), hi = max(hi, c);
        }
      const float3 clamped = fromYCoCg(max(lo, min(hi, toYCoCg(history))));
      const int nearest = std::clamp(static_cast<int>(p.x), 0, w - 1) +
                          std::clamp(static_cast<int>(p.y), 0, h - 1) * w;
      const int frames = std::min<int>(count_[static_cast<size_t>(nearest)] + 1, kMovingHistory);
      next_[i] = lerp(clamped, current, 1.0f / static_cast<float>(frames));
      next_count_[i] = static_cast<uint8_t>(frames);
    }
  }
  history_.swap(next_);
  count_.swap(next_count_);
  still_sum_ = current_;
  still_frames_ = 1;
}

void TemporalResolver::keepDepth(const Frame& frame, const float4x4& view_projection,
                                 Jitter jitter) {
  const float4x4 inverse_current = inverse(view_projection);
  previous_depth_.resize(frame.pixelCount());
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const size_t i = static_cast<size_t>(y) * width_ + x;
      const float depth = frame.depth[i];
      if (!std::isfinite(depth)) {
        previous_depth_[i] = kInfinity;
        continue;
      }
      // Clip w of the point: 1 / the w of inverse(view_projection) * its NDC position.
      const float world_w =
          rowW(inverse_current, ndcOfSample(x, y, depth, jitter, width_, height_));
      previous_depth_[i] = world_w != 0.0f ? 1.0f / world_w : kInfinity;
    }
}

void TemporalResolver::encodeInto(Frame& frame) const {
  const size_t n = frame.pixelCount();
  for (size_t i = 0; i < n; ++i) {
    const float3 c = history_[i];
    frame.color[i] = encodeSrgb8(c.x) | static_cast<uint32_t>(encodeSrgb8(c.y)) << 8 |
                     static_cast<uint32_t>(encodeSrgb8(c.z)) << 16 |
                     (frame.color[i] & 0xff000000u);
  }
}

}  // namespace tessera::viewer
