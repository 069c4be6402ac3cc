// The tile raster kernel for multisampling: each triangle into every sample layer of a tile, the
// layers' samples at their own positions (msaa.h). The same arithmetic per sample as the
// one-sample walk (raster_kernel.h), compiled once per instruction set, so every variant gives
// the same bits.
#pragma once

#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "render/raster_kernel.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

// A large triangle's coverage and depth at one sample of every pixel: the triangle moved by the
// sample's offset from the pixel centre (-offset), rasterized at pixel centres. The edge values at
// the centre of the moved triangle are the original's at the sample, exactly: a and b stay, c
// takes a * dx + b * dy, and the depth plane's origin moves by the offset in pixels; the keys'
// centre flags (kCentreKeyBit) come from the original's values, the moved one's less a * dx +
// b * dy. The record's box holds every pixel any sample may cover (setup grows it by
// sampleReach); the moved triangle's own box, from its snapped vertices (which a, b and x0, y0
// give back exactly), is narrower by up to a pixel on each side. (Small triangles take every
// layer in one walk: rasterSmallSamples.) Not inlined: in the walk over the tile's triangles it
// took registers from the small triangles' walks, which took 3% more instructions.
template <DepthRule kRule>
__attribute__((noinline)) void rasterSample(const RasterTriangle& t, const RasterWide& w,
                                            uint32_t key, const SampleShift& shift,
                                            TileVisibility& tile) {
  // The snapped vertices in 1/256 pixel (edge 2 runs v0 -> v1, edge 1 v2 -> v0; setup.cpp).
  const int32_t v0x = static_cast<int32_t>(t.x0 * static_cast<float>(kSubpixelOne));
  const int32_t v0y = static_cast<int32_t>(t.y0 * static_cast<float>(kSubpixelOne));
  const int32_t v1x = v0x + t.b[2], v1y = v0y - t.a[2];
  const int32_t v2x = v0x - t.b[1], v2y = v0y + t.a[1];
  // pixelRange (setup.h) of the moved vertices, within the record's box and the tile.
  const int32_t lo_x = std::min({v0x, v1x, v2x}) - shift.dx,
                hi_x = std::max({v0x, v1x, v2x}) - shift.dx;
  const int32_t lo_y = std::min({v0y, v1y, v2y}) - shift.dy,
                hi_y = std::max({v0y, v1y, v2y}) - shift.dy;
  const int x_begin =
      std::max({static_cast<int>(t.min_x), tile.x0, -((kSubpixelHalf - lo_x) >> kSubpixelBits)});
  const int x_end = std::min({static_cast<int>(t.max_x), tile.x0 + tile.width - 1,
                              (hi_x - kSubpixelHalf) >> kSubpixelBits});
  const int y_begin =
      std::max({static_cast<int>(t.min_y), tile.y0, -((kSubpixelHalf - lo_y) >> kSubpixelBits)});
  const int y_end =
      std::min({t.maxY(), tile.y0 + tile.height - 1, (hi_y - kSubpixelHalf) >> kSubpixelBits});
  if (x_begin > x_end || y_begin > y_end) return;
  RasterTriangle moved = t;
  moved.x0 = t.x0 - shift.pixels_x;
  moved.y0 = t.y0 - shift.pixels_y;
  RasterWide moved_wide;
  int64_t centre_shift[3];
  for (int k = 0; k < 3; ++k) {
    centre_shift[k] = int64_t{t.a[k]} * shift.dx + int64_t{t.b[k]} * shift.dy;
    moved_wide.c[k] = w.c[k] + centre_shift[k];
  }
  moved_wide.z_min = w.z_min;
  rasterBlocks<kRule, true>(moved, moved_wide, key, tile, x_begin, x_end, y_begin, y_end,
                            centre_shift);
}

// What rasterSmallSamples keeps per layer: the edge offsets of its samples, the depth plane's
// origin of the moved triangle (rasterSample), and whether Hi-Z leaves it anything to draw.
struct SampleLayerEdges {
  I32x8 offset[kMaxSamples + 1][3];
  float x0[kMaxSamples + 1], y0[kMaxSamples + 1];
  bool drawn[kMaxSamples + 1];
};

// rasterNarrow for every layer at once: a small triangle at most four pixels wide, two rows a
// step (lanes 0-3 row y, lanes 4-7 row y + 1), each layer's edge values the centre's plus its
// offset and its depth as rasterSample forms it (rasterNarrow's operations: the same bits).
template <DepthRule kRule>
TESSERA_LANES_INLINE void rasterNarrowSamples(const RasterTriangle& t, uint32_t key,
                                              TileVisibility* const* layers,
                                              const SampleLayerEdges& le, int layer_count,
                                              int x_begin, int x_end, int y_begin, int y_end) {
  const TileVisibility& tile = *layers[0];
  const F32x8 centre_x = toFloat(splat(x_begin) + narrowColumn()) + splat(0.5f);
  F32x8 dz[kMaxSamples + 1];
  for (int i = 0; i < layer_count; ++i) dz[i] = splat(t.dzdx) * (centre_x - splat(le.x0[i]));
  const F32x8 z0 = splat(t.z0), dzdy = splat(t.dzdy);
  walkNarrowBox(
      t, tile, x_begin, x_end, y_begin, y_end,
      [&](int offset, F32x8 centre_y, I32x8 e0, I32x8 e1, I32x8 e2,
          I32x8 in_box) __attribute__((always_inline)) {
        const I32x8 keys = centreFlagged(key, e0, e1, e2);
        for (int i = 0; i < layer_count; ++i) {
          if (!le.drawn[i]) continue;
          const I32x8 covered = nonNegative((e0 + le.offset[i][0]) | (e1 + le.offset[i][1]) |
                                            (e2 + le.offset[i][2])) &
                                in_box;
          // No branch on a layer the step misses: the test writes back what it read
          // (rasterSmall).
          const F32x8 z = (z0 + dzdy * (centre_y - splat(le.y0[i]))) + dz[i];
          depthTest2x4<kRule>(keys, z, covered, layers[i]->depth + offset, layers[i]->key + offset);
        }
      });
}

// The layers' sample shifts in lanes (lane i: layer i's dx and dy in 1/256 pixel; at most eight
// layers), made once a tile: each edge's offsets of every layer then take one multiply-add.
struct ShiftLanes {
  I32x8 dx, dy;
};

// A small triangle into every layer at once: rasterSmall's walk over its box, eight pixels at a
// time (rasterNarrowSamples' two rows of four when it is at most four pixels wide), with each
// layer's edge values the centre's plus that sample's a * dx + b * dy (within int32: smallBox
// with the sample reach) and its depth as rasterSample forms it (the same bits). `lanes`: the
// shifts in lanes, or null.
template <DepthRule kRule>
TESSERA_LANES_INLINE void rasterSmallSamples(const RasterTriangle& t, uint32_t key,
                                             TileVisibility* const* layers,
                                             const SampleShift* shifts, int layer_count,
                                             const ShiftLanes* lanes) {
  const TileVisibility& tile = *layers[0];
  const int x_begin = std::max<int>(t.min_x, tile.x0);
  const int x_end = std::min(static_cast<int>(t.max_x), tile.x0 + tile.width - 1);
  const int y_begin = std::max<int>(t.min_y, tile.y0);
  const int y_end = std::min(t.maxY(), tile.y0 + tile.height - 1);
  if (x_begin > x_end || y_begin > y_end) return;
  SampleLayerEdges le;
  if (lanes) {
    alignas(32) int32_t offset[3][8];
    for (int k = 0; k < 3; ++k)
      store(offset[k], splat(t.a[k]) * lanes->dx + splat(t.b[k]) * lanes->dy);
    for (int i = 0; i < layer_count; ++i)
      for (int k = 0; k < 3; ++k) le.offset[i][k] = splat(offset[k][i]);
  } else {
    for (int i = 0; i < layer_count; ++i)
      for (int k = 0; k < 3; ++k)
        le.offset[i][k] = splat(t.a[k] * shifts[i].dx + t.b[k] * shifts[i].dy);
  }
  int drawn_count = 0;
  for (int i = 0; i < layer_count; ++i) {
    le.x0[i] = t.x0 - shifts[i].pixels_x;
    le.y0[i] = t.y0 - shifts[i].pixels_y;
    le.drawn[i] = true;
    if (kRule == DepthRule::kNearest && layers[i]->hiz_bounded) {
      RasterTriangle moved = t;
      moved.x0 = le.x0[i];
      moved.y0 = le.y0[i];
      le.drawn[i] = !hiddenByHiZ(moved, *layers[i], x_begin, x_end, y_begin, y_end);
    }
    drawn_count += le.drawn[i];
  }
  if (drawn_count == 0) return;
  // Two rows or more, as rasterTriangle's choice of rasterNarrow.
  if (x_end - x_begin < 4 && y_end > y_begin) {
    rasterNarrowSamples<kRule>(t, key, layers, le, layer_count, x_begin, x_end, y_begin, y_end);
    return;
  }
  // depthAcross8 of each layer's moved triangle (rasterSample) at the first step of a row (most
  // rows take one).
  F32x8 first_across[kMaxSamples + 1];
  for (int i = 0; i < layer_count; ++i) first_across[i] = depthAcross8(t, x_begin, le.x0[i]);
  // A copy of the walk for the usual case, every layer drawn (no Hi-Z bound in the tile), without
  // a test per layer and step.
  auto walk = [&](auto every_layer) __attribute__((always_inline)) {
    walkSmallBox(
        t, tile, x_begin, x_end, y_begin, y_end,
        [&](int y, int row_offset, int x, I32x8 e0, I32x8 e1, I32x8 e2, I32x8 in_range)
            __attribute__((always_inline)) {
              const I32x8 keys = centreFlagged(key, e0, e1, e2);
              // rowDepth of each layer's moved triangle (rasterSample), the layers side by side.
              float z_rows[kMaxSamples + 1];
              for (int i = 0; i < layer_count; ++i) z_rows[i] = rowDepth(t, y, le.y0[i]);
              for (int i = 0; i < layer_count; ++i) {
                if (!every_layer && !le.drawn[i]) continue;
                const I32x8 covered = nonNegative((e0 + le.offset[i][0]) | (e1 + le.offset[i][1]) |
                                                  (e2 + le.offset[i][2])) &
                                      in_range;
                // No branch on a layer the step misses (rasterSmall's reason).
                const F32x8 across = x == x_begin ? first_across[i] : depthAcross8(t, x, le.x0[i]);
                depthTestRow8<kRule>(keys, z_rows[i], across, covered,
                                     layers[i]->depth + (row_offset + x),
                                     layers[i]->key + (row_offset + x));
              }
            });
  };
  if (drawn_count == layer_count)
    walk(std::true_type{});
  else
    walk(std::false_type{});
}

// One triangle into each layer of `layers`, layer i at shifts[i] (`lanes`: the same in lanes, or
// null).
template <DepthRule kRule = DepthRule::kNearest>
TESSERA_LANES_INLINE void rasterTriangleSamples(const RasterTriangle& t, const RasterWide& w,
                                                uint32_t key, TileVisibility* const* layers,
                                                const SampleShift* shifts, int layer_count,
                                                const ShiftLanes* lanes = nullptr) {
  if (t.small()) {
    rasterSmallSamples<kRule>(t, key, layers, shifts, layer_count, lanes);
    return;
  }
  for (int i = 0; i < layer_count; ++i) rasterSample<kRule>(t, w, key, shifts[i], *layers[i]);
}

// Every triangle of the tile into each layer of `layers`, layer i at shifts[i].
TESSERA_LANES_INLINE void rasterTileSamples(const std::vector<TriangleChunk>& chunks,
                                            size_t chunk_count, int tile_index,
                                            TileVisibility* const* layers,
                                            const SampleShift* shifts, int layer_count) {
  alignas(32) int32_t dx[8] = {}, dy[8] = {};
  for (int i = 0; i < std::min(layer_count, 8); ++i) dx[i] = shifts[i].dx, dy[i] = shifts[i].dy;
  const ShiftLanes lanes{load<I32x8>(dx), load<I32x8>(dy)};
  const ShiftLanes* const in_lanes = layer_count <= 8 ? &lanes : nullptr;
  auto draw = [&](const RasterTriangle& t, const RasterWide& w, uint32_t key)
      __attribute__((always_inline)) {
    rasterTriangleSamples(t, w, key, layers, shifts, layer_count, in_lanes);
  };
  auto masked = [&](const TriangleChunk& chunk, uint32_t record, uint32_t key) {
    rasterMasked<false>(chunk, record, key, layers, shifts, layer_count, true);
  };
  if (anyMasked(chunks, chunk_count))
    walkTileBins<true>(chunks, chunk_count, tile_index, draw, masked);
  else
    walkTileBins<false>(chunks, chunk_count, tile_index, draw, masked);
}

void rasterTileSamplesKernel(const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                             int tile_index, TileVisibility* const* layers,
                             const SampleShift* shifts, int layer_count) {
  withSampleCount(
      layer_count, [&](int n) __attribute__((always_inline)) {
        rasterTileSamples(chunks, chunk_count, tile_index, layers, shifts, n);
      });
}

}  // namespace
}  // namespace tessera::render
