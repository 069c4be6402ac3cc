// Texture sampling eight lanes at a time, for the shading kernels (shade_lanes.h): sampleTexture
// (shade.cpp) with the same integer and float operations per lane (the bilinear filter's are
// FixedFilter's, texture.h), so every variant gives the same bits.
// Bilinear and trilinear filtering, every wrap mode, the sampler's transform; nearest filtering and
// coordinates of 65536 and beyond are left to the caller, lane by lane.
#pragma once

#include <algorithm>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

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

// One channel of eight texels (bits `shift`..`shift + 7`) as the filter reads it: `table` is
// texelFixedTable's.
TESSERA_LANES_INLINE I32x8 fixedChannel(I32x8 texels, int shift, const int32_t* table) {
  return gatherWords(reinterpret_cast<const uint32_t*>(table),
                     shiftRight(texels, shift) & splat(int32_t{0xff}));
}

struct LevelLanes {
  int width, height;
  const uint32_t* texels;
  const int16_t* linear;  // Texture::linearTexels of this level, or null
};

// Eight lanes of eight 16-bit values from p (unaligned), widened: the generic form of what the
// AVX2 path of fixedQuads8 reads a register half at a time.
TESSERA_LANES_INLINE I32x8 widen16(const int16_t* p) {
#if defined(TESSERA_SIMD_SCALAR)
  alignas(32) int32_t v[8];
  for (int i = 0; i < 8; ++i) v[i] = p[i];
  return load<I32x8>(v);
#else
  typedef int16_t I16x8 __attribute__((vector_size(16), aligned(2)));
  return __builtin_convertvector(*reinterpret_cast<const I16x8*>(p), I32x8);
#endif
}

// The weights of the filter across (w0 for the left texel, w1 for the right) as the 16-bit pair
// w0 | w1 << 16 that maddPairs takes.
TESSERA_LANES_INLINE I32x8 weightPairs(I32x8 w1) {
  return (splat(FixedFilter::kWeightOne) - w1) | shiftLeft(w1, 16);
}

// a * w0 + b * w1 in each lane, for a and b in [0, kTexelOne] and `weights` = weightPairs: one
// multiply-add of 16-bit pairs (pmaddwd) where the target has it (SSE2 has no 32-bit multiply:
// five instructions each).
TESSERA_LANES_INLINE I32x8 maddPairs(I32x8 a, I32x8 b, I32x8 weights) {
#if defined(__AVX2__)
  const I32x8 pairs = a | shiftLeft(b, 16);
  return reinterpret_cast<I32x8>(
      _mm256_madd_epi16(reinterpret_cast<__m256i>(pairs), reinterpret_cast<__m256i>(weights)));
#elif defined(__SSE2__) && !defined(TESSERA_SIMD_SCALAR)
  typedef int32_t I32x4 __attribute__((vector_size(16)));
  const I32x8 pairs = a | shiftLeft(b, 16);
  const auto madd = [](I32x4 x, I32x4 w) {
    return reinterpret_cast<I32x4>(
        _mm_madd_epi16(reinterpret_cast<__m128i>(x), reinterpret_cast<__m128i>(w)));
  };
  const I32x4 low = madd(__builtin_shufflevector(pairs, pairs, 0, 1, 2, 3),
                         __builtin_shufflevector(weights, weights, 0, 1, 2, 3));
  const I32x4 high = madd(__builtin_shufflevector(pairs, pairs, 4, 5, 6, 7),
                          __builtin_shufflevector(weights, weights, 4, 5, 6, 7));
  return __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7);
#else
  return a * (weights & splat(int32_t{0xffff})) + b * shiftRight(weights, 16);
#endif
}

// The filter across and down (FixedFilter) for one channel of eight lanes: a and b the upper row's
// left and right texels, c and d the lower row's, `weights` their weightPairs.
TESSERA_LANES_INLINE F32x8 fixedLerp8(I32x8 a, I32x8 b, I32x8 c, I32x8 d, I32x8 weights, F32x8 ty) {
  const F32x8 upper = toFloat(maddPairs(a, b, weights));
  const F32x8 lower = toFloat(maddPairs(c, d, weights));
  return (upper + (lower - upper) * ty) * splat(FixedFilter::kScale);
}

// The four channels of the texels at `index` (eight lanes) of a level's copy, channel by channel.
TESSERA_LANES_INLINE void loadFixed8(const int16_t* linear, I32x8 index, I32x8 out[4]) {
  alignas(32) int32_t at[8], channel[4][8];
  store(at, index);
  for (int l = 0; l < 8; ++l)
    for (int k = 0; k < 4; ++k) channel[k][l] = linear[4 * static_cast<size_t>(at[l]) + k];
  for (int k = 0; k < 4; ++k) out[k] = load<I32x8>(channel[k]);
}

// The filter of the quads whose upper left texels are at `at` (each lane's index in a level
// `width` texels wide, its right and lower neighbours inside the level) from the level's copy,
// `channels` channels into out. Each lane's texel and its right neighbour are 16 consecutive
// bytes. On AVX2 two lanes a register: the pair's channels interleaved by a byte shuffle and
// blended across by one vpmaddwd (fixedLerp8's integers), down in float, then one in-lane 4x4
// transpose; on SSE2 one lane a register and two 4x4 transposes; elsewhere a 16-bit load widened
// per lane and row, an 8x8 transpose each, and fixedLerp8. The same bits every way.
TESSERA_LANES_INLINE void fixedQuads8(const int16_t* linear, const int32_t at[8], int width,
                                      I32x8 w1, F32x8 ty, int channels, F32x8 out[4]) {
  const size_t down = 4 * static_cast<size_t>(width);
#if defined(__AVX2__)
  const __m256i weights = reinterpret_cast<__m256i>(weightPairs(w1));
  const __m256i interleave = _mm256_setr_epi8(0, 1, 8, 9, 2, 3, 10, 11, 4, 5, 12, 13, 6, 7, 14, 15,
                                              0, 1, 8, 9, 2, 3, 10, 11, 4, 5, 12, 13, 6, 7, 14, 15);
  const auto pair = [&](const int16_t* a, const int16_t* b, __m256i w) {
    const __m256i texels = _mm256_inserti128_si256(
        _mm256_castsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(a))),
        _mm_loadu_si128(reinterpret_cast<const __m128i*>(b)), 1);
    return _mm256_cvtepi32_ps(_mm256_madd_epi16(_mm256_shuffle_epi8(texels, interleave), w));
  };
  __m256 o[4];
  for (int p = 0; p < 4; ++p) {
    // Lanes p and p + 4: the low and high halves.
    const __m256i lanes = _mm256_setr_epi32(p, p, p, p, p + 4, p + 4, p + 4, p + 4);
    const __m256i w = _mm256_permutevar8x32_epi32(weights, lanes);
    const __m256 t = _mm256_permutevar8x32_ps(reinterpret_cast<__m256>(ty), lanes);
    const int16_t* a = linear + 4 * static_cast<size_t>(at[p]);
    const int16_t* b = linear + 4 * static_cast<size_t>(at[p + 4]);
    const __m256 upper = pair(a, b, w), lower = pair(a + down, b + down, w);
    o[p] = _mm256_add_ps(upper, _mm256_mul_ps(_mm256_sub_ps(lower, upper), t));
  }
  const __m256 t0 = _mm256_unpacklo_ps(o[0], o[1]), t1 = _mm256_unpacklo_ps(o[2], o[3]);
  const __m256 t2 = _mm256_unpackhi_ps(o[0], o[1]), t3 = _mm256_unpackhi_ps(o[2], o[3]);
  const __m256 columns[4] = {_mm256_shuffle_ps(t0, t1, 0x44), _mm256_shuffle_ps(t0, t1, 0xee),
                             _mm256_shuffle_ps(t2, t3, 0x44), _mm256_shuffle_ps(t2, t3, 0xee)};
  for (int k = 0; k < channels; ++k)
    out[k] = reinterpret_cast<F32x8>(columns[k]) * splat(FixedFilter::kScale);
#elif defined(__SSE2__) && !defined(TESSERA_SIMD_SCALAR)
  // One lane a register: its two texels' channels interleaved by two unpacks, blended across by
  // one pmaddwd a row, down in float; then a 4x4 transpose for lanes 0-3 and one for 4-7.
  alignas(32) int32_t weights[8];
  alignas(32) float fractions[8];
  store(weights, weightPairs(w1));
  store(fractions, ty);
  const auto across = [](const int16_t* p, __m128i w) {
    const __m128i texels = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
    return _mm_cvtepi32_ps(
        _mm_madd_epi16(_mm_unpacklo_epi16(texels, _mm_unpackhi_epi64(texels, texels)), w));
  };
  __m128 o[8];
  for (int l = 0; l < 8; ++l) {
    const int16_t* p = linear + 4 * static_cast<size_t>(at[l]);
    const __m128i w = _mm_set1_epi32(weights[l]);
    const __m128 upper = across(p, w), lower = across(p + down, w);
    o[l] = _mm_add_ps(upper, _mm_mul_ps(_mm_sub_ps(lower, upper), _mm_set1_ps(fractions[l])));
  }
  _MM_TRANSPOSE4_PS(o[0], o[1], o[2], o[3]);
  _MM_TRANSPOSE4_PS(o[4], o[5], o[6], o[7]);
  typedef float F32x4 __attribute__((vector_size(16)));
  for (int k = 0; k < channels; ++k)
    out[k] = __builtin_shufflevector(reinterpret_cast<F32x4>(o[k]),
                                     reinterpret_cast<F32x4>(o[4 + k]), 0, 1, 2, 3, 4, 5, 6, 7) *
             splat(FixedFilter::kScale);
#else
  F32x8 top[8], bottom[8];  // as bits: channels 0-3 of the left texel, then of the right one
  for (int l = 0; l < 8; ++l) {
    const int16_t* p = linear + 4 * static_cast<size_t>(at[l]);
    top[l] = fromBits(widen16(p));
    bottom[l] = fromBits(widen16(p + down));
  }
  transpose8x8(top);
  transpose8x8(bottom);
  const I32x8 weights = weightPairs(w1);
  for (int k = 0; k < channels; ++k)
    out[k] = fixedLerp8(bitsOf(top[k]), bitsOf(top[4 + k]), bitsOf(bottom[k]),
                        bitsOf(bottom[4 + k]), weights, ty);
#endif
}

// Where sampleLevel's bilinear filter reads a level for the lanes of `mask` (the others read texel
// 0): the quad's columns xa, xb and rows ya, yb (wrapped), the right texels' weights w1 and the
// lower row's fraction ty.
struct BilinearQuads {
  I32x8 xa, xb, ya, yb, w1;
  F32x8 ty;
  // Every lane's quad is two neighbouring texels of two neighbouring rows (none at a wrap or a
  // clamp): what fixedQuads8 reads.
  TESSERA_LANES_INLINE bool adjacent() const {
    const I32x8 one = splat(int32_t{1});
    return !any(~(equal(xb, xa + one) & equal(yb, ya + one)));
  }
};
TESSERA_LANES_INLINE BilinearQuads bilinearQuads8(const LevelLanes& level, const Sampler& sampler,
                                                  I32x8 mask, const Uv8& uv) {
  const F32x8 sx = uv.u * splat(static_cast<float>(level.width)) - splat(0.5f);
  const F32x8 sy = (splat(1.0f) - uv.v) * splat(static_cast<float>(level.height)) - splat(0.5f);
  const F32x8 x0f = floorLanes(sx), y0f = floorLanes(sy);
  const F32x8 tx = sx - x0f;
  const I32x8 x0 = select(mask, truncate(x0f), splat(int32_t{0}));
  const I32x8 y0 = select(mask, truncate(y0f), splat(int32_t{0}));
  BilinearQuads q;
  wrapPair8(x0, level.width, sampler.wrap_s, q.xa, q.xb);
  wrapPair8(y0, level.height, sampler.wrap_t, q.ya, q.yb);
  q.w1 = truncate(tx * splat(static_cast<float>(FixedFilter::kWeightOne)));
  q.ty = sy - y0f;
  return q;
}

// sampleLevel's bilinear filter (texture.cpp, FixedFilter) in one level for the lanes of `mask`
// (the others read texel 0), `channels` channels (3: RGB, 4: RGBA); coordinates below 65536 in
// magnitude.
TESSERA_LANES_INLINE void bilinear8(const LevelLanes& level, bool srgb, const Sampler& sampler,
                                    I32x8 mask, const Uv8& uv, int channels, F32x8 out[4]) {
  const BilinearQuads quads = bilinearQuads8(level, sampler, mask, uv);
  const I32x8 xa = quads.xa, xb = quads.xb, w1 = quads.w1;
  const F32x8 ty = quads.ty;
  const I32x8 w = splat(int32_t{level.width});
  const I32x8 row_a = quads.ya * w, row_b = quads.yb * w;
  I32x8 q[4][4];  // the channels of the quad's texels (xa, ya), (xb, ya), (xa, yb), (xb, yb)
  if (level.linear) {
    if (quads.adjacent()) {
      alignas(32) int32_t at[8];
      store(at, row_a + xa);
      fixedQuads8(level.linear, at, level.width, w1, ty, channels, out);
      return;
    }
    loadFixed8(level.linear, row_a + xa, q[0]);
    loadFixed8(level.linear, row_a + xb, q[1]);
    loadFixed8(level.linear, row_b + xa, q[2]);
    loadFixed8(level.linear, row_b + xb, q[3]);
  } else {
    const uint32_t* texels = level.texels;
    const I32x8 c[4] = {gatherWords(texels, row_a + xa), gatherWords(texels, row_a + xb),
                        gatherWords(texels, row_b + xa), gatherWords(texels, row_b + xb)};
    const int32_t* colour = texelFixedTable(srgb);
    const int32_t* unorm = texelFixedTable(false);
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < channels; ++k)
        q[i][k] = fixedChannel(c[i], 8 * k, k < 3 ? colour : unorm);
  }
  for (int k = 0; k < channels; ++k)
    out[k] = fixedLerp8(q[0][k], q[1][k], q[2][k], q[3][k], weightPairs(w1), ty);
}

TESSERA_LANES_INLINE LevelLanes levelLanes(const Texture& texture, int level) {
  const int16_t* linear = texture.linearTexels(level);
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

// The levels sampleTexture8 reads where needsLod, as sampleLod: the level of detail clamped to
// [0, last] (NaN to 0), bilinear in level floor(lod), blended with the next where the fraction is
// not 0. Lanes may need different levels: each level in use is read for the lanes that need it.
struct LodLevels {
  I32x8 lower;       // each lane's lower level
  I32x8 two_levels;  // the lanes of `mask` that blend their lower level with the next
  F32x8 blend;       // the fraction towards the next
  int first, last;   // the levels in use by the lanes of `mask`
  // The lanes that read `level` as their lower level, and as their upper one.
  TESSERA_LANES_INLINE I32x8 asLower(I32x8 mask, int level) const {
    return mask & equal(lower, splat(int32_t{level}));
  }
  TESSERA_LANES_INLINE I32x8 asUpper(int level) const {
    return two_levels & equal(lower + splat(int32_t{1}), splat(int32_t{level}));
  }
  // A channel of the lower levels' reads `a` blended towards the upper levels' `b`.
  TESSERA_LANES_INLINE F32x8 blended(F32x8 a, F32x8 b) const {
    return select(two_levels, a + (b - a) * blend, a);
  }
};
TESSERA_LANES_INLINE LodLevels lodLevels8(const Texture& texture, I32x8 mask, const Uv8& uv,
                                          const Uv8& right, const Uv8& down) {
  F32x8 lod = textureLod8(uv, right, down, static_cast<float>(texture.width),
                          static_cast<float>(texture.height));
  const int last = texture.levelCount() - 1;
  const F32x8 last_f = splat(static_cast<float>(last));
  lod = select(positive(lod), lod, splat(0.0f));
  lod = select(lessThan(last_f, lod), last_f, lod);
  LodLevels levels;
  levels.lower = truncate(lod);
  levels.blend = lod - toFloat(levels.lower);
  levels.two_levels =
      mask & ~equal(levels.blend, splat(0.0f)) & lessThan(levels.lower, splat(last));
  levels.first = last;
  levels.last = 0;
  for (int l = 0; l < 8; ++l) {
    if (!lane(mask, l)) continue;
    levels.first = std::min(levels.first, lane(levels.lower, l));
    levels.last =
        std::max(levels.last, lane(levels.lower, l) + (lane(levels.two_levels, l) ? 1 : 0));
  }
  return levels;
}

// Whether every lane of `mask` has coordinates below 65536 in magnitude (where sanitize is the
// identity), which sampleTexture8 takes.
TESSERA_LANES_INLINE bool inReach8(I32x8 mask, const Uv8& uv) {
  const F32x8 limit = splat(65536.0f), low = splat(-65536.0f);
  return !any(mask & ~(lessThan(uv.u, limit) & lessThan(low, uv.u) & lessThan(uv.v, limit) &
                       lessThan(low, uv.v)));
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
  if (!inReach8(mask, uv)) return false;
  if (!reads.lod) {
    bilinear8(reads.base, texture.srgb, sampler, mask, uv, channels, out);
    return true;
  }
  const LodLevels levels = lodLevels8(texture, mask, uv, right, down);
  F32x8 a[4], b[4], level_out[4];
  for (int k = 0; k < 4; ++k) a[k] = b[k] = splat(0.0f);
  for (int level = levels.first; level <= levels.last; ++level) {
    const I32x8 as_a = levels.asLower(mask, level), as_b = levels.asUpper(level);
    if (!any(as_a | as_b)) continue;
    bilinear8(levelLanes(texture, level), texture.srgb, sampler, as_a | as_b, uv, channels,
              level_out);
    for (int k = 0; k < channels; ++k) {
      a[k] = select(as_a, level_out[k], a[k]);
      b[k] = select(as_b, level_out[k], b[k]);
    }
  }
  for (int k = 0; k < channels; ++k) out[k] = levels.blended(a[k], b[k]);
  return true;
}

// sampleTexture8 of `texture` through `sampler`, looked up for these eight lanes alone.
TESSERA_LANES_INLINE bool sampleTexture8(const Texture& texture, const Sampler& sampler, I32x8 mask,
                                         Uv8 uv, Uv8 right, Uv8 down, int channels, F32x8 out[4]) {
  return sampleTexture8(textureReads(texture, sampler), mask, uv, right, down, channels, out);
}

}  // namespace
}  // namespace tessera::render
