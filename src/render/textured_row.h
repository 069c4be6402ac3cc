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

// The textured groups of row ty that shadeTile prepared, filtered one after another (on AVX-512 two
// at a time where they can be) into the row's linear colours; a group whose coordinates are beyond
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
  for (int g = 0; g < count; ++g) {
    const TexturedGroup& group = groups[g];
    albedo.use(group.material);
    const TextureReads& reads = albedo.reads;
    Vec3x8 color{zero, zero, zero}, normal{zero, zero, zero};
#if defined(TESSERA_LANES16)
    // Two groups side by side in sixteen lanes where they can be (texture_lanes16.h).
    if (albedo.pairs && g + 1 < count && groups[g + 1].material == albedo.material) {
      Vec3x8 next;
      if (filterTexturedPair(group, groups[g + 1], reads, lights, color, next)) {
        store_group(group, color);
        store_group(groups[g + 1], next);
        ++g;
        continue;
      }
    }
#endif
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
