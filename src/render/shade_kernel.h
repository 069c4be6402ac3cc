// The shading kernel: a tile's visible pixels, eight at a time, shaded once at their centres
// (shade_lanes.h) and encoded to sRGB a row at a time; with MSAA the mixed pixels of each row are
// resolved before the encode, their fragments eight at a time (fragment_queue.h). Compiled per
// instruction set (kernels_<isa>.cpp); every variant gives the same bits.
#pragma once

#include <optional>
#include <utility>

#include "render/fragment_queue.h"
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

// The textured groups of row ty that shadeTile prepared, filtered one after another (on AVX-512 two
// at a time where they can be) into the row's linear colours; a group whose coordinates are beyond
// the eight-lane filter's reach is shaded triangle by triangle.
TESSERA_LANES_INLINE void filterTexturedRow(const TileVisibility& tile, int ty,
                                            const TexturedGroup groups[], int count,
                                            const ShadeTriangle* const records[],
                                            const ShadeExtras* const extras[],
                                            const LightRig& lights, float linear[3][kTileSize]) {
  const float py = static_cast<float>(tile.y0 + ty) + 0.5f;
  const F32x8 zero = splat(0.0f);
  const auto store_group = [&](const TexturedGroup& group, const Vec3x8& color) {
    store(linear[0] + group.tx, color.x);
    store(linear[1] + group.tx, color.y);
    store(linear[2] + group.tx, color.z);
  };
  for (int g = 0; g < count; ++g) {
    const TexturedGroup& group = groups[g];
    Vec3x8 color{zero, zero, zero}, normal{zero, zero, zero};
#if defined(TESSERA_LANES16)
    // Two groups side by side in sixteen lanes where they can be (texture_lanes16.h).
    if (g + 1 < count && pairApplies(group, groups[g + 1])) {
      Vec3x8 next;
      if (filterTexturedPair(group, groups[g + 1], lights, color, next)) {
        store_group(group, color);
        store_group(groups[g + 1], next);
        ++g;
        continue;
      }
    }
#endif
    if (!filterTexturedGroup(group, lights, color)) {
      const I32x8 keys = load<I32x8>(tile.key + ty * kTileSize + group.tx);
      const F32x8 px = toFloat(splat(tile.x0 + group.tx) + iota()) + splat(0.5f);
      shadeApart(keys, group.covered, records, extras, lights, false, px, py, color, normal);
    }
    store_group(group, color);
  }
}

// The solidRgba of the last two triangles whose groups of one triangle a tile's plain rows met,
// kept across the rows: a row across a quad split on its diagonal meets both of its triangles in
// turn, and each change of triangle took an encode (a long chain), which on the cube at
// 1920x1080 was most of shadePlainRow's time while a cache of the last triangle alone was kept.
struct SolidColours {
  uint32_t key[2] = {kEmptyKey, kEmptyKey};  // [0]: the last met
  uint32_t rgba[2] = {kNoSolid, kNoSolid};
  // Triangle t's solidRgba; `k` is its key (never kEmptyKey).
  TESSERA_LANES_INLINE uint32_t of(uint32_t k, const ShadeTriangle& t) {
    if (k == key[0]) return rgba[0];
    if (k != key[1]) {
      key[1] = k;
      rgba[1] = solidRgba(t);
    }
    std::swap(key[0], key[1]);
    std::swap(rgba[0], rgba[1]);
    return rgba[0];
  }
};

// Row ty of a plain tile (every triangle untextured, not Phong, no normal AOV) into the row's
// linear colours: eight pixels of one triangle take shadePlainLanes (of one whose corners share a
// colour, that colour, and its sRGB in `solid` for the encode), of several shadeMixed, and
// with MSAA (`kSampled`) a group holding a mixed pixel is resolved with the row's other such
// groups (shadePlainSampled, then `queue`'s fragments eight at a time). A function of its own,
// not inlined into shadeTile: in the one function of every path the compiler kept this loop's
// colours and masks on the stack, and the plain frames' shading took 10% longer.
template <bool kSampled>
__attribute__((noinline)) void shadePlainRow(const TileVisibility& tile, int ty,
                                             const ShadeTriangle* const records[],
                                             const MsaaShading* msaa, FragmentQueue* queue,
                                             float linear[3][kTileSize],
                                             uint32_t solid[kTileSize / 8], SolidColours& solids) {
  const I32x8 empty = splat(static_cast<int32_t>(kEmptyKey));
  const float py = static_cast<float>(tile.y0 + ty) + 0.5f;
  bool row_mixed = false;
  const auto shade_queued = [&](int first, int count) __attribute__((always_inline)) {
    shadeQueuedPlain(records, *queue, first, count, tile.x0, tile.y0 + ty, linear);
  };
  for (int tx = 0; tx < tile.width; tx += 8) {
    const int i = ty * kTileSize + tx;
    const I32x8 keys = load<I32x8>(tile.key + i);
    const I32x8 covered = ~equal(keys, empty);
    solid[tx / 8] = kSolidEmpty;
    if (!any(covered)) continue;
    solid[tx / 8] = kNoSolid;
    Vec3x8 color;
    const I32x8 mixed = kSampled ? load<I32x8>(msaa->tiles->mixed + i) : splat(int32_t{0});
    const bool sampled = kSampled && any(mixed);
    if (sampled) {
      color = shadePlainSampled(*msaa, records, i, tx, tile.x0 + tx, tile.y0 + ty, mixed, *queue);
    } else {
      const F32x8 px = toFloat(splat(tile.x0 + tx) + iota()) + splat(0.5f);
      const uint32_t first = static_cast<uint32_t>(lane(keys, firstLane(covered)));
      if (any(covered & ~equal(keys, splat(static_cast<int32_t>(first))))) {
        const ShadeTriangle* lanes[8];
        laneRecords(laneKeys(keys, covered, first), records, lanes);
        color = shadeMixed(lanes, px, splat(py));
      } else {
        // One triangle's pixels (the lanes it does not cover are encoded as the background).
        const ShadeTriangle& t = records[keyChunk(first)][keyLocal(first)];
        const uint32_t rgba = solids.of(first, t);
        if (rgba != kNoSolid) {
          // interpolateColor's value at any pixel: no barycentrics, and the encode is done.
          color = {splat(t.color[0].x), splat(t.color[0].y), splat(t.color[0].z)};
          solid[tx / 8] = rgba;
        } else {
          color = shadePlainLanes(t, px, py);
        }
      }
    }
    store(linear[0] + tx, color.x);
    store(linear[1] + tx, color.y);
    store(linear[2] + tx, color.z);
    if (sampled) {
      row_mixed = true;
      shadeQueue(*queue, false, shade_queued);
    }
  }
  if (kSampled && row_mixed) {
    shadeQueue(*queue, true, shade_queued);
    finishMixedRow(*msaa, tile, ty, linear);
  }
}

// Row ty of a tile that is not plain (see shadeTile) into the row's linear colours and, when
// asked, the tile's normals. A function of its own, as shadePlainRow is: apart from the encode,
// the compiler keeps more of the row's values in registers.
template <bool kSampled>
__attribute__((noinline)) void shadeRow(const TileVisibility& tile, int ty,
                                        const ShadeTriangle* const records[],
                                        const ShadeExtras* const extras[], const LightRig& lights,
                                        bool want_normals, const MsaaShading* msaa,
                                        FragmentQueue* queue, float linear[3][kTileSize],
                                        ShadedTile& out) {
  const I32x8 empty = splat(static_cast<int32_t>(kEmptyKey));
  const F32x8 zero = splat(0.0f);
  const float py = static_cast<float>(tile.y0 + ty) + 0.5f;
  TexturedGroup textured_groups[kTileSize / 8];
  int textured_count = 0;
  for (int tx = 0; tx < tile.width; tx += 8) {
    const int i = ty * kTileSize + tx;
    const I32x8 keys = load<I32x8>(tile.key + i);
    const I32x8 covered = ~equal(keys, empty);
    if (!any(covered)) continue;
    const F32x8 px = toFloat(splat(tile.x0 + tx) + iota()) + splat(0.5f);
    Vec3x8 color{zero, zero, zero}, normal{zero, zero, zero};
    const uint32_t first = static_cast<uint32_t>(lane(keys, firstLane(covered)));
    const bool several = any(covered & ~equal(keys, splat(static_cast<int32_t>(first))));
    bool shaded = true;
    if (several && !want_normals) {
      // Every triangle of the eight textured alike without per-pixel lighting (filtered with the
      // row's other such groups, below), or lit per pixel alike without maps: one evaluation for
      // the eight (mixed_lanes.h).
      const ShadeTriangle& t = records[keyChunk(first)][keyLocal(first)];
      const bool textured = texturedPlain(t);
      shaded = textured || litPlain(t);
      if (shaded) {
        const MixedRecords r = mixedRecords(keys, covered, first, records, extras);
        if (textured) {
          TexturedGroup& group = textured_groups[textured_count];
          shaded = prepareTexturedGroup(r.lanes, r.extras, covered, px, splat(py), group);
          if (shaded) {
            group.tx = tx;
            ++textured_count;
            continue;
          }
        } else {
          shaded = shadeLitMixed(r.lanes, r.extras, covered, lights, px, splat(py), color);
        }
      }
    } else if (!several && !want_normals &&
               texturedGroupApplies(records[keyChunk(first)][keyLocal(first)])) {
      // One textured triangle's pixels: filtered with the row's other textured groups.
      TexturedGroup& group = textured_groups[textured_count];
      prepareTexturedGroup(records[keyChunk(first)][keyLocal(first)],
                           extras[keyChunk(first)][keyLocal(first)], covered, px, splat(py), group);
      group.tx = tx;
      ++textured_count;
      continue;
    } else {
      shaded = false;
    }
    if (!shaded)
      shadeApart(keys, covered, records, extras, lights, want_normals, px, py, color, normal);
    storeShadedGroup(color, normal, want_normals, tx, i, linear, out);
  }
  filterTexturedRow(tile, ty, textured_groups, textured_count, records, extras, lights, linear);
  if (kSampled) resolveMixedRow(*msaa, tile, ty, records, extras, lights, *queue, linear);
}

// Shades the tile in pixel order, eight pixels of a row at a time, then encodes the row to sRGB
// and stores it whole (no read-modify-write of partly written pixels). Eight pixels of one triangle
// take one evaluation. A tile whose triangles are all plain (`plain`: untextured, not Phong, no
// normal AOV) takes shadePlainRow. Otherwise (shadeRow) eight pixels of several triangles are
// shaded lane by lane from their own records when all are textured alike without per-pixel
// lighting (prepareTexturedGroup) or when all are lit per pixel alike without maps (shadeLitMixed:
// one evaluation of the lights), else each triangle is evaluated once for the eight and the results
// merged in registers (shadeApart). Textured groups without per-pixel lighting, of one triangle or
// several, are filtered once the row's other work is done, one after another: a filter is a chain
// of dependent gathers, and the row's filters side by side keep the core busy where one between
// each group's other work left it waiting.
// `kSampled`: msaa is given (an instance of its own, so one sample pays nothing for it).
template <bool kSampled>
TESSERA_LANES_INLINE void shadeTile(const TileVisibility& tile,
                                    const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                                    const LightRig& lights, bool want_normals, bool plain,
                                    uint32_t background, const MsaaShading* msaa, ShadedTile& out) {
  const ShadeTriangle* records[kMaxChunks];
  const ShadeExtras* extras[kMaxChunks];
  for (size_t c = 0; c < chunk_count; ++c) {
    records[c] = chunks[c].shade.data();
    extras[c] = chunks[c].extras.data();
  }
  // A row's colours in linear light, encoded once the row is shaded: the encode is a long chain
  // of dependent operations, and eight groups of it side by side keep the core busy where one
  // after each group's shading left it waiting.
  alignas(32) float linear[3][kTileSize];
  // A plain row's groups of one solid triangle (shadePlainRow); the groups past a narrow tile's
  // width, which the sixteen-lane encode reads beside the last one, stay kNoSolid.
  uint32_t solid[kTileSize / 8] = {};
  SolidColours solids;
  std::optional<FragmentQueue> queue;
  if (kSampled) queue.emplace(*msaa);
  for (int ty = 0; ty < tile.height; ++ty) {
    if (plain) {
      shadePlainRow<kSampled>(tile, ty, records, msaa, queue ? &*queue : nullptr, linear, solid,
                              solids);
      encodeShadedRow(tile, ty, linear, solid, background, out);
    } else {
      shadeRow<kSampled>(tile, ty, records, extras, lights, want_normals, msaa,
                         queue ? &*queue : nullptr, linear, out);
      encodeShadedRow(tile, ty, linear, nullptr, background, out);
    }
  }
}

void shadeTileKernel(const TileVisibility& tile, const std::vector<TriangleChunk>& chunks,
                     size_t chunk_count, const LightRig& lights, bool want_normals, bool plain,
                     uint32_t background, const MsaaShading* msaa, ShadedTile& out) {
  if (msaa)
    shadeTile<true>(tile, chunks, chunk_count, lights, want_normals, plain, background, msaa, out);
  else
    shadeTile<false>(tile, chunks, chunk_count, lights, want_normals, plain, background, msaa, out);
}

}  // namespace
}  // namespace tessera::render
