// Two textured groups of a row filtered side by side in sixteen lanes (a 512-bit register each),
// for the AVX-512 kernels (TESSERA_LANES16): the coordinates, wraps and weights of
// texture_lanes.h's bilinear8 once for both groups instead of once for each, then both groups'
// texels through fixedQuads16. The same operations per lane as bilinear8, so the same bits. It
// takes the common case only (one level, the texture's copy, no transform, repeat on a power of
// two or clamp, every lane's four texels in one quad); the caller filters the two groups eight
// lanes at a time otherwise.
#pragma once

#if defined(TESSERA_LANES16)

#include "render/mixed_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

TESSERA_LANES_INLINE F32x16 join16(F32x8 low, F32x8 high) {
  return __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
}
TESSERA_LANES_INLINE I32x16 join16(I32x8 low, I32x8 high) {
  return __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
}
TESSERA_LANES_INLINE F32x8 lowHalf(F32x16 a) {
  return __builtin_shufflevector(a, a, 0, 1, 2, 3, 4, 5, 6, 7);
}
TESSERA_LANES_INLINE F32x8 highHalf(F32x16 a) {
  return __builtin_shufflevector(a, a, 8, 9, 10, 11, 12, 13, 14, 15);
}
TESSERA_LANES_INLINE bool any16(I32x16 mask) {
  const __m512i m = reinterpret_cast<__m512i>(mask);
  return _mm512_test_epi32_mask(m, m) != 0;
}
// As floorLanes.
TESSERA_LANES_INLINE F32x16 floor16(F32x16 a) {
  // The maskz form with every lane: the plain instruction (simd_lanes.h).
  return reinterpret_cast<F32x16>(_mm512_maskz_roundscale_ps(
      0xffff, reinterpret_cast<__m512>(a), _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
}

// transpose8x8 in each half of sixteen lanes: rows 0-7 of the low halves, and of the high ones,
// become their columns (the same shuffles, per 256 bits).
TESSERA_LANES_INLINE void transpose8x8Halves(F32x16 r[8]) {
  F32x16 t[8], u[8];
  for (int i = 0; i < 8; i += 2) {
    t[i] = __builtin_shufflevector(r[i], r[i + 1], 0, 16, 1, 17, 4, 20, 5, 21, 8, 24, 9, 25, 12, 28,
                                   13, 29);
    t[i + 1] = __builtin_shufflevector(r[i], r[i + 1], 2, 18, 3, 19, 6, 22, 7, 23, 10, 26, 11, 27,
                                       14, 30, 15, 31);
  }
  for (int i = 0; i < 8; i += 4) {
    u[i] = __builtin_shufflevector(t[i], t[i + 2], 0, 1, 16, 17, 4, 5, 20, 21, 8, 9, 24, 25, 12, 13,
                                   28, 29);
    u[i + 1] = __builtin_shufflevector(t[i], t[i + 2], 2, 3, 18, 19, 6, 7, 22, 23, 10, 11, 26, 27,
                                       14, 15, 30, 31);
    u[i + 2] = __builtin_shufflevector(t[i + 1], t[i + 3], 0, 1, 16, 17, 4, 5, 20, 21, 8, 9, 24, 25,
                                       12, 13, 28, 29);
    u[i + 3] = __builtin_shufflevector(t[i + 1], t[i + 3], 2, 3, 18, 19, 6, 7, 22, 23, 10, 11, 26,
                                       27, 14, 15, 30, 31);
  }
  for (int i = 0; i < 4; ++i) {
    r[i] = __builtin_shufflevector(u[i], u[i + 4], 0, 1, 2, 3, 16, 17, 18, 19, 8, 9, 10, 11, 24, 25,
                                   26, 27);
    r[i + 4] = __builtin_shufflevector(u[i], u[i + 4], 4, 5, 6, 7, 20, 21, 22, 23, 12, 13, 14, 15,
                                       28, 29, 30, 31);
  }
}

// wrapPair8 for the two wraps pairQuads16 takes (isPairWrap).
TESSERA_LANES_INLINE void wrapPair16(I32x16 i, int size, TextureWrap wrap, I32x16& first,
                                     I32x16& second) {
  const I32x16 next = i + 1;
  if (wrap == TextureWrap::kClamp) {
    const int32_t last = size - 1;
    first = i < 0 ? 0 : (last < i ? last : i);
    second = next < 0 ? 0 : (last < next ? last : next);
    return;
  }
  first = i & (size - 1);
  second = next & (size - 1);
}

TESSERA_LANES_INLINE bool isPairWrap(TextureWrap wrap, int size) {
  return wrap == TextureWrap::kClamp || (wrap == TextureWrap::kRepeat && (size & (size - 1)) == 0);
}

// fixedQuads8 for sixteen lanes (the RGB channels): four lanes a 512-bit register, lanes p, p + 4,
// p + 8 and p + 12 in its four quarters, so that the in-lane 4x4 transpose leaves the lanes in
// order. The same integers and floats per lane, so the same bits.
TESSERA_LANES_INLINE void fixedQuads16(const int16_t* linear, const int32_t at[16], int width,
                                       I32x16 w1, F32x16 ty, F32x16 out[3]) {
  const size_t down = 4 * static_cast<size_t>(width);
  const __m512i weights = reinterpret_cast<__m512i>((FixedFilter::kWeightOne - w1) | (w1 << 16));
  const __m512i interleave =
      _mm512_broadcast_i32x4(_mm_setr_epi8(0, 1, 8, 9, 2, 3, 10, 11, 4, 5, 12, 13, 6, 7, 14, 15));
  const auto quarters = [&](int p, size_t offset, __m512i w) {
    const auto at_lane = [&](int l) {
      return _mm_loadu_si128(
          reinterpret_cast<const __m128i*>(linear + 4 * static_cast<size_t>(at[l]) + offset));
    };
    __m512i texels = _mm512_castsi128_si512(at_lane(p));
    texels = _mm512_inserti32x4(texels, at_lane(p + 4), 1);
    texels = _mm512_inserti32x4(texels, at_lane(p + 8), 2);
    texels = _mm512_inserti32x4(texels, at_lane(p + 12), 3);
    return _mm512_cvtepi32_ps(_mm512_madd_epi16(_mm512_shuffle_epi8(texels, interleave), w));
  };
  __m512 o[4];
  for (int p = 0; p < 4; ++p) {
    const __m512i lanes = _mm512_setr_epi32(p, p, p, p, p + 4, p + 4, p + 4, p + 4, p + 8, p + 8,
                                            p + 8, p + 8, p + 12, p + 12, p + 12, p + 12);
    const __m512i w = _mm512_permutexvar_epi32(lanes, weights);
    const __m512 t = _mm512_permutexvar_ps(lanes, reinterpret_cast<__m512>(ty));
    const __m512 upper = quarters(p, 0, w), lower = quarters(p, down, w);
    o[p] = _mm512_add_ps(upper, _mm512_mul_ps(_mm512_sub_ps(lower, upper), t));
  }
  const __m512 t0 = _mm512_unpacklo_ps(o[0], o[1]), t1 = _mm512_unpacklo_ps(o[2], o[3]);
  const __m512 t2 = _mm512_unpackhi_ps(o[0], o[1]), t3 = _mm512_unpackhi_ps(o[2], o[3]);
  const __m512 columns[3] = {_mm512_shuffle_ps(t0, t1, 0x44), _mm512_shuffle_ps(t0, t1, 0xee),
                             _mm512_shuffle_ps(t2, t3, 0x44)};
  for (int k = 0; k < 3; ++k)
    out[k] = reinterpret_cast<F32x16>(columns[k]) * splat16(FixedFilter::kScale);
}

// Whether groups of a material whose albedo is read as `reads` can be filtered two side by side:
// in one level, from its decoded copy, untransformed, with wraps wrapPair16 takes.
TESSERA_LANES_INLINE bool pairReads(const TextureReads& reads) {
  const Sampler& sampler = *reads.sampler;
  return !reads.lod && !reads.moved && isPairWrap(sampler.wrap_s, reads.base.width) &&
         isPairWrap(sampler.wrap_t, reads.base.height) && reads.base.linear != nullptr;
}

// Where filterTexturedGroup of a and b (groups of one material, whose albedo's `reads` pairReads
// takes) reads its texels, side by side in sixteen lanes: fixedQuads16's `at`, weights and
// fractions into at[0..15], w1[0..15] and ty[0..15]. False, with nothing written, where a lane's
// coordinates are beyond the eight-lane filter's reach or its four texels are not one quad of the
// copy (at a clamped edge or a repeat's seam): the caller filters each group.
TESSERA_LANES_INLINE bool pairQuads16(const TexturedGroup& a, const TexturedGroup& b,
                                      const TextureReads& reads, int32_t at[16], int32_t w1[16],
                                      float ty[16]) {
  const Sampler& sampler = *reads.sampler;
  const I32x16 mask = join16(a.covered, b.covered);
  const F32x16 u = join16(a.uv.u, b.uv.u), v = join16(a.uv.v, b.uv.v);
  const F32x16 limit = splat16(65536.0f), low = splat16(-65536.0f);
  if (any16(mask & ~((u < limit) & (low < u) & (v < limit) & (low < v)))) return false;
  const int width = reads.base.width, height = reads.base.height;
  const F32x16 sx = u * splat16(static_cast<float>(width)) - splat16(0.5f);
  const F32x16 sy = (splat16(1.0f) - v) * splat16(static_cast<float>(height)) - splat16(0.5f);
  const F32x16 x0f = floor16(sx), y0f = floor16(sy);
  const F32x16 tx = sx - x0f;
  const I32x16 zero = splat16(int32_t{0});
  const I32x16 x0 = mask != 0 ? truncate16(x0f) : zero;
  const I32x16 y0 = mask != 0 ? truncate16(y0f) : zero;
  I32x16 xa, xb, ya, yb;
  wrapPair16(x0, width, sampler.wrap_s, xa, xb);
  wrapPair16(y0, height, sampler.wrap_t, ya, yb);
  if (any16(~((xb == xa + 1) & (yb == ya + 1)))) return false;
  store(at, ya * width + xa);
  store(w1, truncate16(tx * splat16(static_cast<float>(FixedFilter::kWeightOne))));
  store(ty, sy - y0f);
  return true;
}

// filterTexturedGroup of a and b from their quads (pairQuads16's at, w1 and ty), into ca and cb.
TESSERA_LANES_INLINE void filterPairQuads(const TexturedGroup& a, const TexturedGroup& b,
                                          const TextureReads& reads, const int32_t at[16],
                                          const int32_t w1[16], const float ty[16],
                                          const LightRig& lights, Vec3x8& ca, Vec3x8& cb) {
  F32x16 albedo[3];
  fixedQuads16(reads.base.linear, at, reads.base.width, load<I32x16>(w1), load<F32x16>(ty), albedo);
  const Vec3x8* colors[2] = {&a.color, &b.color};
  F32x16 out[3];
  for (int k = 0; k < 3; ++k) {
    const F32x8 Vec3x8::*channel = k == 0 ? &Vec3x8::x : k == 1 ? &Vec3x8::y : &Vec3x8::z;
    out[k] = join16(colors[0]->*channel, colors[1]->*channel) * albedo[k];
  }
  ca = {lowHalf(out[0]), lowHalf(out[1]), lowHalf(out[2])};
  cb = {highHalf(out[0]), highHalf(out[1]), highHalf(out[2])};
  if (lights.tone.active()) {
    toneMap8(lights.tone, ca.x, ca.y, ca.z);
    toneMap8(lights.tone, cb.x, cb.y, cb.z);
  }
}

}  // namespace
}  // namespace tessera::render

#endif  // TESSERA_LANES16
