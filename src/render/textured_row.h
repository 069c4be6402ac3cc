// The textured groups of a row filtered together, for the shading kernel (shade_kernel.h), and
// the triangle-by-triangle shading of eight pixels that takes any group the faster paths cannot.
// Compiled per instruction set; every variant gives the same bits.
#pragma once

#include "render/mixed_lanes.h"
#include "render/shade_lanes.h"
#include "render/texture_lanes16.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

// Eight pixels shaded triangle by triangle: each triangle of the lanes of `covered` evaluated once
// for the eight (shadeLanes) and the results merged in registers.
TESSERA_LANES_INLINE void shadeApart(I32x8 keys, I32x8 covered,
                                     const ShadeTriangle* const records[],
                                     const ShadeExtras* const extras[], const LightRig& lights,
                                     bool want_normals, F32x8 px, float py, Vec3x8& color,
                                     Vec3x8& normal) {
  I32x8 todo = covered;
  do {
    const uint32_t key = static_cast<uint32_t>(lane(keys, firstLane(todo)));
    const I32x8 mask = equal(keys, splat(static_cast<int32_t>(key)));
    const ShadeTriangle& t = records[keyChunk(key)][keyLocal(key)];
    const ShadeExtras& e = extras[keyChunk(key)][keyLocal(key)];
    shadeLanes(t, e, lights, want_normals, px, py, mask, color, normal);
    todo = todo & ~mask;
  } while (any(todo));
}

// The albedo's reads of the last textured group's material (textureReads), looked up again where
// the material changes; kept across a tile's rows (looked up for each row, the copy of the
// struct waited on the stores that made it, 4% of the textured sphere's shading).
struct AlbedoReads {
  const Material* material = nullptr;
  TextureReads reads{};
  bool pairs = false;  // pairReads
  TESSERA_LANES_INLINE void use(const Material* m) {
    if (m == material) return;
    material = m;
    reads = textureReads(*m->albedo, m->sampler);
#if defined(TESSERA_LANES16)
    pairs = pairReads(reads);
#endif
  }
};

// Where a row's textured groups read their texels, planned before any is read (planRowQuads):
// group g's quads at 8 g of each slot's arrays (fixedQuads8's `at`, weights and fractions; a
// pair's sixteen lanes, pairQuads16's, at its first group's). A group read with a level of detail
// (kLevels) takes a slot a level, at most two, and `levels` says which lanes take each.
struct RowQuads {
  enum Kind : uint8_t { kNone, kOne, kPair, kLevels };  // kPair: with the next group
  alignas(64) int32_t at[2][kTileSize];
  alignas(64) int32_t w1[2][kTileSize];
  alignas(64) float ty[2][kTileSize];
  struct Levels {
    LodLevels lod;
    const int16_t* linear[2];  // each slot's level's copy, or null for a slot no lane reads
    int width[2];
    I32x8 as_lower[2], as_upper[2];
  };
  Levels levels[kTileSize / 8];
  Kind kind[kTileSize / 8];
};

// Slot `slot`'s quads of group g (fixedQuads8's), from `quads` of a level `width` texels wide.
TESSERA_LANES_INLINE void storeQuads(RowQuads& row, int slot, int g, const BilinearQuads& quads,
                                     int width) {
  const int at = 8 * g;
  store(row.at[slot] + at, quads.ya * splat(int32_t{width}) + quads.xa);
  store(row.w1[slot] + at, quads.w1);
  store(row.ty[slot] + at, quads.ty);
}

// planRowQuads of a group read with a level of detail (sampleTexture8's levels): true, with its
// slots filled, where its lanes read at most two levels, each from its copy and in adjacent quads.
TESSERA_LANES_INLINE bool planLevels(const TexturedGroup& group, const TextureReads& reads, int g,
                                     RowQuads& row) {
  RowQuads::Levels& plan = row.levels[g];
  plan.lod = lodLevels8(*reads.texture, group.covered, group.uv, group.right, group.down);
  if (plan.lod.last - plan.lod.first > 1) return false;
  for (int slot = 0; slot < 2; ++slot) {
    const int level = plan.lod.first + slot;
    plan.linear[slot] = nullptr;
    if (level > plan.lod.last) continue;
    plan.as_lower[slot] = plan.lod.asLower(group.covered, level);
    plan.as_upper[slot] = plan.lod.asUpper(level);
    const I32x8 mask = plan.as_lower[slot] | plan.as_upper[slot];
    if (!any(mask)) continue;
    const LevelLanes lanes = levelLanes(*reads.texture, level);
    if (!lanes.linear) return false;
    const BilinearQuads quads = bilinearQuads8(lanes, *reads.sampler, mask, group.uv);
    if (!quads.adjacent()) return false;
    storeQuads(row, slot, g, quads, lanes.width);
    plan.linear[slot] = lanes.linear;
    plan.width[slot] = lanes.width;
  }
  return true;
}

// The row's groups whose filter reads adjacent quads from its levels' fixed-point copies (their
// material's albedo read without a transform, every covered lane in reach and none at a wrap or a
// clamp), planned into `quads`; on AVX-512 two such groups side by side where the wraps allow
// (pairReads). Their texels are then read one group after another with nothing between but the
// blends, so that the core has the loads of several groups in flight: with each group's
// coordinates, wraps and indices between them it had one group's (the textured sphere at
// 1920x1080, AVX2 kernels: 0.84-0.93 of the frame). The first group's material decides; groups
// of another are not planned.
TESSERA_LANES_INLINE void planRowQuads(const TexturedGroup groups[], int count, AlbedoReads& albedo,
                                       RowQuads& quads) {
  for (int g = 0; g < count; ++g) quads.kind[g] = RowQuads::kNone;
  if (count == 0) return;
  albedo.use(groups[0].material);
  const TextureReads& reads = albedo.reads;
  if (reads.moved || !reads.base.linear) return;
  for (int g = 0; g < count; ++g) {
    const TexturedGroup& group = groups[g];
    if (group.material != albedo.material || !inReach8(group.covered, group.uv)) continue;
    if (reads.lod) {
      if (planLevels(group, reads, g, quads)) quads.kind[g] = RowQuads::kLevels;
      continue;
    }
#if defined(TESSERA_LANES16)
    const int at = 8 * g;
    if (albedo.pairs && g + 1 < count && groups[g + 1].material == albedo.material &&
        pairQuads16(group, groups[g + 1], reads, quads.at[0] + at, quads.w1[0] + at,
                    quads.ty[0] + at)) {
      quads.kind[g++] = RowQuads::kPair;
      continue;
    }
#endif
    const BilinearQuads q = bilinearQuads8(reads.base, *reads.sampler, group.covered, group.uv);
    if (!q.adjacent()) continue;
    storeQuads(quads, 0, g, q, reads.base.width);
    quads.kind[g] = RowQuads::kOne;
  }
}

// The albedo of planned group g (planRowQuads: kOne or kLevels) from its quads.
TESSERA_LANES_INLINE void filterPlannedQuads(const RowQuads& quads, int g,
                                             const TextureReads& reads, F32x8 texel[4]) {
  const int at = 8 * g;
  if (quads.kind[g] == RowQuads::kOne) {
    fixedQuads8(reads.base.linear, quads.at[0] + at, reads.base.width,
                load<I32x8>(quads.w1[0] + at), load<F32x8>(quads.ty[0] + at), 3, texel);
    return;
  }
  const RowQuads::Levels& plan = quads.levels[g];
  F32x8 a[3], b[3], level_out[4];
  for (int k = 0; k < 3; ++k) a[k] = b[k] = splat(0.0f);
  for (int slot = 0; slot < 2; ++slot) {
    if (!plan.linear[slot]) continue;
    fixedQuads8(plan.linear[slot], quads.at[slot] + at, plan.width[slot],
                load<I32x8>(quads.w1[slot] + at), load<F32x8>(quads.ty[slot] + at), 3, level_out);
    for (int k = 0; k < 3; ++k) {
      a[k] = select(plan.as_lower[slot], level_out[k], a[k]);
      b[k] = select(plan.as_upper[slot], level_out[k], b[k]);
    }
  }
  for (int k = 0; k < 3; ++k) texel[k] = plan.lod.blended(a[k], b[k]);
}

// The textured groups of row ty that shadeTile prepared, filtered one after another (the quads
// planned first: planRowQuads) into the row's linear colours; a group whose coordinates are beyond
// the eight-lane filter's reach is shaded triangle by triangle.
TESSERA_LANES_INLINE void filterTexturedRow(const TileVisibility& tile, int ty,
                                            const TexturedGroup groups[], int count,
                                            const ShadeTriangle* const records[],
                                            const ShadeExtras* const extras[],
                                            const LightRig& lights, AlbedoReads& albedo,
                                            float linear[3][kTileSize]) {
  const float py = static_cast<float>(tile.y0 + ty) + 0.5f;
  const F32x8 zero = splat(0.0f);
  const auto store_group = [&](const TexturedGroup& group, const Vec3x8& color) {
    store(linear[0] + group.tx, color.x);
    store(linear[1] + group.tx, color.y);
    store(linear[2] + group.tx, color.z);
  };
  RowQuads quads;
  planRowQuads(groups, count, albedo, quads);
  for (int g = 0; g < count; ++g) {
    const TexturedGroup& group = groups[g];
    albedo.use(group.material);
    const TextureReads& reads = albedo.reads;
#if defined(TESSERA_LANES16)
    if (quads.kind[g] == RowQuads::kPair) {
      const int at = 8 * g;
      Vec3x8 color, next;
      filterPairQuads(group, groups[g + 1], reads, quads.at[0] + at, quads.w1[0] + at,
                      quads.ty[0] + at, lights, color, next);
      store_group(group, color);
      store_group(groups[++g], next);
      continue;
    }
#endif
    if (quads.kind[g] != RowQuads::kNone) {
      F32x8 texel[4];
      filterPlannedQuads(quads, g, reads, texel);
      store_group(group, texturedColour(group, texel, lights));
      continue;
    }
    Vec3x8 color{zero, zero, zero}, normal{zero, zero, zero};
    if (!filterTexturedGroup(group, reads, lights, color)) {
      const I32x8 keys = load<I32x8>(tile.key + ty * kTileSize + group.tx);
      const F32x8 px = toFloat(splat(tile.x0 + group.tx) + iota()) + splat(0.5f);
      shadeApart(keys, group.covered, records, extras, lights, false, px, py, color, normal);
    }
    store_group(group, color);
  }
}

}  // namespace
}  // namespace tessera::render
