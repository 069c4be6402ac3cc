// The eight-lane types of simd_lanes.h for the vector translation units: GCC/Clang vector
// extensions, with x86 intrinsics where the target has them (included by simd_lanes.h when
// TESSERA_SIMD_SCALAR is not defined).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#if !defined(TESSERA_LANES_INLINE)
#error "include render/simd_lanes.h, not this file"
#endif

namespace tessera::render {
namespace {

typedef int32_t I32x8 __attribute__((vector_size(32)));
typedef int64_t I64x8 __attribute__((vector_size(64)));
typedef float F32x8 __attribute__((vector_size(32)));
typedef uint32_t U32x8 __attribute__((vector_size(32)));

template <typename T>
TESSERA_LANES_INLINE auto splat(T x) {
  if constexpr (std::is_same_v<T, int64_t>) {
    return I64x8{} + x;
  } else if constexpr (std::is_same_v<T, float>) {
    // A broadcast, not 0 + x: that costs an add and turns -0 into +0 (the scalar lanes keep -0).
    return F32x8{x, x, x, x, x, x, x, x};
  } else {
    static_assert(std::is_same_v<T, int32_t>);
    return I32x8{} + x;
  }
}
TESSERA_LANES_INLINE I32x8 iota() {
  return I32x8{0, 1, 2, 3, 4, 5, 6, 7};
}
TESSERA_LANES_INLINE I32x8 lessThan(F32x8 a, F32x8 b) {
  return a < b;
}
TESSERA_LANES_INLINE I32x8 nonNegative(I32x8 a) {
  return a >= 0;
}
TESSERA_LANES_INLINE I32x8 nonNegative(I64x8 a) {
  return __builtin_convertvector(a >= 0, I32x8);
}
TESSERA_LANES_INLINE I32x8 lessOrEqual(I32x8 a, I32x8 b) {
  return a <= b;
}
TESSERA_LANES_INLINE F32x8 toFloat(I32x8 a) {
  return __builtin_convertvector(a, F32x8);
}
TESSERA_LANES_INLINE I64x8 widen(I32x8 a) {
  return __builtin_convertvector(a, I64x8);
}
TESSERA_LANES_INLINE I32x8 select(I32x8 mask, I32x8 a, I32x8 b) {
  return mask ? a : b;
}
TESSERA_LANES_INLINE F32x8 select(I32x8 mask, F32x8 a, F32x8 b) {
  return mask ? a : b;
}
// One test instruction where the target has it (a lane loop compiles to eight extracts).
TESSERA_LANES_INLINE bool any(I32x8 mask) {
#if defined(__AVX__)
  const __m256i m = reinterpret_cast<__m256i>(mask);
  return !_mm256_testz_si256(m, m);
#elif defined(__SSE2__)
  __m128i half[2];
  std::memcpy(half, &mask, sizeof half);
  return _mm_movemask_epi8(_mm_or_si128(half[0], half[1])) != 0;
#else
  int32_t r = 0;
  for (int l = 0; l < 8; ++l) r |= mask[l];
  return r != 0;
#endif
}
// Row l of the 8x8 matrix r becomes column l: interleave pairs, then quads, then halves (the
// shuffles map to unpack, shufps and vperm2f128).
TESSERA_LANES_INLINE void transpose8x8(F32x8 r[8]) {
#if defined(__SSE2__) && !defined(__AVX__)
  // GCC lowers the eight-lane shuffles below to single-float moves without AVX: transpose the
  // four 4x4 blocks as registers of four, the two off the diagonal trading places.
  __m128 h[2][8];  // h[half][row]
  for (int i = 0; i < 8; ++i) {
    std::memcpy(h[0] + i, reinterpret_cast<const char*>(&r[i]), 16);
    std::memcpy(h[1] + i, reinterpret_cast<const char*>(&r[i]) + 16, 16);
  }
  for (int k = 0; k < 2; ++k)
    for (int b = 0; b < 8; b += 4)
      _MM_TRANSPOSE4_PS(h[k][b], h[k][b + 1], h[k][b + 2], h[k][b + 3]);
  for (int i = 0; i < 4; ++i) {
    std::memcpy(reinterpret_cast<char*>(&r[i]), h[0] + i, 16);
    std::memcpy(reinterpret_cast<char*>(&r[i]) + 16, h[0] + 4 + i, 16);
    std::memcpy(reinterpret_cast<char*>(&r[4 + i]), h[1] + i, 16);
    std::memcpy(reinterpret_cast<char*>(&r[4 + i]) + 16, h[1] + 4 + i, 16);
  }
#else
  // __builtin_shufflevector: GCC 12 and Clang both have it (GCC's __builtin_shuffle is GCC's own).
  F32x8 t[8], u[8];
  for (int i = 0; i < 8; i += 2) {
    t[i] = __builtin_shufflevector(r[i], r[i + 1], 0, 8, 1, 9, 4, 12, 5, 13);
    t[i + 1] = __builtin_shufflevector(r[i], r[i + 1], 2, 10, 3, 11, 6, 14, 7, 15);
  }
  for (int i = 0; i < 8; i += 4) {
    u[i] = __builtin_shufflevector(t[i], t[i + 2], 0, 1, 8, 9, 4, 5, 12, 13);
    u[i + 1] = __builtin_shufflevector(t[i], t[i + 2], 2, 3, 10, 11, 6, 7, 14, 15);
    u[i + 2] = __builtin_shufflevector(t[i + 1], t[i + 3], 0, 1, 8, 9, 4, 5, 12, 13);
    u[i + 3] = __builtin_shufflevector(t[i + 1], t[i + 3], 2, 3, 10, 11, 6, 7, 14, 15);
  }
  for (int i = 0; i < 4; ++i) {
    r[i] = __builtin_shufflevector(u[i], u[i + 4], 0, 1, 2, 3, 8, 9, 10, 11);
    r[i + 4] = __builtin_shufflevector(u[i], u[i + 4], 4, 5, 6, 7, 12, 13, 14, 15);
  }
#endif
}
// Bit l set where lane l of the mask is (its sign bit, as a comparison leaves it).
TESSERA_LANES_INLINE unsigned laneBits(I32x8 mask) {
#if defined(__AVX__)
  return static_cast<unsigned>(_mm256_movemask_ps(reinterpret_cast<__m256>(mask)));
#elif defined(__SSE2__)
  __m128 half[2];
  std::memcpy(half, &mask, sizeof half);
  return static_cast<unsigned>(_mm_movemask_ps(half[0]) | (_mm_movemask_ps(half[1]) << 4));
#else
  unsigned bits = 0;
  for (int l = 0; l < 8; ++l) bits |= static_cast<unsigned>(mask[l] < 0) << l;
  return bits;
#endif
}
// The first lane of a mask that is not all zero.
TESSERA_LANES_INLINE int firstLane(I32x8 mask) {
  return __builtin_ctz(laneBits(mask));
}
TESSERA_LANES_INLINE I32x8 equal(I32x8 a, I32x8 b) {
  return a == b;
}
TESSERA_LANES_INLINE I32x8 positive(F32x8 a) {
  return a > 0.0f;
}
TESSERA_LANES_INLINE F32x8 squareRoot(F32x8 a) {
  F32x8 r;
  for (int l = 0; l < 8; ++l) r[l] = __builtin_sqrtf(a[l]);  // becomes one vector sqrt
  return r;
}
TESSERA_LANES_INLINE F32x8 maximum(F32x8 a, F32x8 b) {
  return a < b ? b : a;
}
// a < b ? a : b and a > b ? a : b lane by lane (the x86 min and max: a NaN in a gives b). One
// instruction with AVX; GCC does not fold the compare and blend into it by itself.
TESSERA_LANES_INLINE F32x8 lowerOf(F32x8 a, F32x8 b) {
#if defined(__AVX__)
  return reinterpret_cast<F32x8>(
      _mm256_min_ps(reinterpret_cast<__m256>(a), reinterpret_cast<__m256>(b)));
#else
  return a < b ? a : b;
#endif
}
TESSERA_LANES_INLINE F32x8 upperOf(F32x8 a, F32x8 b) {
#if defined(__AVX__)
  return reinterpret_cast<F32x8>(
      _mm256_max_ps(reinterpret_cast<__m256>(a), reinterpret_cast<__m256>(b)));
#else
  return a > b ? a : b;
#endif
}
TESSERA_LANES_INLINE I32x8 bitsOf(F32x8 a) {
  return reinterpret_cast<I32x8>(a);
}
TESSERA_LANES_INLINE I32x8 shiftRight(I32x8 a, int n) {
  return a >> n;
}
TESSERA_LANES_INLINE I32x8 shiftLeft(I32x8 a, int n) {
  return reinterpret_cast<I32x8>(reinterpret_cast<U32x8>(a) << n);
}
TESSERA_LANES_INLINE I32x8 truncate(F32x8 a) {
  return __builtin_convertvector(a, I32x8);
}
// table[index[l]] for every lane (each index must be valid, whatever the lane holds): one
// gather instruction with AVX2 (GCC does not turn the lane loop into one by itself).
TESSERA_LANES_INLINE F32x8 gather(const float* table, I32x8 index) {
#if defined(__AVX2__)
  return reinterpret_cast<F32x8>(
      _mm256_i32gather_ps(table, reinterpret_cast<__m256i>(index), sizeof(float)));
#else
  F32x8 r;
  for (int l = 0; l < 8; ++l) r[l] = table[index[l]];
  return r;
#endif
}
TESSERA_LANES_INLINE I32x8 lessThan(I32x8 a, I32x8 b) {
  return a < b;
}
TESSERA_LANES_INLINE I32x8 gatherWords(const uint32_t* table, I32x8 index) {
#if defined(__AVX2__)
  return reinterpret_cast<I32x8>(_mm256_i32gather_epi32(
      reinterpret_cast<const int*>(table), reinterpret_cast<__m256i>(index), sizeof(uint32_t)));
#else
  I32x8 r;
  for (int l = 0; l < 8; ++l) r[l] = static_cast<int32_t>(table[index[l]]);
  return r;
#endif
}
TESSERA_LANES_INLINE F32x8 floorLanes(F32x8 a) {
#if defined(__AVX__)
  // One vroundps: GCC 12 turns the lane loop below into eight vroundss and the shuffles between.
  return reinterpret_cast<F32x8>(_mm256_floor_ps(reinterpret_cast<__m256>(a)));
#else
  for (int l = 0; l < 8; ++l) a[l] = __builtin_floorf(a[l]);
  return a;
#endif
}
// table[index[l]] for indices in [0, 8): one in-register permute where the target has it (a
// gather instruction takes about thirteen cycles on AMD cores).
TESSERA_LANES_INLINE F32x8 lookup8(const float* table, I32x8 index) {
#if defined(__AVX2__)
  return reinterpret_cast<F32x8>(
      _mm256_permutevar8x32_ps(_mm256_loadu_ps(table), reinterpret_cast<__m256i>(index)));
#else
  return gather(table, index);
#endif
}
// table[index[l]] for indices in [0, 16): two in-register permutes where the target has them.
TESSERA_LANES_INLINE F32x8 lookup16(const float* table, I32x8 index) {
#if defined(__AVX2__)
  const __m256i i = reinterpret_cast<__m256i>(index);
  const __m256 low = _mm256_permutevar8x32_ps(_mm256_loadu_ps(table), i);
  const __m256 high = _mm256_permutevar8x32_ps(_mm256_loadu_ps(table + 8), i);
  // Lanes with index >= 8 take the high half (the permutes use the index's low three bits).
  const __m256 upper = _mm256_castsi256_ps(_mm256_slli_epi32(i, 28));
  return reinterpret_cast<F32x8>(_mm256_blendv_ps(low, high, upper));
#else
  return gather(table, index);
#endif
}
TESSERA_LANES_INLINE float lane(F32x8 a, int l) {
  return a[l];
}
TESSERA_LANES_INLINE int32_t lane(I32x8 a, int l) {
  return a[l];
}
TESSERA_LANES_INLINE void setLane(F32x8& a, int l, float x) {
  a[l] = x;
}
TESSERA_LANES_INLINE F32x8 fromBits(I32x8 a) {
  return reinterpret_cast<F32x8>(a);
}
TESSERA_LANES_INLINE F32x8 negate(F32x8 a) {
  return -a;  // flips the sign bit, like scalar unary minus
}
TESSERA_LANES_INLINE I32x8 equal(F32x8 a, F32x8 b) {
  return a == b;
}
// lessThan, lessOrEqual, positive, equal and select again, as masks the same in every variant,
// but fast on SSE2 as well: without AVX, GCC 12 compiles those eight-lane compares and
// conditionals one lane at a time (a scalar compare, setcc, and a branch per lane for select);
// split into two four-lane halves they are one instruction each. (The older kernels still use the
// originals.)
#if defined(__AVX__)
TESSERA_LANES_INLINE I32x8 maskLess(F32x8 a, F32x8 b) {
  return a < b;
}
TESSERA_LANES_INLINE I32x8 maskLessOrEqual(I32x8 a, I32x8 b) {
  return a <= b;
}
TESSERA_LANES_INLINE I32x8 maskEqual(F32x8 a, F32x8 b) {
  return a == b;
}
TESSERA_LANES_INLINE I32x8 maskEqual(I32x8 a, I32x8 b) {
  return a == b;
}
template <typename V>
TESSERA_LANES_INLINE V blend(I32x8 mask, V a, V b) {
  return mask ? a : b;
}
#else
// Applies op to the four-lane halves of a and b.
template <typename R, typename V, typename Op>
TESSERA_LANES_INLINE R byHalves(V a, V b, Op op) {
  typedef std::remove_reference_t<decltype(a[0])> T;
  typedef T V4 __attribute__((vector_size(16)));
  V4 ah[2], bh[2];
  std::memcpy(ah, &a, sizeof ah);
  std::memcpy(bh, &b, sizeof bh);
  const decltype(op(ah[0], bh[0])) rh[2] = {op(ah[0], bh[0]), op(ah[1], bh[1])};
  R r;
  std::memcpy(&r, rh, sizeof r);
  return r;
}
TESSERA_LANES_INLINE I32x8 maskLess(F32x8 a, F32x8 b) {
  return byHalves<I32x8>(a, b, [](auto x, auto y) { return x < y; });
}
TESSERA_LANES_INLINE I32x8 maskLessOrEqual(I32x8 a, I32x8 b) {
  return byHalves<I32x8>(a, b, [](auto x, auto y) { return x <= y; });
}
TESSERA_LANES_INLINE I32x8 maskEqual(F32x8 a, F32x8 b) {
  return byHalves<I32x8>(a, b, [](auto x, auto y) { return x == y; });
}
TESSERA_LANES_INLINE I32x8 maskEqual(I32x8 a, I32x8 b) {
  return byHalves<I32x8>(a, b, [](auto x, auto y) { return x == y; });
}
template <typename V>
TESSERA_LANES_INLINE V blend(I32x8 mask, V a, V b) {
  // On bits, so that the halves of mask, a and b have one type.
  const I32x8 ai = reinterpret_cast<I32x8>(a), bi = reinterpret_cast<I32x8>(b);
  return reinterpret_cast<V>((mask & ai) | (~mask & bi));
}
#endif
TESSERA_LANES_INLINE I32x8 maskPositive(F32x8 a) {
  return maskLess(F32x8{}, a);
}
// Exactly static_cast<int32_t>(std::lrint(a)) per lane: round half to even in the default
// rounding mode, and the low 32 bits of lrint's long where the value does not fit.
TESSERA_LANES_INLINE I32x8 roundToInt(F32x8 a) {
  I32x8 r;
#if defined(__AVX__)
  r = reinterpret_cast<I32x8>(_mm256_cvtps_epi32(reinterpret_cast<__m256>(a)));
#elif defined(__SSE2__)
  __m128 half[2];
  std::memcpy(half, &a, sizeof half);
  const __m128i rounded[2] = {_mm_cvtps_epi32(half[0]), _mm_cvtps_epi32(half[1])};
  std::memcpy(&r, rounded, sizeof r);
#else
  for (int l = 0; l < 8; ++l) r[l] = static_cast<int32_t>(std::lrint(a[l]));
#endif
  // cvtps2dq answers INT32_MIN for NaN and for anything outside int32, where lrint's long cast to
  // int32 keeps its low bits (0 for NaN). Rare (cut vertices, degenerate w): redo those lanes.
  const I32x8 maybe_out_of_range = maskEqual(r, splat(INT32_MIN));
  if (any(maybe_out_of_range)) {
    for (int l = 0; l < 8; ++l)
      if (r[l] == INT32_MIN) r[l] = static_cast<int32_t>(std::lrint(a[l]));
  }
  return r;
}
// Within each half (lanes 0-3 and 4-7), row l of the 4x4 matrix r becomes column l: the first
// two steps of transpose8x8 (unpack and shufps, no lane crossing).
TESSERA_LANES_INLINE void transpose4x4Halves(F32x8 r[4]) {
#if defined(__SSE2__) && !defined(__AVX__)
  // GCC lowers the eight-lane shuffles below to single-float moves without AVX: transpose each
  // half as a register of four.
  __m128 h[2][4];
  for (int i = 0; i < 4; ++i) std::memcpy(h[0] + i, reinterpret_cast<const char*>(&r[i]), 16);
  for (int i = 0; i < 4; ++i) std::memcpy(h[1] + i, reinterpret_cast<const char*>(&r[i]) + 16, 16);
  for (int k = 0; k < 2; ++k) _MM_TRANSPOSE4_PS(h[k][0], h[k][1], h[k][2], h[k][3]);
  for (int i = 0; i < 4; ++i) {
    std::memcpy(reinterpret_cast<char*>(&r[i]), h[0] + i, 16);
    std::memcpy(reinterpret_cast<char*>(&r[i]) + 16, h[1] + i, 16);
  }
#else
  // __builtin_shufflevector: GCC 12 and Clang both have it.
  const F32x8 t0 = __builtin_shufflevector(r[0], r[1], 0, 8, 1, 9, 4, 12, 5, 13);
  const F32x8 t1 = __builtin_shufflevector(r[0], r[1], 2, 10, 3, 11, 6, 14, 7, 15);
  const F32x8 t2 = __builtin_shufflevector(r[2], r[3], 0, 8, 1, 9, 4, 12, 5, 13);
  const F32x8 t3 = __builtin_shufflevector(r[2], r[3], 2, 10, 3, 11, 6, 14, 7, 15);
  r[0] = __builtin_shufflevector(t0, t2, 0, 1, 8, 9, 4, 5, 12, 13);
  r[1] = __builtin_shufflevector(t0, t2, 2, 3, 10, 11, 6, 7, 14, 15);
  r[2] = __builtin_shufflevector(t1, t3, 0, 1, 8, 9, 4, 5, 12, 13);
  r[3] = __builtin_shufflevector(t1, t3, 2, 3, 10, 11, 6, 7, 14, 15);
#endif
}
// The low 16 bits of each lane, to eight consecutive uint16_t.
TESSERA_LANES_INLINE void storeU16(uint16_t* p, I32x8 a) {
  typedef uint16_t U16x8 __attribute__((vector_size(16)));
  const U16x8 narrow = __builtin_convertvector(a, U16x8);
  std::memcpy(p, &narrow, sizeof narrow);
}

// Added for the setup kernel (setup_kernel.h).
typedef double F64x8 __attribute__((vector_size(64)));
TESSERA_LANES_INLINE F64x8 splat(double x) {
  return F64x8{x, x, x, x, x, x, x, x};
}
TESSERA_LANES_INLINE F64x8 toDouble(I32x8 a) {
  return __builtin_convertvector(a, F64x8);
}
// Rounded to nearest, as static_cast<float>(double).
TESSERA_LANES_INLINE F32x8 toFloat(F64x8 a) {
  return __builtin_convertvector(a, F32x8);
}
// Eight 64-bit lanes as sixteen 32-bit ones: lane l's low half is element 2l, its high half 2l+1.
typedef int32_t I32x16 __attribute__((vector_size(64)));
// Shuffles, not __builtin_convertvector (GCC narrows 64-bit lanes to 32 one lane at a time), and
// of native-width pieces (a 64-byte shuffle goes through memory, one element at a time).
typedef int32_t I32x4 __attribute__((vector_size(16)));
template <int kOdd>
TESSERA_LANES_INLINE I32x8 pickHalves(I32x16 a) {
#if defined(__AVX__)
  // Halves taken as 64-bit elements (an I32x16 shuffle goes through memory too).
  typedef int64_t I64x4 __attribute__((vector_size(32)));
  const I64x8 wide = reinterpret_cast<I64x8>(a);
  const I32x8 lo = reinterpret_cast<I32x8>(I64x4(__builtin_shufflevector(wide, wide, 0, 1, 2, 3)));
  const I32x8 hi = reinterpret_cast<I32x8>(I64x4(__builtin_shufflevector(wide, wide, 4, 5, 6, 7)));
  return __builtin_shufflevector(lo, hi, kOdd, kOdd + 2, kOdd + 4, kOdd + 6, kOdd + 8, kOdd + 10,
                                 kOdd + 12, kOdd + 14);
#else
  const I32x4 q0 = __builtin_shufflevector(a, a, 0, 1, 2, 3);
  const I32x4 q1 = __builtin_shufflevector(a, a, 4, 5, 6, 7);
  const I32x4 q2 = __builtin_shufflevector(a, a, 8, 9, 10, 11);
  const I32x4 q3 = __builtin_shufflevector(a, a, 12, 13, 14, 15);
  const I32x4 h0 = __builtin_shufflevector(q0, q1, kOdd, kOdd + 2, kOdd + 4, kOdd + 6);
  const I32x4 h1 = __builtin_shufflevector(q2, q3, kOdd, kOdd + 2, kOdd + 4, kOdd + 6);
  return __builtin_shufflevector(h0, h1, 0, 1, 2, 3, 4, 5, 6, 7);
#endif
}
TESSERA_LANES_INLINE I32x8 evenHalves(I32x16 a) {
  return pickHalves<0>(a);
}
TESSERA_LANES_INLINE I32x8 oddHalves(I32x16 a) {
  return pickHalves<1>(a);
}
// Compared a quarter or a half at a time: GCC compares wider-than-native vectors lane by lane.
typedef double F64x2 __attribute__((vector_size(16)));
TESSERA_LANES_INLINE I32x8 lessThan(F64x8 a, F64x8 b) {
  // Each 64-bit mask is all ones or zero: its low half will do.
  auto quarter = [&](auto i) {
    constexpr int k = decltype(i)::value * 2;
    const F64x2 x = __builtin_shufflevector(a, a, k, k + 1);
    const F64x2 y = __builtin_shufflevector(b, b, k, k + 1);
    return reinterpret_cast<I32x4>(x < y);
  };
  const I32x4 q0 = quarter(std::integral_constant<int, 0>{});
  const I32x4 q1 = quarter(std::integral_constant<int, 1>{});
  const I32x4 q2 = quarter(std::integral_constant<int, 2>{});
  const I32x4 q3 = quarter(std::integral_constant<int, 3>{});
  const I32x4 h0 = __builtin_shufflevector(q0, q1, 0, 2, 4, 6);
  const I32x4 h1 = __builtin_shufflevector(q2, q3, 0, 2, 4, 6);
  return __builtin_shufflevector(h0, h1, 0, 1, 2, 3, 4, 5, 6, 7);
}
// For lanes holding integers below 2^51 in magnitude: their exact int64 values. Adding 1.5 * 2^52
// puts the integer in the low mantissa bits (without AVX-512DQ there is no vector conversion).
TESSERA_LANES_INLINE I64x8 exactInt64(F64x8 a) {
  const F64x8 magic = splat(0x1.8p52);
  return reinterpret_cast<I64x8>(a + magic) - reinterpret_cast<I64x8>(magic);
}
// The low and the high 32 bits of each lane.
TESSERA_LANES_INLINE I32x8 low32(I64x8 a) {
  return evenHalves(reinterpret_cast<I32x16>(a));
}
TESSERA_LANES_INLINE I32x8 high32(I64x8 a) {
  return oddHalves(reinterpret_cast<I32x16>(a));
}
TESSERA_LANES_INLINE I32x8 minimum(I32x8 a, I32x8 b) {
  return b < a ? b : a;
}
TESSERA_LANES_INLINE I32x8 maximum(I32x8 a, I32x8 b) {
  return a < b ? b : a;
}
TESSERA_LANES_INLINE F32x8 floatsOf(I32x8 a) {
  return reinterpret_cast<F32x8>(a);
}
// Lane l from the double at `first` + l * stride bytes.
TESSERA_LANES_INLINE F64x8 loadStrided(const double* first, size_t stride) {
  F64x8 r;
  for (int l = 0; l < 8; ++l)
    r[l] = *reinterpret_cast<const double*>(reinterpret_cast<const char*>(first) + l * stride);
  return r;
}

#if defined(__AVX2__)
// A table of f(bits) for every eight-bit lane mask: eight bytes a mask, one a lane (byteLanes).
template <typename F>
constexpr auto laneMaskTable(F f) {
  struct Table {
    uint64_t of[256];
  } t{};
  for (unsigned bits = 0; bits < 256; ++bits) t.of[bits] = f(bits);
  return t;
}
// Eight bytes into eight lanes, byte l into lane l.
TESSERA_LANES_INLINE I32x8 byteLanes(uint64_t bytes) {
  return reinterpret_cast<I32x8>(
      _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(static_cast<long long>(bytes))));
}
#endif
#if defined(__AVX2__) && !defined(__AVX512VL__)
// compressLanes' permutations: for each eight-bit mask, the indices of its set lanes in order, one
// byte each, the rest 0.
constexpr uint64_t compressIndices(unsigned bits) {
  uint64_t indices = 0;
  int n = 0;
  for (unsigned l = 0; l < 8; ++l)
    if (bits & (1u << l)) indices |= uint64_t{l} << (8 * n++);
  return indices;
}
constexpr auto kCompressIndices = laneMaskTable(compressIndices);
#endif
// The lanes of v where `mask` is set moved to the front in lane order (the lanes after them hold
// anything); `count` becomes their number.
TESSERA_LANES_INLINE I32x8 compressLanes(I32x8 v, I32x8 mask, int& count) {
#if defined(__AVX512VL__)
  const __mmask8 k =
      _mm256_cmpneq_epi32_mask(reinterpret_cast<__m256i>(mask), _mm256_setzero_si256());
  count = __builtin_popcount(k);
  return reinterpret_cast<I32x8>(_mm256_maskz_compress_epi32(k, reinterpret_cast<__m256i>(v)));
#elif defined(__AVX2__)
  const unsigned bits = laneBits(mask);
  count = __builtin_popcount(bits);
  return reinterpret_cast<I32x8>(
      _mm256_permutevar8x32_epi32(reinterpret_cast<__m256i>(v),
                                  reinterpret_cast<__m256i>(byteLanes(kCompressIndices.of[bits]))));
#else
  I32x8 r = v;
  int n = 0;
  for (int l = 0; l < 8; ++l)
    if (mask[l]) r[n++] = v[l];
  count = n;
  return r;
#endif
}

}  // namespace
}  // namespace tessera::render
