// The tile stage of the nonlinear projections (ray_setup.h): coverage and depth by each pixel's
// ray, shading from the ray's barycentrics (shade_lanes.h). Written once against eight-lane types
// and compiled per instruction set (kernels_<isa>.cpp) with the same operations per lane, so every
// variant gives the same bits.
#pragma once

#include <vector>

#include <tessera/render/projection.h>
#include <tessera/scene/scene.h>

#include "render/bin.h"
#include "render/msaa.h"
#include "render/msaa_kernel.h"
#include "render/ray_setup.h"
#include "render/shade_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

struct Ray8 {
  F32x8 x, y, z;
};

TESSERA_LANES_INLINE Ray8 loadRays(const RayLayer& layer, size_t at) {
  return {load<F32x8>(layer.x.data() + at), load<F32x8>(layer.y.data() + at),
          load<F32x8>(layer.z.data() + at)};
}

// E_k of eight rays, as dotRay.
TESSERA_LANES_INLINE F32x8 edgeValue(const RayTriangle& t, int k, const Ray8& d) {
  return (d.x * splat(t.n[k][0]) + d.y * splat(t.n[k][1])) + d.z * splat(t.n[k][2]);
}

TESSERA_LANES_INLINE I32x8 lessOrEqualF(F32x8 a, F32x8 b) {
  return lessThan(a, b) | equal(a, b);
}

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

// The lanes whose ray passes through the triangle: rayCovers' tests, the same edge values.
TESSERA_LANES_INLINE I32x8 raysCover(const RayTriangle& t, const Ray8& d) {
  const F32x8 zero = splat(0.0f);
  I32x8 covered = splat(int32_t{-1});
  F32x8 e[3];
  for (int k = 0; k < 3; ++k) {
    e[k] = edgeValue(t, k, d);
    const I32x8 owner = splat(static_cast<int32_t>(-((t.owner >> k) & 1)));
    covered = covered & (lessThan(zero, e[k]) | (equal(e[k], zero) & owner));
  }
  return covered & lessThan(zero, (e[0] + e[1]) + e[2]);
}

// The barycentrics of eight rays' hits, as rayBarycentrics.
TESSERA_LANES_INLINE void rayBarycentrics8(const RayTriangle& t, const Ray8& d, F32x8& b0,
                                           F32x8& b1, F32x8& b2) {
  const F32x8 e0 = edgeValue(t, 0, d), e1 = edgeValue(t, 1, d), e2 = edgeValue(t, 2, d);
  const F32x8 inv_s = splat(1.0f) / ((e0 + e1) + e2);
  b1 = e1 * inv_s;
  b2 = e2 * inv_s;
  b0 = splat(1.0f) - b1 - b2;
}

float3 rayAt(const RayLayer& layer, size_t at) {
  return {layer.x[at], layer.y[at], layer.z[at]};
}

// What shading a tile reads of the frame's rays.
struct RayShading {
  const LightRig& lights;
  const std::vector<TriangleChunk>& chunks;
  const RayTable& rays;
  int width, height;

  // Shades the lanes of `mask` from triangle `key` at the rays d (pixels x .. x + 7 of row y);
  // lanes the eight-lane texture filter does not take find their level of detail from the centre
  // rays of the next pixels right and down (or left and up at the image's edge).
  TESSERA_LANES_INLINE void shade(uint32_t key, const Ray8& d, int x, int y, I32x8 mask,
                                  bool want_normals, Vec3x8& color, Vec3x8& normal) const {
    const TriangleChunk& chunk = chunks[keyChunk(key)];
    const ShadeTriangle& t = chunk.shade[keyLocal(key)];
    const ShadeExtras& e = chunk.extras[keyLocal(key)];
    const RayTriangle& r = chunk.ray[keyLocal(key)];
    F32x8 b0, b1, b2;
    rayBarycentrics8(r, d, b0, b1, b2);
    // The barycentrics at the centre rays of the next pixels right and down of pixel x + l (or
    // left and up at the image's edge: a one-pixel-wide image has no neighbour, the pixel itself).
    auto neighbours = [&](int l, Barycentrics& br, Barycentrics& bd) {
      const int px = x + l;
      const int right = px + 1 < width ? px + 1 : std::max(px - 1, 0);
      const int down = y + 1 < height ? y + 1 : std::max(y - 1, 0);
      const size_t w = static_cast<size_t>(width);
      rayBarycentrics(r, rayAt(rays.centre(), static_cast<size_t>(y) * w + right), br.b0, br.b1,
                      br.b2);
      rayBarycentrics(r, rayAt(rays.centre(), static_cast<size_t>(down) * w + px), bd.b0, bd.b1,
                      bd.b2);
    };
    shadeLanesAt(
        t, e, lights, want_normals, b0, b1, b2, mask, color, normal,
        [&](int l, const Barycentrics& b) {
          Barycentrics br, bd;
          neighbours(l, br, bd);
          return sampleAlbedo(t, e, b, br, bd);
        },
        [](Vec3x8&, Vec3x8&) { return false; },
        [&](int l, const Barycentrics& b, const Texture& texture, const Sampler& sampler) {
          Barycentrics br, bd;
          neighbours(l, br, bd);
          return sampleTexture(texture, sampler, e, b, br, bd);
        });
  }
};

// Each chunk's first shading and ray records, for laneRecords.
struct RayRecords {
  const ShadeTriangle* shade[kMaxChunks];
  const RayTriangle* ray[kMaxChunks];
};

// Whether a pixel of triangle t is its interpolated vertex colours alone (untextured, lit per
// vertex or unlit): what shadeRayMixed takes.
TESSERA_LANES_INLINE bool rayPlain(const ShadeTriangle& t) {
  return !t.has_uv && t.shading != Shading::kPhong && t.shading != Shading::kPbr;
}

// Eight rays d (the lanes of `covered`, whose keys name several triangles, `first` a covered
// lane's) of triangles that are all rayPlain, each lane shaded from its own triangle's records:
// the edge normals and colours of eight records loaded at once and transposed into lanes, then
// RayShading::shade's operations per lane (rayBarycentrics8, interpolateColor, the tone curve), so
// the same bits in one evaluation instead of one per triangle. False, with `color` untouched,
// where a lane's triangle is not rayPlain.
TESSERA_LANES_INLINE bool shadeRayMixed(const RayRecords& records, const LightRig& lights,
                                        I32x8 keys, I32x8 covered, uint32_t first, const Ray8& d,
                                        Vec3x8& color) {
  const LaneKeys k = laneKeys(keys, covered, first);
  const ShadeTriangle* lanes[8];
  laneRecords(k, records.shade, lanes);
  for (int l = 0; l < 8; ++l)
    if (!rayPlain(*lanes[l])) return false;
  const RayTriangle* rays[8];
  laneRecords(k, records.ray, rays);
  const float* at[8];
  for (int l = 0; l < 8; ++l) at[l] = &rays[l]->n[0][0];
  F32x8 n[9], f[kPlainFields];
  corners9(at, n);
  loadPlainFields(lanes, f);
  // edgeValue's operations with each lane's own normals.
  const F32x8 e0 = (d.x * n[0] + d.y * n[1]) + d.z * n[2];
  const F32x8 e1 = (d.x * n[3] + d.y * n[4]) + d.z * n[5];
  const F32x8 e2 = (d.x * n[6] + d.y * n[7]) + d.z * n[8];
  const F32x8 inv_s = splat(1.0f) / ((e0 + e1) + e2);
  Vec3x8 c = plainColor(f, e1 * inv_s, e2 * inv_s);
  if (lights.tone.active()) toneMap8(lights.tone, c.x, c.y, c.z);
  const F32x8 zero = splat(0.0f);
  color = {select(covered, c.x, zero), select(covered, c.y, zero), select(covered, c.z, zero)};
  return true;
}

// The sample-s fragments of eight pixels (the lanes of `first`), each triangle shaded at the centre
// ray of the lanes whose centre ray passes through it and at sample s's ray elsewhere.
Vec3x8 shadeRayFragments(const RayShading& rs, int s, I32x8 keys, I32x8 first, int x, int y) {
  const size_t at = static_cast<size_t>(y) * static_cast<size_t>(rs.width) + static_cast<size_t>(x);
  const Ray8 centre = loadRays(rs.rays.centre(), at), sample = loadRays(rs.rays.sample(s), at);
  const F32x8 zero = splat(0.0f);
  Vec3x8 color{zero, zero, zero}, normal{zero, zero, zero};
  I32x8 todo = first;
  while (any(todo)) {
    const uint32_t key = static_cast<uint32_t>(lane(keys, firstLane(todo)));
    const I32x8 mine = todo & equal(keys, splat(static_cast<int32_t>(key)));
    const RayTriangle& r = rs.chunks[keyChunk(key)].ray[keyLocal(key)];
    const I32x8 c = mine & raysCover(r, centre);
    const Ray8 d{select(c, centre.x, sample.x), select(c, centre.y, sample.y),
                 select(c, centre.z, sample.z)};
    rs.shade(key, d, x, y, mine, false, color, normal);
    todo = todo & ~mine;
  }
  return color;
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
  RayRecords records;
  for (size_t c = 0; c < chunk_count; ++c) {
    records.shade[c] = chunks[c].shade.data();
    records.ray[c] = chunks[c].ray.data();
  }
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
      // Several triangles lit per vertex: one evaluation from each lane's records.
      const uint32_t first = static_cast<uint32_t>(lane(keys, firstLane(todo)));
      if (!want_normals && rayPlain(records.shade[keyChunk(first)][keyLocal(first)]) &&
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
    if (msaa)
      resolveMixedRowWith(
          *msaa, tile, ty,
          linear, [&](int s, I32x8 keys, I32x8 first, int x, int y) __attribute__((always_inline)) {
            return shadeRayFragments(rs, s, keys, first, x, y);
          });
    encodeShadedRow(tile, ty, linear, nullptr, background, out);
  }
}

}  // namespace
}  // namespace tessera::render
