// The shading kernel: a tile's visible pixels, eight at a time, shaded once at their centres
// (shade_lanes.h) and encoded to sRGB a row at a time; with MSAA the mixed pixels of each row are
// resolved before the encode, their fragments eight at a time (fragment_queue.h). Compiled per
// instruction set (kernels_<isa>.cpp); every variant gives the same bits.
#pragma once

#include <optional>
#include <utility>

#include "render/fragment_queue.h"
#include "render/mixed_lanes.h"
#include "render/plain_lanes16.h"
#include "render/row_runs.h"
#include "render/shade_lanes.h"
#include "render/texture_lanes16.h"
#include "render/textured_row.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

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

// The groups of eight pixels of row ty of a tile, sorted without a branch per group: bit g of
// `single` (of `several`) set where group g holds covered pixels of one triangle (of more than
// one), and with `mixed` (MsaaShading's flags, or null) of `sampled` where it holds a mixed
// pixel (not then in the other two); first[g] is the key of its first covered pixel (kEmptyKey
// where none is). The shading then takes each kind in a loop of its own: along a row the kind
// changes from group to group, and a branch between them, group by group, mispredicted
// (BM_TileShade 6-9% longer).
// With `two` (shadeRow, in tiles that may hold textured triangles), bit g of `two` is also set
// where group g's covered pixels hold exactly two triangles (it stays in `several`), second[g]
// the other's key. (The plain rows leave it out: there it cost more than it saved, bunny
// shadePlainRow +11% instructions, the bunny filling the frame +3.4%: their groups of several
// mostly hold three triangles or more.)
struct RowGroups {
  uint32_t single = 0, several = 0, sampled = 0, two = 0;
  uint32_t first[kTileSize / 8], second[kTileSize / 8];
};
TESSERA_LANES_INLINE RowGroups sortRowGroups(const TileVisibility& tile, int ty,
                                             const int32_t* mixed, bool two = false) {
  const I32x8 empty = splat(static_cast<int32_t>(kEmptyKey));
  RowGroups r;
  for (int tx = 0, g = 0; tx < tile.width; tx += 8, ++g) {
    const I32x8 keys = load<I32x8>(tile.key + ty * kTileSize + tx);
    const I32x8 covered = ~equal(keys, empty);
    const unsigned bits = laneBits(covered);
    // An empty group's "first" is its last lane, kEmptyKey, and it holds no other key.
    const int32_t first = lane(keys, __builtin_ctz(bits | 0x80u));
    const I32x8 others = covered & ~equal(keys, splat(first));
    const bool several = any(others);
    const bool sampled = mixed && bits != 0 && any(load<I32x8>(mixed + ty * kTileSize + tx));
    r.first[g] = static_cast<uint32_t>(first);
    r.single |= static_cast<uint32_t>(bits != 0 && !several && !sampled) << g;
    r.several |= static_cast<uint32_t>(several && !sampled) << g;
    r.sampled |= static_cast<uint32_t>(sampled) << g;
    if (two) {
      const int32_t second = lane(keys, __builtin_ctz(laneBits(others) | 0x80u));
      r.second[g] = static_cast<uint32_t>(second);
      r.two |=
          static_cast<uint32_t>(several && !sampled && !any(others & ~equal(keys, splat(second))))
          << g;
    }
  }
  return r;
}

// Group g of row ty as sortRowGroups left it: its first column, keys and covered lanes, and the
// key of its first covered pixel.
struct RowGroup {
  int tx;
  I32x8 keys, covered;
  uint32_t first;
};
TESSERA_LANES_INLINE RowGroup rowGroup(const TileVisibility& tile, int ty, const RowGroups& groups,
                                       int g) {
  const I32x8 keys = load<I32x8>(tile.key + ty * kTileSize + 8 * g);
  return {8 * g, keys, ~equal(keys, splat(static_cast<int32_t>(kEmptyKey))), groups.first[g]};
}

// Calls body(g) for each set bit g of `groups`, lowest first.
template <typename Body>
TESSERA_LANES_INLINE void forEachGroup(uint32_t groups, Body&& body) {
  for (; groups != 0; groups &= groups - 1) body(__builtin_ctz(groups));
}

// forEachGroup two groups at a time: body(a, b) for the two lowest bits left while two or more
// are; returns the group left over (one bit or none).
template <typename Body>
TESSERA_LANES_INLINE uint32_t forEachGroupPair(uint32_t groups, Body&& body) {
  while (groups & (groups - 1)) {
    const int a = __builtin_ctz(groups);
    groups &= groups - 1;
    const int b = __builtin_ctz(groups);
    groups &= groups - 1;
    body(a, b);
  }
  return groups;
}

// Eight pixels of one plain triangle (the key `first`; the lanes it does not cover are encoded as
// the background): of one whose corners share a colour, that colour, its sRGB in `solid`.
TESSERA_LANES_INLINE Vec3x8 shadePlainSingle(const ShadeTriangle* const records[], uint32_t first,
                                             F32x8 px, float py, SolidColours& solids,
                                             uint32_t& solid) {
  const ShadeTriangle& t = records[keyChunk(first)][keyLocal(first)];
  const uint32_t rgba = solids.of(first, t);
  if (rgba != kNoSolid) {
    // interpolateColor's value at any pixel: no barycentrics, and the encode is done.
    solid = rgba;
    return {splat(t.color[0].x), splat(t.color[0].y), splat(t.color[0].z)};
  }
  return shadePlainLanes(t, px, py);
}

// Eight pixels of several plain triangles (`first`: the first covered lane's key).
TESSERA_LANES_INLINE Vec3x8 shadePlainSeveral(const ShadeTriangle* const records[], I32x8 keys,
                                              I32x8 covered, uint32_t first, F32x8 px, float py) {
  const ShadeTriangle* lanes[8];
  laneRecords(laneKeys(keys, covered, first), records, lanes);
  return shadeMixed(lanes, px, splat(py));
}

TESSERA_LANES_INLINE F32x8 pixelCentresX(const TileVisibility& tile, int tx) {
  return toFloat(splat(tile.x0 + tx) + iota()) + splat(0.5f);
}

TESSERA_LANES_INLINE void storeLinear(float linear[3][kTileSize], int tx, const Vec3x8& color) {
  store(linear[0] + tx, color.x);
  store(linear[1] + tx, color.y);
  store(linear[2] + tx, color.z);
}

// The sRGB of row ty of a plain tile when one solid triangle covers all of it (and, with `mixed`,
// no pixel of it is mixed): the inside of a large triangle, as most rows of the cube's faces at
// 1920x1080. The tile then stores that colour across the row (storeSolidRow), the value
// shadePlainSingle and the encode give each of its groups, without the row's sorting, a record
// look-up per group or the encode. kNoSolid for any other row.
TESSERA_LANES_INLINE uint32_t solidRowRgba(const TileVisibility& tile, int ty,
                                           const ShadeTriangle* const records[],
                                           const int32_t* mixed, SolidColours& solids) {
  const int row = ty * kTileSize;
  const uint32_t key = tile.key[row];
  if (key == kEmptyKey) return kNoSolid;
  const I32x8 first = splat(static_cast<int32_t>(key));
  I32x8 other = splat(int32_t{0});
  for (int tx = 0; tx < tile.width; tx += 8) {
    other = other | ~equal(load<I32x8>(tile.key + row + tx), first);
    if (mixed) other = other | load<I32x8>(mixed + row + tx);
  }
  if (any(other)) return kNoSolid;
  return solids.of(key, records[keyChunk(key)][keyLocal(key)]);
}

#if defined(TESSERA_LANES16)
// The groups of `several` (of row ty, sorted by sortRowGroups) two at a time in sixteen lanes
// (shadeMixedPair) into the row's linear colours; returns the one left over, if any.
TESSERA_LANES_INLINE uint32_t shadeSeveralPairs(const TileVisibility& tile, int ty,
                                                const RowGroups& groups, uint32_t several,
                                                const ShadeTriangle* const records[],
                                                float linear[3][kTileSize]) {
  const F32x8 py = splat(static_cast<float>(tile.y0 + ty) + 0.5f);
  return forEachGroupPair(
      several, [&](int ga, int gb) __attribute__((always_inline)) {
        const RowGroup a = rowGroup(tile, ty, groups, ga);
        const RowGroup b = rowGroup(tile, ty, groups, gb);
        const ShadeTriangle* ra[8];
        const ShadeTriangle* rb[8];
        laneRecords(laneKeys(a.keys, a.covered, a.first), records, ra);
        laneRecords(laneKeys(b.keys, b.covered, b.first), records, rb);
        Vec3x8 ca, cb;
        shadeMixedPair(ra, pixelCentresX(tile, a.tx), py, rb, pixelCentresX(tile, b.tx), py, ca,
                       cb);
        storeLinear(linear, a.tx, ca);
        storeLinear(linear, b.tx, cb);
      });
}

// The groups of `sampled` (row ty's groups holding a mixed pixel) two at a time
// (shadePlainSampledPair), each pair followed by the queue's rounds queued before it, two at a
// time (shade_pair); returns the group left over, if any.
template <typename ShadePair>
TESSERA_LANES_INLINE uint32_t shadeSampledPairs(const TileVisibility& tile, int ty,
                                                uint32_t sampled, const MsaaShading& msaa,
                                                const ShadeTriangle* const records[],
                                                FragmentQueue& queue, float linear[3][kTileSize],
                                                ShadePair shade_pair) {
  return forEachGroupPair(
      sampled, [&](int ga, int gb) __attribute__((always_inline)) {
        const int txa = 8 * ga, txb = 8 * gb;
        const int ia = ty * kTileSize + txa, ib = ty * kTileSize + txb;
        const int ready = queue.count;
        Vec3x8 ca, cb;
        shadePlainSampledPair(msaa, records, tile.y0 + ty, ia, txa, tile.x0 + txa,
                              load<I32x8>(msaa.tiles->mixed + ia), ib, txb, tile.x0 + txb,
                              load<I32x8>(msaa.tiles->mixed + ib), queue, ca, cb);
        storeLinear(linear, txa, ca);
        storeLinear(linear, txb, cb);
        shadeQueuePairs(queue, ready, shade_pair);
      });
}
#endif

// Row ty of a plain tile (every triangle untextured, not Phong, no normal AOV) into the row's
// linear colours: eight pixels of one triangle take shadePlainSingle, of several shadeMixed, and
// with MSAA (`kSampled`) a group holding a mixed pixel is resolved with the row's other such
// groups (shadePlainSampled, then `queue`'s fragments eight at a time, each added to its pixel in
// sample order). The groups are sorted first (sortRowGroups), each kind shaded in a loop of its
// own; on AVX-512 groups of several triangles, mixed groups and the queue's rounds go two at a
// time in sixteen lanes (plain_lanes16.h). A function of its own, not inlined into shadeTile: in
// the one function of every path the compiler kept this loop's colours and masks on the stack,
// and the plain frames' shading took 10% longer.
template <bool kSampled>
__attribute__((noinline)) void shadePlainRow(const TileVisibility& tile, int ty,
                                             const ShadeTriangle* const records[],
                                             const MsaaShading* msaa, FragmentQueue* queue,
                                             float linear[3][kTileSize],
                                             uint32_t solid[kTileSize / 8], SolidColours& solids) {
  const float py = static_cast<float>(tile.y0 + ty) + 0.5f;
#if defined(__AVX2__) && !defined(TESSERA_LANES16)
  // By the row's runs (row_runs.h) on AVX2; on AVX-512 the groups of several triangles two at a
  // time in sixteen lanes (shadeSeveralPairs) did better (the bunny at 1080p 6.7% faster).
  if (!kSampled) {
    // Every group empty until the runs hand it its colours (the sorted groups set them again).
    for (int g = 0; g * 8 < tile.width; ++g) solid[g] = kSolidEmpty;
    if (preparePlainRow(
            tile, ty, records, [&](int tx, const Vec3x8& color) __attribute__((always_inline)) {
              storeLinear(linear, tx, color);
              solid[tx / 8] = kNoSolid;
            }))
      return;
  }
#endif
  const RowGroups groups = sortRowGroups(tile, ty, kSampled ? msaa->tiles->mixed : nullptr);
  for (int g = 0; g * 8 < tile.width; ++g)
    solid[g] = groups.first[g] == kEmptyKey ? kSolidEmpty : kNoSolid;
  const auto shade_single = [&](int g) __attribute__((always_inline)) {
    storeLinear(linear, 8 * g,
                shadePlainSingle(records, groups.first[g], pixelCentresX(tile, 8 * g), py, solids,
                                 solid[g]));
  };
  const auto shade_several = [&](int g) __attribute__((always_inline)) {
    const RowGroup r = rowGroup(tile, ty, groups, g);
    storeLinear(
        linear, r.tx,
        shadePlainSeveral(records, r.keys, r.covered, r.first, pixelCentresX(tile, r.tx), py));
  };
  forEachGroup(groups.single, shade_single);
#if defined(TESSERA_LANES16)
  forEachGroup(shadeSeveralPairs(tile, ty, groups, groups.several, records, linear), shade_several);
#else
  forEachGroup(groups.several, shade_several);
#endif
  if constexpr (kSampled) {
    if (groups.sampled == 0) return;
    const auto shade_queued = [&](int first, int count) __attribute__((always_inline)) {
      shadeQueuedPlain(records, *queue, first, count, tile.x0, tile.y0 + ty, linear);
    };
#if defined(TESSERA_LANES16)
    // On AVX-512 the rounds go two at a time (shadeQueuedPlainPair), the last one or none left to
    // finishQueue, and so do the groups (shadeSampledPairs).
    const auto shade_pair = [&](int first) __attribute__((always_inline)) {
      shadeQueuedPlainPair(records, *queue, first, tile.x0, tile.y0 + ty, linear);
    };
#endif
    const auto shade_sampled = [&](int g) __attribute__((always_inline)) {
      const int tx = 8 * g, i = ty * kTileSize + tx;
      const I32x8 mixed = load<I32x8>(msaa->tiles->mixed + i);
      const int ready = queue->count;
      storeLinear(
          linear, tx,
          shadePlainSampled(*msaa, records, i, tx, tile.x0 + tx, tile.y0 + ty, mixed, *queue));
#if defined(TESSERA_LANES16)
      shadeQueuePairs(*queue, ready, shade_pair);
#else
      shadeQueue(*queue, ready, shade_queued);
#endif
    };
#if defined(TESSERA_LANES16)
    forEachGroup(
        shadeSampledPairs(tile, ty, groups.sampled, *msaa, records, *queue, linear, shade_pair),
        shade_sampled);
    shadeQueuePairs(*queue, queue->count, shade_pair);
#else
    forEachGroup(groups.sampled, shade_sampled);
#endif
    finishQueue(*queue, shade_queued);
    finishMixedRow(*msaa, tile, ty, linear);
  }
}

// A row's groups of untextured Phong triangles whose lights wait for the row's end
// (phongDeferrable): their colours in the row's linear colours, their interpolated normals here,
// bit g of `groups` set for the eight pixels at 8 g. finishPhongRow lights them two groups at a
// time in sixteen lanes on AVX-512, where a division or square root of sixteen lanes costs about
// as much as one of eight (docs/perf-notes/speed-2026-12-06.md).
struct DeferredPhong {
  alignas(32) float normal[3][kTileSize];
  uint32_t groups = 0;
  TESSERA_LANES_INLINE void add(float linear[3][kTileSize], int tx, const Vec3x8& color,
                                const Vec3x8& n) {
    storeLinear(linear, tx, color);
    storeLinear(normal, tx, n);
    groups |= 1u << (tx / 8);
  }
};

// The lights of a row's deferred Phong groups, into `linear`: two groups at a time in sixteen
// lanes on AVX-512 without a tone curve, else one at a time.
TESSERA_LANES_INLINE void finishPhongRow(const LightRig& lights, const DeferredPhong& deferred,
                                         float linear[3][kTileSize]) {
  uint32_t groups = deferred.groups;
  const auto& normal = deferred.normal;
#if defined(TESSERA_LANES16)
  if (!lights.tone.active()) {
    groups = forEachGroupPair(
        groups, [&](int ga, int gb) __attribute__((always_inline)) {
          const int a = 8 * ga, b = 8 * gb;
          F32x16 c[3], n[3];
          for (int k = 0; k < 3; ++k) {
            c[k] = join16(load<F32x8>(linear[k] + a), load<F32x8>(linear[k] + b));
            n[k] = join16(load<F32x8>(normal[k] + a), load<F32x8>(normal[k] + b));
          }
          finishPhong16(lights, c, n);
          for (int k = 0; k < 3; ++k) {
            store(linear[k] + a, lowHalf(c[k]));
            store(linear[k] + b, highHalf(c[k]));
          }
        });
  }
#endif
  const auto finish_one = [&](int g) __attribute__((always_inline)) {
    const int tx = 8 * g;
    const Vec3x8 color{load<F32x8>(linear[0] + tx), load<F32x8>(linear[1] + tx),
                       load<F32x8>(linear[2] + tx)};
    const Vec3x8 n{load<F32x8>(normal[0] + tx), load<F32x8>(normal[1] + tx),
                   load<F32x8>(normal[2] + tx)};
    storeLinear(linear, tx, finishPhong8(lights, color, n));
  };
  forEachGroup(groups, finish_one);
}

// Row ty of a tile that is not plain (see shadeTile) into the row's linear colours and, when
// asked, the tile's normals. A function of its own, as shadePlainRow is: apart from the encode,
// the compiler keeps more of the row's values in registers. `lit_alike`: every record is
// TriangleChunk::lit_alike; `textured_alike`: every record's (TriangleChunk::textured_alike), or
// null.
template <bool kSampled>
__attribute__((noinline)) void shadeRow(
    const TileVisibility& tile, int ty, const ShadeTriangle* const records[],
    const ShadeExtras* const extras[], const LightRig& lights, bool want_normals, bool textured,
    bool lit_alike, [[maybe_unused]] const Material* textured_alike, const MsaaShading* msaa,
    FragmentQueue* queue, AlbedoReads& albedo, float linear[3][kTileSize], ShadedTile& out) {
  const F32x8 zero = splat(0.0f);
  const float py = static_cast<float>(tile.y0 + ty) + 0.5f;
  TexturedGroup textured_groups[kTileSize / 8];
  int textured_count = 0;
  const bool defer_phong = phongDeferrable(lights, want_normals);
  DeferredPhong phong;
#if defined(__AVX2__)
  // Rows whose every covered pixel is textured alike without per-pixel lighting, or Phong without
  // textures, take each lane's fields from its run's column (row_runs.h).
  if (!kSampled && textured && !want_normals) {
    textured_count = prepareTexturedRow(tile, ty, records, extras, textured_groups, textured_alike);
    if (textured_count >= 0) {
      filterTexturedRow(tile, ty, textured_groups, textured_count, records, extras, lights, albedo,
                        linear);
      return;
    }
    textured_count = 0;
  }
  if (!kSampled && lit_alike && defer_phong &&
      prepareLitRow(
          tile, ty, records, extras,
          [&](int tx, const Vec3x8& color, const Vec3x8& normal)
              __attribute__((always_inline)) { phong.add(linear, tx, color, normal); })) {
    finishPhongRow(lights, phong, linear);
    return;
  }
#endif
  // Group r: shaded triangle by triangle (shadeApart) and stored.
  const auto shade_apart = [&](const RowGroup& r, F32x8 px, Vec3x8 color)
      __attribute__((always_inline)) {
    Vec3x8 normal{zero, zero, zero};
    shadeApart(r.keys, r.covered, records, extras, lights, want_normals, px, py, color, normal);
    storeShadedGroup(color, normal, want_normals, r.tx, ty * kTileSize + r.tx, linear, out);
  };
  const RowGroups groups = sortRowGroups(tile, ty, nullptr, textured && !want_normals);
  const auto shade_single = [&](int g) __attribute__((always_inline)) {
    const RowGroup r = rowGroup(tile, ty, groups, g);
    const F32x8 px = pixelCentresX(tile, r.tx);
    const ShadeTriangle& t = records[keyChunk(r.first)][keyLocal(r.first)];
    if (defer_phong && t.shading == Shading::kPhong && !t.has_uv) {
      Vec3x8 color, normal;
      phongInputs(t, extras[keyChunk(r.first)][keyLocal(r.first)], px, py, color, normal);
      phong.add(linear, r.tx, color, normal);
      return;
    }
    if (!want_normals && texturedGroupApplies(t)) {
      // One textured triangle's pixels: filtered with the row's other textured groups.
      TexturedGroup& group = textured_groups[textured_count];
      prepareTexturedGroup(t, extras[keyChunk(r.first)][keyLocal(r.first)], r.covered, px,
                           splat(py), group);
      group.tx = r.tx;
      ++textured_count;
      return;
    }
    shade_apart(r, px, Vec3x8{zero, zero, zero});
  };
  const auto shade_several = [&](int g) __attribute__((always_inline)) {
    const RowGroup r = rowGroup(tile, ty, groups, g);
    const F32x8 px = pixelCentresX(tile, r.tx);
    Vec3x8 color{zero, zero, zero};
    if (!want_normals) {
      // Every triangle of the eight textured alike without per-pixel lighting (filtered with the
      // row's other such groups, below), or lit per pixel alike without maps: one evaluation for
      // the eight (mixed_lanes.h).
      const ShadeTriangle& t = records[keyChunk(r.first)][keyLocal(r.first)];
      const bool textured = !lit_alike && texturedPlain(t);
      if (textured || lit_alike || litPlain(t)) {
        const MixedRecords m = mixedRecords(r.keys, r.covered, r.first, records, extras);
        if (textured) {
          TexturedGroup& group = textured_groups[textured_count];
          if (prepareTexturedGroup(m.lanes, m.extras, r.covered, px, splat(py), group)) {
            group.tx = r.tx;
            ++textured_count;
            return;
          }
        } else if (defer_phong && t.shading == Shading::kPhong &&
                   (lit_alike || litAlike(m.lanes))) {
          Vec3x8 normal;
          phongInputsMixed(m.lanes, m.extras, px, splat(py), color, normal);
          phong.add(linear, r.tx, color, normal);
          return;
        } else if (shadeLitMixed(m.lanes, m.extras, r.covered, lights, px, splat(py), color,
                                 lit_alike)) {
          storeShadedGroup(color, Vec3x8{zero, zero, zero}, false, r.tx, ty * kTileSize + r.tx,
                           linear, out);
          return;
        }
      }
    }
    shade_apart(r, px, color);
  };
  // Two triangles textured alike: each lane's fields picked from the two records, not eight
  // records loaded and transposed.
  const auto shade_two = [&](int g) __attribute__((always_inline)) {
    const uint32_t ka = groups.first[g], kb = groups.second[g];
    const ShadeTriangle& a = records[keyChunk(ka)][keyLocal(ka)];
    const ShadeTriangle& b = records[keyChunk(kb)][keyLocal(kb)];
    if (b.material != a.material || !texturedPlain(b) || !texturedGroupApplies(a)) {
      shade_several(g);
      return;
    }
    const RowGroup r = rowGroup(tile, ty, groups, g);
    TexturedGroup& group = textured_groups[textured_count];
    prepareTexturedGroup(a, extras[keyChunk(ka)][keyLocal(ka)], b,
                         extras[keyChunk(kb)][keyLocal(kb)],
                         equal(r.keys, splat(static_cast<int32_t>(kb))), r.covered,
                         pixelCentresX(tile, r.tx), splat(py), group);
    group.tx = r.tx;
    ++textured_count;
  };
  // Groups of one triangle first, then those of two, then of more (sortRowGroups).
  forEachGroup(groups.single, shade_single);
  forEachGroup(groups.two, shade_two);
  forEachGroup(groups.several & ~groups.two, shade_several);
  finishPhongRow(lights, phong, linear);
  filterTexturedRow(tile, ty, textured_groups, textured_count, records, extras, lights, albedo,
                    linear);
  if (kSampled)
    resolveMixedRow(*msaa, tile, ty, records, extras, lights, lit_alike, *queue, linear);
}

// The material every record of the tile's chunks is textured alike through
// (TriangleChunk::textured_alike; chunks without records aside), where the eight-lane filter takes
// it (texturedGroupApplies); null otherwise.
TESSERA_LANES_INLINE const Material* texturedAlike(const std::vector<TriangleChunk>& chunks,
                                                   size_t chunk_count) {
  const Material* alike = nullptr;
  for (size_t c = 0; c < chunk_count; ++c) {
    if (chunks[c].size == 0) continue;
    if (!chunks[c].textured_alike || (alike && chunks[c].textured_alike != alike)) return nullptr;
    alike = chunks[c].textured_alike;
  }
  return alike && texture8Applies(*alike->albedo, alike->sampler) ? alike : nullptr;
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
  bool textured = false;  // some record may be texturedPlain
  bool lit_alike = true;  // every record is litPlain Phong
  for (size_t c = 0; c < chunk_count; ++c) {
    records[c] = chunks[c].shade.data();
    extras[c] = chunks[c].extras.data();
    textured |= chunks[c].textured_plain;
    lit_alike &= chunks[c].lit_alike;
  }
  const Material* textured_alike = texturedAlike(chunks, chunk_count);
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
  AlbedoReads albedo;
  for (int ty = 0; ty < tile.height; ++ty) {
    if (plain) {
      const uint32_t rgba =
          solidRowRgba(tile, ty, records, kSampled ? msaa->tiles->mixed : nullptr, solids);
      if (rgba != kNoSolid) {
        storeSolidRow(tile, ty, rgba, out);
        continue;
      }
      shadePlainRow<kSampled>(tile, ty, records, msaa, queue ? &*queue : nullptr, linear, solid,
                              solids);
      encodeShadedRow(tile, ty, linear, solid, background, out);
    } else {
      shadeRow<kSampled>(tile, ty, records, extras, lights, want_normals, textured, lit_alike,
                         textured_alike, msaa, queue ? &*queue : nullptr, albedo, linear, out);
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

// encodeShadedRow's encode of `count` values (a multiple of 16), its width at a time: what the
// tests run every float of [0, 1] through, for each instruction set.
void encodeSrgbKernel(const float* linear, size_t count, uint8_t* codes) {
  for (size_t i = 0; i < count; i += 16) {
#if defined(TESSERA_LANES16)
    const I32x16 c = encodeSrgb8x16(load<F32x16>(linear + i));
    for (int l = 0; l < 16; ++l) codes[i + l] = static_cast<uint8_t>(c[l]);
#else
    for (size_t half = i; half < i + 16; half += 8) {
      const I32x8 c = encodeSrgb8x8(load<F32x8>(linear + half));
      for (int l = 0; l < 8; ++l) codes[half + l] = static_cast<uint8_t>(lane(c, l));
    }
#endif
  }
}

}  // namespace
}  // namespace tessera::render
