// The tile raster kernel, written once against eight-lane types (simd_lanes.h) and compiled
// once per instruction set (kernels_<isa>.cpp). Every variant runs the same arithmetic in the
// same order, so they produce the same bits.
//
// Coverage comes in two forms:
//   - small triangles (most of a real mesh), whose edge values provably fit in 32 bits over their
//     bounding box, step 32-bit edge values eight pixels at a time (two rows of four when the
//     triangle is at most four pixels wide);
//   - other triangles go through 8x8 blocks: each block is classified by its four corner pixel
//     centres in 64-bit arithmetic as outside (skipped), inside (depth test only), or partial
//     (64-bit edge values per pixel).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "render/bin.h"
#include "render/mask_kernel.h"
#include "render/raster.h"
#include "render/simd_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

constexpr int kLanes = 8;
constexpr int kBlock = 8;

// A covered pixel's test: the z-buffer's (nearer than the stored depth wins; Hi-Z skips what
// cannot win) or the painter's (painter.h: every covered pixel is written, so the later triangle
// wins, and Hi-Z is off). A template argument, so the z-buffer's kernels stay as they were.
enum class DepthRule { kNearest, kLatest };

// The z plane's change from the row's value at the centres of pixels x .. x + 7, for the plane's
// origin at x0 (a sample layer's moved triangle: rasterSample).
TESSERA_LANES_INLINE F32x8 depthAcross8(const RasterTriangle& t, int x, float x0) {
  const F32x8 centre = toFloat(splat(x) + iota()) + splat(0.5f);
  return splat(t.dzdx) * (centre - splat(x0));
}
TESSERA_LANES_INLINE F32x8 depthAcross8(const RasterTriangle& t, int x) {
  return depthAcross8(t, x, t.x0);
}

// Depth-tests the eight pixels at depth[0..7] and keys[0..7]: covered lanes nearer than the stored
// depth take z and the key; the others write back what they read (the tile rows are padded, so the
// eight slots always exist). z is the plane at the pixel centre, the row's depth plus depthAcross8
// at the first of the eight, computed exactly as everywhere else.
// `key`: each lane's (a sample layer's keys carry the centre flag, kCentreKeyBit), or one for all.
template <DepthRule kRule = DepthRule::kNearest>
TESSERA_LANES_INLINE void depthTestRow8(I32x8 key, float z_row, F32x8 across, I32x8 covered,
                                        float* depth, uint32_t* keys) {
  const F32x8 z = splat(z_row) + across;
  const F32x8 stored = load<F32x8>(depth);
  const I32x8 pass = kRule == DepthRule::kLatest ? covered : covered & lessThan(z, stored);
  store(depth, select(pass, z, stored));
  store(keys, select(pass, key, load<I32x8>(keys)));
}
template <DepthRule kRule = DepthRule::kNearest>
TESSERA_LANES_INLINE void depthTestRow8(uint32_t key, float z_row, F32x8 across, I32x8 covered,
                                        float* depth, uint32_t* keys) {
  depthTestRow8<kRule>(splat(static_cast<int32_t>(key)), z_row, across, covered, depth, keys);
}

// A sample layer's keys for a step whose edge values at the pixel centres are e0, e1, e2: `key`
// with kCentreKeyBit in the lanes whose centre passes the three tests.
TESSERA_LANES_INLINE I32x8 centreFlagged(uint32_t key, I32x8 e0, I32x8 e1, I32x8 e2) {
  return splat(static_cast<int32_t>(key)) |
         (nonNegative(e0 | e1 | e2) & splat(static_cast<int32_t>(kCentreKeyBit)));
}

template <DepthRule kRule = DepthRule::kNearest>
TESSERA_LANES_INLINE void depthTestRow8(const RasterTriangle& t, uint32_t key, float z_row, int x,
                                        I32x8 covered, float* depth, uint32_t* keys) {
  depthTestRow8<kRule>(key, z_row, depthAcross8(t, x), covered, depth, keys);
}

// The z plane at the centres of row y, for the plane's origin at y0 (a sample layer's moved
// triangle: rasterSample) or the triangle's.
TESSERA_LANES_INLINE float rowDepth(const RasterTriangle& t, int y, float y0) {
  return t.z0 + t.dzdy * (static_cast<float>(y) + 0.5f - y0);
}
TESSERA_LANES_INLINE float rowDepth(const RasterTriangle& t, int y) {
  return rowDepth(t, y, t.y0);
}

// rowDepth of rows y .. y + 7, lane by lane the same operations.
TESSERA_LANES_INLINE F32x8 rowDepths8(const RasterTriangle& t, int y) {
  return splat(t.z0) + splat(t.dzdy) * ((toFloat(splat(y) + iota()) + splat(0.5f)) - splat(t.y0));
}

// The index of pixel (x, y), in window coordinates, in the tile's depth and key arrays. Pointers
// are formed at a pixel inside the tile, never at a row's window origin left of the tile, which
// is outside the array (undefined behaviour; UBSan's bounds check reports it).
TESSERA_LANES_INLINE int tilePixel(const TileVisibility& tile, int x, int y) {
  return (y - tile.y0) * kTileSize + (x - tile.x0);
}

// A small triangle's edge k at the centre of pixel (x, y) in its box: from the value at the box's
// first pixel, in int64 (the same integer as a * px + b * py + c), within int32 (small()).
TESSERA_LANES_INLINE int32_t smallEdgeAt(const RasterTriangle& t, int k, int x, int y) {
  return static_cast<int32_t>(t.corner[k] +
                              static_cast<int64_t>(t.a[k]) * ((x - t.min_x) * kSubpixelOne) +
                              static_cast<int64_t>(t.b[k]) * ((y - t.min_y) * kSubpixelOne));
}

// Walks a small triangle's box from (x_begin, y_begin) to (x_end, y_end), eight pixels of a row at
// a time, calling visit(y, row_offset, x, e0, e1, e2, in_range) with the three edge values at the
// centres of pixels x .. x + 7 and the lanes within x_end; row_offset + x is tilePixel(x, y). The
// values are row + step * (x - x_begin + lane), formed by adds; a row is stepped only when another
// follows, so no value past row y_end is formed: with two rows or more the box is at least a pixel
// tall, and |b| * one pixel fits (RasterTriangle::small). The row's values stay in lanes from row
// to row: the same int32 sums as a scalar stepped with the lane offsets added each row, which took
// most of a row's instructions. The box is not empty (x_begin <= x_end, y_begin <= y_end): the
// first step is visited before any test.
template <typename Visit>
TESSERA_LANES_INLINE void walkSmallBox(const RasterTriangle& t, const TileVisibility& tile,
                                       int x_begin, int x_end, int y_begin, int y_end,
                                       Visit visit) {
  I32x8 row[3], row_step[3], chunk_step[3];
  const I32x8 lane = iota();
  for (int k = 0; k < 3; ++k) {
    row[k] = splat(smallEdgeAt(t, k, x_begin, y_begin)) + splat(t.a[k] * kSubpixelOne) * lane;
    row_step[k] = splat(t.b[k] * kSubpixelOne);
    chunk_step[k] = splat(t.a[k] * kSubpixelOne * kLanes);
  }
  const I32x8 last = splat(x_end), first_column = splat(x_begin) + lane;
  int row_offset = tilePixel(tile, x_begin, y_begin) - x_begin;
  for (int y = y_begin;;) {
    I32x8 e0 = row[0], e1 = row[1], e2 = row[2], column = first_column;
    for (int x = x_begin;;) {
      visit(y, row_offset, x, e0, e1, e2, lessOrEqual(column, last));
      x += kLanes;
      if (x > x_end) break;
      e0 = e0 + chunk_step[0];
      e1 = e1 + chunk_step[1];
      e2 = e2 + chunk_step[2];
      column = column + splat(kLanes);
    }
    if (++y > y_end) break;
    for (int k = 0; k < 3; ++k) row[k] = row[k] + row_step[k];
    row_offset += kTileSize;
  }
}

template <DepthRule kRule>
TESSERA_LANES_INLINE void rasterSmall(const RasterTriangle& t, uint32_t key, TileVisibility& tile,
                                      int x_begin, int x_end, int y_begin, int y_end) {
  const F32x8 first_across = depthAcross8(t, x_begin);  // most boxes are one chunk wide
  // The rows' depths formed eight at a time before the walk (at most a tile's rows).
  alignas(32) float z_rows[kTileSize];
  for (int y = y_begin; y <= y_end; y += kLanes) store(z_rows + (y - y_begin), rowDepths8(t, y));
  walkSmallBox(
      t, tile, x_begin, x_end, y_begin, y_end,
      [&](int y, int row_offset, int x, I32x8 e0, I32x8 e1, I32x8 e2, I32x8 in_range)
          __attribute__((always_inline)) {
            const I32x8 covered = nonNegative(e0 | e1 | e2) & in_range;
            // No branch on an empty group: where no lane is covered the depth test
            // writes back what it read. At a small triangle's edges such a branch goes
            // either way and mispredicted often enough to cost more than the work it
            // saved (docs/perf-notes/frame-stages.md, round 5).
            const F32x8 across = x == x_begin ? first_across : depthAcross8(t, x);
            depthTestRow8<kRule>(key, z_rows[y - y_begin], across, covered,
                                 tile.depth + (row_offset + x), tile.key + (row_offset + x));
          });
}

// The lanes of a step of walkNarrowBox: column 0-3 in the box, and row 0 (lanes 0-3) or 1 (4-7).
TESSERA_LANES_INLINE I32x8 narrowColumn() {
  return iota() & splat(int32_t{3});
}
TESSERA_LANES_INLINE I32x8 narrowSecondRow() {
  return shiftRight(iota(), 2);
}

// Walks a small triangle's box at most four pixels wide two rows a step, lanes 0-3 on row y and
// lanes 4-7 on row y + 1, calling visit(offset, centre_y, e0, e1, e2, in_box) with tilePixel of
// (x_begin, y), the lanes' row centres y + 0.5 (stepped by 2, exactly: below 2^23, so each lane
// holds what rowDepth computes from), the edge values at the lanes' pixel centres (smallEdgeAt's
// integers, formed by adds) and the lanes inside the box.
template <typename Visit>
TESSERA_LANES_INLINE void walkNarrowBox(const RasterTriangle& t, const TileVisibility& tile,
                                        int x_begin, int x_end, int y_begin, int y_end,
                                        Visit visit) {
  const I32x8 column = narrowColumn(), second_row = narrowSecondRow();
  I32x8 edge[3];
  int32_t step_y[3];
  for (int k = 0; k < 3; ++k) {
    // Fits: the triangle is small (RasterTriangle::small; smallBox allows for the sample
    // offsets), and the pixels are within its box or a row past it.
    edge[k] = splat(smallEdgeAt(t, k, x_begin, y_begin)) + splat(t.a[k] * kSubpixelOne) * column +
              splat(t.b[k] * kSubpixelOne) * second_row;
    step_y[k] = 2 * t.b[k] * kSubpixelOne;
  }
  const I32x8 in_columns = lessOrEqual(column, splat(x_end - x_begin));
  F32x8 centre_y = toFloat(splat(y_begin) + second_row) + splat(0.5f);
  int offset = tilePixel(tile, x_begin, y_begin);
  for (int y = y_begin; y <= y_end; y += 2) {
    // Stepped at the top so no value beyond row y_end + 1 is formed (see rasterNarrow's caller).
    if (y != y_begin) {
      for (int k = 0; k < 3; ++k) edge[k] = edge[k] + splat(step_y[k]);
      centre_y = centre_y + splat(2.0f);
      offset += 2 * kTileSize;
    }
    // Lanes 4-7 of the last step: row y_end + 1, outside the box. A comparison, not a branch on
    // the last step: the branch mispredicted at every box's end.
    const I32x8 in_box = in_columns & lessOrEqual(splat(y) + second_row, splat(y_end));
    visit(offset, centre_y, edge[0], edge[1], edge[2], in_box);
  }
}

// depthTestRow8 for a step of walkNarrowBox: the two rows of four at depth and depth + kTileSize.
template <DepthRule kRule>
TESSERA_LANES_INLINE void depthTest2x4(I32x8 key, F32x8 z, I32x8 covered, float* depth,
                                       uint32_t* keys) {
  const F32x8 stored = load2x4<F32x8>(depth, depth + kTileSize);
  const I32x8 pass = kRule == DepthRule::kLatest ? covered : covered & lessThan(z, stored);
  store2x4(depth, depth + kTileSize, select(pass, z, stored));
  store2x4(keys, keys + kTileSize, select(pass, key, load2x4<I32x8>(keys, keys + kTileSize)));
}
template <DepthRule kRule>
TESSERA_LANES_INLINE void depthTest2x4(uint32_t key, F32x8 z, I32x8 covered, float* depth,
                                       uint32_t* keys) {
  depthTest2x4<kRule>(splat(static_cast<int32_t>(key)), z, covered, depth, keys);
}

// Triangles at most four pixels wide (most of a dense mesh): walkNarrowBox, so a step does the
// work of two rows of rasterSmall. The same values per pixel as rasterSmall (edge values, z),
// hence the same bits.
template <DepthRule kRule>
TESSERA_LANES_INLINE void rasterNarrow(const RasterTriangle& t, uint32_t key, TileVisibility& tile,
                                       int x_begin, int x_end, int y_begin, int y_end) {
  const F32x8 centre_dx = toFloat(splat(x_begin) + narrowColumn()) + splat(0.5f) - splat(t.x0);
  const F32x8 dz = splat(t.dzdx) * centre_dx;
  const F32x8 z0 = splat(t.z0), dzdy = splat(t.dzdy), y0 = splat(t.y0);
  walkNarrowBox(
      t, tile, x_begin, x_end, y_begin, y_end,
      [&](int offset, F32x8 centre_y, I32x8 e0, I32x8 e1, I32x8 e2, I32x8 in_box)
          __attribute__((always_inline)) {
            // No branch on an empty group, as in rasterSmall.
            const I32x8 covered = nonNegative(e0 | e1 | e2) & in_box;
            const F32x8 z = (z0 + dzdy * (centre_y - y0)) + dz;
            depthTest2x4<kRule>(key, z, covered, tile.depth + offset, tile.key + offset);
          });
}

TESSERA_LANES_INLINE int64_t edgeAt(const RasterTriangle& t, const RasterWide& w, int k, int x,
                                    int y) {
  return t.a[k] * (static_cast<int64_t>(x) * kSubpixelOne + kSubpixelHalf) +
         t.b[k] * (static_cast<int64_t>(y) * kSubpixelOne + kSubpixelHalf) + w.c[k];
}

// The edge values at the centres of pixels bx .. bx + 7 of row y, in 64 bits (lanes64: iota).
TESSERA_LANES_INLINE void rowEdges(const RasterTriangle& t, const RasterWide& w, int bx, int y,
                                   I64x8 lanes64, I64x8 e[3]) {
  for (int k = 0; k < 3; ++k)
    e[k] = splat(edgeAt(t, w, k, bx, y)) +
           lanes64 * splat(static_cast<int64_t>(t.a[k]) * kSubpixelOne);
}

// Rows y0 .. y1 of the block at column bx (in_range: its columns in the triangle's box) of a
// sample layer's walk (rasterBlocks with kFlagCentres), the keys with their centre flags. `inside`:
// the block's pixels pass the moved triangle's edge tests; centres_inside, centres_outside: all or
// none of them pass the original's at their centres. Most blocks of a large triangle are inside
// on both counts, and take a loop of their own.
template <DepthRule kRule>
TESSERA_LANES_INLINE void flaggedBlockRows(const RasterTriangle& t, const RasterWide& w,
                                           uint32_t key, TileVisibility& tile, int bx, int y0,
                                           int y1, I32x8 in_range, bool inside, bool centres_inside,
                                           bool centres_outside, const int64_t* centre_shift) {
  const I32x8 block_keys = splat(static_cast<int32_t>(centres_inside ? key | kCentreKeyBit : key));
  const F32x8 across = depthAcross8(t, bx);
  float* depth = tile.depth + tilePixel(tile, bx, y0);
  uint32_t* keys = tile.key + tilePixel(tile, bx, y0);
  if (inside && (centres_inside || centres_outside)) {
    for (int y = y0; y <= y1; ++y, depth += kTileSize, keys += kTileSize)
      depthTestRow8<kRule>(block_keys, rowDepth(t, y), across, in_range, depth, keys);
    return;
  }
  const I64x8 lanes64 = widen(iota());
  const I32x8 bit = splat(static_cast<int32_t>(kCentreKeyBit));
  for (int y = y0; y <= y1; ++y, depth += kTileSize, keys += kTileSize) {
    I64x8 e[3];
    rowEdges(t, w, bx, y, lanes64, e);
    const I32x8 covered = inside ? in_range : in_range & nonNegative(e[0] | e[1] | e[2]);
    const I32x8 flagged = centres_inside || centres_outside
                              ? block_keys
                              : block_keys | (nonNegative((e[0] - splat(centre_shift[0])) |
                                                          (e[1] - splat(centre_shift[1])) |
                                                          (e[2] - splat(centre_shift[2]))) &
                                              bit);
    depthTestRow8<kRule>(flagged, rowDepth(t, y), across, covered, depth, keys);
  }
}

// The greatest depth the walk computes for t at the 8x8 block whose first pixel is (bx, by), which
// bounds what the block stores once t has covered it all. Each step of rowDepth and depthAcross8
// rounds monotonically in y and in x, and so does the sum of the two, so the greatest is at a
// corner: the greater row of the first and last, plus the greater of the first and last column
// (the lanes' arithmetic in scalars, the same bits). Read back from the stored depths, the bound
// took a horizontal maximum per block, an eighth of the walk of the cube's large triangles.
TESSERA_LANES_INLINE float blockDepthBound(const RasterTriangle& t, int bx, int by) {
  const auto across = [&](int x) { return t.dzdx * (static_cast<float>(x) + 0.5f - t.x0); };
  return std::max(rowDepth(t, by), rowDepth(t, by + kBlock - 1)) +
         std::max(across(bx), across(bx + kBlock - 1));
}

// A large triangle's walk, block by block. `centre_shift` (kFlagCentres: a sample layer's walk of
// the triangle moved by the sample's offset, rasterSample) holds what each edge's value at a
// sample exceeds its value at the pixel centre by (a * dx + b * dy), from which the keys get their
// centre flags (kCentreKeyBit, as centreFlagged gives the small walks theirs).
template <DepthRule kRule, bool kFlagCentres = false>
TESSERA_LANES_INLINE void rasterBlocks(const RasterTriangle& triangle, const RasterWide& w,
                                       uint32_t key, TileVisibility& tile, int x_begin, int x_end,
                                       int y_begin, int y_end,
                                       const int64_t* centre_shift = nullptr) {
  // A copy the walk's stores cannot reach: through the reference, every store to the tile's
  // depths (floats) and keys (32-bit integers) might have changed the record's planes and
  // edges, so each row reloaded them and formed depthAcross8 again.
  const RasterTriangle t = triangle;
  // Blocks are aligned to the tile so a block row never leaves the tile's rows.
  const int bx_first = tile.x0 + ((x_begin - tile.x0) & ~(kBlock - 1));
  const int by_first = tile.y0 + ((y_begin - tile.y0) & ~(kBlock - 1));
  const I32x8 lanes = iota();
  const I64x8 lanes64 = widen(lanes);
  for (int by = by_first; by <= y_end; by += kBlock) {
    const int y0 = std::max(by, y_begin), y1 = std::min(by + kBlock - 1, y_end);
    for (int bx = bx_first; bx <= x_end; bx += kBlock) {
      const int x0 = std::max(bx, x_begin), x1 = std::min(bx + kBlock - 1, x_end);
      // Classify the block by the edge values at its corner pixel centres: an edge is linear,
      // so its extremes over the block are at the corners, and exactly (integers) the value at
      // the first corner plus the steps across and down that lower or raise it.
      bool outside = false, inside = true;
      // The same of the edges at the pixel centres (kFlagCentres).
      bool centres_outside = false, centres_inside = true;
      const int64_t across = static_cast<int64_t>(x1 - x0) * kSubpixelOne;
      const int64_t down = static_cast<int64_t>(y1 - y0) * kSubpixelOne;
      for (int k = 0; k < 3; ++k) {
        const int64_t e00 = edgeAt(t, w, k, x0, y0);
        const int64_t step_x = t.a[k] * across, step_y = t.b[k] * down;
        const int64_t lo = e00 + std::min<int64_t>(step_x, 0) + std::min<int64_t>(step_y, 0);
        const int64_t hi = e00 + std::max<int64_t>(step_x, 0) + std::max<int64_t>(step_y, 0);
        outside |= hi < 0;
        inside &= lo >= 0;
        if constexpr (kFlagCentres) {
          centres_outside |= hi - centre_shift[k] < 0;
          centres_inside &= lo - centre_shift[k] >= 0;
        }
      }
      if (outside) continue;
      float& block_max =
          tile.block_max_depth[((by - tile.y0) / kBlock) * TileVisibility::kHiZBlocksPerRow +
                               (bx - tile.x0) / kBlock];
      // Hi-Z: every stored depth here is nearer.
      if (kRule == DepthRule::kNearest && w.z_min >= block_max) continue;
      const I32x8 columns = splat(bx) + lanes;
      const I32x8 in_range = lessOrEqual(splat(x0), columns) & lessOrEqual(columns, splat(x1));
      if constexpr (kFlagCentres) {
        flaggedBlockRows<kRule>(t, w, key, tile, bx, y0, y1, in_range, inside, centres_inside,
                                centres_outside, centre_shift);
      } else {
        const F32x8 across = depthAcross8(t, bx);
        float* depth = tile.depth + tilePixel(tile, bx, y0);
        uint32_t* keys = tile.key + tilePixel(tile, bx, y0);
        for (int y = y0; y <= y1; ++y, depth += kTileSize, keys += kTileSize) {
          I32x8 covered = in_range;
          if (!inside) {
            I64x8 e[3];
            rowEdges(t, w, bx, y, lanes64, e);
            covered = covered & nonNegative(e[0] | e[1] | e[2]);
          }
          depthTestRow8<kRule>(key, rowDepth(t, y), across, covered, depth, keys);
        }
      }
      // A block now wholly written by this triangle gets a tighter bound.
      if (kRule == DepthRule::kNearest && inside && x0 == bx && x1 == bx + kBlock - 1 && y0 == by &&
          y1 == by + kBlock - 1) {
        block_max = std::min(block_max, blockDepthBound(t, bx, by));
        tile.hiz_bounded = true;
      }
    }
  }
}

// Hi-Z for a small triangle: rejected when no depth it can write is below the bound of any block
// its box touches. Its depths are at least the plane's least value over the corners of its box
// (the plane is linear, the covered pixels inside the box), less a margin far above the rounding
// of depthTestRow8's arithmetic.
TESSERA_LANES_INLINE bool hiddenByHiZ(const RasterTriangle& t, const TileVisibility& tile,
                                      int x_begin, int x_end, int y_begin, int y_end) {
  const float across_begin = t.dzdx * (static_cast<float>(x_begin) + 0.5f - t.x0);
  const float across_end = t.dzdx * (static_cast<float>(x_end) + 0.5f - t.x0);
  const float z_low = std::min(rowDepth(t, y_begin), rowDepth(t, y_end)) +
                      std::min(across_begin, across_end) - 0x1p-16f;
  // Shifts: the offsets from the tile's corner are not negative.
  constexpr int kShift = __builtin_ctz(kBlock);
  const int bx0 = (x_begin - tile.x0) >> kShift, bx1 = (x_end - tile.x0) >> kShift;
  const int by0 = (y_begin - tile.y0) >> kShift, by1 = (y_end - tile.y0) >> kShift;
  for (int by = by0; by <= by1; ++by)
    for (int bx = bx0; bx <= bx1; ++bx)
      if (!(z_low >= tile.block_max_depth[by * TileVisibility::kHiZBlocksPerRow + bx]))
        return false;
  return true;
}

// `wide` is read only for a large triangle.
template <DepthRule kRule = DepthRule::kNearest>
TESSERA_LANES_INLINE void rasterTriangle(const RasterTriangle& t, const RasterWide& wide,
                                         uint32_t key, TileVisibility& tile) {
  const int x_begin = std::max<int>(t.min_x, tile.x0);
  const int x_end = std::min(static_cast<int>(t.max_x), tile.x0 + tile.width - 1);
  const int y_begin = std::max<int>(t.min_y, tile.y0);
  const int y_end = std::min(t.maxY(), tile.y0 + tile.height - 1);
  if (x_begin > x_end || y_begin > y_end) return;
  if (t.small()) {
    if (kRule == DepthRule::kNearest && tile.hiz_bounded &&
        hiddenByHiZ(t, tile, x_begin, x_end, y_begin, y_end))
      return;
    // Two rows or more: the box is then at least a pixel tall, so |b| * 2 pixels < 2^30 (from
    // RasterTriangle::small) and the row after y_end that rasterNarrow forms still fits in int32.
    if (x_end - x_begin < 4 && y_end > y_begin)
      rasterNarrow<kRule>(t, key, tile, x_begin, x_end, y_begin, y_end);
    else
      rasterSmall<kRule>(t, key, tile, x_begin, x_end, y_begin, y_end);
  } else {
    rasterBlocks<kRule>(t, wide, key, tile, x_begin, x_end, y_begin, y_end);
  }
}

// Triangles: about a memory latency of raster work. Measured frame by frame with the walk across
// chunks: 5 to 8 all gave the tile stage 4-5%, 3 about 1%.
constexpr int kPrefetchAhead = 6;

// A position in the walk over a tile's bins: chunk after chunk, each chunk's list in order.
struct BinCursor {
  size_t chunk;
  const uint32_t* it;
  const uint32_t* end;
};

// Moves to the next entry, across chunks; false past the last.
TESSERA_LANES_INLINE bool advance(const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                                  int tile_index, BinCursor& at) {
  if (++at.it != at.end) return true;
  while (++at.chunk < chunk_count) {
    at.it = chunks[at.chunk].bins.begin(tile_index);
    at.end = chunks[at.chunk].bins.end(tile_index);
    if (at.it != at.end) return true;
  }
  return false;
}

// Calls draw(raster, wide, key) for every triangle binned to the tile, in submission order;
// with kMaybeMasked, masked(chunk, record, key) for those whose material is alphaMode MASK
// (mask_kernel.h). Without it (no chunk holds one: anyMasked) the walk tests nothing per triangle.
template <bool kMaybeMasked, typename Draw, typename Masked>
TESSERA_LANES_INLINE void walkTileBins(const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                                       int tile_index, Draw draw, Masked masked) {
  // Every chunk's list for this tile, all at once (each is a line or two, written by setup on
  // either core), and where the next tile's lists are kept, which this worker most likely takes
  // next: walked one after another, each list was a miss of its own.
  if (chunk_count == 0) return;
  const int tile_count = static_cast<int>(chunks[0].bins.tileCount());
  for (size_t c = 0; c < chunk_count; ++c) {
    const ChunkBins& bins = chunks[c].bins;
    __builtin_prefetch(bins.begin(tile_index));
    if (tile_index + 1 < tile_count) __builtin_prefetch(bins.listOf(tile_index + 1));
  }
  // The first entry, then a second cursor kPrefetchAhead entries further on, across chunk
  // boundaries, so that the first triangles of every chunk's list are prefetched too.
  BinCursor at{0, nullptr, nullptr};
  for (; at.chunk < chunk_count; ++at.chunk) {
    at.it = chunks[at.chunk].bins.begin(tile_index);
    at.end = chunks[at.chunk].bins.end(tile_index);
    if (at.it != at.end) break;
  }
  if (at.chunk == chunk_count) return;
  BinCursor ahead = at;
  bool ahead_valid = true;
  for (int i = 0; i < kPrefetchAhead && ahead_valid; ++i)
    ahead_valid = advance(chunks, chunk_count, tile_index, ahead);
  do {
    if (ahead_valid) {
      // The record a few triangles ahead (one line), and its shading record for the shading
      // pass that follows (the first two lines: all that untextured flat and Gouraud pixels
      // read), with, for pixels lit per pixel or textured, the lines of its extras that hold the
      // normals and texture coordinates (bytes 0 to 59) and, where they are read, the world
      // positions.
      // Records are written by setup long before and scattered: without this, both passes wait
      // on them.
      const TriangleChunk& next = chunks[ahead.chunk];
      __builtin_prefetch(&next.raster[*ahead.it]);
      const char* shade = reinterpret_cast<const char*>(&next.shade[*ahead.it]);
      __builtin_prefetch(shade);
      __builtin_prefetch(shade + 64);
      if (next.reads_normals || next.textured_plain) {
        const char* extras = reinterpret_cast<const char*>(&next.extras[*ahead.it]);
        __builtin_prefetch(extras);
        __builtin_prefetch(extras + offsetof(ShadeExtras, uv1) - 1);
        if (next.reads_world) {
          __builtin_prefetch(extras + offsetof(ShadeExtras, world));
          __builtin_prefetch(extras + offsetof(ShadeExtras, tangent) - 1);
        }
      }
      ahead_valid = advance(chunks, chunk_count, tile_index, ahead);
    }
    const TriangleChunk& chunk = chunks[at.chunk];
    const uint32_t key = makeKey(static_cast<uint32_t>(at.chunk), *at.it);
    if (kMaybeMasked && chunk.any_masked && isMasked(chunk, *at.it))
      masked(chunk, *at.it, key);
    else
      draw(chunk.raster[*at.it], chunk.wide[*at.it], key);
  } while (advance(chunks, chunk_count, tile_index, at));
}

// Whether any chunk holds a masked record this frame.
TESSERA_LANES_INLINE bool anyMasked(const std::vector<TriangleChunk>& chunks, size_t chunk_count) {
  for (size_t c = 0; c < chunk_count; ++c)
    if (chunks[c].any_masked) return true;
  return false;
}

// rasterTileKernel's walk for frames with masked records: a function of its own, so that the walk
// without them compiles as it did before masks existed.
template <bool kMaybeMasked>
__attribute__((noinline)) void rasterTileWalk(const std::vector<TriangleChunk>& chunks,
                                              size_t chunk_count, int tile_index,
                                              TileVisibility& tile) {
  walkTileBins<kMaybeMasked>(
      chunks, chunk_count, tile_index,
      [&](const RasterTriangle& t, const RasterWide& w, uint32_t key)
          __attribute__((always_inline)) { rasterTriangle(t, w, key, tile); },
      [&](const TriangleChunk& chunk, uint32_t record, uint32_t key) {
        TileVisibility* const layers[1] = {&tile};
        const SampleShift centre[1] = {};
        rasterMasked<false>(chunk, record, key, layers, centre, 1, false);
      });
}

void rasterTileKernel(const std::vector<TriangleChunk>& chunks, size_t chunk_count, int tile_index,
                      TileVisibility& tile) {
  if (anyMasked(chunks, chunk_count))
    rasterTileWalk<true>(chunks, chunk_count, tile_index, tile);
  else
    rasterTileWalk<false>(chunks, chunk_count, tile_index, tile);
}

}  // namespace
}  // namespace tessera::render
