// Eight pixels of several triangles shaded in one evaluation, for the shading kernel
// (shade_kernel.h) and the resolve of multisampled pixels (fragment_queue.h): each lane's fields
// are loaded from its own triangle's records, eight records at a time, and transposed into lanes
// (untextured: shadeMixed; textured alike without per-pixel lighting: prepareTexturedGroup; lit per
// pixel alike: shadeLitMixed), each lane's records found by laneRecords. The same float operations
// per lane as shadeLanes (shade_lanes.h), so the same bits.
#pragma once

#include <cstddef>
#include <cstdint>

#include "render/shade_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

// Each lane's triangle in lanes (lanes outside `covered` take `first`'s): its chunk and its index
// in that chunk's records.
struct LaneKeys {
  alignas(32) uint32_t chunk[8];
  I32x8 local;
};
TESSERA_LANES_INLINE LaneKeys laneKeys(I32x8 keys, I32x8 covered, uint32_t first) {
  const I32x8 owner = select(covered, keys, splat(static_cast<int32_t>(first)));
  LaneKeys k;
  store(k.chunk, shiftRight(owner, kChunkKeyShift) & splat(int32_t{kMaxChunks - 1}));
  k.local = owner & splat(static_cast<int32_t>((1u << kLocalKeyBits) - 1));
  return k;
}

// laneKeys where the lanes outside `valid` (at least one lane) borrow the first valid lane's key.
TESSERA_LANES_INLINE LaneKeys laneKeys(I32x8 keys, I32x8 valid) {
  return laneKeys(keys, valid, static_cast<uint32_t>(lane(keys, firstLane(valid))));
}

// Each lane's record of the chunks' arrays `chunk_records` (each chunk's first record): byte
// offsets (32-bit: kMaxTrianglesPerChunk) are formed in lanes, then read back one lane at a time
// (per lane in scalar code, the textured frame's shading took 10% more instructions).
template <typename Record>
TESSERA_LANES_INLINE void laneRecords(const LaneKeys& k, const Record* const chunk_records[],
                                      const Record* lanes[8]) {
  static_assert(uint64_t{kMaxTrianglesPerChunk} * sizeof(Record) <= uint64_t{0xffffffffu},
                "a chunk's records span more than a 32-bit byte offset reaches");
  alignas(32) uint32_t lane_offset[8];
  store(lane_offset, k.local * splat(static_cast<int32_t>(sizeof(Record))));
  for (int l = 0; l < 8; ++l)
    lanes[l] = reinterpret_cast<const Record*>(
        reinterpret_cast<const char*>(chunk_records[k.chunk[l]]) + lane_offset[l]);
}

// Each lane's ShadeTriangle and ShadeExtras for eight pixels of keys `keys` (laneRecords).
struct MixedRecords {
  const ShadeTriangle* lanes[8];
  const ShadeExtras* extras[8];
};
TESSERA_LANES_INLINE MixedRecords mixedRecords(I32x8 keys, I32x8 covered, uint32_t first,
                                               const ShadeTriangle* const records[],
                                               const ShadeExtras* const extras[]) {
  const LaneKeys k = laneKeys(keys, covered, first);
  MixedRecords r;
  laneRecords(k, records, r.lanes);
  laneRecords(k, extras, r.extras);
  return r;
}

// The float fields from x0 to color[2], in order: what an untextured flat, Gouraud or unlit pixel
// reads. shadeMixed loads them from eight records at once.
constexpr int kPlainFields = 18;
static_assert(offsetof(ShadeTriangle, color) == offsetof(ShadeTriangle, x0) + 9 * sizeof(float) &&
                  sizeof(ShadeTriangle::color) == 9 * sizeof(float) &&
                  offsetof(ShadeTriangle, sdy) == offsetof(ShadeTriangle, x0) + 8 * sizeof(float),
              "shadeMixed reads x0..sdy and color[3] as 18 consecutive floats");
static_assert(sizeof(ShadeTriangle) >= offsetof(ShadeTriangle, x0) + 16 * sizeof(float),
              "shadeMixed reads 16 floats from x0 eight at a time");

// The kPlainFields floats of eight records, transposed into lanes, each handed to put(k, lanes) as
// it is formed: k = 0..8 x0, y0, inv_w0, p1dx, p1dy, p2dx, p2dy, sdx, sdy, then 9..17
// color[0..2].xyz. (A caller that stores them elsewhere takes them so: gathered in an array first,
// the AVX2 kernels kept the array on the stack and copied it in a loop of its own.)
template <typename Put>
TESSERA_LANES_INLINE void loadPlainFieldsBy(const ShadeTriangle* const records[8], Put&& put) {
  for (int block = 0; block < 2; ++block) {
    F32x8 f[8];
    for (int l = 0; l < 8; ++l) f[l] = load<F32x8>(&records[l]->x0 + block * 8);
    transpose8x8(f);
    for (int k = 0; k < 8; ++k) put(block * 8 + k, f[k]);
  }
  const float* last_two[8];
  for (int l = 0; l < 8; ++l) last_two[l] = &records[l]->x0 + 16;
  F32x8 a, b;
  loadPairs(last_two, a, b);
  put(16, a);
  put(17, b);
}
// The same into f[0..17].
TESSERA_LANES_INLINE void loadPlainFields(const ShadeTriangle* const records[8],
                                          F32x8 f[kPlainFields]) {
  loadPlainFieldsBy(
      records, [&](int k, F32x8 v) __attribute__((always_inline)) { f[k] = v; });
}

// BroadcastFields (texture_lanes.h) of two records a and b, b's in the lanes of `in_b` and a's in
// the others: the values loadPlainFields (uvCorners8) gives for such lanes, picked from two
// broadcasts.
struct PickedFields {
  const float *a, *b;
  I32x8 in_b;
  TESSERA_LANES_INLINE F32x8 operator[](int k) const {
    return select(in_b, splat(b[k]), splat(a[k]));
  }
};

// Fields 9..17 (the corners' colours) of eight records in lanes, from the transposed second block
// of eight fields (`block`: fields 8..15) and the last two (y, z: color[2].y and .z).
struct ColourFields {
  const F32x8* block;
  F32x8 y, z;
  TESSERA_LANES_INLINE F32x8 operator[](int k) const {
    return k < 16 ? block[k - 8] : k == 16 ? y : z;
  }
};

// Perspective-correct barycentrics of the lanes' triangles (loadPlainFields' f, or the fields of
// BroadcastFields or PickedFields) at (px, py), with shadeLanes' operations.
// In two steps, for a caller that has the fields x0..sdx (f[0..7]) before sdy (f[8]):
// barycentricSums from the first eight, then finishBarycentrics with sdy.
struct BarycentricSums {
  F32x8 dy, s, n1, n2;  // s: inv_w0 + sdx dx; n1, n2: b1's and b2's numerators
};
template <typename Fields>
TESSERA_LANES_INLINE BarycentricSums barycentricSums(Fields f, F32x8 px, F32x8 py) {
  const F32x8 dx = px - f[0];
  const F32x8 dy = py - f[1];
  return {dy, f[2] + f[7] * dx, f[3] * dx + f[4] * dy, f[5] * dx + f[6] * dy};
}
TESSERA_LANES_INLINE void finishBarycentrics(const BarycentricSums& sums, F32x8 sdy, F32x8& b0,
                                             F32x8& b1, F32x8& b2) {
  const F32x8 inv_s = splat(1.0f) / (sums.s + sdy * sums.dy);
  b1 = sums.n1 * inv_s;
  b2 = sums.n2 * inv_s;
  b0 = splat(1.0f) - b1 - b2;
}
template <typename Fields>
TESSERA_LANES_INLINE void plainBarycentrics(Fields f, F32x8 px, F32x8 py, F32x8& b0, F32x8& b1,
                                            F32x8& b2) {
  finishBarycentrics(barycentricSums(f, px, py), f[8], b0, b1, b2);
}

// A float3[3] of the lanes' triangles (v[3 k + c]: component c of corner k) at barycentrics b0,
// b1, b2: interpolate's operations with each lane's own corners.
TESSERA_LANES_INLINE Vec3x8 interpolate9(const F32x8 v[9], F32x8 b0, F32x8 b1, F32x8 b2) {
  return {v[0] * b0 + v[3] * b1 + v[6] * b2, v[1] * b0 + v[4] * b1 + v[7] * b2,
          v[2] * b0 + v[5] * b1 + v[8] * b2};
}

// Fields whose 12..17 hold the corners' colours 1 and 2 less corner 0's instead of the colours
// (the row runs' columns: RunFields) say so by a kColourDifferences of true.
template <typename Fields>
concept ColourDifferences = Fields::kColourDifferences;
// The interpolated vertex colours of the lanes' triangles at barycentrics b1, b2:
// interpolateColor's operations with each lane's own corners (c0 + (c1 - c0) b1 + (c2 - c0) b2,
// the differences taken from the fields where they hold them).
template <typename Fields>
TESSERA_LANES_INLINE Vec3x8 plainColor(Fields f, F32x8 b1, F32x8 b2) {
  if constexpr (ColourDifferences<Fields>) {
    return {f[9] + f[12] * b1 + f[15] * b2, f[10] + f[13] * b1 + f[16] * b2,
            f[11] + f[14] * b1 + f[17] * b2};
  } else {
    return {f[9] + (f[12] - f[9]) * b1 + (f[15] - f[9]) * b2,
            f[10] + (f[13] - f[10]) * b1 + (f[16] - f[10]) * b2,
            f[11] + (f[14] - f[11]) * b1 + (f[17] - f[11]) * b2};
  }
}

// Whether each of eight records' corners share one colour (ShadeTriangle::solid). The first
// alone decides most groups of meshes lit per vertex, whose triangles are seldom solid.
TESSERA_LANES_INLINE bool allSolid(const ShadeTriangle* const records[8]) {
  if (!records[0]->solid) return false;
  bool solid = true;
  for (int l = 1; l < 8; ++l) solid &= records[l]->solid;
  return solid;
}

// The colours of eight solid records (allSolid): each lane's color[0], which interpolateColor
// gives at any pixel of its triangle. Four loads and a transpose, where the barycentrics took
// eighteen fields transposed and a division.
TESSERA_LANES_INLINE Vec3x8 solidColors(const ShadeTriangle* const records[8]) {
  F32x8 c[4];  // color[0] and the next float of lanes l and l + 4
  for (int l = 0; l < 4; ++l)
    c[l] = load2x4<F32x8>(&records[l]->color[0].x, &records[l + 4]->color[0].x);
  transpose4x4Halves(c);  // c[k]: channel k of lanes 0-3, then of lanes 4-7
  return {c[0], c[1], c[2]};
}

// Eight pixels owned by several triangles, all untextured and not Phong-shaded (colour = the
// interpolated vertex colours): lane l is shaded from its own triangle's record, whose fields
// are loaded eight records at a time and transposed into lanes. The same operations per lane as
// shadeLanes, so the same bits; one evaluation instead of one per triangle. Where every lane's
// triangle is solid (flat faces under directional light) its colour is that of every pixel, and
// the barycentrics are left out.
TESSERA_LANES_INLINE Vec3x8 shadeMixed(const ShadeTriangle* const records[8], F32x8 px, F32x8 py) {
  if (allSolid(records)) return solidColors(records);
  F32x8 f[kPlainFields];
  loadPlainFields(records, f);
  F32x8 b0, b1, b2;
  plainBarycentrics(f, px, py, b0, b1, b2);
  return plainColor(f, b1, b2);
}

// Whether a pixel of triangle t gets its colour from the albedo texture and the interpolated
// vertex colours alone (textured flat, Gouraud or unlit): what prepareTexturedGroup takes.
TESSERA_LANES_INLINE bool texturedPlain(const ShadeTriangle& t) {
  return t.has_uv && t.shading != Shading::kPhong && t.shading != Shading::kPbr;
}

// The texture coordinates of the lanes' triangles' corners in UV set `set`, transposed into lanes:
// u0, v0, u1, v1, u2, v2 (eight floats read from each record: the set's six and two after them).
static_assert(offsetof(ShadeExtras, uv1) == offsetof(ShadeExtras, uv) + 6 * sizeof(float) &&
                  sizeof(ShadeExtras) >= offsetof(ShadeExtras, uv1) + 8 * sizeof(float),
              "uvCorners8 reads eight floats from either UV set");
TESSERA_LANES_INLINE void uvCorners8(const ShadeExtras* const extras[8], int set, F32x8 c[8]) {
  for (int l = 0; l < 8; ++l) c[l] = load<F32x8>(&(set == 1 ? extras[l]->uv1 : extras[l]->uv)->x);
  transpose8x8(c);
}

// Eight pixels owned by several triangles of one textured material that are all texturedPlain
// (colour = interpolated vertex colours x albedo), up to the texture filter: each lane's
// barycentrics and texture coordinates come from its own triangle's records (loaded eight at a
// time and transposed), and the texture is filtered once for the eight lanes instead of once per
// triangle (filterTexturedGroup). The shading kernel filters a row's groups together, after the
// row's other work: each filter is a chain of dependent gathers, and several side by side keep the
// core busy.
struct TexturedGroup {
  Uv8 uv, right, down;  // right and down: at the next pixel centres, set only where needsLod
  Vec3x8 color;         // the interpolated vertex colours
  I32x8 covered;
  const Material* material;
  int tx;  // the first pixel's column in the tile
};

// The group's texture coordinates (in the UV set and at the footprint that `material`'s sampler
// reads) and vertex colours, from its triangles' fields in lanes (f: loadPlainFields', corner:
// uvCorners8's).
template <typename Fields, typename Corners>
TESSERA_LANES_INLINE void prepareTexturedFields(Fields f, Corners corner, const Material* material,
                                                I32x8 covered, F32x8 px, F32x8 py,
                                                TexturedGroup& group) {
  F32x8 b0, b1, b2;
  plainBarycentrics(f, px, py, b0, b1, b2);
  group.uv = uvAt8(corner, b0, b1, b2);
  if (needsLod(*material->albedo, material->sampler)) {
    F32x8 r0, r1, r2, d0, d1, d2;
    plainBarycentrics(f, px + splat(1.0f), py, r0, r1, r2);
    plainBarycentrics(f, px, py + splat(1.0f), d0, d1, d2);
    group.right = uvAt8(corner, r0, r1, r2);
    group.down = uvAt8(corner, d0, d1, d2);
  }
  group.color = plainColor(f, b1, b2);
  group.covered = covered;
  group.material = material;
}

// Whether triangle t's eight-lane texture filter is sampleTexture8's.
TESSERA_LANES_INLINE bool texturedGroupApplies(const ShadeTriangle& t) {
  return texturedPlain(t) && texture8Applies(*t.material->albedo, t.material->sampler);
}

// prepareTexturedFields for eight pixels of several triangles, each lane's fields loaded from its
// own records; false, with `group` untouched, where the group cannot be shaded so (mixed
// materials or shading, a filter sampleTexture8 does not take). Lanes outside `covered` hold a
// covered lane's records.
TESSERA_LANES_INLINE bool prepareTexturedGroup(const ShadeTriangle* const records[8],
                                               const ShadeExtras* const extras[8], I32x8 covered,
                                               F32x8 px, F32x8 py, TexturedGroup& group) {
  const Material* material = records[0]->material;
  for (int l = 0; l < 8; ++l)
    if (records[l]->material != material || !texturedPlain(*records[l])) return false;
  if (!texture8Applies(*material->albedo, material->sampler)) return false;
  if (needsLod(*material->albedo, material->sampler)) {
    F32x8 f[kPlainFields], corner[8];
    loadPlainFields(records, f);
    uvCorners8(extras, material->sampler.texcoord, corner);
    prepareTexturedFields(f, corner, material, covered, px, py, group);
    return true;
  }
  // prepareTexturedFields' operations with each block of eight fields used before the next is
  // loaded: with all 26 in lanes at once, the AVX2 kernels (sixteen registers) stored each
  // transposed field to the stack twice.
  F32x8 block[8];
  for (int l = 0; l < 8; ++l) block[l] = load<F32x8>(&records[l]->x0);
  transpose8x8(block);  // x0, y0, inv_w0, p1dx, p1dy, p2dx, p2dy, sdx
  const BarycentricSums sums = barycentricSums(block, px, py);
  for (int l = 0; l < 8; ++l) block[l] = load<F32x8>(&records[l]->x0 + 8);
  transpose8x8(block);  // sdy, color[0].xyz, color[1].xyz, color[2].x
  F32x8 b0, b1, b2;
  finishBarycentrics(sums, block[0], b0, b1, b2);
  const float* last_two[8];
  for (int l = 0; l < 8; ++l) last_two[l] = &records[l]->x0 + 16;
  ColourFields colours{block, {}, {}};
  loadPairs(last_two, colours.y, colours.z);
  group.color = plainColor(colours, b1, b2);
  uvCorners8(extras, material->sampler.texcoord, block);
  group.uv = uvAt8(block, b0, b1, b2);
  group.covered = covered;
  group.material = material;
  return true;
}

// prepareTexturedFields for eight pixels of one triangle t (texturedGroupApplies), its fields
// broadcast: the same values in every lane, so the same bits as shadeLanes.
TESSERA_LANES_INLINE void prepareTexturedGroup(const ShadeTriangle& t, const ShadeExtras& e,
                                               I32x8 covered, F32x8 px, F32x8 py,
                                               TexturedGroup& group) {
  prepareTexturedFields(BroadcastFields{&t.x0}, BroadcastFields{&uvSet(e, t.material->sampler)->x},
                        t.material, covered, px, py, group);
}

// prepareTexturedFields for eight pixels of two triangles a and b of one material (each
// texturedGroupApplies), the lanes of `in_b` b's and the others a's: each lane's fields picked from
// its triangle's record, the values loadPlainFields and uvCorners8 give, so the same bits.
TESSERA_LANES_INLINE void prepareTexturedGroup(const ShadeTriangle& a, const ShadeExtras& ea,
                                               const ShadeTriangle& b, const ShadeExtras& eb,
                                               I32x8 in_b, I32x8 covered, F32x8 px, F32x8 py,
                                               TexturedGroup& group) {
  prepareTexturedFields(
      PickedFields{&a.x0, &b.x0, in_b},
      PickedFields{&uvSet(ea, a.material->sampler)->x, &uvSet(eb, b.material->sampler)->x, in_b},
      a.material, covered, px, py, group);
}

// The prepared group's colour from its filtered albedo: the vertex colours times the albedo,
// tone-mapped.
TESSERA_LANES_INLINE Vec3x8 texturedColour(const TexturedGroup& group, const F32x8 albedo[3],
                                           const LightRig& lights) {
  Vec3x8 c = group.color;
  c = {c.x * albedo[0], c.y * albedo[1], c.z * albedo[2]};
  if (lights.tone.active()) toneMap8(lights.tone, c.x, c.y, c.z);
  return c;
}

// The prepared group's colour: its vertex colours times the filtered albedo, tone-mapped, the
// albedo read as `reads` (textureReads of the group's material's albedo and sampler) says. The
// same operations per lane as shadeLanes, so the same bits. False, with `color` untouched, where a
// lane's coordinates are beyond sampleTexture8's reach: the caller shades triangle by triangle.
TESSERA_LANES_INLINE bool filterTexturedGroup(const TexturedGroup& group, const TextureReads& reads,
                                              const LightRig& lights, Vec3x8& color) {
  F32x8 albedo[4];
  if (!sampleTexture8(reads, group.covered, group.uv, reads.lod ? group.right : group.uv,
                      reads.lod ? group.down : group.uv, 3, albedo))
    return false;
  color = texturedColour(group, albedo, lights);
  return true;
}

// filterTexturedGroup of one group alone.
TESSERA_LANES_INLINE bool filterTexturedGroup(const TexturedGroup& group, const LightRig& lights,
                                              Vec3x8& color) {
  const Material& m = *group.material;
  return filterTexturedGroup(group, textureReads(*m.albedo, m.sampler), lights, color);
}

static_assert(sizeof(float3) == 3 * sizeof(float), "corners9 reads a float3[3] as nine floats");

// A float3[3] (nine consecutive floats) of eight records, transposed into lanes as interpolate9
// takes them.
TESSERA_LANES_INLINE void corners9(const float* const at[8], F32x8 v[9]) {
  for (int l = 0; l < 8; ++l) v[l] = load<F32x8>(at[l]);
  transpose8x8(v);
  alignas(32) float last[8];
  for (int l = 0; l < 8; ++l) last[l] = at[l][8];
  v[8] = load<F32x8>(last);
}

// One of the float3[3] fields of eight ShadeExtras (normal or world), in lanes.
using ExtrasCorners = float3 (ShadeExtras::*)[3];
TESSERA_LANES_INLINE void extrasCorners(const ShadeExtras* const extras[8], ExtrasCorners field,
                                        F32x8 v[9]) {
  const float* at[8];
  for (int l = 0; l < 8; ++l) at[l] = &(extras[l]->*field)[0].x;
  corners9(at, v);
}

// Whether a pixel of triangle t is lit per pixel from its interpolated normal and vertex colours
// alone (Phong, or PBR whose material reads no map through this mesh): what shadeLitMixed takes.
TESSERA_LANES_INLINE bool litPlain(const ShadeTriangle& t) {
  if (t.has_uv) return false;
  if (t.shading == Shading::kPhong) return true;
  if (t.shading != Shading::kPbr) return false;
  const Material& m = *t.material;
  return (t.pbr_flags & kPbrUv) == 0 ||
         !(m.normal || m.metallic_roughness || m.occlusion || m.emissive);
}

// Whether the lanes' triangles are all litPlain with the first's shading (and, for PBR, its
// material): what shadeLitMixed and shadeLitAt take.
TESSERA_LANES_INLINE bool litAlike(const ShadeTriangle* const records[8]) {
  const ShadeTriangle& t = *records[0];
  const bool pbr = t.shading == Shading::kPbr;
  for (int l = 0; l < 8; ++l) {
    const ShadeTriangle& r = *records[l];
    if (r.shading != t.shading || (pbr && r.material != t.material) || !litPlain(r)) return false;
  }
  return true;
}

// The colours of the lanes' triangles (litAlike; f: loadPlainFields') at barycentrics b0, b1, b2,
// each lane's normals and world positions from its own records: shadeLanes' operations per lane.
TESSERA_LANES_INLINE Vec3x8 shadeLitAt(const ShadeTriangle& t, const F32x8 f[kPlainFields],
                                       const ShadeExtras* const extras[8], I32x8 covered,
                                       const LightRig& lights, F32x8 b0, F32x8 b1, F32x8 b2) {
  const bool pbr = t.shading == Shading::kPbr;
  F32x8 corner[9];
  Vec3x8 c = plainColor(f, b1, b2);
  extrasCorners(extras, &ShadeExtras::normal, corner);
  const Vec3x8 n = normalize8(interpolate9(corner, b0, b1, b2));
  Vec3x8 p{};
  if (pbr || lights.local || lights.shadows) {
    extrasCorners(extras, &ShadeExtras::world, corner);
    p = interpolate9(corner, b0, b1, b2);
  }
  if (pbr) {
    // shadePbrLanes without maps: the material's factors.
    const Material& m = *t.material;
    const Vec3x8 emissive{splat(m.emissive_factor.x), splat(m.emissive_factor.y),
                          splat(m.emissive_factor.z)};
    c = shadePbr8(lights, pbrLobes8(c, splat(m.metallic), splat(m.roughness)), splat(1.0f),
                  emissive, n, p, covered);
  } else {
    const Vec3x8 e = irradiance8(lights, n, p, covered);
    c = {c.x * e.x, c.y * e.y, c.z * e.z};
  }
  if (lights.tone.active()) toneMap8(lights.tone, c.x, c.y, c.z);
  return c;
}

// Eight pixels owned by several triangles that are all litPlain with the same shading (and, for
// PBR, the same material): each lane's barycentrics, colours, normals and world positions come from
// its own triangle's records (loaded eight at a time and transposed), and the lights are evaluated
// once for the eight lanes instead of once per triangle. The same operations per lane as
// shadeLanes, so the same bits. False, with `color` untouched, where that does not apply; lanes
// outside `covered` hold a covered lane's records (and read no shadow map). `alike`: the caller
// knows the records litAlike (TriangleChunk::lit_alike), and they are not looked at for that.
TESSERA_LANES_INLINE bool shadeLitMixed(const ShadeTriangle* const records[8],
                                        const ShadeExtras* const extras[8], I32x8 covered,
                                        const LightRig& lights, F32x8 px, F32x8 py, Vec3x8& color,
                                        bool alike = false) {
  if (!alike && !litAlike(records)) return false;
  F32x8 f[kPlainFields];
  loadPlainFields(records, f);
  F32x8 b0, b1, b2;
  plainBarycentrics(f, px, py, b0, b1, b2);
  color = shadeLitAt(*records[0], f, extras, covered, lights, b0, b1, b2);
  return true;
}

// shadeLitMixed's work for Phong records (litAlike) up to the lights: each lane's interpolated
// vertex colour and interpolated (not yet unit) normal, which finishPhong8 lights where the rig
// needs no world positions.
TESSERA_LANES_INLINE void phongInputsMixed(const ShadeTriangle* const records[8],
                                           const ShadeExtras* const extras[8], F32x8 px, F32x8 py,
                                           Vec3x8& color, Vec3x8& normal) {
  F32x8 f[kPlainFields];
  loadPlainFields(records, f);
  F32x8 b0, b1, b2;
  plainBarycentrics(f, px, py, b0, b1, b2);
  color = plainColor(f, b1, b2);
  F32x8 corner[9];
  extrasCorners(extras, &ShadeExtras::normal, corner);
  normal = interpolate9(corner, b0, b1, b2);
}

}  // namespace
}  // namespace tessera::render
