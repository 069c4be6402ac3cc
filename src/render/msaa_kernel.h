// The multisampling kernels (msaa.h): combining a tile's sample layers, and resolving the mixed
// pixels of a row sample by sample. Written once against eight-lane types and compiled per
// instruction set (kernels_<isa>.cpp), with the same operations per lane, so every variant gives
// the same bits.
#pragma once

#include <cstdint>
#include <vector>

#include "render/bin.h"
#include "render/mixed_lanes.h"
#include "render/msaa.h"
#include "render/shade_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

// SampleTiles::primary, mixed and covered from the sample layers (and the centre layer, when
// `with_centre`).
void combineSamplesKernel(SampleTiles& tiles, int samples, bool with_centre) {
  const TileVisibility& first_layer = *tiles.layers[0];
  TileVisibility& primary = *tiles.primary;
  primary.x0 = first_layer.x0, primary.y0 = first_layer.y0;
  primary.width = first_layer.width, primary.height = first_layer.height;
  const I32x8 empty = splat(static_cast<int32_t>(kEmptyKey));
  const I32x8 zero = splat(int32_t{0});
  for (int ty = 0; ty < primary.height; ++ty) {
    for (int tx = 0; tx < primary.width; tx += 8) {
      const int i = ty * kTileSize + tx;
      const I32x8 k0 = load<I32x8>(first_layer.key + i);
      I32x8 first = k0, mixed = zero;
      I32x8 covered = zero - ~equal(k0, empty);
      for (int s = 1; s < samples; ++s) {
        const I32x8 k = load<I32x8>(tiles.layers[static_cast<size_t>(s)]->key + i);
        mixed = mixed | ~equal(k, k0);
        covered = covered - ~equal(k, empty);
        first = select(equal(first, empty), k, first);
      }
      if (with_centre) {
        const I32x8 centre = load<I32x8>(tiles.layers[static_cast<size_t>(samples)]->key + i);
        first = select(equal(centre, empty), first, centre);
        // The centre's triangle is shaded there (for the normal AOV); where it is not the one
        // every sample holds, the colour comes from the samples' resolve.
        mixed = mixed | ~equal(centre, k0);
      }
      store(primary.key + i, first);
      store(tiles.mixed + i, mixed);
      store(tiles.covered + i, covered);
    }
  }
}

// Whether the centre of pixel (x, y) passes the triangle's three edge tests (the raster kernel's
// arithmetic: a small triangle from its corner values, a large one from c).
TESSERA_LANES_INLINE bool coversCentre(const RasterTriangle& t, const RasterWide& w, int x, int y) {
  for (int k = 0; k < 3; ++k) {
    const int64_t e =
        t.small() ? t.corner[k] + int64_t{t.a[k]} * ((x - t.min_x) * kSubpixelOne) +
                        int64_t{t.b[k]} * ((y - t.min_y) * kSubpixelOne)
                  : int64_t{t.a[k]} * (int64_t{x} * kSubpixelOne + kSubpixelHalf) +
                        int64_t{t.b[k]} * (int64_t{y} * kSubpixelOne + kSubpixelHalf) + w.c[k];
    if (e < 0) return false;
  }
  return true;
}

// The lanes of `lanes` whose pixel centre (columns[l], y) passes the edge tests of their triangle
// (keys; records: each lane's raster record, a valid one in every lane): the exact test, as the
// Vulkan backend's. Small triangles (the pixel lies in the record's box, where their edge values
// fit in int32: RasterTriangle::small) take it in lanes from their records' first ten words,
// loaded eight records at a time and transposed; large ones lane by lane in 64 bits.
TESSERA_LANES_INLINE I32x8 centresCovered(const std::vector<TriangleChunk>& chunks, I32x8 keys,
                                          const RasterTriangle* const records[8], I32x8 lanes,
                                          I32x8 columns, int y) {
  // corner[3], a[3], b[0..1]; then b[2] and min_x | min_y << 16.
  F32x8 w[8], b2, box;
  for (int l = 0; l < 8; ++l) w[l] = load<F32x8>(records[l]);
  transpose8x8(w);
  const float* at8[8];
  for (int l = 0; l < 8; ++l) at8[l] = reinterpret_cast<const float*>(records[l]) + 8;
  loadPairs(at8, b2, box);
  const I32x8 min_x = shiftRight(shiftLeft(bitsOf(box), 16), 16);
  const I32x8 min_y = shiftRight(bitsOf(box), 16);
  const I32x8 dx = (columns - min_x) * splat(kSubpixelOne);
  const I32x8 dy = (splat(y) - min_y) * splat(kSubpixelOne);
  const I32x8 e0 = bitsOf(w[0]) + bitsOf(w[3]) * dx + bitsOf(w[6]) * dy;
  const I32x8 e1 = bitsOf(w[1]) + bitsOf(w[4]) * dx + bitsOf(w[7]) * dy;
  const I32x8 e2 = bitsOf(w[2]) + bitsOf(w[5]) * dx + bitsOf(b2) * dy;
  // A large triangle's corner values are 0 (setup); a small one's are not all 0, as no point lies
  // on all three edges of a triangle with an area (setup drops the others).
  const I32x8 small = ~equal(bitsOf(w[0]) | bitsOf(w[1]) | bitsOf(w[2]), splat(int32_t{0}));
  I32x8 covered = lanes & small & nonNegative(e0 | e1 | e2);
  const I32x8 large = lanes & ~small;
  if (any(large)) {
    alignas(32) int32_t wanted[8], inside[8], column[8];
    alignas(32) uint32_t key[8];
    store(wanted, large);
    store(inside, covered);
    store(column, columns);
    store(key, keys);
    for (int l = 0; l < 8; ++l)
      if (wanted[l] &&
          coversCentre(*records[l], chunks[keyChunk(key[l])].wide[keyLocal(key[l])], column[l], y))
        inside[l] = -1;
    covered = load<I32x8>(inside);
  }
  return covered;
}

// centresCovered with the records found from the keys.
TESSERA_LANES_INLINE I32x8 centresCovered(const std::vector<TriangleChunk>& chunks, I32x8 keys,
                                          I32x8 lanes, I32x8 columns, int y) {
  if (!any(lanes)) return lanes;
  alignas(32) uint32_t key[8];
  store(key, select(lanes, keys, splat(lane(keys, firstLane(lanes)))));
  const RasterTriangle* records[8];
  for (int l = 0; l < 8; ++l) records[l] = &chunks[keyChunk(key[l])].raster[keyLocal(key[l])];
  return centresCovered(chunks, keys, records, lanes, columns, y);
}

// Sample s of row y in pixels: x from the pixel's left edge, y from the top of the image.
TESSERA_LANES_INLINE float sampleX(const MsaaShading& m, int s) {
  return static_cast<float>(m.positions[s].x) * (1.0f / static_cast<float>(kSubpixelOne));
}
TESSERA_LANES_INLINE float sampleY(const MsaaShading& m, int s, int y) {
  return static_cast<float>(y) +
         static_cast<float>(m.positions[s].y) * (1.0f / static_cast<float>(kSubpixelOne));
}

// The sample-s fragments of eight pixels (the lanes of `first`: pixels whose sample s holds a
// triangle that no earlier sample holds), shaded from their own triangles (keys), each at the
// pixel centre when the centre passes the triangle's edge tests and otherwise at sample s (the
// triangle's first in pattern order, the nearest the centre it holds): each triangle once for its
// lanes at the centre and once for those at the sample.
TESSERA_LANES_INLINE Vec3x8 shadeSampleFragments(const MsaaShading& m, int s, I32x8 keys,
                                                 I32x8 first, int x, int y,
                                                 const std::vector<TriangleChunk>& chunks,
                                                 const LightRig& lights) {
  alignas(32) uint32_t key[8];
  store(key, keys);
  const F32x8 column = toFloat(splat(x) + iota());
  const F32x8 centre_x = column + splat(0.5f), sample_x = column + splat(sampleX(m, s));
  const float centre_y = static_cast<float>(y) + 0.5f, sample_y = sampleY(m, s, y);
  const F32x8 zero = splat(0.0f);
  Vec3x8 color{zero, zero, zero}, normal{zero, zero, zero};
  const I32x8 centre = centresCovered(chunks, keys, first, splat(x) + iota(), y);
  I32x8 todo = first;
  while (any(todo)) {
    const uint32_t k = key[firstLane(todo)];
    const I32x8 mine = todo & equal(keys, splat(static_cast<int32_t>(k)));
    const TriangleChunk& chunk = chunks[keyChunk(k)];
    const ShadeTriangle& t = chunk.shade[keyLocal(k)];
    const ShadeExtras& e = chunk.extras[keyLocal(k)];
    const I32x8 at_centre = mine & centre;
    if (any(at_centre))
      shadeLanes(t, e, lights, false, centre_x, centre_y, at_centre, color, normal);
    if (any(mine & ~at_centre))
      shadeLanes(t, e, lights, false, sample_x, sample_y, mine & ~at_centre, color, normal);
    todo = todo & ~mine;
  }
  return color;
}

// Eight plain fragments (shadeMixed's case), lane l from records[l] in pixel x + l (column: x + l)
// of row y: at the pixel centre where `at_centre`, else at the lane's sample, sample_dx right of
// column and at sample_y. One evaluation for the eight.
TESSERA_LANES_INLINE Vec3x8 shadePlainFragments(const ShadeTriangle* const records[8], F32x8 column,
                                                int y, F32x8 sample_dx, F32x8 sample_y,
                                                I32x8 at_centre) {
  F32x8 f[kPlainFields];
  loadPlainFields(records, f);
  F32x8 b0, b1, b2;
  plainBarycentrics(f, select(at_centre, column + splat(0.5f), column + sample_dx),
                    select(at_centre, splat(static_cast<float>(y) + 0.5f), sample_y), b0, b1, b2);
  return plainColor(f, b1, b2);
}

// The later samples' fragments of a row's mixed plain pixels, queued by shadePlainSampled and
// shaded eight at a time across the row's groups (shadeQueuedFragments). Shaded group by group, a
// round of the later samples (per pixel its earliest new triangle) held about three of the eight
// lanes, and most mixed groups took one round or two (docs/perf.md).
struct FragmentQueue {
  // What a flush leaves (fewer than eight), one group's fragments, and the slack of a full store.
  static constexpr int kCapacity = 8 + 8 * (kMaxSamples - 1) + 8;
  static_assert(kTileSize <= 64 && kMaxSamples <= 8, "where's fields: 6 bits, 3 bits, the rest");
  alignas(32) int32_t key[kCapacity];
  // Tile column | sample << 6 | the samples of the pixel its triangle holds << 9.
  alignas(32) int32_t where[kCapacity];
  int count;
  // sampleX and the fraction of sampleY of each sample.
  float sample_x[kMaxSamples], sample_y[kMaxSamples];
  // Each chunk's first raster record (laneRecords), for the centre test.
  const RasterTriangle* raster[kMaxChunks];

  FragmentQueue(const MsaaShading& m, const std::vector<TriangleChunk>& chunks, size_t chunk_count)
      : key{}, where{}, count(0) {
    for (int s = 0; s < kMaxSamples; ++s) {
      sample_x[s] = s < m.samples ? sampleX(m, s) : 0.0f;
      sample_y[s] = s < m.samples ? sampleY(m, s, 0) : 0.0f;
    }
    for (size_t c = 0; c < chunk_count; ++c) raster[c] = chunks[c].raster.data();
  }
};

// The linear colours of pixels x .. x + 7 of row y (tile offset i, tile column tx; chunk_records
// as laneRecords) when every triangle is plain and some of the eight are mixed, each fragment
// shaded where shadeSampleFragments shades it. Sample 0's triangles are shaded here for every lane
// at once (at the centre in the pixels that are not mixed: the one-sample colour); the later
// samples' new triangles of the mixed pixels go to `queue`, in sample order. A mixed pixel's colour
// is left as the sum so far of its uncovered samples' background and sample 0's triangle weighted
// by the samples it holds: shadeQueuedFragments adds the rest, in the order of resolveMixedRowWith,
// and finishMixedRow divides by the sample count.
TESSERA_LANES_INLINE Vec3x8 shadePlainSampled(const MsaaShading& m,
                                              const std::vector<TriangleChunk>& chunks,
                                              const ShadeTriangle* const* chunk_records, int i,
                                              int tx, int x, int y, I32x8 mixed,
                                              FragmentQueue& queue) {
  const I32x8 empty = splat(static_cast<int32_t>(kEmptyKey));
  const I32x8 zero = splat(int32_t{0});
  I32x8 keys[kMaxSamples], held[kMaxSamples], pending[kMaxSamples];
  I32x8 background = zero;
  for (int s = 0; s < m.samples; ++s)
    keys[s] = load<I32x8>(m.tiles->layers[static_cast<size_t>(s)]->key + i);
  for (int s = 0; s < m.samples; ++s) {
    background = background - equal(keys[s], empty);
    pending[s] = mixed & ~equal(keys[s], empty);
    for (int r = 0; r < s; ++r) pending[s] = pending[s] & ~equal(keys[s], keys[r]);
    held[s] = zero;
    for (int r = s; r < m.samples; ++r) held[s] = held[s] - equal(keys[r], keys[s]);
  }
  const F32x8 bg_weight = toFloat(background);
  Vec3x8 sum{splat(m.background.x) * bg_weight, splat(m.background.y) * bg_weight,
             splat(m.background.z) * bg_weight};
  Vec3x8 sample0{sum};
  const I32x8 valid = ~equal(keys[0], empty);
  if (any(valid)) {
    const ShadeTriangle* records[8];
    const RasterTriangle* raster[8];
    const LaneKeys lane_keys = laneKeys(keys[0], valid);
    laneRecords(lane_keys, chunk_records, records);
    laneRecords(lane_keys, queue.raster, raster);
    const I32x8 at_centre =
        ~mixed | centresCovered(chunks, keys[0], raster, pending[0], splat(x) + iota(), y);
    sample0 = shadePlainFragments(records, toFloat(splat(x) + iota()), y, splat(sampleX(m, 0)),
                                  splat(sampleY(m, 0, y)), at_centre);
    const F32x8 weight = toFloat(held[0]);
    sum = {select(pending[0], sum.x + sample0.x * weight, sum.x),
           select(pending[0], sum.y + sample0.y * weight, sum.y),
           select(pending[0], sum.z + sample0.z * weight, sum.z)};
  }
  const I32x8 column = splat(tx) + iota();
  for (int s = 1; s < m.samples; ++s) {
    int n = 0;
    store(queue.key + queue.count, compressLanes(keys[s], pending[s], n));
    store(queue.where + queue.count,
          compressLanes(column | splat(s << 6) | shiftLeft(held[s], 9), pending[s], n));
    queue.count += n;
  }
  return {select(mixed, sum.x, sample0.x), select(mixed, sum.y, sample0.y),
          select(mixed, sum.z, sample0.z)};
}

// Queued fragments first .. first + count - 1 (count at most eight) of row y of the tile at
// column x0 shaded in one evaluation, each weighted by its samples and added to its pixel's sum
// in `linear`, in queue order.
TESSERA_LANES_INLINE void shadeQueuedFragments(const std::vector<TriangleChunk>& chunks,
                                               const ShadeTriangle* const* chunk_records,
                                               const FragmentQueue& queue, int first, int count,
                                               int x0, int y, float linear[3][kTileSize]) {
  const I32x8 valid = lessThan(iota(), splat(count));
  const I32x8 keys = load<I32x8>(queue.key + first);
  const I32x8 where = load<I32x8>(queue.where + first);
  const I32x8 tx = where & splat(int32_t{63});
  const I32x8 sample = shiftRight(where, 6) & splat(int32_t{7});
  const ShadeTriangle* records[8];
  const RasterTriangle* raster[8];
  const LaneKeys lane_keys = laneKeys(keys, valid);
  laneRecords(lane_keys, chunk_records, records);
  laneRecords(lane_keys, queue.raster, raster);
  const I32x8 columns = splat(x0) + tx;
  const Vec3x8 c =
      shadePlainFragments(records, toFloat(columns), y, gather(queue.sample_x, sample),
                          splat(static_cast<float>(y)) + gather(queue.sample_y, sample),
                          centresCovered(chunks, keys, raster, valid, columns, y));
  const F32x8 weight = toFloat(shiftRight(where, 9));
  alignas(32) float add[3][8];
  alignas(32) int32_t pixel[8];
  store(add[0], c.x * weight);
  store(add[1], c.y * weight);
  store(add[2], c.z * weight);
  store(pixel, tx);
  for (int l = 0; l < count; ++l) {
    linear[0][pixel[l]] += add[0][l];
    linear[1][pixel[l]] += add[1][l];
    linear[2][pixel[l]] += add[2][l];
  }
}

// The queue's fragments shaded eight at a time (shadeQueuedFragments), all of them when `all`,
// else while eight are left; what is left moves to the front.
TESSERA_LANES_INLINE void shadeQueue(const std::vector<TriangleChunk>& chunks,
                                     const ShadeTriangle* const* chunk_records,
                                     FragmentQueue& queue, bool all, int x0, int y,
                                     float linear[3][kTileSize]) {
  int first = 0;
  for (; queue.count - first >= 8; first += 8)
    shadeQueuedFragments(chunks, chunk_records, queue, first, 8, x0, y, linear);
  if (all && queue.count > first) {
    shadeQueuedFragments(chunks, chunk_records, queue, first, queue.count - first, x0, y, linear);
    first = queue.count;
  }
  if (first == 0) return;
  store(queue.key, load<I32x8>(queue.key + first));  // fewer than eight left
  store(queue.where, load<I32x8>(queue.where + first));
  queue.count -= first;
}

// Row ty's mixed pixels, their sums complete (shadeQueue with `all`), divided by the sample count.
TESSERA_LANES_INLINE void finishMixedRow(const MsaaShading& m, const TileVisibility& tile, int ty,
                                         float linear[3][kTileSize]) {
  const F32x8 inv_samples = splat(1.0f / static_cast<float>(m.samples));
  for (int tx = 0; tx < tile.width; tx += 8) {
    const I32x8 mixed = load<I32x8>(m.tiles->mixed + ty * kTileSize + tx);
    if (!any(mixed)) continue;
    for (int k = 0; k < 3; ++k)
      store(linear[k] + tx,
            select(mixed, load<F32x8>(linear[k] + tx) * inv_samples, load<F32x8>(linear[k] + tx)));
  }
}

// Replaces the linear colours of row ty's mixed pixels by their resolve, eight pixels at a time:
// the uncovered samples' background, then each distinct triangle in the order of its first
// sample, weighted by the samples it holds, over the sample count. shade(s, keys, first, x, y)
// gives the linear colours of the lanes of `first`: the pixels x .. x + 7 of row y whose sample s
// holds a triangle (keys) that no earlier sample holds.
template <typename ShadeFragments>
TESSERA_LANES_INLINE void resolveMixedRowWith(const MsaaShading& m, const TileVisibility& tile,
                                              int ty, float linear[3][kTileSize],
                                              ShadeFragments shade) {
  const I32x8 empty = splat(static_cast<int32_t>(kEmptyKey));
  const I32x8 zero = splat(int32_t{0});
  const F32x8 inv_samples = splat(1.0f / static_cast<float>(m.samples));
  const int y = tile.y0 + ty;
  for (int tx = 0; tx < tile.width; tx += 8) {
    const int i = ty * kTileSize + tx;
    const I32x8 mixed = load<I32x8>(m.tiles->mixed + i);
    if (!any(mixed)) continue;
    I32x8 keys[kMaxSamples];
    I32x8 background = zero;
    for (int s = 0; s < m.samples; ++s) {
      keys[s] = load<I32x8>(m.tiles->layers[static_cast<size_t>(s)]->key + i);
      background = background - equal(keys[s], empty);
    }
    const F32x8 bg_weight = toFloat(background);
    Vec3x8 sum{splat(m.background.x) * bg_weight, splat(m.background.y) * bg_weight,
               splat(m.background.z) * bg_weight};
    for (int s = 0; s < m.samples; ++s) {
      I32x8 first = mixed & ~equal(keys[s], empty);
      for (int r = 0; r < s; ++r) first = first & ~equal(keys[s], keys[r]);
      if (!any(first)) continue;
      I32x8 held = zero;
      for (int r = s; r < m.samples; ++r) held = held - equal(keys[r], keys[s]);
      const Vec3x8 c = shade(s, keys[s], first, tile.x0 + tx, y);
      // Lanes outside `first` may hold anything (a borrowed record off its triangle): not added.
      const F32x8 weight = toFloat(held);
      sum = {select(first, sum.x + c.x * weight, sum.x), select(first, sum.y + c.y * weight, sum.y),
             select(first, sum.z + c.z * weight, sum.z)};
    }
    store(linear[0] + tx, select(mixed, sum.x * inv_samples, load<F32x8>(linear[0] + tx)));
    store(linear[1] + tx, select(mixed, sum.y * inv_samples, load<F32x8>(linear[1] + tx)));
    store(linear[2] + tx, select(mixed, sum.z * inv_samples, load<F32x8>(linear[2] + tx)));
  }
}

// The resolve of the perspective path when some triangle is not plain (shadePlainSampled is
// the plain one): fragments shaded from the screen-space planes.
void resolveMixedRow(const MsaaShading& m, const TileVisibility& tile, int ty,
                     const std::vector<TriangleChunk>& chunks, const LightRig& lights,
                     float linear[3][kTileSize]) {
  resolveMixedRowWith(
      m, tile, ty,
      linear, [&](int s, I32x8 keys, I32x8 first, int x, int y) __attribute__((always_inline)) {
        return shadeSampleFragments(m, s, keys, first, x, y, chunks, lights);
      });
}

}  // namespace
}  // namespace tessera::render
