// The multisampled resolve of the nonlinear projections' rows (ray_kernel.h), through the
// perspective path's queue of fragments (fragment_queue.h): each distinct triangle of a mixed
// pixel is one fragment, shaded at the pixel's centre ray where that ray passes through the
// triangle and otherwise at the ray of the first sample it holds, weighted by the samples it holds,
// and fragments are shaded eight at a time across the row's groups (where shaded a sample and a
// group at a time, a triangle's evaluation held few lanes). Each lane's colour takes the same
// operations as RayShading::shade gives it, and each fragment is added to its pixel's sum in
// sample order, so the same bits. Compiled per instruction set; every variant gives the same bits.
#pragma once

#include <cstddef>
#include <cstdint>

#include "render/fragment_queue.h"
#include "render/ray_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

// Queued fragments in lanes: their triangles' keys and edge normals and the ray each is shaded at.
struct QueuedRays {
  I32x8 valid, keys, tx;
  F32x8 weight;
  LaneKeys lane_keys;
  F32x8 n[9];  // the triangles' edge normals, corners9's layout
  Ray8 d;
};

// Fragments first .. first + count - 1 of the queue (the other lanes borrow the first's), of row y
// of the tile at column x0: each at its pixel's centre ray where raysCover's tests pass it through
// its triangle, else at its sample's ray.
TESSERA_LANES_INLINE void loadQueuedRays(const RayShading& rs, const RayRecords& records,
                                         const FragmentQueue& queue, int first, int count, int x0,
                                         int y, QueuedRays& q) {
  q.valid = lessThan(iota(), splat(count));
  q.keys = load<I32x8>(queue.key + first);
  alignas(32) int32_t where[8];
  store(where, load<I32x8>(queue.where + first));
  for (int l = count; l < 8; ++l) where[l] = where[0];
  const I32x8 packed = load<I32x8>(where);
  q.tx = packed & splat(int32_t{63});
  q.weight = toFloat(shiftRight(packed, 9));
  // Each lane's centre and sample rays.
  alignas(32) float ray[6][8];
  const RayLayer& centre = rs.rays.centre();
  const size_t row =
      static_cast<size_t>(y) * static_cast<size_t>(rs.width) + static_cast<size_t>(x0);
  for (int l = 0; l < 8; ++l) {
    const size_t at = row + static_cast<size_t>(where[l] & 63);
    const RayLayer& sample = rs.rays.sample((where[l] >> 6) & 7);
    ray[0][l] = centre.x[at], ray[1][l] = centre.y[at], ray[2][l] = centre.z[at];
    ray[3][l] = sample.x[at], ray[4][l] = sample.y[at], ray[5][l] = sample.z[at];
  }
  q.lane_keys = laneKeys(q.keys, q.valid);
  const RayTriangle* triangles[8];
  laneRecords(q.lane_keys, records.ray, triangles);
  rayNormals(triangles, q.n);
  alignas(32) int32_t owner_bits[3][8];
  for (int l = 0; l < 8; ++l)
    for (int k = 0; k < 3; ++k) owner_bits[k][l] = -((triangles[l]->owner >> k) & 1);
  const I32x8 owner[3] = {load<I32x8>(owner_bits[0]), load<I32x8>(owner_bits[1]),
                          load<I32x8>(owner_bits[2])};
  const Ray8 c{load<F32x8>(ray[0]), load<F32x8>(ray[1]), load<F32x8>(ray[2])};
  const I32x8 at_centre = q.valid & raysCover(q.n, owner, c);
  q.d = {select(at_centre, c.x, load<F32x8>(ray[3])), select(at_centre, c.y, load<F32x8>(ray[4])),
         select(at_centre, c.z, load<F32x8>(ray[5]))};
}

// The queued fragments' linear colours: shadeRaysOnce where it applies, else by
// RayShading::shade for each run of lanes of one triangle in consecutive columns.
TESSERA_LANES_INLINE Vec3x8 shadeQueuedRays(const RayShading& rs, const RayRecords& records,
                                            const QueuedRays& q, int x0, int y) {
  Vec3x8 once;
  if (shadeRaysOnce(records, q.lane_keys, q.n, q.d, q.valid, rs.lights, once)) return once;
  // RayShading::shade takes lane l at column x + l: a run of one triangle's lanes whose columns
  // are x + l shares one call.
  const F32x8 zero = splat(0.0f);
  Vec3x8 color{zero, zero, zero}, normal{zero, zero, zero};
  const I32x8 offset = q.tx - iota();
  I32x8 todo = q.valid;
  while (any(todo)) {
    const int l = firstLane(todo);
    const int32_t key = lane(q.keys, l), at = lane(offset, l);
    const I32x8 mine = todo & equal(q.keys, splat(key)) & equal(offset, splat(at));
    rs.shade(static_cast<uint32_t>(key), q.d, x0 + at, y, mine, false, color, normal);
    todo = todo & ~mine;
  }
  return color;
}

// Row ty's mixed pixels: their colours replaced by their resolve (resolveMixedRowBy).
TESSERA_LANES_INLINE void resolveRayMixedRow(const MsaaShading& m, const TileVisibility& tile,
                                             int ty, const RayShading& rs,
                                             const RayRecords& records, FragmentQueue& queue,
                                             float linear[3][kTileSize]) {
  const int y = tile.y0 + ty;
  resolveMixedRowBy(m, tile, ty, queue, linear, [&](int first, int count) {
    QueuedRays q;
    loadQueuedRays(rs, records, queue, first, count, tile.x0, y, q);
    return ShadedFragments{q.tx, q.weight, shadeQueuedRays(rs, records, q, tile.x0, y)};
  });
}

}  // namespace
}  // namespace tessera::render
