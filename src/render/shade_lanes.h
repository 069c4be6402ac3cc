// Shading of eight lanes at a time, for the shading kernel (shade_kernel.h) and the resolve of
// multisampled pixels (fragment_queue.h, ray_queue.h); written once against eight-lane types
// (simd_lanes.h) and compiled per instruction set (kernels_<isa>.cpp). Each lane does exactly the
// float operations, in exactly the order, that shading one pixel takes, so every variant gives the
// same bits. Texture samples are taken eight lanes at a time (texture_lanes.h); nearest ones, and
// lanes outside its common case, lane by lane through the one sampleAlbedo. The interpolation and
// lights are light_lanes.h's, glTF's metallic-roughness shading pbr_lanes.h's.
#pragma once

#include <algorithm>
#include <cstddef>

#include <tessera/scene/color.h>

#include "render/light_lanes.h"
#include "render/pbr_lanes.h"
#include "render/shade.h"
#include "render/simd_lanes.h"
#include "render/texture_lanes.h"
#include "render/tone_lanes.h"
#include "render/vec3_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

// Eight encodeSrgb8s (tessera/scene/color.h), the same codes lane by lane: where a gather is one
// instruction (AVX2, AVX-512), one read of kSrgbEncodeTable and a comparison, a third of the
// polynomial's operations; else encodeSrgb8's own operations.
TESSERA_LANES_INLINE I32x8 encodeSrgb8x8(F32x8 linear) {
  const F32x8 zero = splat(0.0f), one = splat(1.0f);
  // Clamped to [0, 1], NaN to 0: (x > 0 ? x : 0), then (< 1 ? : 1).
  const F32x8 c = lowerOf(upperOf(linear, zero), one);
  const I32x8 bits = bitsOf(c);
#if defined(__AVX2__) && !defined(TESSERA_SIMD_SCALAR)
  using B = SrgbEncodeBuckets;
  const I32x8 bucket = maximum(shiftRight(bits, B::kShift) - splat(B::kFirst - 1), splat(0));
  const I32x8 entry = gatherWords(kSrgbEncodeTable.data(), bucket);
  const I32x8 rest = bits & splat((int32_t{1} << B::kShift) - 1);
  // The first code, plus one unless the rest is below the next code's (lessThan: -1).
  return (entry & splat(int32_t{0xff})) + splat(int32_t{1}) + lessThan(rest, shiftRight(entry, 8));
#else
  // Lanes on the linear segment compute the curve too (from c's exponent, which may be below
  // -9 there: the index is clamped to the table) and take the line.
  const I32x8 e9 = shiftRight(bits, 23) - splat(int32_t{127 - 9});
  const I32x8 index = maximum(e9, splat(int32_t{0}));
  const F32x8 x = fromBits((bits & splat(int32_t{0x7fffff})) | splat(int32_t{0x3f800000})) - one;
  const float* k = SrgbEncode::kPoly;
  const F32x8 p =
      (((splat(k[4]) * x + splat(k[3])) * x + splat(k[2])) * x + splat(k[1])) * x + splat(k[0]);
  F32x8 curve = lookup16(SrgbEncode::kScale, index) * p - splat(SrgbEncode::kOffset);
  curve = lowerOf(curve, splat(255.0f));
  const F32x8 code = select(lessThan(splat(SrgbEncode::kLinearEnd), c), curve,
                            c * splat(SrgbEncode::kLinearFactor));
  return truncate(code + splat(0.5f));
#endif
}

#if defined(TESSERA_LANES16)
// encodeSrgb8x8 for sixteen lanes, by the table.
TESSERA_LANES_INLINE I32x16 encodeSrgb8x16(F32x16 linear) {
  using B = SrgbEncodeBuckets;
  const F32x16 zero = splat16(0.0f), one = splat16(1.0f);
  const F32x16 c = lowerOf16(upperOf16(linear, zero), one);
  const I32x16 bits = reinterpret_cast<I32x16>(c);
  const I32x16 above = (bits >> B::kShift) - (B::kFirst - 1);
  const I32x16 bucket = above > 0 ? above : 0;
  // The masked form with every lane: the plain one reads an undefined source (GCC 12 warns).
  const I32x16 entry = reinterpret_cast<I32x16>(
      _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), 0xffff, reinterpret_cast<__m512i>(bucket),
                                  kSrgbEncodeTable.data(), sizeof(uint32_t)));
  const I32x16 rest = bits & ((int32_t{1} << B::kShift) - 1);
  return (entry & 0xff) - (rest >= (entry >> 8));  // a true comparison is -1
}
#endif

// The albedo of the lanes of `mask` at barycentrics b0, b1, b2 through sampleTexture8; `footprint`
// gives the barycentrics at the next pixel centres right and down (false: it cannot, and trilinear
// filtering is left to the caller). False, with nothing computed, when the caller must sample lane
// by lane.
template <typename Footprint>
TESSERA_LANES_INLINE bool sampleAlbedo8(const ShadeTriangle& t, const ShadeExtras& e, I32x8 mask,
                                        F32x8 b0, F32x8 b1, F32x8 b2, Footprint footprint,
                                        Vec3x8& albedo) {
  const Material& m = *t.material;
  const Texture& texture = *m.albedo;
  if (!texture8Applies(texture, m.sampler)) return false;
  // The corners in the sampler's set.
  const BroadcastFields corners{&uvSet(e, m.sampler)->x};
  const Uv8 uv = uvAt8(corners, b0, b1, b2);
  Uv8 right = uv, down = uv;
  if (needsLod(texture, m.sampler)) {
    Vec3x8 br, bd;
    if (!footprint(br, bd)) return false;
    right = uvAt8(corners, br.x, br.y, br.z);
    down = uvAt8(corners, bd.x, bd.y, bd.z);
  }
  F32x8 out[4];
  if (!sampleTexture8(texture, m.sampler, mask, uv, right, down, 3, out)) return false;
  albedo = {out[0], out[1], out[2]};
  return true;
}

// Shades the lanes of `mask` from triangle t at barycentrics b0, b1, b2, into `color` and, when
// asked, `normal`; the other lanes keep what they hold. When the eight-lane texture filter does not
// take the lanes, they get their albedo from albedo_lane(l, Barycentrics) one at a time;
// footprint(right, down) gives the barycentrics at the next pixel centres right and down for the
// eight-lane filter's level of detail (false: it has none, and the lanes go one at a time). PBR
// maps come from texture_lane(l, Barycentrics, texture, sampler).
template <typename AlbedoLane, typename Footprint, typename TextureLane>
TESSERA_LANES_INLINE void shadeLanesAt(const ShadeTriangle& t, const ShadeExtras& e,
                                       const LightRig& lights, bool want_normals, F32x8 b0,
                                       F32x8 b1, F32x8 b2, I32x8 mask, Vec3x8& color,
                                       Vec3x8& normal, AlbedoLane albedo_lane, Footprint footprint,
                                       TextureLane texture_lane) {
  Vec3x8 c = interpolateColor(t.color, b1, b2);
  Vec3x8 albedo;
  if (t.has_uv && sampleAlbedo8(t, e, mask, b0, b1, b2, footprint, albedo)) {
    c = {c.x * albedo.x, c.y * albedo.y, c.z * albedo.z};
  } else if (t.has_uv) {
    for (int l = 0; l < 8; ++l) {
      if (!lane(mask, l)) continue;
      const float3 a = albedo_lane(l, Barycentrics{lane(b0, l), lane(b1, l), lane(b2, l)});
      setLane(c.x, l, lane(c.x, l) * a.x);
      setLane(c.y, l, lane(c.y, l) * a.y);
      setLane(c.z, l, lane(c.z, l) * a.z);
    }
  }
  if (t.shading == Shading::kPbr) {
    Vec3x8 n;
    c = shadePbrLanes(t, e, lights, b0, b1, b2, mask, c, n, texture_lane);
    if (want_normals)
      normal = {select(mask, n.x, normal.x), select(mask, n.y, normal.y),
                select(mask, n.z, normal.z)};
  } else if (t.shading == Shading::kPhong || (want_normals && t.shading != Shading::kFlat)) {
    const Vec3x8 n = normalize8(interpolate(e.normal, b0, b1, b2));
    if (t.shading == Shading::kPhong) {
      const Vec3x8 p = lights.local || lights.shadows ? interpolate(e.world, b0, b1, b2) : Vec3x8{};
      const Vec3x8 e = irradiance8(lights, n, p, mask);
      c = {c.x * e.x, c.y * e.y, c.z * e.z};
    }
    if (want_normals)
      normal = {select(mask, n.x, normal.x), select(mask, n.y, normal.y),
                select(mask, n.z, normal.z)};
  } else if (want_normals) {
    normal = {select(mask, splat(e.normal[0].x), normal.x),
              select(mask, splat(e.normal[0].y), normal.y),
              select(mask, splat(e.normal[0].z), normal.z)};
  }
  if (lights.tone.active()) toneMap8(lights.tone, c.x, c.y, c.z);
  color = {select(mask, c.x, color.x), select(mask, c.y, color.y), select(mask, c.z, color.z)};
}

// Triangle t's barycentrics (b.x, b.y, b.z) at pixel centres (x, y), exactly as barycentricsAt.
TESSERA_LANES_INLINE void barycentrics8(const ShadeTriangle& t, F32x8 x, float y, Vec3x8& b) {
  const F32x8 dx = x - splat(t.x0);
  const float dy = y - t.y0;
  const F32x8 inv_s = splat(1.0f) / (splat(t.inv_w0) + splat(t.sdx) * dx + splat(t.sdy * dy));
  b.y = (splat(t.p1dx) * dx + splat(t.p1dy * dy)) * inv_s;
  b.z = (splat(t.p2dx) * dx + splat(t.p2dy * dy)) * inv_s;
  b.x = splat(1.0f) - b.y - b.z;
}

// Whether the lights of a Phong pixel can wait for finishPhong8: no world positions (no point or
// spot light, no shadow maps) and no normal AOV.
TESSERA_LANES_INLINE bool phongDeferrable(const LightRig& lights, bool want_normals) {
  return !want_normals && !lights.local && !lights.shadows;
}

// An untextured Phong triangle t's work at pixel centres (px, py) up to the lights (shadeLanes'
// operations): its interpolated vertex colour and interpolated (not yet unit) normal.
TESSERA_LANES_INLINE void phongInputs(const ShadeTriangle& t, const ShadeExtras& e, F32x8 px,
                                      float py, Vec3x8& color, Vec3x8& normal) {
  Vec3x8 b;
  barycentrics8(t, px, py, b);
  color = interpolateColor(t.color, b.y, b.z);
  normal = interpolate(e.normal, b.x, b.y, b.z);
}

// The rest of a Phong pixel's shading (phongDeferrable): the normal made unit, the lights, the
// tone curve; shadeLanes' and shadeLitMixed's operations, so the same bits.
TESSERA_LANES_INLINE Vec3x8 finishPhong8(const LightRig& lights, const Vec3x8& color,
                                         const Vec3x8& normal) {
  const Vec3x8 e = irradiance8(lights, normalize8(normal), Vec3x8{}, splat(int32_t{0}));
  Vec3x8 c{color.x * e.x, color.y * e.y, color.z * e.z};
  if (lights.tone.active()) toneMap8(lights.tone, c.x, c.y, c.z);
  return c;
}

#if defined(TESSERA_LANES16)
// finishPhong8 for two groups side by side in sixteen lanes (AVX-512), the same operations per
// lane, without a tone curve: on this host a division or square root of sixteen lanes takes
// about as long as one of eight. c and n: the colours' and normals' x, y, z.
TESSERA_LANES_INLINE void finishPhong16(const LightRig& lights, F32x16 c[3], const F32x16 n[3]) {
  const F32x16 zero = splat16(0.0f);
  const F32x16 len = reinterpret_cast<F32x16>(_mm512_maskz_sqrt_ps(
      0xffff, reinterpret_cast<__m512>((n[0] * n[0] + n[1] * n[1]) + n[2] * n[2])));
  const F32x16 inv = splat16(1.0f) / len;
  const auto nonzero = len > zero;
  const F32x16 u[3] = {nonzero ? n[0] * inv : zero, nonzero ? n[1] * inv : zero,
                       nonzero ? n[2] * inv : zero};
  F32x16 e[3] = {splat16(lights.ambient.x), splat16(lights.ambient.y), splat16(lights.ambient.z)};
  for (const ShadeLight& light : lights.lights) {
    const F32x16 f = zero - (u[0] * splat16(light.direction.x) + u[1] * splat16(light.direction.y) +
                             u[2] * splat16(light.direction.z));
    const auto lit = f > zero;
    e[0] = e[0] + (lit ? splat16(light.radiance.x) * f : zero);
    e[1] = e[1] + (lit ? splat16(light.radiance.y) * f : zero);
    e[2] = e[2] + (lit ? splat16(light.radiance.z) * f : zero);
  }
  for (int k = 0; k < 3; ++k) c[k] = c[k] * e[k];
}
#endif

// The colour of an untextured flat, Gouraud or unlit triangle (its interpolated vertex colours)
// at pixel centres (px, py): shadeLanes' operations for such a triangle without a tone curve.
TESSERA_LANES_INLINE Vec3x8 shadePlainLanes(const ShadeTriangle& t, F32x8 px, float py) {
  Vec3x8 b;
  barycentrics8(t, px, py, b);
  return interpolateColor(t.color, b.y, b.z);
}

// Shades the lanes of `mask` (pixel centres px, py) from triangle t, into `color` and, when
// asked, `normal`; the other lanes keep what they hold.
TESSERA_LANES_INLINE void shadeLanes(const ShadeTriangle& t, const ShadeExtras& e,
                                     const LightRig& lights, bool want_normals, F32x8 px, float py,
                                     I32x8 mask, Vec3x8& color, Vec3x8& normal) {
  // At (px, py) and, for a level of detail, at the next pixel centres right and down.
  auto barycentrics = [&](F32x8 x, float y, Vec3x8& b) { barycentrics8(t, x, y, b); };
  Vec3x8 b;
  barycentrics(px, py, b);
  shadeLanesAt(
      t, e, lights, want_normals, b.x, b.y, b.z, mask, color, normal,
      [&](int l, const Barycentrics& at) { return sampleAlbedo(t, e, at, lane(px, l), py); },
      [&](Vec3x8& right, Vec3x8& down) {
        barycentrics(px + splat(1.0f), py, right);
        barycentrics(px, py + 1.0f, down);
        return true;
      },
      [&](int l, const Barycentrics& at, const Texture& texture, const Sampler& sampler) {
        return sampleTexture(texture, sampler, t, e, at, lane(px, l), py);
      });
}

// Stores eight pixels' colours at column tx of a row's linear colours and, when asked, their
// normals at pixel i of the tile.
TESSERA_LANES_INLINE void storeShadedGroup(const Vec3x8& color, const Vec3x8& normal,
                                           bool want_normals, int tx, int i,
                                           float linear[3][kTileSize], ShadedTile& out) {
  store(linear[0] + tx, color.x);
  store(linear[1] + tx, color.y);
  store(linear[2] + tx, color.z);
  if (want_normals) {
    store(out.normal_x + i, normal.x);
    store(out.normal_y + i, normal.y);
    store(out.normal_z + i, normal.z);
  }
}

// A group of eight pixels as shadePlainRow leaves it for the encode: kNoSolid, encode its linear
// colours; kSolidEmpty, no pixel covered; else the sRGB of every covered pixel (alpha 0xff, so
// never either of the two).
constexpr uint32_t kNoSolid = 0, kSolidEmpty = 1;

// Eight pixels' linear colours to sRGB, packed with an alpha of 0xff.
TESSERA_LANES_INLINE I32x8 encodeRgba8x8(F32x8 r, F32x8 g, F32x8 b) {
  return encodeSrgb8x8(r) | shiftLeft(encodeSrgb8x8(g), 8) | shiftLeft(encodeSrgb8x8(b), 16) |
         splat(static_cast<int32_t>(0xff000000u));
}

// The encoded colour of every pixel of a triangle whose corners share a colour (interpolateColor
// gives exactly that colour), by encodeShadedRow's operations; kNoSolid for any other triangle.
TESSERA_LANES_INLINE uint32_t solidRgba(const ShadeTriangle& t) {
  if (!t.solid) return kNoSolid;
  const float3& c = t.color[0];
  return static_cast<uint32_t>(lane(encodeRgba8x8(splat(c.x), splat(c.y), splat(c.z)), 0));
}

// Where row ty of the tile's colour goes: the frame's row at out.direct, or out.rgba's.
TESSERA_LANES_INLINE uint32_t* shadedRow(ShadedTile& out, int ty) {
  return out.direct ? out.direct + static_cast<size_t>(ty) * out.direct_stride
                    : out.rgba + ty * kTileSize;
}

// Row ty of the tile, every pixel covered by one solid triangle (solidRowRgba), as `rgba`: what
// encodeShadedRow writes for it without reading the keys and marks. The row's width is a whole
// number of groups of eight, and of sixteen where it goes straight to the frame.
TESSERA_LANES_INLINE void storeSolidRow(const TileVisibility& tile, int ty, uint32_t rgba,
                                        ShadedTile& out) {
  uint32_t* const row = shadedRow(out, ty);
  const I32x8 fill = splat(static_cast<int32_t>(rgba));
  for (int tx = 0; tx < tile.width; tx += 8) store(row + tx, fill);
}

// Encodes row ty of the tile's linear colours to sRGB into out.rgba (or the frame's row at
// out.direct), whole; the background where no triangle is. `solid` (or null) gives
// shadePlainRow's groups of one solid triangle, which take their colour from it.
TESSERA_LANES_INLINE void encodeShadedRow(const TileVisibility& tile, int ty,
                                          const float linear[3][kTileSize], const uint32_t solid[],
                                          uint32_t background, ShadedTile& out) {
  uint32_t* const row = shadedRow(out, ty);
#if defined(TESSERA_LANES16)
  const I32x16 fill = splat16(static_cast<int32_t>(background));  // the encode's width
  // Sixteen pixels a step (the rows are kTileSize wide, a multiple of 16).
  for (int tx = 0; tx < tile.width; tx += 16) {
    const int i = ty * kTileSize + tx;
    const I32x16 covered = load<I32x16>(tile.key + i) != static_cast<int32_t>(kEmptyKey);
    if (!_mm512_test_epi32_mask(reinterpret_cast<__m512i>(covered),
                                reinterpret_cast<__m512i>(covered))) {
      store(row + tx, fill);
      continue;
    }
    I32x16 rgba;
    if (solid && solid[tx / 8] != kNoSolid && solid[tx / 8 + 1] != kNoSolid) {
      rgba = reinterpret_cast<I32x16>(
          _mm512_mask_blend_epi32(0xff00, _mm512_set1_epi32(static_cast<int>(solid[tx / 8])),
                                  _mm512_set1_epi32(static_cast<int>(solid[tx / 8 + 1]))));
    } else {
      rgba = encodeSrgb8x16(load<F32x16>(linear[0] + tx)) |
             encodeSrgb8x16(load<F32x16>(linear[1] + tx)) << 8 |
             encodeSrgb8x16(load<F32x16>(linear[2] + tx)) << 16 | static_cast<int32_t>(0xff000000u);
    }
    store(row + tx, covered ? rgba : fill);
  }
#else
  const I32x8 empty = splat(static_cast<int32_t>(kEmptyKey));
  const I32x8 fill = splat(static_cast<int32_t>(background));
  for (int tx = 0; tx < tile.width; tx += 8) {
    const int i = ty * kTileSize + tx;
    const I32x8 covered = ~equal(load<I32x8>(tile.key + i), empty);
    if (!any(covered)) {
      store(row + tx, fill);
      continue;
    }
    const I32x8 rgba = solid && solid[tx / 8] != kNoSolid
                           ? splat(static_cast<int32_t>(solid[tx / 8]))
                           : encodeRgba8x8(load<F32x8>(linear[0] + tx), load<F32x8>(linear[1] + tx),
                                           load<F32x8>(linear[2] + tx));
    store(row + tx, select(covered, rgba, fill));
  }
#endif
}

}  // namespace
}  // namespace tessera::render
