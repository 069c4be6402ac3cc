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

// Queued fragments in lanes: their triangles' records and the ray each is shaded at.
struct QueuedRays {
  I32x8 valid, keys, tx;
  F32x8 weight;
  LaneKeys lane_keys;
  const RayTriangle* triangles[8];
  F32x8 n[9];  // the triangles' edge normals, corners9's layout
  Ray8 d;
};

// The triangles' edge values at rays d, as edgeValue with each lane's own normals.
TESSERA_LANES_INLINE void edgeValues(const F32x8 n[9], const Ray8& d, F32x8 e[3]) {
  for (int k = 0; k < 3; ++k) e[k] = (d.x * n[3 * k] + d.y * n[3 * k + 1]) + d.z * n[3 * k + 2];
}

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
  laneRecords(q.lane_keys, records.ray, q.triangles);
  const float* at[8];
  alignas(32) int32_t owner[3][8];
  for (int l = 0; l < 8; ++l) {
    at[l] = &q.triangles[l]->n[0][0];
    for (int k = 0; k < 3; ++k) owner[k][l] = -((q.triangles[l]->owner >> k) & 1);
  }
  corners9(at, q.n);
  // raysCover's tests at the centre rays, each lane against its own triangle.
  const Ray8 c{load<F32x8>(ray[0]), load<F32x8>(ray[1]), load<F32x8>(ray[2])};
  const F32x8 zero = splat(0.0f);
  F32x8 e[3];
  edgeValues(q.n, c, e);
  I32x8 at_centre = q.valid & lessThan(zero, (e[0] + e[1]) + e[2]);
  for (int k = 0; k < 3; ++k)
    at_centre = at_centre & (lessThan(zero, e[k]) | (equal(e[k], zero) & load<I32x8>(owner[k])));
  q.d = {select(at_centre, c.x, load<F32x8>(ray[3])), select(at_centre, c.y, load<F32x8>(ray[4])),
         select(at_centre, c.z, load<F32x8>(ray[5]))};
}

// The queued fragments' linear colours: in one evaluation where all are plain (shadeRayMixed's
// operations) or textured alike without per-pixel lighting and without a level of detail
// (filterTexturedGroup from each lane's own records), else by RayShading::shade for each run of
// lanes of one triangle in consecutive columns.
TESSERA_LANES_INLINE Vec3x8 shadeQueuedRays(const RayShading& rs, const RayRecords& records,
                                            const QueuedRays& q, int x0, int y) {
  const ShadeTriangle* lanes[8];
  laneRecords(q.lane_keys, records.shade, lanes);
  bool plain = true, textured = true;
  const Material* material = lanes[0]->material;
  for (int l = 0; l < 8; ++l) {
    plain = plain && rayPlain(*lanes[l]);
    textured = textured && texturedPlain(*lanes[l]) && lanes[l]->material == material;
  }
  if (plain || textured) {
    F32x8 e[3], f[kPlainFields];
    edgeValues(q.n, q.d, e);
    const F32x8 inv_s = splat(1.0f) / ((e[0] + e[1]) + e[2]);
    const F32x8 b1 = e[1] * inv_s, b2 = e[2] * inv_s;
    loadPlainFields(lanes, f);
    if (plain) {
      Vec3x8 c = plainColor(f, b1, b2);
      if (rs.lights.tone.active()) toneMap8(rs.lights.tone, c.x, c.y, c.z);
      return c;
    }
    const Texture& texture = *material->albedo;
    if (texture8Applies(texture, material->sampler) && !needsLod(texture, material->sampler)) {
      const ShadeExtras* extras[8];
      laneRecords(q.lane_keys, records.extras, extras);
      F32x8 corner[8];
      uvCorners8(extras, material->sampler.texcoord, corner);
      const F32x8 b0 = splat(1.0f) - b1 - b2;
      TexturedGroup group;
      group.uv = {corner[0] * b0 + corner[2] * b1 + corner[4] * b2,
                  corner[1] * b0 + corner[3] * b1 + corner[5] * b2};
      group.color = plainColor(f, b1, b2);
      group.covered = q.valid;
      group.material = material;
      Vec3x8 color;
      if (filterTexturedGroup(group, rs.lights, color)) return color;
    }
  }
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
  resolveMixedRowBy(
      m, tile, ty, queue, linear, [&](int first, int count) __attribute__((always_inline)) {
        QueuedRays q;
        loadQueuedRays(rs, records, queue, first, count, tile.x0, y, q);
        addFragments(q.tx, q.weight, count, shadeQueuedRays(rs, records, q, tile.x0, y), linear);
      });
}

}  // namespace
}  // namespace tessera::render
