// The eight-lane types of simd_lanes.h for the scalar translation unit: plain arrays whose
// operators loop over the lanes (included by simd_lanes.h when TESSERA_SIMD_SCALAR is defined).
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
// Bit l set where lane l of the mask is (its sign bit, as a comparison leaves it).
TESSERA_LANES_INLINE unsigned laneBits(I32x8 mask) {
  unsigned bits = 0;
  for (int l = 0; l < 8; ++l) bits |= static_cast<unsigned>(mask.v[l] < 0) << l;
  return bits;
}
// The first lane of a mask that is not all zero.
TESSERA_LANES_INLINE int firstLane(I32x8 mask) {
  return __builtin_ctz(laneBits(mask));
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
// table[index[l]] for indices in [0, 8).
TESSERA_LANES_INLINE F32x8 lookup8(const float* table, I32x8 index) {
  return gather(table, index);
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
// The lanes of v where `mask` is set moved to the front in lane order (the lanes after them hold
// anything); `count` becomes their number.
TESSERA_LANES_INLINE I32x8 compressLanes(I32x8 v, I32x8 mask, int& count) {
  I32x8 r = v;
  int n = 0;
  for (int l = 0; l < 8; ++l)
    if (mask.v[l]) r.v[n++] = v.v[l];
  count = n;
  return r;
}

}  // namespace
}  // namespace tessera::render
