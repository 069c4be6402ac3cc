// The shading kernel: a tile's visible pixels, eight at a time, shaded once at their centres
// (shade_lanes.h) and encoded to sRGB a row at a time; with MSAA the mixed pixels of each row are
// resolved sample by sample before the encode (msaa_kernel.h). Compiled per instruction set
// (kernels_<isa>.cpp); every variant gives the same bits.
#pragma once

#include "render/mixed_lanes.h"
#include "render/msaa_kernel.h"
#include "render/shade_lanes.h"

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

// The textured groups of row ty that shadeTile prepared, filtered one after another into the row's
// linear colours; a group whose coordinates are beyond the eight-lane filter's reach is shaded
// triangle by triangle.
TESSERA_LANES_INLINE void filterTexturedRow(const TileVisibility& tile, int ty,
                                            const TexturedGroup groups[], int count,
                                            const ShadeTriangle* const records[],
                                            const ShadeExtras* const extras[],
                                            const LightRig& lights, float linear[3][kTileSize]) {
  const float py = static_cast<float>(tile.y0 + ty) + 0.5f;
  const F32x8 zero = splat(0.0f);
  for (int g = 0; g < count; ++g) {
    const TexturedGroup& group = groups[g];
    Vec3x8 color{zero, zero, zero}, normal{zero, zero, zero};
    if (!filterTexturedGroup(group, lights, color)) {
      const I32x8 keys = load<I32x8>(tile.key + ty * kTileSize + group.tx);
      const F32x8 px = toFloat(splat(tile.x0 + group.tx) + iota()) + splat(0.5f);
      shadeApart(keys, group.covered, records, extras, lights, false, px, py, color, normal);
    }
    store(linear[0] + group.tx, color.x);
    store(linear[1] + group.tx, color.y);
    store(linear[2] + group.tx, color.z);
  }
}

// Shades the tile in pixel order, eight pixels of a row at a time, then encodes the row to sRGB
// and stores it whole (no read-modify-write of partly written pixels). Eight pixels of one triangle
// take one evaluation; those of several are shaded lane by lane from their own records when every
// triangle is plain (`plain`: untextured, not Phong, no normal AOV), when all are textured alike
// without per-pixel lighting (prepareTexturedGroup) or when all are lit per pixel alike without
// maps (shadeLitMixed: one evaluation of the lights), else each triangle is evaluated once for the
// eight and the results merged in registers (shadeApart). Textured groups without per-pixel
// lighting, of one triangle or several, are filtered once the row's other work is done, one after
// another: a filter is a chain of dependent gathers, and the row's filters side by side keep the
// core busy where one between each group's other work left it waiting.
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
  const I32x8 empty = splat(static_cast<int32_t>(kEmptyKey));
  const F32x8 zero = splat(0.0f);
  // A row's colours in linear light, encoded once the row is shaded: the encode is a long chain
  // of dependent operations, and eight groups of it side by side keep the core busy where one
  // after each group's shading left it waiting.
  alignas(32) float linear[3][kTileSize];
  TexturedGroup textured_groups[kTileSize / 8];
  for (int ty = 0; ty < tile.height; ++ty) {
    const float py = static_cast<float>(tile.y0 + ty) + 0.5f;
    int textured_count = 0;
    for (int tx = 0; tx < tile.width; tx += 8) {
      const int i = ty * kTileSize + tx;
      const I32x8 keys = load<I32x8>(tile.key + i);
      const I32x8 covered = ~equal(keys, empty);
      if (!any(covered)) continue;
      const F32x8 px = toFloat(splat(tile.x0 + tx) + iota()) + splat(0.5f);
      Vec3x8 color{zero, zero, zero}, normal{zero, zero, zero};
      const uint32_t first = static_cast<uint32_t>(lane(keys, firstLane(covered)));
      const I32x8 mixed = kSampled ? load<I32x8>(msaa->tiles->mixed + i) : splat(int32_t{0});
      const bool several = any(covered & ~equal(keys, splat(static_cast<int32_t>(first))));
      bool shaded = true;
      if (kSampled && plain && any(mixed)) {
        color = shadePlainSampled(*msaa, chunks, records, i, tile.x0 + tx, tile.y0 + ty, mixed);
      } else if (several && plain) {
        const ShadeTriangle* lanes[8];
        laneRecords(laneKeys(keys, covered, first), records, lanes);
        color = shadeMixed(lanes, px, splat(py));
      } else if (plain) {
        // One triangle's pixels (the lanes it does not cover are encoded as the background).
        color = shadePlainLanes(records[keyChunk(first)][keyLocal(first)], px, py);
      } else if (several && !want_normals) {
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
                             extras[keyChunk(first)][keyLocal(first)], covered, px, splat(py),
                             group);
        group.tx = tx;
        ++textured_count;
        continue;
      } else {
        shaded = false;
      }
      if (!shaded)
        shadeApart(keys, covered, records, extras, lights, want_normals, px, py, color, normal);
      store(linear[0] + tx, color.x);
      store(linear[1] + tx, color.y);
      store(linear[2] + tx, color.z);
      if (want_normals) {
        store(out.normal_x + i, normal.x);
        store(out.normal_y + i, normal.y);
        store(out.normal_z + i, normal.z);
      }
    }
    filterTexturedRow(tile, ty, textured_groups, textured_count, records, extras, lights, linear);
    if (kSampled && !plain) resolveMixedRow(*msaa, tile, ty, chunks, lights, linear);
    encodeShadedRow(tile, ty, linear, background, out);
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
