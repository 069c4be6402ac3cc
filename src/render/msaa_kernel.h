// The multisampling kernels (msaa.h): combining a tile's sample layers, and resolving the mixed
// pixels of a row sample by sample. Written once against eight-lane types and compiled per
// instruction set (kernels_<isa>.cpp), with the same operations per lane, so every variant gives
// the same bits.
#pragma once

#include <cstdint>
#include <vector>

#include "render/bin.h"
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

// The sample-s fragments of eight pixels (the lanes of `first`: pixels whose sample s holds a
// triangle that no earlier sample holds), shaded from their own triangles (keys), each at the
// pixel centre when the centre passes the triangle's edge tests and otherwise at sample s (the
// triangle's first in pattern order, the nearest the centre it holds).
TESSERA_LANES_INLINE Vec3x8 shadeSampleFragments(const MsaaShading& m, int s, I32x8 keys,
                                                 I32x8 first, int x, int y,
                                                 const std::vector<TriangleChunk>& chunks,
                                                 const LightRig& lights, bool plain) {
  alignas(32) uint32_t key[8];
  alignas(32) int32_t valid[8];
  store(key, keys);
  store(valid, first);
  constexpr float kToPixels = 1.0f / static_cast<float>(kSubpixelOne);
  const float sample_x = static_cast<float>(m.positions[s].x) * kToPixels;
  const float sample_y = static_cast<float>(y) + static_cast<float>(m.positions[s].y) * kToPixels;
  const float centre_y = static_cast<float>(y) + 0.5f;
  // Every lane starts at its centre with a valid lane's triangle (the other lanes keep that:
  // computed, not used); the valid lanes then take their own triangle and shading point.
  alignas(32) float px[8], py[8];
  alignas(32) int32_t at_centre[8];
  store(px, toFloat(splat(x) + iota()) + splat(0.5f));
  store(py, splat(centre_y));
  store(at_centre, splat(int32_t{-1}));
  const uint32_t borrowed = key[firstLane(first)];
  const ShadeTriangle* records[8];
  const ShadeTriangle* borrowed_record = &chunks[keyChunk(borrowed)].shade[keyLocal(borrowed)];
  for (int l = 0; l < 8; ++l) records[l] = borrowed_record;
  for (int l = 0; l < 8; ++l) {
    if (!valid[l]) continue;
    const uint32_t k = key[l];
    const TriangleChunk& chunk = chunks[keyChunk(k)];
    records[l] = &chunk.shade[keyLocal(k)];
    if (coversCentre(chunk.raster[keyLocal(k)], chunk.wide[keyLocal(k)], x + l, y)) continue;
    at_centre[l] = 0;
    px[l] = static_cast<float>(x + l) + sample_x;
    py[l] = sample_y;
  }
  if (plain) return shadeMixed(records, load<F32x8>(px), load<F32x8>(py));
  // Otherwise each triangle once for its lanes at the centre and once for those at the sample.
  const F32x8 zero = splat(0.0f);
  Vec3x8 color{zero, zero, zero}, normal{zero, zero, zero};
  const I32x8 centre_lanes = load<I32x8>(at_centre);
  I32x8 todo = first;
  while (any(todo)) {
    const uint32_t k = key[firstLane(todo)];
    const I32x8 mine = todo & equal(keys, splat(static_cast<int32_t>(k)));
    const TriangleChunk& chunk = chunks[keyChunk(k)];
    const ShadeTriangle& t = chunk.shade[keyLocal(k)];
    const ShadeExtras& e = chunk.extras[keyLocal(k)];
    if (any(mine & centre_lanes))
      shadeLanes(t, e, lights, false, load<F32x8>(px), centre_y, mine & centre_lanes, color, normal);
    if (any(mine & ~centre_lanes))
      shadeLanes(t, e, lights, false, load<F32x8>(px), sample_y, mine & ~centre_lanes, color,
                 normal);
    todo = todo & ~mine;
  }
  return color;
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

// The resolve of the perspective path: fragments shaded from the screen-space planes.
void resolveMixedRow(const MsaaShading& m, const TileVisibility& tile, int ty,
                     const std::vector<TriangleChunk>& chunks, const LightRig& lights, bool plain,
                     float linear[3][kTileSize]) {
  resolveMixedRowWith(m, tile, ty, linear,
                      [&](int s, I32x8 keys, I32x8 first, int x, int y)
                          __attribute__((always_inline)) {
                            return shadeSampleFragments(m, s, keys, first, x, y, chunks, lights,
                                                        plain);
                          });
}

}  // namespace
}  // namespace tessera::render
