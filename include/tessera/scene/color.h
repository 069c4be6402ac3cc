// sRGB transfer functions (IEC 61966-2-1). Shading is linear; encoding happens once, at output.
#pragma once

#include <cstdint>

#include <tessera/math/vec.h>

namespace tessera {

// Exact conversions (slow path, used for tests and tables).
float srgbToLinear(float encoded);
float linearToSrgb(float linear);

// The linear value of each 8-bit sRGB code.
const float* srgbDecodeTable();
inline float decodeSrgb8(uint8_t code) {
  return srgbDecodeTable()[code];
}

// The encode table: linear [2^-12, 1] in 384 buckets of 1/32 octave (by the float's exponent and
// top 5 mantissa bits); within a bucket the code is a straight line in the remaining 18 mantissa
// bits, through the exact curve at the bucket's ends. That line is within 0.01 of a code step of
// the exact curve. Below 2^-12 the curve is linear (12.92 x).
struct SrgbEncodeTable {
  static constexpr uint32_t kFirstBits = 0x39800000u;  // the float 2^-12
  static constexpr int kShift = 18;                    // mantissa bits below the bucket index
  static constexpr int kBuckets = 12 * 32 + 1;         // + one for exactly 1.0
  float offset[kBuckets];                              // the code at the bucket's start
  float slope[kBuckets];                               // code per unit of the low 18 mantissa bits
};
const SrgbEncodeTable& srgbEncodeTable();

// Linear [0, 1] (clamped; NaN counts as 0) to the nearest 8-bit sRGB code, through the table:
// exact for every decoded 8-bit value. The shading kernel encodes eight lanes the same way.
inline uint8_t encodeSrgb8(float linear, const SrgbEncodeTable& table) {
  const float c = linear > 0.0f ? (linear < 1.0f ? linear : 1.0f) : 0.0f;
  float code;
  if (c < 0x1p-12f) {
    code = c * (12.92f * 255.0f);
  } else {
    const uint32_t bits = __builtin_bit_cast(uint32_t, c);
    const uint32_t bucket = (bits - SrgbEncodeTable::kFirstBits) >> SrgbEncodeTable::kShift;
    const float t = static_cast<float>(bits & ((1u << SrgbEncodeTable::kShift) - 1));
    code = table.offset[bucket] + table.slope[bucket] * t;
  }
  return static_cast<uint8_t>(static_cast<int32_t>(code + 0.5f));
}
inline uint8_t encodeSrgb8(float linear) {
  return encodeSrgb8(linear, srgbEncodeTable());
}

// Linear RGBA to packed RGBA8 (sRGB RGB, linear alpha), R in the low byte.
uint32_t packSrgba8(float4 linear);

}  // namespace tessera
