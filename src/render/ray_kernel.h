// The tile stage of the nonlinear projections (ray_setup.h): coverage and depth by each pixel's
// ray, shading from the ray's barycentrics (shade_lanes.h). Written once against eight-lane types
// and compiled per instruction set (kernels_<isa>.cpp) with the same operations per lane, so every
// variant gives the same bits.
#pragma once

#include <optional>
#include <vector>

#include <tessera/render/projection.h>
#include <tessera/scene/scene.h>

#include "render/bin.h"
#include "render/msaa.h"
#include "render/ray_queue.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

// One box of a triangle, clipped to the tile, eight pixels of a row at a time.
TESSERA_LANES_INLINE void rasterRayBox(const RayTriangle& t, const int16_t box[4], uint32_t key,
                                       const RayLayer& layer, int width, RayDepth range,
                                       TileVisibility& tile) {
  const int x_begin = std::max<int>(box[0], tile.x0);
  const int x_end = std::min<int>(box[2], tile.x0 + tile.width - 1);
  const int y_begin = std::max<int>(box[1], tile.y0);
  const int y_end = std::min<int>(box[3], tile.y0 + tile.height - 1);
  if (x_begin > x_end || y_begin > y_end) return;
  const F32x8 zero = splat(0.0f), one = splat(1.0f);
  const F32x8 det = splat(t.det), near = splat(range.near), inv_range = splat(range.inv_range);
  I32x8 owner[3];
  for (int k = 0; k < 3; ++k) owner[k] = splat(static_cast<int32_t>(-((t.owner >> k) & 1)));
  const I32x8 last = splat(x_end);
  const I32x8 key_lanes = splat(static_cast<int32_t>(key));
  for (int y = y_begin; y <= y_end; ++y) {
    const size_t row = static_cast<size_t>(y) * static_cast<size_t>(width);
    // Row starts inside the arrays, pixels from the tile's first column (no pointer before them).
    float* depth = tile.depth + (y - tile.y0) * kTileSize;
    uint32_t* keys = tile.key + (y - tile.y0) * kTileSize;
    for (int x = x_begin; x <= x_end; x += 8) {
      const int at = x - tile.x0;
      const Ray8 d = loadRays(layer, row + static_cast<size_t>(x));
      I32x8 covered = lessOrEqual(splat(x) + iota(), last);
      F32x8 e[3];
      for (int k = 0; k < 3; ++k) {
        e[k] = edgeValue(t, k, d);
        covered = covered & (lessThan(zero, e[k]) | (equal(e[k], zero) & owner[k]));
      }
      const F32x8 sum = (e[0] + e[1]) + e[2];
      const F32x8 z = (det / sum - near) * inv_range;
      covered = covered & lessThan(zero, sum) & lessOrEqualF(zero, z) & lessOrEqualF(z, one);
      const F32x8 stored = load<F32x8>(depth + at);
      const I32x8 pass = covered & lessThan(z, stored);
      store(depth + at, select(pass, z, stored));
      store(keys + at, select(pass, key_lanes, load<I32x8>(keys + at)));
    }
  }
}

void rasterRayTileKernel(const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                         int tile_index, const RayLayer& layer, int width, RayDepth depth,
                         TileVisibility& tile) {
  for (size_t c = 0; c < chunk_count; ++c) {
    const TriangleChunk& chunk = chunks[c];
    for (const uint32_t* it = chunk.bins.begin(tile_index); it != chunk.bins.end(tile_index);
         ++it) {
      const RayTriangle& t = chunk.ray[*it];
      const uint32_t key = makeKey(static_cast<uint32_t>(c), *it);
      rasterRayBox(t, t.box[0], key, layer, width, depth, tile);
      if (t.box[1][0] <= t.box[1][2]) rasterRayBox(t, t.box[1], key, layer, width, depth, tile);
    }
  }
}

void shadeRayTileKernel(const TileVisibility& tile, const std::vector<TriangleChunk>& chunks,
                        size_t chunk_count, const LightRig& lights, bool want_normals,
                        uint32_t background, const RayTable& rays, const MsaaShading* msaa,
                        ShadedTile& out) {
  const RayShading rs{lights, chunks, rays, rays.width(), rays.height()};
  const RayRecords records(chunks, chunk_count);
  std::optional<FragmentQueue> queue;
  if (msaa) queue.emplace(*msaa);
  const I32x8 empty = splat(static_cast<int32_t>(kEmptyKey));
  const F32x8 zero = splat(0.0f);
  alignas(32) float linear[3][kTileSize];
  for (int ty = 0; ty < tile.height; ++ty) {
    const int y = tile.y0 + ty;
    const size_t row = static_cast<size_t>(y) * static_cast<size_t>(rs.width);
    for (int tx = 0; tx < tile.width; tx += 8) {
      const int i = ty * kTileSize + tx;
      const I32x8 keys = load<I32x8>(tile.key + i);
      I32x8 todo = ~equal(keys, empty);
      if (!any(todo)) continue;
      const int x = tile.x0 + tx;
      const Ray8 d = loadRays(rays.centre(), row + static_cast<size_t>(x));
      Vec3x8 color{zero, zero, zero}, normal{zero, zero, zero};
      // Several triangles shaded alike: one evaluation from each lane's records.
      const uint32_t first = static_cast<uint32_t>(lane(keys, firstLane(todo)));
      if (!want_normals && rayBatchable(records.shade[keyChunk(first)][keyLocal(first)]) &&
          any(todo & ~equal(keys, splat(static_cast<int32_t>(first)))) &&
          shadeRayMixed(records, lights, keys, todo, first, d, color)) {
        storeShadedGroup(color, normal, want_normals, tx, i, linear, out);
        continue;
      }
      do {
        const uint32_t key = static_cast<uint32_t>(lane(keys, firstLane(todo)));
        const I32x8 mask = equal(keys, splat(static_cast<int32_t>(key)));
        rs.shade(key, d, x, y, mask, want_normals, color, normal);
        todo = todo & ~mask;
      } while (any(todo));
      storeShadedGroup(color, normal, want_normals, tx, i, linear, out);
    }
    if (msaa) resolveRayMixedRow(*msaa, tile, ty, rs, records, *queue, linear);
    encodeShadedRow(tile, ty, linear, nullptr, background, out);
  }
}

}  // namespace
}  // namespace tessera::render
