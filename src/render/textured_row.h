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
// group g's quads at 8 g of each array (fixedQuads8's `at`, weights and fractions; a pair's
// sixteen lanes, pairQuads16's, at its first group's).
struct RowQuads {
  enum Kind : uint8_t { kNone, kOne, kPair };  // kPair: with the next group
  alignas(64) int32_t at[kTileSize];
  alignas(64) int32_t w1[kTileSize];
  alignas(64) float ty[kTileSize];
  Kind kind[kTileSize / 8];
};

// The row's groups whose filter reads one level's adjacent quads from its fixed-point copy (their
// material's albedo read without a transform or a level of detail, every covered lane in reach
// and none at a wrap or a clamp), planned into `quads`; on AVX-512 two such groups side by side
// where the wraps allow (pairReads). Their texels are then read one group after another with
// nothing between but the blends, so that the core has the loads of several groups in flight:
// with each group's coordinates, wraps and indices between them it had one group's (the textured
// sphere at 1920x1080, AVX2 kernels: 0.84-0.93 of the frame). The first group's material decides;
// groups of another are not planned.
TESSERA_LANES_INLINE void planRowQuads(const TexturedGroup groups[], int count, AlbedoReads& albedo,
                                       RowQuads& quads) {
  for (int g = 0; g < count; ++g) quads.kind[g] = RowQuads::kNone;
  if (count == 0) return;
  albedo.use(groups[0].material);
  const TextureReads& reads = albedo.reads;
  if (reads.moved || reads.lod || !reads.base.linear) return;
  for (int g = 0; g < count; ++g) {
    const TexturedGroup& group = groups[g];
    if (group.material != albedo.material) continue;
    const int at = 8 * g;
#if defined(TESSERA_LANES16)
    if (albedo.pairs && g + 1 < count && groups[g + 1].material == albedo.material &&
        pairQuads16(group, groups[g + 1], reads, quads.at + at, quads.w1 + at, quads.ty + at)) {
      quads.kind[g++] = RowQuads::kPair;
      continue;
    }
#endif
    if (!inReach8(group.covered, group.uv)) continue;
    const BilinearQuads q = bilinearQuads8(reads.base, *reads.sampler, group.covered, group.uv);
    if (!q.adjacent()) continue;
    store(quads.at + at, q.ya * splat(int32_t{reads.base.width}) + q.xa);
    store(quads.w1 + at, q.w1);
    store(quads.ty + at, q.ty);
    quads.kind[g] = RowQuads::kOne;
  }
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
    const int at = 8 * g;
#if defined(TESSERA_LANES16)
    if (quads.kind[g] == RowQuads::kPair) {
      Vec3x8 color, next;
      filterPairQuads(group, groups[g + 1], reads, quads.at + at, quads.w1 + at, quads.ty + at,
                      lights, color, next);
      store_group(group, color);
      store_group(groups[++g], next);
      continue;
    }
#endif
    if (quads.kind[g] == RowQuads::kOne) {
      F32x8 texel[4];
      fixedQuads8(reads.base.linear, quads.at + at, reads.base.width, load<I32x8>(quads.w1 + at),
                  load<F32x8>(quads.ty + at), 3, texel);
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
