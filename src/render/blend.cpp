#include "render/blend.h"

#include <algorithm>
#include <cmath>

#include <tessera/scene/color.h>

#include "render/raster.h"

namespace tessera::render {

float blendRecordDepth(const RasterTriangle& t) {
  const float cx = 0.5f * static_cast<float>(t.min_x + t.max_x) + 0.5f;
  const float cy = 0.5f * static_cast<float>(t.min_y + t.maxY()) + 0.5f;
  const float z = t.z0 + t.dzdx * (cx - t.x0) + t.dzdy * (cy - t.y0);
  return z > 0.0f ? z : 0.0f;
}

void sortBlendEntries(std::vector<BlendEntry>& entries, size_t object_count,
                      std::vector<double>& object_sum, std::vector<uint32_t>& object_entries) {
  object_sum.assign(object_count, 0.0);
  object_entries.assign(object_count, 0);
  // Summed in submission order: the same sum for any chunk layout.
  for (const BlendEntry& e : entries) {
    object_sum[e.object] += e.depth;
    ++object_entries[e.object];
  }
  for (BlendEntry& e : entries)
    e.object_depth = static_cast<float>(object_sum[e.object] / object_entries[e.object]);
  std::sort(entries.begin(), entries.end(), [](const BlendEntry& a, const BlendEntry& b) {
    if (a.object_depth != b.object_depth) return a.object_depth > b.object_depth;
    if (a.object != b.object) return a.object < b.object;
    if (a.depth != b.depth) return a.depth > b.depth;
    return a.key < b.key;
  });
}

void BlendOrder::build(const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                       const std::vector<ObjectTransforms>& objects, const TileGrid& grid) {
  order_.clear();
  // A frame without blended records (most) pays one look at each chunk.
  if (std::all_of(chunks.begin(), chunks.begin() + static_cast<ptrdiff_t>(chunk_count),
                  [](const TriangleChunk& c) { return c.blended.empty(); }))
    return;
  for (size_t c = 0; c < chunk_count; ++c) {
    const TriangleChunk& chunk = chunks[c];
    size_t object = 0;
    for (uint32_t local : chunk.blended) {
      const uint32_t id = chunk.shade[local].triangle_id;
      // Records are in submission order: the object only moves forward.
      if (object >= objects.size() || objects[object].triangle_base > id)
        object = objectHolding(objects, id);
      while (object + 1 < objects.size() && objects[object + 1].triangle_base <= id) ++object;
      const float depth = blendRecordDepth(chunk.raster[local]);
      order_.push_back(
          {0.0f, depth, static_cast<uint32_t>(object), makeKey(static_cast<uint32_t>(c), local)});
    }
  }
  sortBlendEntries(order_, objects.size(), object_sum_, object_count_);
  bins_.reset(grid.tileCount());
  for (const BlendEntry& e : order_)
    bins_.add(grid, chunks[keyChunk(e.key)].raster[keyLocal(e.key)], e.key);
}

void BlendTile::begin(int x0, int y0, int samples, Frame& frame) {
  x0_ = x0, y0_ = y0, samples_ = samples;
  frame_ = &frame;
  constexpr size_t kPixels = size_t{kTileSize} * kTileSize;
  if (touched_.size() < kPixels) touched_.assign(kPixels, 0);
  const size_t per_sample = kPixels * static_cast<size_t>(samples);
  if (coverage_.size() < per_sample) {
    coverage_.resize(per_sample);
    color_.resize(per_sample * 3);
  }
  touched_list_.clear();
}

void BlendTile::touch(int pixel) {
  touched_[static_cast<size_t>(pixel)] = 1;
  touched_list_.push_back(pixel);
  const int x = x0_ + pixel % kTileSize, y = y0_ + pixel / kTileSize;
  const size_t at = static_cast<size_t>(y) * frame_->width + x;
  const uint32_t c = frame_->color[at];
  const float rgb[3] = {decodeSrgb8(c & 0xff), decodeSrgb8((c >> 8) & 0xff),
                        decodeSrgb8((c >> 16) & 0xff)};
  const float covered = frame_->coverage.empty() ? 1.0f : frame_->coverage[at] / 255.0f;
  const size_t first = static_cast<size_t>(pixel) * samples_;
  for (size_t s = first; s < first + samples_; ++s) {
    for (int k = 0; k < 3; ++k) color_[s * 3 + k] = rgb[k];
    coverage_[s] = covered;
  }
}

void BlendTile::over(int pixel, uint32_t sample_mask, float3 color, float alpha) {
  if (!touched_[static_cast<size_t>(pixel)]) touch(pixel);
  // A NaN alpha draws nothing; alpha past 1 is 1.
  const float a = alpha > 0.0f ? (alpha < 1.0f ? alpha : 1.0f) : 0.0f;
  const float keep = 1.0f - a;
  const float rgb[3] = {color.x * a, color.y * a, color.z * a};
  const size_t first = static_cast<size_t>(pixel) * samples_;
  for (int i = 0; i < samples_; ++i) {
    if (!(sample_mask >> i & 1u)) continue;
    float* c = &color_[(first + i) * 3];
    for (int k = 0; k < 3; ++k) c[k] = rgb[k] + c[k] * keep;
    coverage_[first + i] = a + coverage_[first + i] * keep;
  }
}

void BlendTile::finish() {
  const float inv = 1.0f / static_cast<float>(samples_);
  for (int pixel : touched_list_) {
    touched_[static_cast<size_t>(pixel)] = 0;
    const int x = x0_ + pixel % kTileSize, y = y0_ + pixel / kTileSize;
    const size_t at = static_cast<size_t>(y) * frame_->width + x;
    const size_t first = static_cast<size_t>(pixel) * samples_;
    float sum[3] = {0, 0, 0}, covered = 0;
    for (size_t s = first; s < first + samples_; ++s) {
      for (int k = 0; k < 3; ++k) sum[k] += color_[s * 3 + k];
      covered += coverage_[s];
    }
    uint32_t out = frame_->color[at] & 0xff000000u;
    for (int k = 0; k < 3; ++k) out |= uint32_t{encodeSrgb8(sum[k] * inv)} << (8 * k);
    frame_->color[at] = out;
    if (!frame_->coverage.empty())
      frame_->coverage[at] =
          static_cast<uint8_t>(std::lround(std::clamp(covered * inv, 0.0f, 1.0f) * 255.0f));
  }
  touched_list_.clear();
}

}  // namespace tessera::render
