// Eight-lane integer and float types for the raster and shading kernels. In the vector translation
// units they are GCC/Clang vector extensions (one AVX2 register, two SSE2 ones, or half an AVX-512
// one); in the scalar one they are plain arrays whose operators loop over the lanes. The kernel is
// written once against the operations below, so every variant computes the same values.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#if defined(__SSE2__) && !defined(TESSERA_SIMD_SCALAR)
#include <immintrin.h>
#endif

#define TESSERA_LANES_INLINE inline __attribute__((always_inline))

namespace tessera::render {
namespace {

#if defined(TESSERA_SIMD_SCALAR)

template <typename T>
struct Lanes {
  T v[8];
};
using I32x8 = Lanes<int32_t>;
using I64x8 = Lanes<int64_t>;
using F32x8 = Lanes<float>;

#define TESSERA_LANES_BINARY(op)                                           \
  template <typename T>                                                    \
  TESSERA_LANES_INLINE Lanes<T> operator op(Lanes<T> a, Lanes<T> b) {      \
    Lanes<T> r;                                                            \
    for (int l = 0; l < 8; ++l) r.v[l] = static_cast<T>(a.v[l] op b.v[l]); \
    return r;                                                              \
  }
TESSERA_LANES_BINARY(+)
TESSERA_LANES_BINARY(-)
TESSERA_LANES_BINARY(*)
TESSERA_LANES_BINARY(/)
TESSERA_LANES_BINARY(&)
TESSERA_LANES_BINARY(|)
#undef TESSERA_LANES_BINARY

TESSERA_LANES_INLINE Lanes<int32_t> operator~(Lanes<int32_t> a) {
  for (int l = 0; l < 8; ++l) a.v[l] = ~a.v[l];
  return a;
}

template <typename T>
TESSERA_LANES_INLINE Lanes<T> splat(T x) {
  Lanes<T> r;
  for (int l = 0; l < 8; ++l) r.v[l] = x;
  return r;
}
TESSERA_LANES_INLINE I32x8 iota() {
  return {{0, 1, 2, 3, 4, 5, 6, 7}};
}
// Masks: all ones where true.
TESSERA_LANES_INLINE I32x8 lessThan(F32x8 a, F32x8 b) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = a.v[l] < b.v[l] ? -1 : 0;
  return r;
}
TESSERA_LANES_INLINE I32x8 nonNegative(I32x8 a) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = a.v[l] >= 0 ? -1 : 0;
  return r;
}
TESSERA_LANES_INLINE I32x8 nonNegative(I64x8 a) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = a.v[l] >= 0 ? -1 : 0;
  return r;
}
TESSERA_LANES_INLINE I32x8 lessOrEqual(I32x8 a, I32x8 b) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = a.v[l] <= b.v[l] ? -1 : 0;
  return r;
}
TESSERA_LANES_INLINE F32x8 toFloat(I32x8 a) {
  F32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = static_cast<float>(a.v[l]);
  return r;
}
TESSERA_LANES_INLINE I64x8 widen(I32x8 a) {
  I64x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = a.v[l];
  return r;
}
template <typename T>
TESSERA_LANES_INLINE Lanes<T> select(I32x8 mask, Lanes<T> a, Lanes<T> b) {
  Lanes<T> r;
  for (int l = 0; l < 8; ++l) r.v[l] = mask.v[l] ? a.v[l] : b.v[l];
  return r;
}
TESSERA_LANES_INLINE bool any(I32x8 mask) {
  int32_t r = 0;
  for (int l = 0; l < 8; ++l) r |= mask.v[l];
  return r != 0;
}
// Row l of the 8x8 matrix r becomes column l.
TESSERA_LANES_INLINE void transpose8x8(F32x8 r[8]) {
  F32x8 t[8];
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) t[i].v[j] = r[j].v[i];
  for (int i = 0; i < 8; ++i) r[i] = t[i];
}
// The first lane of a mask that is not all zero.
TESSERA_LANES_INLINE int firstLane(I32x8 mask) {
  int l = 0;
  while (!mask.v[l]) ++l;
  return l;
}
TESSERA_LANES_INLINE I32x8 equal(I32x8 a, I32x8 b) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = a.v[l] == b.v[l] ? -1 : 0;
  return r;
}
TESSERA_LANES_INLINE I32x8 positive(F32x8 a) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = a.v[l] > 0.0f ? -1 : 0;
  return r;
}
TESSERA_LANES_INLINE F32x8 squareRoot(F32x8 a) {
  F32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = std::sqrt(a.v[l]);
  return r;
}
TESSERA_LANES_INLINE F32x8 maximum(F32x8 a, F32x8 b) {
  for (int l = 0; l < 8; ++l) a.v[l] = a.v[l] < b.v[l] ? b.v[l] : a.v[l];
  return a;
}
// a < b ? a : b and a > b ? a : b lane by lane (the x86 min and max: a NaN in a gives b).
TESSERA_LANES_INLINE F32x8 lowerOf(F32x8 a, F32x8 b) {
  for (int l = 0; l < 8; ++l) a.v[l] = a.v[l] < b.v[l] ? a.v[l] : b.v[l];
  return a;
}
TESSERA_LANES_INLINE F32x8 upperOf(F32x8 a, F32x8 b) {
  for (int l = 0; l < 8; ++l) a.v[l] = a.v[l] > b.v[l] ? a.v[l] : b.v[l];
  return a;
}
TESSERA_LANES_INLINE I32x8 bitsOf(F32x8 a) {
  I32x8 r;
  std::memcpy(&r, &a, sizeof r);
  return r;
}
TESSERA_LANES_INLINE I32x8 shiftRight(I32x8 a, int n) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = a.v[l] >> n;
  return r;
}
TESSERA_LANES_INLINE I32x8 shiftLeft(I32x8 a, int n) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = static_cast<int32_t>(static_cast<uint32_t>(a.v[l]) << n);
  return r;
}
TESSERA_LANES_INLINE I32x8 truncate(F32x8 a) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = static_cast<int32_t>(a.v[l]);
  return r;
}
TESSERA_LANES_INLINE F32x8 gather(const float* table, I32x8 index) {
  F32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = table[index.v[l]];
  return r;
}
TESSERA_LANES_INLINE I32x8 lessThan(I32x8 a, I32x8 b) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = a.v[l] < b.v[l] ? -1 : 0;
  return r;
}
// table[index[l]] for indices in [0, 16).
TESSERA_LANES_INLINE F32x8 lookup16(const float* table, I32x8 index) {
  return gather(table, index);
}
TESSERA_LANES_INLINE I32x8 gatherWords(const uint32_t* table, I32x8 index) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = static_cast<int32_t>(table[index.v[l]]);
  return r;
}
TESSERA_LANES_INLINE F32x8 floorLanes(F32x8 a) {
  for (int l = 0; l < 8; ++l) a.v[l] = std::floor(a.v[l]);
  return a;
}
TESSERA_LANES_INLINE I32x8 operator-(I32x8 a) {
  for (int l = 0; l < 8; ++l) a.v[l] = -a.v[l];
  return a;
}
TESSERA_LANES_INLINE float lane(F32x8 a, int l) {
  return a.v[l];
}
TESSERA_LANES_INLINE int32_t lane(I32x8 a, int l) {
  return a.v[l];
}
TESSERA_LANES_INLINE void setLane(F32x8& a, int l, float x) {
  a.v[l] = x;
}
TESSERA_LANES_INLINE F32x8 fromBits(I32x8 a) {
  F32x8 r;
  std::memcpy(&r, &a, sizeof r);
  return r;
}
TESSERA_LANES_INLINE F32x8 negate(F32x8 a) {
  for (int l = 0; l < 8; ++l) a.v[l] = -a.v[l];
  return a;
}
TESSERA_LANES_INLINE I32x8 equal(F32x8 a, F32x8 b) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = a.v[l] == b.v[l] ? -1 : 0;
  return r;
}
// Exactly static_cast<int32_t>(std::lrint(a)) per lane: round half to even in the default
// rounding mode, and the low 32 bits of lrint's long where the value does not fit.
TESSERA_LANES_INLINE I32x8 roundToInt(F32x8 a) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = static_cast<int32_t>(std::lrint(a.v[l]));
  return r;
}
// Within each half (lanes 0-3 and 4-7), row l of the 4x4 matrix r becomes column l.
TESSERA_LANES_INLINE void transpose4x4Halves(F32x8 r[4]) {
  F32x8 t[4];
  for (int h = 0; h < 8; h += 4)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) t[i].v[h + j] = r[j].v[h + i];
  for (int i = 0; i < 4; ++i) r[i] = t[i];
}
// The low 16 bits of each lane, to eight consecutive uint16_t.
TESSERA_LANES_INLINE void storeU16(uint16_t* p, I32x8 a) {
  for (int l = 0; l < 8; ++l) p[l] = static_cast<uint16_t>(a.v[l]);
}
// See the vector variants below.
TESSERA_LANES_INLINE I32x8 maskLess(F32x8 a, F32x8 b) {
  return lessThan(a, b);
}
TESSERA_LANES_INLINE I32x8 maskLessOrEqual(I32x8 a, I32x8 b) {
  return lessOrEqual(a, b);
}
TESSERA_LANES_INLINE I32x8 maskPositive(F32x8 a) {
  return positive(a);
}
TESSERA_LANES_INLINE I32x8 maskEqual(F32x8 a, F32x8 b) {
  return equal(a, b);
}
TESSERA_LANES_INLINE I32x8 maskEqual(I32x8 a, I32x8 b) {
  return equal(a, b);
}
template <typename T>
TESSERA_LANES_INLINE Lanes<T> blend(I32x8 mask, Lanes<T> a, Lanes<T> b) {
  return select(mask, a, b);
}

// Added for the setup kernel (setup_kernel.h).
using F64x8 = Lanes<double>;
TESSERA_LANES_INLINE F64x8 toDouble(I32x8 a) {
  F64x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = a.v[l];
  return r;
}
// Rounded to nearest, as static_cast<float>(double).
TESSERA_LANES_INLINE F32x8 toFloat(F64x8 a) {
  F32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = static_cast<float>(a.v[l]);
  return r;
}
TESSERA_LANES_INLINE I32x8 lessThan(F64x8 a, F64x8 b) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = a.v[l] < b.v[l] ? -1 : 0;
  return r;
}
// For lanes holding integers below 2^51 in magnitude: their exact int64 values.
TESSERA_LANES_INLINE I64x8 exactInt64(F64x8 a) {
  I64x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = static_cast<int64_t>(a.v[l]);
  return r;
}
// The low and the high 32 bits of each lane (the halves of its little-endian bytes).
TESSERA_LANES_INLINE I32x8 low32(I64x8 a) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = static_cast<int32_t>(static_cast<uint64_t>(a.v[l]));
  return r;
}
TESSERA_LANES_INLINE I32x8 high32(I64x8 a) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r.v[l] = static_cast<int32_t>(a.v[l] >> 32);
  return r;
}
TESSERA_LANES_INLINE I32x8 minimum(I32x8 a, I32x8 b) {
  for (int l = 0; l < 8; ++l) a.v[l] = b.v[l] < a.v[l] ? b.v[l] : a.v[l];
  return a;
}
TESSERA_LANES_INLINE I32x8 maximum(I32x8 a, I32x8 b) {
  for (int l = 0; l < 8; ++l) a.v[l] = a.v[l] < b.v[l] ? b.v[l] : a.v[l];
  return a;
}
TESSERA_LANES_INLINE F32x8 floatsOf(I32x8 a) {
  F32x8 r;
  std::memcpy(&r, &a, sizeof r);
  return r;
}
// Lane l from the double at `first` + l * stride bytes.
TESSERA_LANES_INLINE F64x8 loadStrided(const double* first, size_t stride) {
  F64x8 r;
  for (int l = 0; l < 8; ++l)
    std::memcpy(&r.v[l], reinterpret_cast<const char*>(first) + l * stride, sizeof(double));
  return r;
}

#else  // vector extensions

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
}
// The first lane of a mask that is not all zero.
TESSERA_LANES_INLINE int firstLane(I32x8 mask) {
#if defined(__AVX__)
  return __builtin_ctz(static_cast<unsigned>(_mm256_movemask_ps(reinterpret_cast<__m256>(mask))));
#elif defined(__SSE2__)
  __m128 half[2];
  std::memcpy(half, &mask, sizeof half);
  return __builtin_ctz(
      static_cast<unsigned>(_mm_movemask_ps(half[0]) | (_mm_movemask_ps(half[1]) << 4)));
#else
  int l = 0;
  while (!mask[l]) ++l;
  return l;
#endif
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
TESSERA_LANES_INLINE F32x8 gather(const float* table, I32x8 index) {
  F32x8 r;
  for (int l = 0; l < 8; ++l) r[l] = table[index[l]];
  return r;
}
TESSERA_LANES_INLINE I32x8 lessThan(I32x8 a, I32x8 b) {
  return a < b;
}
TESSERA_LANES_INLINE I32x8 gatherWords(const uint32_t* table, I32x8 index) {
  I32x8 r;
  for (int l = 0; l < 8; ++l) r[l] = static_cast<int32_t>(table[index[l]]);
  return r;
}
TESSERA_LANES_INLINE F32x8 floorLanes(F32x8 a) {
  for (int l = 0; l < 8; ++l) a[l] = __builtin_floorf(a[l]);  // one vroundps where there is one
  return a;
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

#endif

template <typename V>
TESSERA_LANES_INLINE V load(const void* p) {
  V v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <typename V>
TESSERA_LANES_INLINE void store(void* p, V v) {
  std::memcpy(p, &v, sizeof v);
}
// Two rows of four lanes: lanes 0-3 at row0, lanes 4-7 at row1.
template <typename V>
TESSERA_LANES_INLINE V load2x4(const void* row0, const void* row1) {
#if defined(__AVX__) && !defined(TESSERA_SIMD_SCALAR)
  // Straight into the two halves of a register (through memory, the 32-byte reload of two
  // 16-byte stores misses store forwarding and stalls).
  const __m256 halves =
      _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(static_cast<const float*>(row0))),
                           _mm_loadu_ps(static_cast<const float*>(row1)), 1);
  return reinterpret_cast<V>(halves);
#else
  V v;
  std::memcpy(&v, row0, sizeof v / 2);
  std::memcpy(reinterpret_cast<char*>(&v) + sizeof v / 2, row1, sizeof v / 2);
  return v;
#endif
}
// Lane l of `first` and `second` from p[l][0] and p[l][1]: a transpose of eight pairs.
TESSERA_LANES_INLINE void loadPairs(const float* const p[8], F32x8& first, F32x8& second) {
#if defined(__AVX__) && !defined(TESSERA_SIMD_SCALAR)
  auto two = [](const float* a, const float* b) {  // a[0] a[1] b[0] b[1]
    return _mm_loadh_pi(_mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(a))),
                        reinterpret_cast<const __m64*>(b));
  };
  const __m256 lo =
      _mm256_insertf128_ps(_mm256_castps128_ps256(two(p[0], p[1])), two(p[4], p[5]), 1);
  const __m256 hi =
      _mm256_insertf128_ps(_mm256_castps128_ps256(two(p[2], p[3])), two(p[6], p[7]), 1);
  first = reinterpret_cast<F32x8>(_mm256_shuffle_ps(lo, hi, 0x88));
  second = reinterpret_cast<F32x8>(_mm256_shuffle_ps(lo, hi, 0xdd));
#else
  float a[8], b[8];
  for (int l = 0; l < 8; ++l) {
    a[l] = p[l][0];
    b[l] = p[l][1];
  }
  first = load<F32x8>(a);
  second = load<F32x8>(b);
#endif
}
// Stores v at p, 32-byte aligned, with streaming stores where there are vector ones: the lines
// go to memory without being read for ownership first or kept in this core's caches. For records
// that a later stage reads (setup's raster records); the writer issues an sfence before that
// stage starts.
TESSERA_LANES_INLINE void storeStreaming(void* p, F32x8 v) {
#if defined(__AVX__) && !defined(TESSERA_SIMD_SCALAR)
  _mm256_stream_ps(static_cast<float*>(p), reinterpret_cast<__m256>(v));
#elif defined(__SSE2__) && !defined(TESSERA_SIMD_SCALAR)
  __m128 half[2];
  std::memcpy(half, &v, sizeof half);
  _mm_stream_ps(static_cast<float*>(p), half[0]);
  _mm_stream_ps(static_cast<float*>(p) + 4, half[1]);
#else
  store(p, v);
#endif
}
// Copies `bytes` (a multiple of 8) from src to 8-byte aligned dst with 8-byte streaming stores
// where there are any; as with storeStreaming, the writer fences before a later stage reads.
TESSERA_LANES_INLINE void streamCopy(void* dst, const void* src, size_t bytes) {
#if defined(__SSE2__) && defined(__x86_64__) && !defined(TESSERA_SIMD_SCALAR)
  for (size_t i = 0; i < bytes; i += 8) {
    long long word;
    std::memcpy(&word, static_cast<const char*>(src) + i, 8);
    _mm_stream_si64(reinterpret_cast<long long*>(static_cast<char*>(dst) + i), word);
  }
#else
  std::memcpy(dst, src, bytes);
#endif
}
template <typename V>
TESSERA_LANES_INLINE void store2x4(void* row0, void* row1, V v) {
  std::memcpy(row0, &v, sizeof v / 2);
  std::memcpy(row1, reinterpret_cast<const char*>(&v) + sizeof v / 2, sizeof v / 2);
}

#if defined(__AVX512F__) && !defined(TESSERA_SIMD_SCALAR)
// Sixteen lanes, for the AVX-512 variant's widest loops (a whole 512-bit register): the same
// operations per lane as the eight-lane functions they mirror, so the same bits.
#define TESSERA_LANES16 1
typedef float F32x16 __attribute__((vector_size(64)));
typedef int32_t I32x16 __attribute__((vector_size(64)));

TESSERA_LANES_INLINE F32x16 splat16(float x) {
  return F32x16{} + x;
}
TESSERA_LANES_INLINE I32x16 splat16(int32_t x) {
  return I32x16{} + x;
}
// As roundToInt.
TESSERA_LANES_INLINE I32x16 roundToInt16(F32x16 a) {
  I32x16 r =
      reinterpret_cast<I32x16>(_mm512_maskz_cvtps_epi32(0xffff, reinterpret_cast<__m512>(a)));
  if (_mm512_cmpeq_epi32_mask(reinterpret_cast<__m512i>(r), _mm512_set1_epi32(INT32_MIN))) {
    for (int l = 0; l < 16; ++l)
      if (r[l] == INT32_MIN) r[l] = static_cast<int32_t>(std::lrint(a[l]));
  }
  return r;
}
// As lowerOf and upperOf (the x86 min and max). The maskz forms with every lane here and below
// are the plain instructions, without the undefined source operand GCC 12 warns about.
TESSERA_LANES_INLINE F32x16 lowerOf16(F32x16 a, F32x16 b) {
  return reinterpret_cast<F32x16>(
      _mm512_maskz_min_ps(0xffff, reinterpret_cast<__m512>(a), reinterpret_cast<__m512>(b)));
}
TESSERA_LANES_INLINE F32x16 upperOf16(F32x16 a, F32x16 b) {
  return reinterpret_cast<F32x16>(
      _mm512_maskz_max_ps(0xffff, reinterpret_cast<__m512>(a), reinterpret_cast<__m512>(b)));
}
// As lookup16: table[index[l]] for indices in [0, 16), one permute.
TESSERA_LANES_INLINE F32x16 lookup16x16(const float* table, I32x16 index) {
  return reinterpret_cast<F32x16>(_mm512_maskz_permutexvar_ps(
      0xffff, reinterpret_cast<__m512i>(index), _mm512_loadu_ps(table)));
}
// As truncate.
TESSERA_LANES_INLINE I32x16 truncate16(F32x16 a) {
  return __builtin_convertvector(a, I32x16);
}
#endif

}  // namespace
}  // namespace tessera::render
