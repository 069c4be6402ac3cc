#include <tessera/viewer/temporal.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <thread>

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

float ndcX(int x, Jitter jitter, int width) {
  return 2.0f * (static_cast<float>(x) + 0.5f + jitter.x) / static_cast<float>(width) - 1.0f;
}
float ndcY(int y, Jitter jitter, int height) {
  return 1.0f - 2.0f * (static_cast<float>(y) + 0.5f + jitter.y) / static_cast<float>(height);
}
// Nothing drawn: the far plane.
float ndcZ(float depth) {
  return std::isfinite(depth) ? 2.0f * depth - 1.0f : 1.0f;
}

// Row 3 of `m` times v: the w of a product without the rest.
float rowW(const float4x4& m, float4 v) {
  return m(3, 0) * v.x + m(3, 1) * v.y + m(3, 2) * v.z + m(3, 3) * v.w;
}

// The reprojection of one row of samples: what does not depend on x and the depth, done once.
struct RowReprojection {
  float4 clip_base;        // reprojection * (0, ndc y, 0, 1)
  float4 clip_x, clip_z;   // reprojection's columns 0 and 2
  float w_base, w_x, w_z;  // the same for row 3 of inverse(current)
  float half_width, half_height;

  RowReprojection(const float4x4& reprojection, const float4x4& inverse_current, int y, int width,
                  int height) {
    const float ny = ndcY(y, {}, height);
    clip_base = reprojection.col[1] * ny + reprojection.col[3];
    clip_x = reprojection.col[0], clip_z = reprojection.col[2];
    w_base = inverse_current(3, 1) * ny + inverse_current(3, 3);
    w_x = inverse_current(3, 0), w_z = inverse_current(3, 2);
    half_width = 0.5f * static_cast<float>(width), half_height = 0.5f * static_cast<float>(height);
  }

  // The world point is inverse_current * ndc / its w; its clip position in the previous frame
  // is then reprojection * ndc over the same w, which cancels in the divide by clip w.
  Reprojected at(float ndc_x, float ndc_z) const {
    const float4 clip = clip_base + clip_x * ndc_x + clip_z * ndc_z;
    const float world_w = w_base + w_x * ndc_x + w_z * ndc_z;
    Reprojected r;
    if (!(clip.w > 0.0f) || world_w == 0.0f) {
      r.x = r.y = -std::numeric_limits<float>::infinity();  // behind the previous camera
      return r;
    }
    const float inverse_w = 1.0f / clip.w;
    r.x = (clip.x * inverse_w + 1.0f) * half_width;
    r.y = (1.0f - clip.y * inverse_w) * half_height;
    r.view_depth = clip.w / world_w;
    return r;
  }
};

// Runs body(y0, y1) over bands of rows, one band per hardware thread (the calling thread takes
// the first). Each pixel is computed alone, so the result does not depend on the banding.
template <typename Body>
void forRowBands(int rows, const Body& body) {
  const int most = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int bands = std::clamp(rows / 32, 1, std::min(most, 16));
  std::vector<std::jthread> helpers;
  helpers.reserve(static_cast<size_t>(bands - 1));
  for (int b = 1; b < bands; ++b)
    helpers.emplace_back(
        [&body, rows, bands, b] { body(rows * b / bands, rows * (b + 1) / bands); });
  body(0, rows / bands);
}

void decodeRows(const Frame& frame, std::vector<float3>& out) {
  const float* decode = srgbDecodeTable();
  out.resize(frame.pixelCount());
  forRowBands(frame.height, [&](int y0, int y1) {
    const size_t end = static_cast<size_t>(y1) * frame.width;
    for (size_t i = static_cast<size_t>(y0) * frame.width; i < end; ++i) {
      const uint32_t c = frame.color[i];
      out[i] = {decode[c & 0xff], decode[(c >> 8) & 0xff], decode[(c >> 16) & 0xff]};
    }
  });
}

// The YCoCg box of a row's pixels and their left and right neighbours: the horizontal half of
// the 3x3 neighbourhood (min and max are separable).
void rowBox(const float3* row, int width, float3* lo, float3* hi) {
  float3 left = toYCoCg(row[0]), middle = left;
  for (int x = 0; x < width; ++x) {
    const float3 right = x + 1 < width ? toYCoCg(row[x + 1]) : middle;
    lo[x] = min(min(left, middle), right);
    hi[x] = max(max(left, middle), right);
    left = middle, middle = right;
  }
}

// A pixel's reprojected history: its colour, clamped, and the frames it holds.
struct HistorySample {
  float3 color;
  int frames = 0;
};

}  // namespace

Reprojected reprojectPixel(const float4x4& reprojection, const float4x4& inverse_current, int x,
                           int y, float depth, int width, int height) {
  return RowReprojection(reprojection, inverse_current, y, width, height)
      .at(ndcX(x, {}, width), ndcZ(depth));
}

void TemporalResolver::start(const Frame& frame) {
  width_ = frame.width, height_ = frame.height;
  const size_t n = frame.pixelCount();
  history_ = current_;
  still_sum_ = current_;
  next_.resize(n);
  next_color_.resize(n);
  count_.assign(n, 1);
  next_count_.resize(n);
  still_frames_ = 1;
  valid_ = true;
}

void TemporalResolver::resolve(Frame& frame, const float4x4& view_projection, Jitter jitter) {
  TESSERA_CHECK(frame.depth.size() == frame.pixelCount() &&
                frame.color.size() == frame.depth.size())
      << "temporal reprojection needs the frame's colour and depth";
  if (frame.pixelCount() == 0) return;
  const bool resized = frame.width != width_ || frame.height != height_;
  const bool still =
      valid_ && !resized &&
      std::memcmp(&view_projection, &previous_view_projection_, sizeof view_projection) == 0;
  if (still && converged()) {
    // Nothing changes any more: the image, and the depth of the frame that completed it.
    std::memcpy(frame.color.data(), converged_color_.data(), frame.pixelCount() * 4);
    return;
  }
  decodeRows(frame, current_);
  if (!valid_ || resized) {
    start(frame);
  } else if (still) {
    // The depth of the first frame at this camera stays: the others differ only by the jitter.
    accumulateStill();
    encodeInto(frame);
    return;
  } else {
    blendMoving(frame, view_projection);
  }
  previous_view_projection_ = view_projection;
  keepDepth(frame, view_projection, jitter);
}

void TemporalResolver::accumulateStill() {
  if (still_frames_ == 1) next_ = history_;  // the image shown when the camera stopped
  ++still_frames_;
  const float scale = 1.0f / static_cast<float>(kJitterCycle);
  const float base_weight = static_cast<float>(kJitterCycle - still_frames_);
  forRowBands(height_, [&](int y0, int y1) {
    const size_t end = static_cast<size_t>(y1) * width_;
    for (size_t i = static_cast<size_t>(y0) * width_; i < end; ++i) {
      still_sum_[i] += current_[i];
      // At a whole cycle the base's weight is 0 and this is the sum times 1/cycle exactly, as
      // the Accumulator computes it.
      history_[i] = (still_sum_[i] + next_[i] * base_weight) * scale;
      count_[i] = static_cast<uint8_t>(std::min<int>(count_[i] + 1, kMovingHistory));
    }
  });
}

namespace {

// What blendMoving reads and writes, for the per-pixel work.
struct MovingPass {
  int width, height;
  const std::vector<float3>& history;
  const std::vector<float>& previous_depth;
  const std::vector<uint8_t>& count;

  // The history of a point reprojected to p, if any of the 2x2 history pixels around it saw the
  // same surface: bilinear, clamped into lo..hi (YCoCg), with the nearest pixel's count.
  bool sample(const Reprojected& p, float depth, float3 lo, float3 hi, HistorySample& out) const {
    const int w = width, h = height;
    if (!(p.x >= 0.0f && p.x <= static_cast<float>(w) && p.y >= 0.0f &&
          p.y <= static_cast<float>(h)))
      return false;  // off screen in the previous frame
    const float sx = p.x - 0.5f, sy = p.y - 0.5f;
    const float fx0 = std::floor(sx), fy0 = std::floor(sy);
    const float fx = sx - fx0, fy = sy - fy0;
    const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
    const size_t xs[2] = {static_cast<size_t>(std::clamp(x0, 0, w - 1)),
                          static_cast<size_t>(std::clamp(x0 + 1, 0, w - 1))};
    const size_t rows[2] = {static_cast<size_t>(std::clamp(y0, 0, h - 1)) * w,
                            static_cast<size_t>(std::clamp(y0 + 1, 0, h - 1)) * w};
    // Disocclusion: none of them saw this surface (a nearer one hid it, or this is background
    // where a surface was).
    bool seen = false;
    const bool surface = std::isfinite(depth);
    for (size_t row : rows)
      for (size_t x : xs) {
        const float d = previous_depth[row + x];
        seen |= surface ? std::fabs(d - p.view_depth) <= kDepthTolerance * p.view_depth
                        : !std::isfinite(d);
      }
    if (!seen) return false;
    auto at = [&](int tx, int ty) { return history[rows[ty] + xs[tx]]; };
    const float3 blended = lerp(lerp(at(0, 0), at(1, 0), fx), lerp(at(0, 1), at(1, 1), fx), fy);
    // Stale history (a surface that changed colour, a highlight that moved) is pulled into the
    // box of the colours around the pixel now.
    out.color = fromYCoCg(max(lo, min(hi, toYCoCg(blended))));
    out.frames = count[rows[fy < 0.5f ? 0 : 1] + xs[fx < 0.5f ? 0 : 1]];
    return true;
  }
};

// Whether the 3x3 neighbourhood of (x, y) is one colour (alpha aside), given row pointers.
bool flatAround(const uint32_t* const rows[3], int x, int width) {
  const uint32_t c = rows[1][x] & 0xffffffu;
  const int left = std::max(x - 1, 0), right = std::min(x + 1, width - 1);
  for (int r = 0; r < 3; ++r)
    if ((rows[r][left] & 0xffffffu) != c || (rows[r][x] & 0xffffffu) != c ||
        (rows[r][right] & 0xffffffu) != c)
      return false;
  return true;
}

// encodeSrgb8 by table (its codes in a lookup and a comparison instead of a polynomial).
uint32_t encodePixel(float3 c, uint32_t alpha_from) {
  return encodeSrgb8ByTable(c.x) | static_cast<uint32_t>(encodeSrgb8ByTable(c.y)) << 8 |
         static_cast<uint32_t>(encodeSrgb8ByTable(c.z)) << 16 | (alpha_from & 0xff000000u);
}

}  // namespace

void TemporalResolver::blendMoving(Frame& frame, const float4x4& view_projection) {
  const int w = width_, h = height_;
  const float4x4 inverse_current = inverse(view_projection);
  const float4x4 reprojection = previous_view_projection_ * inverse_current;
  const MovingPass pass{w, h, history_, previous_depth_, count_};
  forRowBands(h, [&](int band_y0, int band_y1) {
    // The horizontal boxes of three rows, in turn: row r in slot r % 3.
    std::vector<float3> lo(static_cast<size_t>(3) * w), hi(lo.size());
    auto box = [&](int r) {
      const size_t slot = static_cast<size_t>(r % 3) * w;
      rowBox(&current_[static_cast<size_t>(r) * w], w, &lo[slot], &hi[slot]);
    };
    box(std::max(band_y0 - 1, 0));
    if (band_y0 > 0) box(band_y0);
    for (int y = band_y0; y < band_y1; ++y) {
      if (y + 1 < h) box(y + 1);
      const int around[3] = {std::max(y - 1, 0), y, std::min(y + 1, h - 1)};
      const uint32_t* colors[3];
      const float3 *rows_lo[3], *rows_hi[3];
      for (int r = 0; r < 3; ++r) {
        colors[r] = &frame.color[static_cast<size_t>(around[r]) * w];
        rows_lo[r] = &lo[static_cast<size_t>(around[r] % 3) * w];
        rows_hi[r] = &hi[static_cast<size_t>(around[r] % 3) * w];
      }
      // History pixels are unjittered (the average of a cycle of offsets centred on each pixel):
      // the pixel's centre is what is reprojected, with the depth its sample saw.
      const RowReprojection row(reprojection, inverse_current, y, w, h);
      // The encoded colours go to a row of their own: the next row's neighbourhoods still read
      // this row's frame colours.
      uint32_t* out = &next_color_[static_cast<size_t>(y) * w];
      for (int x = 0; x < w; ++x) {
        const size_t i = static_cast<size_t>(y) * w + x;
        const float3 current = current_[i];
        out[x] = frame.color[i];
        // One colour all around: any history clamps to it, so the blend is the current colour.
        if (flatAround(colors, x, w)) {
          next_[i] = current;
          next_count_[i] = static_cast<uint8_t>(std::min<int>(count_[i] + 1, kMovingHistory));
          continue;
        }
        const float depth = frame.depth[i];
        const float3 box_lo = min(min(rows_lo[0][x], rows_lo[1][x]), rows_lo[2][x]);
        const float3 box_hi = max(max(rows_hi[0][x], rows_hi[1][x]), rows_hi[2][x]);
        HistorySample history;
        if (!pass.sample(row.at(ndcX(x, {}, w), ndcZ(depth)), depth, box_lo, box_hi, history)) {
          next_[i] = current, next_count_[i] = 1;
          continue;
        }
        const int frames = std::min(history.frames + 1, kMovingHistory);
        next_[i] = lerp(history.color, current, 1.0f / static_cast<float>(frames));
        next_count_[i] = static_cast<uint8_t>(frames);
        out[x] = encodePixel(next_[i], frame.color[i]);
      }
    }
  });
  frame.color.swap(next_color_);
  history_.swap(next_);
  count_.swap(next_count_);
  // The first frame at this camera: the still sum starts with it (current_ is decoded afresh
  // for the next frame, so it can be taken rather than copied).
  still_sum_.swap(current_);
  still_frames_ = 1;
}

void TemporalResolver::keepDepth(const Frame& frame, const float4x4& view_projection,
                                 Jitter jitter) {
  const float4x4 inverse_current = inverse(view_projection);
  previous_depth_.resize(frame.pixelCount());
  forRowBands(height_, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const float ny = ndcY(y, jitter, height_);
      for (int x = 0; x < width_; ++x) {
        const size_t i = static_cast<size_t>(y) * width_ + x;
        const float depth = frame.depth[i];
        // Clip w of the point: 1 / the w of inverse(view_projection) * its NDC position.
        const float world_w =
            std::isfinite(depth)
                ? rowW(inverse_current, {ndcX(x, jitter, width_), ny, ndcZ(depth), 1.0f})
                : 0.0f;
        previous_depth_[i] = world_w != 0.0f ? 1.0f / world_w : kInfinity;
      }
    }
  });
}

void TemporalResolver::encodeInto(Frame& frame) {
  forRowBands(height_, [&](int y0, int y1) {
    const size_t end = static_cast<size_t>(y1) * width_;
    for (size_t i = static_cast<size_t>(y0) * width_; i < end; ++i)
      frame.color[i] = encodePixel(history_[i], frame.color[i]);
  });
  if (converged()) converged_color_ = frame.color;
}

}  // namespace tessera::viewer
