// Shading of eight lanes at a time, for the shading kernel (shade_kernel.h) and the resolve of
// multisampled pixels (msaa_kernel.h); written once against eight-lane types (simd_lanes.h) and
// compiled per instruction set (kernels_<isa>.cpp). Each lane does exactly the float operations, in
// exactly the order, that shading one pixel takes, so every variant gives the same bits. Bilinear
// texture samples are taken eight lanes at a time (sampleBilinear8); trilinear ones, and lanes
// outside its common case, lane by lane through the one sampleAlbedo.
#pragma once

#include <algorithm>
#include <cstddef>

#include <tessera/scene/color.h>

#include "render/shade.h"
#include "render/simd_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

struct Vec3x8 {
  F32x8 x, y, z;
};

TESSERA_LANES_INLINE Vec3x8 interpolate(const float3 v[3], F32x8 b0, F32x8 b1, F32x8 b2) {
  return {splat(v[0].x) * b0 + splat(v[1].x) * b1 + splat(v[2].x) * b2,
          splat(v[0].y) * b0 + splat(v[1].y) * b1 + splat(v[2].y) * b2,
          splat(v[0].z) * b0 + splat(v[1].z) * b1 + splat(v[2].z) * b2};
}

// As tessera::normalize: zero for a zero vector.
TESSERA_LANES_INLINE Vec3x8 normalize8(Vec3x8 v) {
  const F32x8 len = squareRoot(v.x * v.x + v.y * v.y + v.z * v.z);
  const F32x8 inv = splat(1.0f) / len;
  const I32x8 nonzero = positive(len);
  const F32x8 zero = splat(0.0f);
  return {select(nonzero, v.x * inv, zero), select(nonzero, v.y * inv, zero),
          select(nonzero, v.z * inv, zero)};
}

// As clamp(v, 0, 1) (std::clamp's comparisons: NaN stays NaN).
TESSERA_LANES_INLINE F32x8 clamp01(F32x8 v) {
  const F32x8 zero = splat(0.0f), one = splat(1.0f);
  return select(lessThan(v, zero), zero, select(lessThan(one, v), one, v));
}

// As render::localFactor (lights.h), lane by lane.
TESSERA_LANES_INLINE F32x8 localFactor8(const ShadeLight& light, const Vec3x8& n, const Vec3x8& p) {
  const Vec3x8 l{splat(light.position.x) - p.x, splat(light.position.y) - p.y,
                 splat(light.position.z) - p.z};
  const F32x8 d2 = (l.x * l.x + l.y * l.y) + l.z * l.z;
  const F32x8 inv_d = splat(1.0f) / squareRoot(d2);
  const Vec3x8 u{l.x * inv_d, l.y * inv_d, l.z * inv_d};
  const F32x8 cos_theta = (n.x * u.x + n.y * u.y) + n.z * u.z;
  const F32x8 window = clamp01(splat(1.0f) - d2 * d2 * splat(light.inv_range4));
  const F32x8 cd =
      splat(0.0f) - ((splat(light.direction.x) * u.x + splat(light.direction.y) * u.y) +
                     splat(light.direction.z) * u.z);
  const F32x8 t = clamp01(cd * splat(light.spot_scale) + splat(light.spot_offset));
  return cos_theta * ((window * (t * t)) / d2);
}

// As render::irradiance: ambient plus every light, at world points p (read only when the rig has
// a point or spot light).
TESSERA_LANES_INLINE Vec3x8 irradiance8(const LightRig& rig, const Vec3x8& n, const Vec3x8& p) {
  Vec3x8 e{splat(rig.ambient.x), splat(rig.ambient.y), splat(rig.ambient.z)};
  const F32x8 zero = splat(0.0f);
  for (const ShadeLight& light : rig.lights) {
    F32x8 f;
    if (light.type == LightType::kDirectional)
      f = zero - (n.x * splat(light.direction.x) + n.y * splat(light.direction.y) +
                  n.z * splat(light.direction.z));
    else
      f = localFactor8(light, n, p);
    const I32x8 lit = positive(f);
    e.x = e.x + select(lit, splat(light.radiance.x) * f, zero);
    e.y = e.y + select(lit, splat(light.radiance.y) * f, zero);
    e.z = e.z + select(lit, splat(light.radiance.z) * f, zero);
  }
  return e;
}

// Eight encodeSrgb8s (tessera/scene/color.h), the same operations lane by lane.
TESSERA_LANES_INLINE I32x8 encodeSrgb8x8(F32x8 linear) {
  const F32x8 zero = splat(0.0f), one = splat(1.0f);
  // Clamped to [0, 1], NaN to 0: (x > 0 ? x : 0), then (< 1 ? : 1).
  const F32x8 c = lowerOf(upperOf(linear, zero), one);
  const I32x8 bits = bitsOf(c);
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
}

#if defined(TESSERA_LANES16)
// encodeSrgb8x8 for sixteen lanes, the same operations.
TESSERA_LANES_INLINE I32x16 encodeSrgb8x16(F32x16 linear) {
  const F32x16 zero = splat16(0.0f), one = splat16(1.0f);
  const F32x16 c = lowerOf16(upperOf16(linear, zero), one);
  const I32x16 bits = reinterpret_cast<I32x16>(c);
  const I32x16 e9 = (bits >> 23) - (127 - 9);
  const I32x16 index = e9 > 0 ? e9 : 0;
  const F32x16 x = reinterpret_cast<F32x16>((bits & 0x7fffff) | 0x3f800000) - one;
  const float* k = SrgbEncode::kPoly;
  const F32x16 p =
      (((splat16(k[4]) * x + splat16(k[3])) * x + splat16(k[2])) * x + splat16(k[1])) * x +
      splat16(k[0]);
  F32x16 curve = lookup16x16(SrgbEncode::kScale, index) * p - splat16(SrgbEncode::kOffset);
  curve = lowerOf16(curve, splat16(255.0f));
  const F32x16 code = SrgbEncode::kLinearEnd < c ? curve : c * splat16(SrgbEncode::kLinearFactor);
  return truncate16(code + splat16(0.5f));
}
#endif

// One channel of eight texels (bits `shift`..`shift + 7`) in linear light, as decodeTexel.
TESSERA_LANES_INLINE F32x8 decodeChannel(I32x8 texels, int shift, bool srgb, const float* decode) {
  const I32x8 code = shiftRight(texels, shift) & splat(int32_t{0xff});
  return srgb ? gather(decode, code) : toFloat(code) / splat(255.0f);
}

// Texture::sample's bilinear filter (texture.cpp: sampleLevel) for the albedo of the lanes of
// `mask`, eight lanes at a time with the same operations, for the common case: bilinear filtering
// (or trilinear without mip levels), coordinates below 65536 (where sanitize is the identity) and
// texel positions within one texture width or height of the texture (what repeat wraps without a
// division). False, with nothing computed, when a lane falls outside that: the caller samples lane
// by lane.
TESSERA_LANES_INLINE bool sampleBilinear8(const ShadeTriangle& t, const ShadeExtras& e, I32x8 mask,
                                          F32x8 b0, F32x8 b1, F32x8 b2, Vec3x8& albedo) {
  const Material& m = *t.material;
  const Texture& texture = *m.albedo;
  const bool bilinear = m.sampler.filter == TextureFilter::kBilinear ||
                        (m.sampler.filter == TextureFilter::kTrilinear && texture.mips.empty());
  // Up to 16384 texels a side (what the image loader accepts), texel positions (below 65536
  // times the size) and indices stay within int32.
  constexpr int kMaxSide = 16384;
  if (!bilinear || texture.width <= 0 || texture.height <= 0 || texture.width > kMaxSide ||
      texture.height > kMaxSide)
    return false;
  // uvAt: e.uv[0] * b0 + e.uv[1] * b1 + e.uv[2] * b2.
  const F32x8 u = splat(e.uv[0].x) * b0 + splat(e.uv[1].x) * b1 + splat(e.uv[2].x) * b2;
  const F32x8 v = splat(e.uv[0].y) * b0 + splat(e.uv[1].y) * b1 + splat(e.uv[2].y) * b2;
  const F32x8 limit = splat(65536.0f), low = splat(-65536.0f);
  if (any(mask & ~(lessThan(u, limit) & lessThan(low, u) & lessThan(v, limit) & lessThan(low, v))))
    return false;
  const int width = texture.width, height = texture.height;
  const F32x8 sx = u * splat(static_cast<float>(width)) - splat(0.5f);
  const F32x8 sy = (splat(1.0f) - v) * splat(static_cast<float>(height)) - splat(0.5f);
  const F32x8 x0f = floorLanes(sx), y0f = floorLanes(sy);
  const F32x8 tx = sx - x0f, ty = sy - y0f;
  // Uncovered lanes may hold anything: they read texel 0.
  const I32x8 x0 = select(mask, truncate(x0f), splat(int32_t{0}));
  const I32x8 y0 = select(mask, truncate(y0f), splat(int32_t{0}));
  const I32x8 w = splat(width), h = splat(height), one = splat(int32_t{1});
  I32x8 xa, xb, ya, yb;
  if (m.sampler.wrap == TextureWrap::kClamp) {
    auto clampTo = [](I32x8 i, I32x8 size) {
      const I32x8 zero = splat(int32_t{0}), last = size - splat(int32_t{1});
      return select(lessThan(i, zero), zero, select(lessThan(last, i), last, i));
    };
    xa = clampTo(x0, w), xb = clampTo(x0 + one, w);
    ya = clampTo(y0, h), yb = clampTo(y0 + one, h);
  } else {
    // Repeat, for i in [-size, 2 * size): one add or subtract of the size.
    if (any(lessThan(x0, -w) | lessThan(w + w - one, x0 + one) | lessThan(y0, -h) |
            lessThan(h + h - one, y0 + one)))
      return false;
    auto wrap = [](I32x8 i, I32x8 size) {
      return select(lessThan(i, splat(int32_t{0})), i + size,
                    select(lessThan(i, size), i, i - size));
    };
    xa = wrap(x0, w), xb = wrap(x0 + one, w);
    ya = wrap(y0, h), yb = wrap(y0 + one, h);
  }
  const uint32_t* texels = texture.texels.data();
  const I32x8 c00 = gatherWords(texels, ya * w + xa), c10 = gatherWords(texels, ya * w + xb);
  const I32x8 c01 = gatherWords(texels, yb * w + xa), c11 = gatherWords(texels, yb * w + xb);
  const float* decode = srgbDecodeTable();
  F32x8 channel[3];
  for (int k = 0; k < 3; ++k) {
    // lerp(a, b, t) = a + (b - a) * t: across, then down.
    const F32x8 t00 = decodeChannel(c00, 8 * k, texture.srgb, decode);
    const F32x8 t10 = decodeChannel(c10, 8 * k, texture.srgb, decode);
    const F32x8 t01 = decodeChannel(c01, 8 * k, texture.srgb, decode);
    const F32x8 t11 = decodeChannel(c11, 8 * k, texture.srgb, decode);
    const F32x8 top = t00 + (t10 - t00) * tx;
    const F32x8 bottom = t01 + (t11 - t01) * tx;
    channel[k] = top + (bottom - top) * ty;
  }
  albedo = {channel[0], channel[1], channel[2]};
  return true;
}

// Shades the lanes of `mask` from triangle t at barycentrics b0, b1, b2, into `color` and, when
// asked, `normal`; the other lanes keep what they hold. Lanes the eight-lane bilinear filter does
// not take get their albedo from albedo_lane(l, Barycentrics) one at a time.
template <typename AlbedoLane>
TESSERA_LANES_INLINE void shadeLanesAt(const ShadeTriangle& t, const ShadeExtras& e,
                                       const LightRig& lights, bool want_normals, F32x8 b0,
                                       F32x8 b1, F32x8 b2, I32x8 mask, Vec3x8& color,
                                       Vec3x8& normal, AlbedoLane albedo_lane) {
  Vec3x8 c = interpolate(t.color, b0, b1, b2);
  Vec3x8 albedo;
  if (t.has_uv && sampleBilinear8(t, e, mask, b0, b1, b2, albedo)) {
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
  if (t.shading == Shading::kPhong || (want_normals && t.shading != Shading::kFlat)) {
    const Vec3x8 n = normalize8(interpolate(e.normal, b0, b1, b2));
    if (t.shading == Shading::kPhong) {
      const Vec3x8 p = lights.local ? interpolate(e.world, b0, b1, b2) : Vec3x8{};
      const Vec3x8 e = irradiance8(lights, n, p);
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
  color = {select(mask, c.x, color.x), select(mask, c.y, color.y), select(mask, c.z, color.z)};
}

// Shades the lanes of `mask` (pixel centres px, py) from triangle t, into `color` and, when
// asked, `normal`; the other lanes keep what they hold.
TESSERA_LANES_INLINE void shadeLanes(const ShadeTriangle& t, const ShadeExtras& e,
                                     const LightRig& lights, bool want_normals, F32x8 px, float py,
                                     I32x8 mask, Vec3x8& color, Vec3x8& normal) {
  // Barycentrics exactly as barycentricsAt.
  const F32x8 dx = px - splat(t.x0);
  const float dy = py - t.y0;
  const F32x8 inv_s = splat(1.0f) / (splat(t.inv_w0) + splat(t.sdx) * dx + splat(t.sdy * dy));
  const F32x8 b1 = (splat(t.p1dx) * dx + splat(t.p1dy * dy)) * inv_s;
  const F32x8 b2 = (splat(t.p2dx) * dx + splat(t.p2dy * dy)) * inv_s;
  const F32x8 b0 = splat(1.0f) - b1 - b2;
  shadeLanesAt(
      t, e, lights, want_normals, b0, b1, b2, mask, color, normal,
      [&](int l, const Barycentrics& b) { return sampleAlbedo(t, e, b, lane(px, l), py); });
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

// The kPlainFields floats of eight records, transposed into lanes: f[0..8] x0, y0, inv_w0, p1dx,
// p1dy, p2dx, p2dy, sdx, sdy, then f[9..17] color[0..2].xyz.
TESSERA_LANES_INLINE void loadPlainFields(const ShadeTriangle* const records[8],
                                          F32x8 f[kPlainFields]) {
  for (int block = 0; block < 2; ++block) {
    for (int l = 0; l < 8; ++l) f[block * 8 + l] = load<F32x8>(&records[l]->x0 + block * 8);
    transpose8x8(f + block * 8);
  }
  const float* last_two[8];
  for (int l = 0; l < 8; ++l) last_two[l] = &records[l]->x0 + 16;
  loadPairs(last_two, f[16], f[17]);
}

// Perspective-correct barycentrics of the lanes' triangles (loadPlainFields) at (px, py), with
// shadeLanes' operations.
TESSERA_LANES_INLINE void plainBarycentrics(const F32x8 f[kPlainFields], F32x8 px, F32x8 py,
                                            F32x8& b0, F32x8& b1, F32x8& b2) {
  const F32x8 dx = px - f[0];
  const F32x8 dy = py - f[1];
  const F32x8 inv_s = splat(1.0f) / (f[2] + f[7] * dx + f[8] * dy);
  b1 = (f[3] * dx + f[4] * dy) * inv_s;
  b2 = (f[5] * dx + f[6] * dy) * inv_s;
  b0 = splat(1.0f) - b1 - b2;
}

// The interpolated vertex colours of the lanes' triangles at barycentrics b0, b1, b2.
TESSERA_LANES_INLINE Vec3x8 plainColor(const F32x8 f[kPlainFields], F32x8 b0, F32x8 b1, F32x8 b2) {
  return {f[9] * b0 + f[12] * b1 + f[15] * b2, f[10] * b0 + f[13] * b1 + f[16] * b2,
          f[11] * b0 + f[14] * b1 + f[17] * b2};
}

// Eight pixels owned by several triangles, all untextured and not Phong-shaded (colour = the
// interpolated vertex colours): lane l is shaded from its own triangle's record, whose fields
// are loaded eight records at a time and transposed into lanes. The same operations per lane as
// shadeLanes, so the same bits; one evaluation instead of one per triangle.
TESSERA_LANES_INLINE Vec3x8 shadeMixed(const ShadeTriangle* const records[8], F32x8 px, F32x8 py) {
  F32x8 f[kPlainFields];
  loadPlainFields(records, f);
  F32x8 b0, b1, b2;
  plainBarycentrics(f, px, py, b0, b1, b2);
  return plainColor(f, b0, b1, b2);
}

// Encodes row ty of the tile's linear colours to sRGB into out.rgba, whole; the background where
// no triangle is.
TESSERA_LANES_INLINE void encodeShadedRow(const TileVisibility& tile, int ty,
                                          const float linear[3][kTileSize], uint32_t background,
                                          ShadedTile& out) {
#if defined(TESSERA_LANES16)
  const I32x16 fill = splat16(static_cast<int32_t>(background));  // the encode's width
  // Sixteen pixels a step (the rows are kTileSize wide, a multiple of 16).
  for (int tx = 0; tx < tile.width; tx += 16) {
    const int i = ty * kTileSize + tx;
    const I32x16 covered = load<I32x16>(tile.key + i) != static_cast<int32_t>(kEmptyKey);
    if (!_mm512_test_epi32_mask(reinterpret_cast<__m512i>(covered),
                                reinterpret_cast<__m512i>(covered))) {
      store(out.rgba + i, fill);
      continue;
    }
    const I32x16 rgba = encodeSrgb8x16(load<F32x16>(linear[0] + tx)) |
                        encodeSrgb8x16(load<F32x16>(linear[1] + tx)) << 8 |
                        encodeSrgb8x16(load<F32x16>(linear[2] + tx)) << 16 |
                        static_cast<int32_t>(0xff000000u);
    store(out.rgba + i, covered ? rgba : fill);
  }
#else
  const I32x8 empty = splat(static_cast<int32_t>(kEmptyKey));
  const I32x8 fill = splat(static_cast<int32_t>(background));
  const I32x8 opaque = splat(static_cast<int32_t>(0xff000000u));
  for (int tx = 0; tx < tile.width; tx += 8) {
    const int i = ty * kTileSize + tx;
    const I32x8 covered = ~equal(load<I32x8>(tile.key + i), empty);
    if (!any(covered)) {
      store(out.rgba + i, fill);
      continue;
    }
    const I32x8 rgba = encodeSrgb8x8(load<F32x8>(linear[0] + tx)) |
                       shiftLeft(encodeSrgb8x8(load<F32x8>(linear[1] + tx)), 8) |
                       shiftLeft(encodeSrgb8x8(load<F32x8>(linear[2] + tx)), 16) | opaque;
    store(out.rgba + i, select(covered, rgba, fill));
  }
#endif
}

}  // namespace
}  // namespace tessera::render
