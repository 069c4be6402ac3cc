// A row's triangles as runs, for the shading kernel (shade_kernel.h): the pixels of a row of a
// tile form runs of one key, and each run's fields (its triangle's ShadeTriangle fields and its
// corners' texture coordinates or normals) take one column of a small table. A lane of a group of
// eight then reads its triangle's field with one in-register permute of the eight columns from
// the run of the group's first lane (lookup8), whatever the number of triangles in the group: no
// record looked up and no transpose per group, and no sorting of the groups by kind. The records
// are loaded and transposed once per eight runs instead of once per group of several triangles.
// The fields are the same floats, and the preparation the same operations (prepareTexturedFields,
// phongInputsMixed, shadeMixed), so the same bits. Rows textured alike without per-pixel lighting,
// rows of Phong triangles without textures whose lights wait for the row's end, and (AVX2) plain
// rows without solid triangles. Only where lookup8 is a permute (AVX2 and up); the other
// instruction sets take the groups' records (mixed_lanes.h).
#pragma once

#include <algorithm>
#include <cstdint>

#include "render/mixed_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

#if defined(__AVX2__)
// For each eight-bit mask of the lanes that start a run, each lane's run counted from the run of
// lane 0 (how many of lanes 1..l start one), one byte a lane (byteLanes).
constexpr uint64_t runOffsets(unsigned bits) {
  uint64_t offsets = 0;
  for (unsigned l = 0; l < 8; ++l)
    offsets |= uint64_t{static_cast<unsigned>(__builtin_popcount(bits & ((2u << l) - 2u)))}
               << (8 * l);
  return offsets;
}
constexpr auto kRunOffsets = laneMaskTable(runOffsets);

struct RowRuns {
  // A row of kTileSize pixels holds at most kTileSize runs. The columns are filled eight at a time.
  static constexpr int kColumns = kTileSize;
  alignas(32) float plain[kPlainFields][kColumns];  // loadPlainFields' fields, a run a column
  // The texture coordinates' corners (uvCorners8's; rows 6 and 7 unused) or the normals' (nine).
  alignas(32) float corner[9][kColumns];
  alignas(32) uint32_t key[kTileSize + 8];  // each run's key (compressLanes' room after)
  int count;
  int first[kTileSize / 8];        // each group's run of its lane 0
  uint32_t starts[kTileSize / 8];  // each group's lanes that start a run
  // The columns fillRowRuns fills: the runs' and those past the last up to a multiple of eight.
  int filledColumns() const { return (count + 7) & ~7; }
};

// A group's fields in lanes, each lane's from its run's column: BroadcastFields' interface.
// `from`: the first of the eight columns read (at most the last eight filled), `offset` each
// lane's column from there.
struct RunFields {
  const float (*rows)[RowRuns::kColumns];
  int from;
  I32x8 offset;
  // Fields 12..17 hold the corners' colours 1 and 2 less corner 0's (fillRowRuns).
  static constexpr bool kColourDifferences = true;
  TESSERA_LANES_INLINE F32x8 operator[](int k) const { return lookup8(rows[k] + from, offset); }
};

// The runs of row ty of `tile`: their keys, and each group's first run and run starts.
TESSERA_LANES_INLINE void findRowRuns(const TileVisibility& tile, int ty, RowRuns& runs) {
  const uint32_t* row = tile.key + ty * kTileSize;
  int n = 0;
  for (int tx = 0, g = 0; tx < tile.width; tx += 8, ++g) {
    const I32x8 keys = load<I32x8>(row + tx);
    // Each lane's key against the one before it (the first group's lane 0 starts a run). The
    // first group's keys moved up a lane in registers: read from a copy on the stack, the load
    // waited for the copy's stores.
    const I32x8 prev =
        g == 0 ? reinterpret_cast<I32x8>(_mm256_permutevar8x32_epi32(
                     reinterpret_cast<__m256i>(keys), _mm256_setr_epi32(0, 0, 1, 2, 3, 4, 5, 6)))
               : load<I32x8>(row + tx - 1);
    const I32x8 starts = ~equal(keys, prev) | (g == 0 ? iota() == 0 : I32x8{});
    const unsigned bits = laneBits(starts);
    runs.first[g] = n - 1 + static_cast<int>(bits & 1u);
    runs.starts[g] = bits;
    int count;
    store(runs.key + n, compressLanes(keys, starts, count));
    n += count;
  }
  runs.count = n;
}

// What a row's runs hold beside the ShadeTriangle fields: nothing (plain rows, preparePlainRow),
// the texture coordinates' corners of triangles textured alike without per-pixel lighting
// (prepareTexturedRow), or the normals' corners of Phong triangles without textures
// (prepareLitRow).
enum class RunCorners { kNone, kUv, kNormal };

// The runs' fields into their columns, eight runs at a time (loadPlainFields, and uvCorners8 or
// extrasCorners), the empty runs' (kEmptyKey) and the columns past the last run's from the row's
// first triangle. False where some run's triangle is not one the row's kind takes: for kUv,
// texturedPlain with the first's material, the first texturedGroupApplies; for kNormal, Phong
// without texture coordinates; for kNone, not solid (the caller then shades the row's groups
// from their records). `extras`: unread for kNone. `alike` (kUv): every record's material and
// texturedGroupApplies (TriangleChunk::textured_alike, checked by the caller), or null; the runs'
// records are then not looked at for that.
// `material`: the first triangle's (null where no pixel is covered).
template <RunCorners kCorners>
TESSERA_LANES_INLINE bool fillRowRuns(const ShadeTriangle* const records[],
                                      const ShadeExtras* const extras[], RowRuns& runs,
                                      const Material*& material, const Material* alike = nullptr) {
  // Each run's records; the empty runs' (listed in `empty`) and those past the last filled in
  // below.
  const ShadeTriangle* lanes[kTileSize];
  const ShadeExtras* lane_extras[kTileSize];
  int empty[kTileSize];
  int empty_count = 0;
  int first = -1;
  material = nullptr;
  for (int r = 0; r < runs.count; ++r) {
    const uint32_t key = runs.key[r];
    if (key == kEmptyKey) {
      empty[empty_count++] = r;
      continue;
    }
    const ShadeTriangle* t = &records[keyChunk(key)][keyLocal(key)];
    lanes[r] = t;
    if (kCorners != RunCorners::kNone) lane_extras[r] = &extras[keyChunk(key)][keyLocal(key)];
    if (kCorners == RunCorners::kNone) {
      if (t->solid) return false;
      if (first < 0) first = r;
    } else if (kCorners == RunCorners::kNormal) {
      if (t->shading != Shading::kPhong || t->has_uv) return false;
      if (first < 0) first = r;
    } else if (first < 0) {
      if (!alike && !texturedGroupApplies(*t)) return false;
      first = r;
    } else if (!alike && (t->material != lanes[first]->material || !texturedPlain(*t))) {
      return false;
    }
  }
  if (first < 0) return true;  // no covered pixel: nothing to prepare
  material = lanes[first]->material;
  const int columns = runs.filledColumns();
  const auto from_first = [&](int r) __attribute__((always_inline)) {
    lanes[r] = lanes[first];
    if (kCorners != RunCorners::kNone) lane_extras[r] = lane_extras[first];
  };
  for (int e = 0; e < empty_count; ++e) from_first(empty[e]);
  for (int r = runs.count; r < columns; ++r) from_first(r);
  for (int c = 0; c < columns; c += 8) {
    // The corners' colours 1 and 2 as their differences from corner 0's (RunFields' colours):
    // plainColor's subtractions once a run instead of once a group, the same floats.
    F32x8 colour0[3];
    loadPlainFieldsBy(
        lanes + c, [&](int k, F32x8 v) __attribute__((always_inline)) {
          if (k >= 9 && k < 12) colour0[k - 9] = v;
          store(runs.plain[k] + c, k < 12 ? v : v - colour0[(k - 9) % 3]);
        });
    F32x8 corner[9];
    if (kCorners == RunCorners::kNone) continue;
    if (kCorners == RunCorners::kNormal) {
      extrasCorners(lane_extras + c, &ShadeExtras::normal, corner);
      for (int k = 0; k < 9; ++k) store(runs.corner[k] + c, corner[k]);
    } else {
      uvCorners8(lane_extras + c, material->sampler.texcoord, corner);
      for (int k = 0; k < 6; ++k) store(runs.corner[k] + c, corner[k]);
    }
  }
  return true;
}

// Row ty cut into its runs (findRowRuns) and their columns filled (fillRowRuns<kCorners>), then
// for each covered group body(tx, covered, fields, corners, material, px, py): the group's first
// column, covered lanes, ShadeTriangle fields and corners in lanes (each lane's from its run's
// column: lane l's run is first[g] plus the runs lanes 1..l start), the row's first triangle's
// material and the pixel centres. False, with no group handed, where fillRowRuns is.
template <RunCorners kCorners, typename Body>
TESSERA_LANES_INLINE bool byRowRuns(const TileVisibility& tile, int ty,
                                    const ShadeTriangle* const records[],
                                    const ShadeExtras* const extras[], Body&& body,
                                    const Material* alike = nullptr) {
  RowRuns runs;
  findRowRuns(tile, ty, runs);
  const Material* material;
  if (!fillRowRuns<kCorners>(records, extras, runs, material, alike)) return false;
  if (!material) return true;                      // no covered pixel
  const int last_from = runs.filledColumns() - 8;  // the last eight columns filled
  const F32x8 py = splat(static_cast<float>(tile.y0 + ty) + 0.5f);
  const I32x8 empty = splat(static_cast<int32_t>(kEmptyKey));
  const uint32_t* row = tile.key + ty * kTileSize;
  for (int tx = 0, g = 0; tx < tile.width; tx += 8, ++g) {
    const I32x8 covered = ~equal(load<I32x8>(row + tx), empty);
    if (!any(covered)) continue;
    const int from = std::min(runs.first[g], last_from);
    const I32x8 offset = byteLanes(kRunOffsets.of[runs.starts[g]]) + splat(runs.first[g] - from);
    body(tx, covered, RunFields{runs.plain, from, offset}, RunFields{runs.corner, from, offset},
         material, toFloat(splat(tile.x0 + tx) + iota()) + splat(0.5f), py);
  }
  return true;
}

// Row ty of a tile of Phong triangles without textures (TriangleChunk::lit_alike), its groups'
// interpolated colours and normals (phongInputsMixed's operations) handed to add(tx, color,
// normal) for the lights; false, with nothing handed, where fillRowRuns found a triangle the row
// cannot take so.
template <typename Add>
TESSERA_LANES_INLINE bool prepareLitRow(const TileVisibility& tile, int ty,
                                        const ShadeTriangle* const records[],
                                        const ShadeExtras* const extras[], Add&& add) {
  return byRowRuns<RunCorners::kNormal>(
      tile, ty, records, extras,
      [&](int tx, I32x8, RunFields f, RunFields n, const Material*, F32x8 px, F32x8 py)
          __attribute__((always_inline)) {
            F32x8 b0, b1, b2;
            plainBarycentrics(f, px, py, b0, b1, b2);
            const Vec3x8 color = plainColor(f, b1, b2);
            F32x8 corner[9];
            for (int k = 0; k < 9; ++k) corner[k] = n[k];
            add(tx, color, interpolate9(corner, b0, b1, b2));
          });
}

// Row ty of a plain tile (shadePlainRow's), its groups' interpolated vertex colours (shadeMixed's
// operations) handed to put(tx, color); false, with nothing handed, where some triangle is solid
// (shadePlainRow's shortcuts then take it).
template <typename Put>
TESSERA_LANES_INLINE bool preparePlainRow(const TileVisibility& tile, int ty,
                                          const ShadeTriangle* const records[], Put&& put) {
  return byRowRuns<RunCorners::kNone>(
      tile, ty, records, nullptr,
      [&](int tx, I32x8, RunFields f, RunFields, const Material*, F32x8 px, F32x8 py)
          __attribute__((always_inline)) {
            F32x8 b0, b1, b2;
            plainBarycentrics(f, px, py, b0, b1, b2);
            put(tx, plainColor(f, b1, b2));
          });
}

// The textured groups of row ty (prepareTexturedFields) into groups[]; their number, or -1 where
// fillRowRuns found the row not all textured alike. `alike`: fillRowRuns'.
TESSERA_LANES_INLINE int prepareTexturedRow(const TileVisibility& tile, int ty,
                                            const ShadeTriangle* const records[],
                                            const ShadeExtras* const extras[],
                                            TexturedGroup groups[], const Material* alike) {
  int count = 0;
  const bool taken = byRowRuns<RunCorners::kUv>(
      tile, ty, records, extras,
      [&](int tx, I32x8 covered, RunFields f, RunFields uv, const Material* material, F32x8 px,
          F32x8 py) __attribute__((always_inline)) {
        TexturedGroup& group = groups[count++];
        prepareTexturedFields(f, uv, material, covered, px, py, group);
        group.tx = tx;
      },
      alike);
  return taken ? count : -1;
}
#endif

}  // namespace
}  // namespace tessera::render
