#include "render/point_pass.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include <tessera/base/check.h>
#include <tessera/render/projection.h>
#include <tessera/scene/color.h>

namespace tessera::render {

namespace {

constexpr size_t kBlock = 256;             // points projected per call
constexpr size_t kChunk = kBlock * 128;    // points per count/place job: 306 for 10M
constexpr uint32_t kHidden = 0xffffffffu;  // a point not drawn
constexpr float kFarOff = 1e9f;            // window coordinates beyond this are not drawn

struct ProjectedBlock {
  float x[kBlock], y[kBlock];
  uint32_t depth[kBlock];  // window depth bits, kHidden when not drawn
};

uint32_t depthBits(float z) {
  return std::bit_cast<uint32_t>(z + 0.0f);  // -0 as +0: window depth orders as its bits
}

// Projects points[0, n) into `out`. Not inlined, so that the count and place stages run the
// same instructions and get the same bits.
__attribute__((noinline)) void projectBlock(const PointCamera& camera, int width, int height,
                                            const float3* points, size_t n, ProjectedBlock& out) {
  const float w = static_cast<float>(width), h = static_cast<float>(height);
  if (camera.projection == Projection::kPerspective) {
    const float4x4& m = camera.view_projection;
    for (size_t i = 0; i < n; ++i) {
      const float4 c = m * float4{points[i], 1.0f};
      const float x = (c.x / c.w * 0.5f + 0.5f) * w, y = (0.5f - c.y / c.w * 0.5f) * h;
      const float z = c.z / c.w * 0.5f + 0.5f;
      const bool seen = c.w > 0.0f && z >= 0.0f && z <= 1.0f && x > -kFarOff && x < kFarOff &&
                        y > -kFarOff && y < kFarOff;
      out.x[i] = x;
      out.y[i] = y;
      out.depth[i] = seen ? depthBits(z) : kHidden;
    }
    return;
  }
  const RayLines& mode = camera.rays;
  for (size_t i = 0; i < n; ++i) {
    const float3 q = (camera.view * float4{points[i], 1.0f}).xyz();
    const double d[3] = {q.x, q.y, q.z};
    const double distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double sx = 0, sy = 0;
    const bool seen =
        distance >= mode.near && distance <= mode.far &&
        projectDirection(mode.projection, d, width, height, mode.fov_y_radians, sx, sy);
    out.x[i] = static_cast<float>(sx);
    out.y[i] = static_cast<float>(sy);
    out.depth[i] =
        seen ? depthBits(static_cast<float>((distance - mode.near) / (mode.far - mode.near)))
             : kHidden;
  }
}

// floor and ceil for |v| < 2^31 without a call into libm (the baseline x86-64 has no roundss).
int floorToInt(float v) {
  const int i = static_cast<int>(v);
  return i - (static_cast<float>(i) > v);
}
int ceilToInt(float v) {
  const int i = static_cast<int>(v);
  return i + (static_cast<float>(i) < v);
}

// The pixels along one axis (of `size`) that a disc of radius r about c can touch: with centres
// within r (and the one holding c), or antialiased within r + 0.5. Coordinates are clamped to
// [-1, size] first, which changes no pixel on the image and keeps the conversions in range.
inline PixelSpan discSpan(float c, float r, bool antialiased, int size) {
  const float top = static_cast<float>(size);
  auto clamped = [top](float v) { return std::min(std::max(v, -1.0f), top); };
  const int holding = floorToInt(clamped(c));
  int low, high;
  if (antialiased) {
    low = std::min(floorToInt(clamped(c - r)), holding);
    high = std::max(floorToInt(clamped(c + r)), holding);
  } else {
    low = std::min(ceilToInt(clamped(c - r - 0.5f)), holding);
    high = std::max(floorToInt(clamped(c + r - 0.5f)), holding);
  }
  return {std::max(low, 0), std::min(high, size - 1)};
}

// Whether pixel (px, py) belongs to the disc: its centre within r (d2: squared distance) or it
// holds the point (hx, hy); antialiased, also those within r + 0.5 (a part of the disc's edge).
struct DiscTest {
  float r2, reach2;
  bool antialiased;

  bool centre(float d2, int px, int py, int hx, int hy) const {
    return d2 <= r2 || (px == hx && py == hy);
  }
  bool touches(float d2, int px, int py, int hx, int hy) const {
    return centre(d2, px, py, hx, hy) || (antialiased && d2 < reach2);
  }
};

// A sprite's sphere: window depth as the surface comes towards the eye by h (0 at the disc's
// edge, 1 at its centre) of its world radius: ((a + h b) / (c + h d)) e + f.
struct SphereDepth {
  float a, b, c, d, e, f;
  float world_radius;

  float at(float h) const { return std::max(0.0f, (a + h * b) / (c + h * d) * e + f); }
};

SphereDepth sphereDepth(const PointCamera& camera, float3 p, float radius_px, int height,
                        const float3x3& camera_to_world) {
  if (camera.projection == Projection::kPerspective) {
    const float4 clip = camera.view_projection * float4{p, 1.0f};
    // Pixels per world unit at w = 1, along the camera's up axis (no w: no perspective divide).
    const float4 up = camera.view_projection * float4{camera_to_world.col[1], 0.0f};
    const float radius = radius_px * clip.w / (up.y * 0.5f * static_cast<float>(height));
    const float4 back = camera.view_projection * float4{camera_to_world.col[2], 0.0f};
    return {clip.z, radius * back.z, clip.w, radius * back.w, 0.5f, 0.5f, radius};
  }
  const float3 q = (camera.view * float4{p, 1.0f}).xyz();
  const float distance = length(q);
  const float near = static_cast<float>(camera.rays.near),
              far = static_cast<float>(camera.rays.far);
  // The nonlinear modes' pixels span about fov / height radians each, across and along.
  const float radius = radius_px * distance * static_cast<float>(camera.rays.fov_y_radians) /
                       static_cast<float>(height);
  return {distance - near, -radius, far - near, 0.0f, 1.0f, 0.0f, radius};
}

// The camera-space normal of a sphere impostor at offset (u, v) (in radii, v up) from the centre
// of the disc of the camera-space point q: facing the eye, then tilted by the offset.
float3 spriteNormal(float3 q, float u, float v) {
  const float3 back = normalize(float3{0, 0, 0} - q);
  float3 right = cross(float3{0, 1, 0}, back);
  right = dot(right, right) > 1e-12f ? normalize(right) : float3{1, 0, 0};
  const float3 up = cross(back, right);
  const float s = u * u + v * v;
  if (s > 1.0f) {
    const float k = 1.0f / std::sqrt(s);
    return right * (u * k) + up * (v * k);
  }
  return right * u + up * v + back * std::sqrt(1.0f - s);
}

}  // namespace

namespace {

// Calls visit(index, x, y, depth_bits, rows) for every point of `chunk` that is drawn.
template <typename Visit>
void forEachVisible(const PointCamera& camera, const PointList& points, size_t chunk, int width,
                    int height, float radius, bool antialiased, Visit&& visit) {
  const size_t begin = chunk * kChunk, end = std::min(points.size(), begin + kChunk);
  ProjectedBlock block;
  for (size_t first = begin; first < end; first += kBlock) {
    const size_t n = std::min(kBlock, end - first);
    projectBlock(camera, width, height, points.positions.data() + first, n, block);
    for (size_t i = 0; i < n; ++i) {
      if (block.depth[i] == kHidden) continue;
      const PixelSpan rows = discSpan(block.y[i], radius, antialiased, height);
      if (rows.empty() || discSpan(block.x[i], radius, antialiased, width).empty()) continue;
      visit(first + i, block.x[i], block.y[i], block.depth[i], rows);
    }
  }
}

}  // namespace

void PointPass::countChunk(size_t chunk) {
  uint32_t* counts = &counts_[chunk * static_cast<size_t>(bands_)];
  std::fill(counts, counts + bands_, 0u);
  forEachVisible(camera_, scene_->points, chunk, width_, height_, radius_, antialiased_,
                 [&](size_t, float, float, uint32_t, PixelSpan rows) {
                   for (int b = rows.first / kPointBandRows; b <= rows.last / kPointBandRows; ++b)
                     ++counts[b];
                 });
}

void PointPass::placeChunk(size_t chunk) {
  const std::vector<uint32_t>& colors = scene_->points.colors;
  const bool own_colors = colors.size() == scene_->points.size();
  const uint32_t default_color = packSrgba8(float4{options_->points.color, 1.0f});
  uint32_t* next = &counts_[chunk * static_cast<size_t>(bands_)];  // each band's next slot
  forEachVisible(camera_, scene_->points, chunk, width_, height_, radius_, antialiased_,
                 [&](size_t index, float x, float y, uint32_t depth, PixelSpan rows) {
                   const uint32_t color = own_colors ? colors[index] : default_color;
                   for (int b = rows.first / kPointBandRows; b <= rows.last / kPointBandRows; ++b) {
                     const size_t slot = band_start_[b] + next[b]++;
                     records_[slot] = Record{x, y, depth, static_cast<uint32_t>(index)};
                     record_colors_[slot] = color;
                   }
                 });
}

void PointPass::draw(const Scene& scene, const RenderOptions& options, const PointCamera& camera,
                     bool antialiased, WorkerPool& pool, Frame& frame) {
  const PointList& points = scene.points;
  if (points.empty()) return;
  TESSERA_CHECK(std::isfinite(options.points.size) && options.points.size > 0.0f)
      << "point size " << options.points.size << " is not above 0";
  TESSERA_CHECK(points.size() < kHidden) << points.size() << " points";
  TESSERA_CHECK(frame.depth.size() == frame.pixelCount()) << "the point pass needs a depth buffer";
  scene_ = &scene;
  options_ = &options;
  camera_ = camera;
  antialiased_ = antialiased;
  width_ = frame.width;
  height_ = frame.height;
  bands_ = (height_ + kPointBandRows - 1) / kPointBandRows;
  radius_ = 0.5f * options.points.size;
  camera_to_world_ = transpose(upper3x3(camera.view));  // the view is rigid
  lights_.prepare(scene);

  // Count, then lay the bands out (band by band, chunk by chunk), then place.
  const size_t chunks = (points.size() + kChunk - 1) / kChunk;
  const size_t bands = static_cast<size_t>(bands_);
  if (counts_.size() < chunks * bands) counts_.resize(chunks * bands);
  pool.parallelFor(chunks, [&](size_t c, int) { countChunk(c); });
  band_start_.resize(bands + 1);
  size_t total = 0;
  for (size_t b = 0; b < bands; ++b) {
    band_start_[b] = total;
    for (size_t c = 0; c < chunks; ++c) {
      const uint32_t count = counts_[c * bands + b];
      counts_[c * bands + b] = static_cast<uint32_t>(total - band_start_[b]);
      total += count;
    }
    TESSERA_CHECK(total - band_start_[b] < kHidden) << "a band of " << total << " points";
  }
  band_start_[bands] = total;
  if (records_.size() < total) {
    records_.resize(total);
    record_colors_.resize(total);
  }
  pool.parallelFor(chunks, [&](size_t c, int) { placeChunk(c); });

  if (keys_.size() < frame.pixelCount()) {
    keys_.resize(frame.pixelCount());
    win_color_.resize(frame.pixelCount());
    win_coverage_.resize(frame.pixelCount());
  }
  pool.parallelFor(bands, [&](size_t b, int) { splatBand(static_cast<int>(b), frame); });
}

void PointPass::splatBand(int band, Frame& frame) {
  const int y0 = band * kPointBandRows, y1 = std::min(height_, y0 + kPointBandRows);
  const size_t base = static_cast<size_t>(y0) * static_cast<size_t>(width_);
  const size_t pixels = static_cast<size_t>(y1 - y0) * static_cast<size_t>(width_);
  uint64_t* keys = &keys_[base];
  const float* depth = &frame.depth[base];
  for (size_t i = 0; i < pixels; ++i) keys[i] = uint64_t{std::bit_cast<uint32_t>(depth[i])} << 32;

  const size_t first = band_start_[band], count = band_start_[band + 1] - first;
  const Record* records = &records_[first];
  const uint32_t* colors = &record_colors_[first];
  const bool sprites = options_->points.sprites;
  const DiscTest test{radius_ * radius_, (radius_ + 0.5f) * (radius_ + 0.5f), antialiased_};
  for (size_t rank = 0; rank < count; ++rank) {
    const Record& rec = records[rank];
    PixelSpan rows = discSpan(rec.y, radius_, antialiased_, height_);
    rows.first = std::max(rows.first, y0);
    rows.last = std::min(rows.last, y1 - 1);
    const PixelSpan cols = discSpan(rec.x, radius_, antialiased_, width_);
    const uint64_t flat_key = uint64_t{rec.depth} << 32 | (rank + 1);
    const int hx = floorToInt(rec.x), hy = floorToInt(rec.y);
    if (!sprites && !antialiased_) {
      splatFlat(rows, cols, rec.x, rec.y, flat_key, colors[rank]);
      continue;
    }
    SphereDepth sphere{};
    if (sprites)
      sphere = sphereDepth(camera_, scene_->points.positions[rec.index], radius_, height_,
                           camera_to_world_);
    for (int py = rows.first; py <= rows.last; ++py) {
      const float dy = static_cast<float>(py) + 0.5f - rec.y, dy2 = dy * dy;
      const size_t row = base + static_cast<size_t>(py - y0) * static_cast<size_t>(width_);
      for (int px = cols.first; px <= cols.last; ++px) {
        const float dx = static_cast<float>(px) + 0.5f - rec.x, d2 = dx * dx + dy2;
        if (!test.touches(d2, px, py, hx, hy)) continue;
        uint64_t key = flat_key;
        if (sprites) {
          const float h = std::sqrt(std::max(0.0f, 1.0f - d2 / test.r2));
          key = uint64_t{depthBits(sphere.at(h))} << 32 | (rank + 1);
        }
        const size_t i = row + static_cast<size_t>(px);
        if (!(key < keys_[i])) continue;
        // The winner so far: its colour and coverage kept beside the key, so that the resolve
        // of flat discs reads nothing but this band's pixels.
        keys_[i] = key;
        win_color_[i] = colors[rank];
        win_coverage_[i] = coverageByte(test.centre(d2, px, py, hx, hy), d2);
      }
    }
  }
  resolveBand(band, frame);
}

void PointPass::splatFlat(PixelSpan rows, PixelSpan cols, float x, float y, uint64_t key,
                          uint32_t color) {
  // Without branches on coverage or depth (they mispredict about half the time): every
  // candidate pixel stores, the old value where the point does not win.
  const float r2 = radius_ * radius_;
  const int hx = floorToInt(x), hy = floorToInt(y);
  for (int py = rows.first; py <= rows.last; ++py) {
    const float dy = static_cast<float>(py) + 0.5f - y, dy2 = dy * dy;
    const size_t row = static_cast<size_t>(py) * static_cast<size_t>(width_);
    uint64_t* keys = &keys_[row];
    uint32_t* colors = &win_color_[row];
    for (int px = cols.first; px <= cols.last; ++px) {
      const float dx = static_cast<float>(px) + 0.5f - x;
      const bool inside = (dx * dx + dy2 <= r2) | ((px == hx) & (py == hy));
      const uint64_t old = keys[px];
      // All ones where the point wins: masks, as the compiler keeps `?:` here as branches.
      const uint64_t wins = uint64_t{0} - static_cast<uint64_t>(inside & (key < old));
      keys[px] = old ^ ((old ^ key) & wins);
      colors[px] ^= (colors[px] ^ color) & static_cast<uint32_t>(wins);
    }
  }
}

uint8_t PointPass::coverageByte(bool centre, float d2) const {
  if (!antialiased_) return 255;
  // A covered centre counts at least half (the pixel holding a tiny point), an uncovered one
  // less: the centre is covered exactly where the byte is 128 or more.
  const float coverage = std::clamp(radius_ + 0.5f - std::sqrt(d2), centre ? 0.5f : 0.0f, 1.0f);
  return static_cast<uint8_t>(std::min(centre ? 255L : 127L, std::lround(coverage * 255.0f)));
}

void PointPass::resolveBand(int band, Frame& frame) {
  const int y0 = band * kPointBandRows, y1 = std::min(height_, y0 + kPointBandRows);
  const Record* records = &records_[band_start_[band]];
  const bool sprites = options_->points.sprites;
  const float3 facing = camera_to_world_.col[2];  // flat discs face the camera
  const size_t begin = static_cast<size_t>(y0) * static_cast<size_t>(width_);
  const size_t end = static_cast<size_t>(y1) * static_cast<size_t>(width_);
  for (size_t i = begin; i < end; ++i) {
    const uint64_t key = keys_[i];
    const uint32_t rank = static_cast<uint32_t>(key);
    if (rank == 0) continue;
    const uint8_t coverage = antialiased_ ? win_coverage_[i] : 255;
    float3 normal = facing;
    if (sprites) {
      const int px = static_cast<int>(i % static_cast<size_t>(width_));
      const int py = static_cast<int>(i / static_cast<size_t>(width_));
      const float3 color = spriteColor(records[rank - 1], px, py, normal);
      writePixel(frame, i, color, coverage);
    } else if (coverage == 255) {
      frame.color[i] = win_color_[i];
    } else {
      const uint32_t c = win_color_[i];
      writePixel(frame, i,
                 {decodeSrgb8(static_cast<uint8_t>(c)), decodeSrgb8(static_cast<uint8_t>(c >> 8)),
                  decodeSrgb8(static_cast<uint8_t>(c >> 16))},
                 coverage);
    }
    if (!frame.coverage.empty()) frame.coverage[i] = std::max(frame.coverage[i], coverage);
    if (coverage < 128) continue;  // the centre is not covered
    frame.depth[i] = std::bit_cast<float>(static_cast<uint32_t>(key >> 32));
    if (!frame.triangle_id.empty()) frame.triangle_id[i] = kNoTriangle;
    if (!frame.normal.empty()) frame.normal[i] = normal;
  }
}

float3 PointPass::spriteColor(const Record& rec, int px, int py, float3& normal) const {
  const PointList& points = scene_->points;
  const float dx = static_cast<float>(px) + 0.5f - rec.x;
  const float dy = static_cast<float>(py) + 0.5f - rec.y;
  const float3 p = points.positions[rec.index];
  const float3 q = (camera_.view * float4{p, 1.0f}).xyz();
  normal = normalize(camera_to_world_ * spriteNormal(q, dx / radius_, -dy / radius_));
  const float world_radius =
      sphereDepth(camera_, p, radius_, height_, camera_to_world_).world_radius;
  float3 albedo = options_->points.color;
  if (points.colors.size() == points.size()) {
    const uint32_t c = points.colors[rec.index];
    albedo = {decodeSrgb8(static_cast<uint8_t>(c)), decodeSrgb8(static_cast<uint8_t>(c >> 8)),
              decodeSrgb8(static_cast<uint8_t>(c >> 16))};
  }
  return albedo * irradiance(lights_, normal, p + normal * world_radius);
}

void PointPass::writePixel(Frame& frame, size_t i, float3 color, uint8_t coverage) {
  if (coverage == 255) {
    frame.color[i] = packSrgba8(float4{color, 1.0f});
    return;
  }
  // As the line pass blends (lines.h): in linear light, over the frame's colour.
  frame.color[i] = blendOver(frame.color[i], color, static_cast<float>(coverage) * (1.0f / 255.0f));
}

}  // namespace tessera::render
