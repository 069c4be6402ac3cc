// The mixed pixels of a multisampled row (msaa.h), shaded through a queue of fragments: each
// distinct triangle of a mixed pixel is one fragment, shaded at the pixel centre when the centre
// passes the triangle's edge tests and otherwise at the first sample it holds, and weighted by the
// samples it holds. Fragments are queued as the row's groups are visited and shaded eight at a
// time across the groups, each added to its pixel's sum in queue order (each pixel's sample order);
// at the row's end the sums, which began with the uncovered samples' background, are divided by
// the sample count. Shaded group by group instead, a round of a group held about three of its
// eight lanes. A round is shaded a group after its fragments were queued: shaded at once, its loads
// waited on the pushes' stores just made, which a load spanning several of them cannot take
// forwarded (docs/perf-notes/msaa-rounds-7-to-11.md). Compiled per instruction set; every variant
// gives the same bits.
#pragma once

#include <cstdint>
#include <vector>

#include "render/msaa_kernel.h"
#include "render/plain_lanes16.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

struct FragmentQueue {
  // A row's fragments (every sample of every pixel at most), and room for the last push's full
  // store past them.
  static constexpr int kCapacity = kTileSize * kMaxSamples + 8;
  static_assert(kTileSize <= 64 && kMaxSamples <= 8, "where's fields: 6 bits, 3 bits, the rest");
  alignas(32) int32_t key[kCapacity];
  // Tile column | sample << 6 | the samples of the pixel its triangle holds << 9.
  alignas(32) int32_t where[kCapacity];
  int count;
  int shaded = 0;  // the fragments before this one are shaded
  // sampleX and the fraction of sampleY of each sample.
  float sample_x[kMaxSamples], sample_y[kMaxSamples];

  explicit FragmentQueue(const MsaaShading& m) : key{}, where{}, count(0) {
    for (int s = 0; s < kMaxSamples; ++s) {
      sample_x[s] = s < m.samples ? sampleX(m, s) : 0.0f;
      sample_y[s] = s < m.samples ? sampleY(m, s, 0) : 0.0f;
    }
  }

  // The lanes of `lanes` (pixels tx .. tx + 7 of the tile, their triangles `keys` at sample s,
  // holding `held` samples each) at the queue's end.
  TESSERA_LANES_INLINE void push(I32x8 keys, I32x8 lanes, int tx, int s, I32x8 held) {
    int n = 0;
    store(key + count, compressLanes(keys, lanes, n));
    store(where + count,
          compressLanes((splat(tx) + iota()) | splat(s << 6) | shiftLeft(held, 9), lanes, n));
    count += n;
  }
};

// Queued fragments in lanes: their triangles' records and the point each is shaded at.
struct QueuedFragments {
  I32x8 valid, keys, tx;
  F32x8 px, py, weight;
  LaneKeys lane_keys;
  const ShadeTriangle* records[8];
};

// Fragments first .. first + count - 1 of the queue (count at most eight; the other lanes borrow
// the first's triangle) of row y of the tile at column x0.
TESSERA_LANES_INLINE void loadQueued(const ShadeTriangle* const* chunk_records,
                                     const FragmentQueue& queue, int first, int count, int x0,
                                     int y, QueuedFragments& q) {
  q.valid = lessThan(iota(), splat(count));
  const I32x8 keys = load<I32x8>(queue.key + first);
  const I32x8 at_centre = centresCovered(keys, q.valid);
  q.keys = unflagged(keys);
  const I32x8 where = load<I32x8>(queue.where + first);
  q.tx = where & splat(int32_t{63});
  const I32x8 sample = shiftRight(where, 6) & splat(int32_t{7});
  q.weight = toFloat(shiftRight(where, 9));
  q.lane_keys = laneKeys(q.keys, q.valid);
  laneRecords(q.lane_keys, chunk_records, q.records);
  const F32x8 column = toFloat(splat(x0) + q.tx);
  q.px = select(at_centre, column + splat(0.5f), column + lookup8(queue.sample_x, sample));
  q.py = select(at_centre, splat(static_cast<float>(y) + 0.5f),
                splat(static_cast<float>(y)) + lookup8(queue.sample_y, sample));
}

// The fragments' linear colours `color` (tile columns tx), weighted, added to their pixels' sums
// in lane order.
TESSERA_LANES_INLINE void addFragments(I32x8 tx, F32x8 weight, int count, const Vec3x8& color,
                                       float linear[3][kTileSize]) {
  alignas(32) float add[3][8];
  alignas(32) int32_t pixel[8];
  store(add[0], color.x * weight);
  store(add[1], color.y * weight);
  store(add[2], color.z * weight);
  store(pixel, tx);
  for (int l = 0; l < count; ++l) {
    linear[0][pixel[l]] += add[0][l];
    linear[1][pixel[l]] += add[1][l];
    linear[2][pixel[l]] += add[2][l];
  }
}

// The whole rounds of eight among the first `ready` fragments of the queue not yet shaded, by
// shade(first, count) in queue order. `ready`: the count before the last group's pushes, whose
// stores a round then seldom waits on.
template <typename Shade>
TESSERA_LANES_INLINE void shadeQueue(FragmentQueue& queue, int ready, Shade shade) {
  for (; queue.shaded + 8 <= ready; queue.shaded += 8) shade(queue.shaded, 8);
}

// shadeQueue two rounds at a time: shade_pair(first) shades fragments first .. first + 15.
template <typename Pair>
TESSERA_LANES_INLINE void shadeQueuePairs(FragmentQueue& queue, int ready, Pair shade_pair) {
  for (; queue.shaded + 16 <= ready; queue.shaded += 16) shade_pair(queue.shaded);
}

// Every fragment of the queue not yet shaded (the last round fewer than eight); the queue then
// starts empty.
template <typename Shade>
TESSERA_LANES_INLINE void finishQueue(FragmentQueue& queue, Shade shade) {
  shadeQueue(queue, queue.count, shade);
  if (queue.shaded < queue.count) shade(queue.shaded, queue.count - queue.shaded);
  queue.count = queue.shaded = 0;
}

// Row ty's mixed pixels, their sums complete (finishQueue), divided by the sample count.
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

// The samples' keys of pixels tile offset i .. i + 7 and what the resolve derives from them:
// per sample, the pixels of `mixed` where it holds a triangle no earlier sample holds (pending)
// and how many samples hold that triangle (held); and the background's share of each pixel's sum.
struct MixedGroup {
  I32x8 keys[kMaxSamples], held[kMaxSamples], pending[kMaxSamples];
  Vec3x8 sum;
};
TESSERA_LANES_INLINE void loadMixedGroup(const MsaaShading& m, int i, I32x8 mixed, MixedGroup& g) {
  withSampleCount(
      m.samples, [&](int samples) __attribute__((always_inline)) {
        const I32x8 empty = splat(static_cast<int32_t>(kEmptyKey));
        const I32x8 zero = splat(int32_t{0});
        I32x8 background = zero;
        for (int s = 0; s < samples; ++s)
          g.keys[s] = load<I32x8>(m.tiles->layers[static_cast<size_t>(s)]->key + i);
        for (int s = 0; s < samples; ++s) {
          background = background - equal(g.keys[s], empty);
          g.pending[s] = mixed & ~equal(g.keys[s], empty);
          for (int r = 0; r < s; ++r) g.pending[s] = g.pending[s] & ~equal(g.keys[s], g.keys[r]);
          g.held[s] = zero;
          for (int r = s; r < samples; ++r) g.held[s] = g.held[s] - equal(g.keys[r], g.keys[s]);
        }
        const F32x8 bg_weight = toFloat(background);
        g.sum = {splat(m.background.x) * bg_weight, splat(m.background.y) * bg_weight,
                 splat(m.background.z) * bg_weight};
      });
}

// The linear colours of pixels x .. x + 7 of row y (tile offset i, tile column tx; chunk_records
// as laneRecords) when every triangle is plain and some of the eight are mixed. Sample 0's
// triangles are shaded here for every lane at once (at the centre in the pixels that are not
// mixed: the one-sample colour); the later samples' new triangles of the mixed pixels go to
// `queue`. A mixed pixel's colour is left as its sum so far: the background's share and sample
// 0's triangle weighted by the samples it holds.
// In three steps, for a caller that shades two groups' sample 0 at once (shadeSampledPair):
// the group's samples, sample 0's records and the points it is shaded at (false: no lane holds a
// triangle at sample 0), then the sums and the later samples' pushes.
struct SampledGroup {
  MixedGroup g;
  I32x8 mixed;
  const ShadeTriangle* records[8];
  F32x8 px, py;
};
TESSERA_LANES_INLINE bool prepareSampled(const MsaaShading& m,
                                         const ShadeTriangle* const* chunk_records, int i, int x,
                                         int y, I32x8 mixed, SampledGroup& s) {
  loadMixedGroup(m, i, mixed, s.g);
  s.mixed = mixed;
  const I32x8 valid = ~equal(s.g.keys[0], splat(static_cast<int32_t>(kEmptyKey)));
  if (!any(valid)) return false;
  laneRecords(laneKeys(s.g.keys[0], valid), chunk_records, s.records);
  const I32x8 at_centre = ~mixed | centresCovered(s.g.keys[0], s.g.pending[0]);
  const F32x8 column = toFloat(splat(x) + iota());
  s.px = select(at_centre, column + splat(0.5f), column + splat(sampleX(m, 0)));
  s.py = select(at_centre, splat(static_cast<float>(y) + 0.5f), splat(sampleY(m, 0, y)));
  return true;
}
// `sample0`: the colours of the group's sample-0 triangles (or null where prepareSampled found
// none).
TESSERA_LANES_INLINE Vec3x8 finishSampled(const MsaaShading& m, const SampledGroup& s,
                                          const Vec3x8* sample0, int tx, FragmentQueue& queue) {
  const MixedGroup& g = s.g;
  Vec3x8 sum = g.sum;
  const Vec3x8 c = sample0 ? *sample0 : g.sum;
  if (sample0) {
    const F32x8 weight = toFloat(g.held[0]);
    sum = {select(g.pending[0], sum.x + c.x * weight, sum.x),
           select(g.pending[0], sum.y + c.y * weight, sum.y),
           select(g.pending[0], sum.z + c.z * weight, sum.z)};
  }
  for (int k = 1; k < m.samples; ++k) queue.push(g.keys[k], g.pending[k], tx, k, g.held[k]);
  return {select(s.mixed, sum.x, c.x), select(s.mixed, sum.y, c.y), select(s.mixed, sum.z, c.z)};
}
TESSERA_LANES_INLINE Vec3x8 shadePlainSampled(const MsaaShading& m,
                                              const ShadeTriangle* const* chunk_records, int i,
                                              int tx, int x, int y, I32x8 mixed,
                                              FragmentQueue& queue) {
  SampledGroup s;
  if (!prepareSampled(m, chunk_records, i, x, y, mixed, s))
    return finishSampled(m, s, nullptr, tx, queue);
  const Vec3x8 sample0 = shadeMixed(s.records, s.px, s.py);
  return finishSampled(m, s, &sample0, tx, queue);
}

// The queued plain fragments first .. first + count - 1 of row y shaded and added to their sums.
TESSERA_LANES_INLINE void shadeQueuedPlain(const ShadeTriangle* const* chunk_records,
                                           const FragmentQueue& queue, int first, int count, int x0,
                                           int y, float linear[3][kTileSize]) {
  QueuedFragments q;
  loadQueued(chunk_records, queue, first, count, x0, y, q);
  addFragments(q.tx, q.weight, count, shadeMixed(q.records, q.px, q.py), linear);
}

#if defined(TESSERA_LANES16)
// shadePlainSampled of two groups a and b of row y (tile offsets ia, ib, tile columns txa, txb,
// frame columns xa, xb), their sample-0 triangles shaded in sixteen lanes (plain_lanes16.h) where
// both have some; a's later fragments are queued before b's, as two calls queue them.
TESSERA_LANES_INLINE void shadePlainSampledPair(const MsaaShading& m,
                                                const ShadeTriangle* const* chunk_records, int y,
                                                int ia, int txa, int xa, I32x8 mixed_a, int ib,
                                                int txb, int xb, I32x8 mixed_b,
                                                FragmentQueue& queue, Vec3x8& ca, Vec3x8& cb) {
  SampledGroup a, b;
  const bool has_a = prepareSampled(m, chunk_records, ia, xa, y, mixed_a, a);
  const bool has_b = prepareSampled(m, chunk_records, ib, xb, y, mixed_b, b);
  Vec3x8 sa, sb;
  if (has_a && has_b) {
    shadeMixedPair(a.records, a.px, a.py, b.records, b.px, b.py, sa, sb);
  } else {
    if (has_a) sa = shadeMixed(a.records, a.px, a.py);
    if (has_b) sb = shadeMixed(b.records, b.px, b.py);
  }
  ca = finishSampled(m, a, has_a ? &sa : nullptr, txa, queue);
  cb = finishSampled(m, b, has_b ? &sb : nullptr, txb, queue);
}

// shadeQueuedPlain of two full rounds, fragments first .. first + 15, in sixteen lanes
// (plain_lanes16.h); the two rounds' colours are added in queue order, as two calls add them.
TESSERA_LANES_INLINE void shadeQueuedPlainPair(const ShadeTriangle* const* chunk_records,
                                               const FragmentQueue& queue, int first, int x0, int y,
                                               float linear[3][kTileSize]) {
  QueuedFragments a, b;
  loadQueued(chunk_records, queue, first, 8, x0, y, a);
  loadQueued(chunk_records, queue, first + 8, 8, x0, y, b);
  Vec3x8 ca, cb;
  shadeMixedPair(a.records, a.px, a.py, b.records, b.px, b.py, ca, cb);
  addFragments(a.tx, a.weight, 8, ca, linear);
  addFragments(b.tx, b.weight, 8, cb, linear);
}
#endif

// The colours of queued fragments of any triangles: in one evaluation where all are textured alike
// without per-pixel lighting (prepareTexturedGroup) or lit per pixel alike without maps
// (shadeLitMixed), else triangle by triangle and point by point (shadeLanes). The same operations
// per lane on every path, so the same bits. `lit_alike`: every record is TriangleChunk::lit_alike.
TESSERA_LANES_INLINE Vec3x8 shadeFragments(const QueuedFragments& q,
                                           const ShadeExtras* const* chunk_extras,
                                           const LightRig& lights, bool lit_alike) {
  const ShadeExtras* extras[8];
  laneRecords(q.lane_keys, chunk_extras, extras);
  Vec3x8 color;
  const ShadeTriangle& t = *q.records[0];
  if (lit_alike) {
    shadeLitMixed(q.records, extras, q.valid, lights, q.px, q.py, color, true);
    return color;
  }
  if (texturedPlain(t)) {
    TexturedGroup group;
    if (prepareTexturedGroup(q.records, extras, q.valid, q.px, q.py, group) &&
        filterTexturedGroup(group, lights, color))
      return color;
  } else if (litPlain(t) && shadeLitMixed(q.records, extras, q.valid, lights, q.px, q.py, color)) {
    return color;
  }
  const F32x8 zero = splat(0.0f);
  color = {zero, zero, zero};
  Vec3x8 normal{zero, zero, zero};
  alignas(32) float row[8];
  alignas(32) uint32_t key[8];
  store(row, q.py);
  store(key, q.keys);
  I32x8 todo = q.valid;
  while (any(todo)) {
    const int l = firstLane(todo);
    const I32x8 mine =
        todo & equal(q.keys, splat(static_cast<int32_t>(key[l]))) & equal(q.py, splat(row[l]));
    shadeLanes(*q.records[l], *extras[l], lights, false, q.px, row[l], mine, color, normal);
    todo = todo & ~mine;
  }
  return color;
}

// Queued fragments' linear colours and where they go: tile columns and weights.
struct ShadedFragments {
  I32x8 tx;
  F32x8 weight;
  Vec3x8 color;
};

// Row ty's mixed pixels: their colours (the centre colours the row's shading left) replaced by
// their resolve, every fragment through the queue; shade(first, count) gives the ShadedFragments
// of queued fragments (the perspective path's, below; the ray renderer's, ray_queue.h).
template <typename Shade>
TESSERA_LANES_INLINE void resolveMixedRowBy(const MsaaShading& m, const TileVisibility& tile,
                                            int ty, FragmentQueue& queue,
                                            float linear[3][kTileSize], Shade shade) {
  const auto add = [&](int first, int count) __attribute__((always_inline)) {
    const ShadedFragments f = shade(first, count);
    addFragments(f.tx, f.weight, count, f.color, linear);
  };
  bool row_mixed = false;
  for (int tx = 0; tx < tile.width; tx += 8) {
    const int i = ty * kTileSize + tx;
    const I32x8 mixed = load<I32x8>(m.tiles->mixed + i);
    if (!any(mixed)) continue;
    row_mixed = true;
    MixedGroup g;
    loadMixedGroup(m, i, mixed, g);
    store(linear[0] + tx, select(mixed, g.sum.x, load<F32x8>(linear[0] + tx)));
    store(linear[1] + tx, select(mixed, g.sum.y, load<F32x8>(linear[1] + tx)));
    store(linear[2] + tx, select(mixed, g.sum.z, load<F32x8>(linear[2] + tx)));
    const int ready = queue.count;
    for (int s = 0; s < m.samples; ++s) queue.push(g.keys[s], g.pending[s], tx, s, g.held[s]);
    shadeQueue(queue, ready, add);
  }
  if (!row_mixed) return;
  finishQueue(queue, add);
  finishMixedRow(m, tile, ty, linear);
}

// resolveMixedRowBy of a perspective row when some triangle of the tile is not plain (`lit_alike`:
// every record is TriangleChunk::lit_alike).
TESSERA_LANES_INLINE void resolveMixedRow(const MsaaShading& m, const TileVisibility& tile, int ty,
                                          const ShadeTriangle* const* chunk_records,
                                          const ShadeExtras* const* chunk_extras,
                                          const LightRig& lights, bool lit_alike,
                                          FragmentQueue& queue, float linear[3][kTileSize]) {
  const int y = tile.y0 + ty;
  resolveMixedRowBy(m, tile, ty, queue, linear, [&](int first, int count) {
    QueuedFragments q;
    loadQueued(chunk_records, queue, first, count, tile.x0, y, q);
    return ShadedFragments{q.tx, q.weight, shadeFragments(q, chunk_extras, lights, lit_alike)};
  });
}

}  // namespace
}  // namespace tessera::render
