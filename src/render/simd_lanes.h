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

// Forced inline by default: the AVX2 and AVX-512 kernels are the fast ones. The scalar and SSE2
// units, and the sanitizer builds' AVX2 kernels (CMakeLists.txt), define it as plain inline: forced
// into whole kernels, their wider code took GCC and clang minutes to compile.
#if !defined(TESSERA_LANES_INLINE)
#define TESSERA_LANES_INLINE inline __attribute__((always_inline))
#endif

#if defined(TESSERA_SIMD_SCALAR)
#include "render/simd_lanes_scalar.h"
#else
#include "render/simd_lanes_vector.h"
#endif

namespace tessera::render {
namespace {

// Calls body(count). Where count is 4 (4x MSAA without the centre layer: tessera render's
// default) the call is a copy of its own with the count a constant, in which the compiler unrolls
// the body's loops over the samples or layers; `body` must be forced inline for that.
template <typename Body>
TESSERA_LANES_INLINE void withSampleCount(int count, Body&& body) {
  if (count == 4)
    body(4);
  else
    body(count);
}

// What both kinds of lanes share, written against their operations.

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
// As truncate.
TESSERA_LANES_INLINE I32x16 truncate16(F32x16 a) {
  return __builtin_convertvector(a, I32x16);
}
#endif

}  // namespace
}  // namespace tessera::render
