// Texture sampling eight lanes at a time, for the shading kernels (shade_lanes.h): sampleTexture
// (shade.cpp) with the same float operations per lane, so every variant gives the same bits.
// Bilinear and trilinear filtering, every wrap mode, the sampler's transform; nearest filtering and
// coordinates of 65536 and beyond are left to the caller, lane by lane.
#pragma once

#include <algorithm>

#include <tessera/scene/color.h>
#include <tessera/scene/texture.h>

#include "render/shade.h"
#include "render/simd_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

struct Uv8 {
  F32x8 u, v;
};

// Consecutive floats of one record in every lane, broadcast where they are read: `f[k]` is float k
// in all eight lanes, as the transposed fields of eight records give it lane by lane (the
// ShadeTriangle fields, a UV set's corners). Read so, not broadcast into an array first, they are
// not spilled: GCC kept such arrays on the stack, and their stores and reloads were a third of a
// textured group of one triangle's instructions (AVX2).
struct BroadcastFields {
  const float* p;
  TESSERA_LANES_INLINE F32x8 operator[](int k) const { return splat(p[k]); }
};

// The texture coordinates at barycentrics b0, b1, b2 of the lanes' triangles, whose corners
// corner[0..5] are u0, v0, u1, v1, u2, v2 in lanes (uvCorners8's, or one triangle's
// BroadcastFields): uvAt's operations (shade.cpp), so the same bits.
template <typename Corners>
TESSERA_LANES_INLINE Uv8 uvAt8(Corners corner, F32x8 b0, F32x8 b1, F32x8 b2) {
  return {corner[0] * b0 + corner[2] * b1 + corner[4] * b2,
          corner[1] * b0 + corner[3] * b1 + corner[5] * b2};
}

// lodLog2 (shade.cpp), lane by lane.
TESSERA_LANES_INLINE F32x8 lodLog2x8(F32x8 x) {
  const I32x8 bits = bitsOf(x);
  const I32x8 e = shiftRight(bits, 23) - splat(int32_t{127});
  const F32x8 m = fromBits((bits & splat(int32_t{0x7fffff})) | splat(int32_t{0x3f800000}));
  const F32x8 one = splat(1.0f);
  const F32x8 s = (m - one) / (m + one);
  const F32x8 s2 = s * s;
  const float* k = kLodLog2Series;
  const F32x8 p = ((splat(k[3]) * s2 + splat(k[2])) * s2 + splat(k[1])) * s2 + splat(k[0]);
  return toFloat(e) + s * p;
}

// textureLod (shade.cpp), lane by lane.
TESSERA_LANES_INLINE F32x8 textureLod8(const Uv8& uv, const Uv8& right, const Uv8& down,
                                       float width, float height) {
  const F32x8 w = splat(width), h = splat(height);
  const F32x8 dxx = (right.u - uv.u) * w, dxy = (right.v - uv.v) * h;
  const F32x8 dyx = (down.u - uv.u) * w, dyy = (down.v - uv.v) * h;
  const F32x8 rho2 = maximum(dxx * dxx + dxy * dxy, dyx * dyx + dyy * dyy);
  return select(positive(rho2), splat(0.5f) * lodLog2x8(rho2), splat(0.0f));
}

TESSERA_LANES_INLINE Uv8 applyAffine(const UvAffine& m, const Uv8& uv) {
  return {(splat(m.m00) * uv.u + splat(m.m01) * uv.v) + splat(m.m02),
          (splat(m.m10) * uv.u + splat(m.m11) * uv.v) + splat(m.m12)};
}

// Texels i and i + 1 of an axis of `size` texels, wrapped as wrapTexel does. One add or subtract
// for i in [-size, 2 size - 1) (every lane, after a texture's coordinates stay within one
// repetition of it); lane by lane through wrapTexel otherwise.
TESSERA_LANES_INLINE void wrapPair8(I32x8 i, int size, TextureWrap wrap, I32x8& first,
                                    I32x8& second) {
  const I32x8 zero = splat(int32_t{0}), one = splat(int32_t{1}), n = splat(int32_t{size});
  const I32x8 next = i + one;
  if (wrap == TextureWrap::kClamp) {
    const I32x8 last = n - one;
    first = select(lessThan(i, zero), zero, select(lessThan(last, i), last, i));
    second = select(lessThan(next, zero), zero, select(lessThan(last, next), last, next));
    return;
  }
  const I32x8 period_end = n + n - one;  // 2 size - 1
  if ((size & (size - 1)) == 0) {
    // A power of two: i mod size (and mod 2 size) is a mask, for any i.
    if (wrap == TextureWrap::kRepeat) {
      first = i & (n - one);
      second = next & (n - one);
      return;
    }
    auto mirror = [&](I32x8 j) {
      const I32x8 m = j & period_end;
      return select(lessThan(m, n), m, period_end - m);
    };
    first = mirror(i);
    second = mirror(next);
    return;
  }
  if (any(lessThan(i, zero - n) | lessThan(period_end, next))) {
    alignas(32) int32_t wrapped[2][8];
    for (int l = 0; l < 8; ++l) {
      wrapped[0][l] = wrapTexel(lane(i, l), size, wrap);
      wrapped[1][l] = wrapTexel(lane(next, l), size, wrap);
    }
    first = load<I32x8>(wrapped[0]);
    second = load<I32x8>(wrapped[1]);
    return;
  }
  auto one_period = [&](I32x8 j) {
    if (wrap == TextureWrap::kRepeat)
      return select(lessThan(j, zero), j + n, select(lessThan(j, n), j, j - n));
    // Mirrored: -1 - j below 0, 2 size - 1 - j from size.
    return select(lessThan(j, zero), zero - one - j, select(lessThan(j, n), j, period_end - j));
  };
  first = one_period(i);
  second = one_period(next);
}

// One channel of eight texels (bits `shift`..`shift + 7`) in linear light, as decodeTexel.
TESSERA_LANES_INLINE F32x8 decodeChannel(I32x8 texels, int shift, bool srgb, const float* decode) {
  const I32x8 code = shiftRight(texels, shift) & splat(int32_t{0xff});
  return srgb ? gather(decode, code) : toFloat(code) / splat(255.0f);
}

struct LevelLanes {
  int width, height;
  const uint32_t* texels;
  const float* linear;  // Texture::linearTexels of this level, or null
};

// The four channels of the texels at `index` (eight lanes) from a level's linear copy: a load of
// each lane's four floats (two lanes a register) and a transpose, where the RGBA8 texels take a
// gather and then a table gather per channel. The values are decodeChannel's, so the same bits.
TESSERA_LANES_INLINE void loadLinear8(const float* linear, I32x8 index, F32x8 out[4]) {
  alignas(32) int32_t at[8];
  store(at, index);
  for (int l = 0; l < 4; ++l)
    out[l] = load2x4<F32x8>(linear + 4 * static_cast<size_t>(at[l]),
                            linear + 4 * static_cast<size_t>(at[l + 4]));
  transpose4x4Halves(out);  // out[k]: channel k of lanes 0-3, then of lanes 4-7
}

// loadLinear8 of the four texels (x, y), (x + 1, y), (x, y + 1) and (x + 1, y + 1) of a level
// `width` texels wide, where `index` is each lane's (x, y): each lane's texel and its right
// neighbour are eight consecutive floats, one load a row and a transpose. top[k] and bottom[k]:
// channel k of (x, y) and (x, y + 1); top[4 + k] and bottom[4 + k] of their right neighbours.
TESSERA_LANES_INLINE void loadLinearQuads8(const float* linear, I32x8 index, int width,
                                           F32x8 top[8], F32x8 bottom[8]) {
  alignas(32) int32_t at[8];
  store(at, index);
  const size_t down = 4 * static_cast<size_t>(width);
  for (int l = 0; l < 8; ++l) {
    const float* p = linear + 4 * static_cast<size_t>(at[l]);
    top[l] = load<F32x8>(p);
    bottom[l] = load<F32x8>(p + down);
  }
  transpose8x8(top);
  transpose8x8(bottom);
}

// sampleLevel's bilinear filter (texture.cpp) in one level for the lanes of `mask` (the others
// read texel 0), `channels` channels (3: RGB, 4: RGBA); coordinates below 65536 in magnitude.
TESSERA_LANES_INLINE void bilinear8(const LevelLanes& level, bool srgb, const Sampler& sampler,
                                    I32x8 mask, const Uv8& uv, int channels, F32x8 out[4]) {
  const F32x8 sx = uv.u * splat(static_cast<float>(level.width)) - splat(0.5f);
  const F32x8 sy = (splat(1.0f) - uv.v) * splat(static_cast<float>(level.height)) - splat(0.5f);
  const F32x8 x0f = floorLanes(sx), y0f = floorLanes(sy);
  const F32x8 tx = sx - x0f, ty = sy - y0f;
  const I32x8 x0 = select(mask, truncate(x0f), splat(int32_t{0}));
  const I32x8 y0 = select(mask, truncate(y0f), splat(int32_t{0}));
  I32x8 xa, xb, ya, yb;
  wrapPair8(x0, level.width, sampler.wrap_s, xa, xb);
  wrapPair8(y0, level.height, sampler.wrap_t, ya, yb);
  const I32x8 w = splat(int32_t{level.width});
  const uint32_t* texels = level.texels;
  const I32x8 row_a = ya * w, row_b = yb * w;
  // lerp(a, b, t) = a + (b - a) * t: across, then down.
  if (level.linear) {
    F32x8 top[8], bottom[8];  // channels 0-3 of the left texel, then of the right one
    const I32x8 one = splat(int32_t{1});
    if (any(~(equal(xb, xa + one) & equal(yb, ya + one)))) {  // a lane at a wrap or a clamp
      loadLinear8(level.linear, row_a + xa, top);
      loadLinear8(level.linear, row_a + xb, top + 4);
      loadLinear8(level.linear, row_b + xa, bottom);
      loadLinear8(level.linear, row_b + xb, bottom + 4);
    } else {
      loadLinearQuads8(level.linear, row_a + xa, level.width, top, bottom);
    }
    for (int k = 0; k < channels; ++k) {
      const F32x8 upper = top[k] + (top[4 + k] - top[k]) * tx;
      const F32x8 lower = bottom[k] + (bottom[4 + k] - bottom[k]) * tx;
      out[k] = upper + (lower - upper) * ty;
    }
    return;
  }
  const I32x8 c00 = gatherWords(texels, row_a + xa), c10 = gatherWords(texels, row_a + xb);
  const I32x8 c01 = gatherWords(texels, row_b + xa), c11 = gatherWords(texels, row_b + xb);
  const float* decode = kSrgbDecode.data();
  for (int k = 0; k < channels; ++k) {
    const bool encoded = srgb && k < 3;  // alpha is linear
    const F32x8 t00 = decodeChannel(c00, 8 * k, encoded, decode);
    const F32x8 t10 = decodeChannel(c10, 8 * k, encoded, decode);
    const F32x8 t01 = decodeChannel(c01, 8 * k, encoded, decode);
    const F32x8 t11 = decodeChannel(c11, 8 * k, encoded, decode);
    const F32x8 top = t00 + (t10 - t00) * tx;
    const F32x8 bottom = t01 + (t11 - t01) * tx;
    out[k] = top + (bottom - top) * ty;
  }
}

TESSERA_LANES_INLINE LevelLanes levelLanes(const Texture& texture, int level) {
  const float* linear = texture.linearTexels(level);
  if (level == 0) return {texture.width, texture.height, texture.texels.data(), linear};
  const TextureLevel& m = texture.mips[static_cast<size_t>(level - 1)];
  return {m.width, m.height, m.texels.data(), linear};
}

// Whether sampleTexture8 can take reads of `texture` through `sampler` (up to 16384 texels a side,
// what the image loader accepts: texel positions, below 65536 times the size, and indices stay
// within int32).
TESSERA_LANES_INLINE bool texture8Applies(const Texture& texture, const Sampler& sampler) {
  constexpr int kMaxSide = 16384;
  return sampler.filter != TextureFilter::kNearest && texture.width > 0 && texture.height > 0 &&
         texture.width <= kMaxSide && texture.height <= kMaxSide;
}

// What sampleTexture8 reads of a texture through a sampler, looked up once for the many groups
// of eight pixels that read it: a row's textured groups mostly share one material, and looking
// these up for each group (the transform's identity, the decoded copy, the level of detail) was
// 2% of the textured sphere's shading instructions.
struct TextureReads {
  const Texture* texture;
  const Sampler* sampler;
  LevelLanes base;  // level 0
  bool lod;         // needsLod
  bool moved;       // the sampler's transform is not the identity; then `affine` is its matrix
  UvAffine affine;
};
TESSERA_LANES_INLINE TextureReads textureReads(const Texture& texture, const Sampler& sampler) {
  TextureReads r{&texture,
                 &sampler,
                 levelLanes(texture, 0),
                 needsLod(texture, sampler),
                 !sampler.transform.identity(),
                 UvAffine{}};
  if (r.moved) r.affine = sampler.transform.affine();
  return r;
}

// sampleTexture (shade.cpp) for the lanes of `mask`, where texture8Applies: uv before the
// sampler's transform, right and down the same at the next pixel centres (read where needsLod).
// False, with nothing computed, when a lane's coordinates reach 65536 in magnitude (where
// sanitize is not the identity): the caller samples lane by lane.
TESSERA_LANES_INLINE bool sampleTexture8(const TextureReads& reads, I32x8 mask, Uv8 uv, Uv8 right,
                                         Uv8 down, int channels, F32x8 out[4]) {
  const Texture& texture = *reads.texture;
  const Sampler& sampler = *reads.sampler;
  if (reads.moved) {
    uv = applyAffine(reads.affine, uv);
    right = applyAffine(reads.affine, right);
    down = applyAffine(reads.affine, down);
  }
  const F32x8 limit = splat(65536.0f), low = splat(-65536.0f);
  if (any(mask & ~(lessThan(uv.u, limit) & lessThan(low, uv.u) & lessThan(uv.v, limit) &
                   lessThan(low, uv.v))))
    return false;
  if (!reads.lod) {
    bilinear8(reads.base, texture.srgb, sampler, mask, uv, channels, out);
    return true;
  }
  F32x8 lod = textureLod8(uv, right, down, static_cast<float>(texture.width),
                          static_cast<float>(texture.height));
  // As sampleLod: clamped to [0, last] (NaN to 0), bilinear in level floor(lod), blended with the
  // next where the fraction is not 0. Lanes may need different levels: each level in use is
  // sampled for the lanes that need it.
  const int last = texture.levelCount() - 1;
  const F32x8 last_f = splat(static_cast<float>(last));
  lod = select(positive(lod), lod, splat(0.0f));
  lod = select(lessThan(last_f, lod), last_f, lod);
  const I32x8 lower = truncate(lod);
  const F32x8 blend = lod - toFloat(lower);
  const I32x8 two_levels = mask & ~equal(blend, splat(0.0f)) & lessThan(lower, splat(last));
  int first_level = last, last_level = 0;
  for (int l = 0; l < 8; ++l) {
    if (!lane(mask, l)) continue;
    first_level = std::min(first_level, lane(lower, l));
    last_level = std::max(last_level, lane(lower, l) + (lane(two_levels, l) ? 1 : 0));
  }
  F32x8 a[4], b[4], level_out[4];
  for (int k = 0; k < 4; ++k) a[k] = b[k] = splat(0.0f);
  for (int level = first_level; level <= last_level; ++level) {
    const I32x8 at = splat(int32_t{level});
    const I32x8 as_a = mask & equal(lower, at);
    const I32x8 as_b = two_levels & equal(lower + splat(int32_t{1}), at);
    if (!any(as_a | as_b)) continue;
    bilinear8(levelLanes(texture, level), texture.srgb, sampler, as_a | as_b, uv, channels,
              level_out);
    for (int k = 0; k < channels; ++k) {
      a[k] = select(as_a, level_out[k], a[k]);
      b[k] = select(as_b, level_out[k], b[k]);
    }
  }
  for (int k = 0; k < channels; ++k)
    out[k] = select(two_levels, a[k] + (b[k] - a[k]) * blend, a[k]);
  return true;
}

// sampleTexture8 of `texture` through `sampler`, looked up for these eight lanes alone.
TESSERA_LANES_INLINE bool sampleTexture8(const Texture& texture, const Sampler& sampler, I32x8 mask,
                                         Uv8 uv, Uv8 right, Uv8 down, int channels, F32x8 out[4]) {
  return sampleTexture8(textureReads(texture, sampler), mask, uv, right, down, channels, out);
}

}  // namespace
}  // namespace tessera::render
