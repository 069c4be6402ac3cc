// sRGB transfer functions (IEC 61966-2-1). Shading is linear; encoding happens once, at output.
#pragma once

#include <array>
#include <cstdint>

#include <tessera/math/vec.h>

namespace tessera {

// Exact conversions (slow path, used for tests and tables).
float srgbToLinear(float encoded);
float linearToSrgb(float linear);

// The linear value of each 8-bit sRGB code.
const float* srgbDecodeTable();
// The same values in an object filled before main, for the shading kernels' inner loops: its
// address is a constant, where a call to srgbDecodeTable() there makes the compiler store and
// reload every vector register live across it. (Static initializers of other files call
// srgbDecodeTable() instead: this one may not be filled yet when they run.)
extern const std::array<float, 256> kSrgbDecode;
inline float decodeSrgb8(uint8_t code) {
  return srgbDecodeTable()[code];
}

// The 8-bit encode as a formula, which the Vulkan shaders and the scalar and SSE2 kernels compute
// (kSrgbEncodeTable below gives the same codes by lookup, for kernels with a gather). Above the
// linear segment (12.92 x up to 0.0031308), a value is c = m * 2^e with m in [1, 2) and e in
// [-9, 0], and
//   255 * (1.055 * c^(1/2.4) - 0.055) = kScale[e + 9] * m^(5/12) - 0.055 * 255,
// with kScale[j] = 255 * 1.055 * 2^((j - 9) * 5/12) and m^(5/12) a degree-4 polynomial in m - 1
// (least squares, within 0.004 code units). The result is the exact curve's nearest code within
// 0.503 (exact for every decoded 8-bit value). The Vulkan shaders repeat these operations and
// constants (makeColorTables uploads them), so both give the same codes.
struct SrgbEncode {
  static constexpr float kLinearEnd = 0x1.9a5c38p-9f;      // 0.0031308
  static constexpr float kLinearFactor = 0x1.9bd334p+11f;  // 12.92 * 255
  static constexpr float kOffset = 0x1.c0ccccp+3f;         // 0.055 * 255
  static constexpr float kPoly[5] = {0x1.0000c6p+0f, 0x1.aa0586p-2f, -0x1.dadc1ep-4f,
                                     0x1.73ab08p-5f, -0x1.5d2276p-7f};
  // [e + 9]: e in [-9, 0] is used; the formula carries on to 16 entries (e up to 6) so that two
  // 8-lane permutes read a whole table.
  static constexpr float kScale[16] = {
      0x1.3fed2cp+4f, 0x1.ab0cf2p+4f, 0x1.1d05a6p+5f,  0x1.7c7574p+5f,
      0x1.fbda00p+5f, 0x1.52f344p+6f, 0x1.c471bep+6f,  0x1.2df86ap+7f,
      0x1.931502p+7f, 0x1.0d0666p+8f, 0x1.671af4p+8f,  0x1.df591ap+8f,
      0x1.3fed2cp+9f, 0x1.ab0cf2p+9f, 0x1.1d05a6p+10f, 0x1.7c7574p+10f};
};

// Linear [0, 1] (clamped; NaN counts as 0) to the nearest 8-bit sRGB code (SrgbEncode). The
// shading kernel encodes eight lanes with the same operations.
inline uint8_t encodeSrgb8(float linear) {
  const float c = linear > 0.0f ? (linear < 1.0f ? linear : 1.0f) : 0.0f;
  float code;
  if (c <= SrgbEncode::kLinearEnd) {
    code = c * SrgbEncode::kLinearFactor;
  } else {
    const uint32_t bits = __builtin_bit_cast(uint32_t, c);
    const int32_t e = static_cast<int32_t>(bits >> 23) - 127;
    const float x = __builtin_bit_cast(float, (bits & 0x7fffffu) | 0x3f800000u) - 1.0f;
    const float* k = SrgbEncode::kPoly;
    const float p = (((k[4] * x + k[3]) * x + k[2]) * x + k[1]) * x + k[0];
    code = SrgbEncode::kScale[e + 9] * p - SrgbEncode::kOffset;
    code = code < 255.0f ? code : 255.0f;
  }
  return static_cast<uint8_t>(static_cast<int32_t>(code + 0.5f));
}

// encodeSrgb8 by table, for the per-pixel encodes (the shading kernels' eight or sixteen lanes by
// one gather, the viewer's passes): the same code for every float. A bucket is an exponent and
// the top 8 bits of the mantissa, from 2^-13 (below it every code is 0) up to 1; within one the
// code climbs by at most one, so an entry holds the bucket's first code (bits 0-7) and the lowest
// remaining 15 bits of mantissa at which the code is one more (bits 8-23; 2^15: never). That
// relies on encodeSrgb8 never going down as the value goes up within a bucket, which the tests
// check for every float in [2^-13, 1].
struct SrgbEncodeBuckets {
  static constexpr int kShift = 23 - 8;
  static constexpr int32_t kFirst = (127 - 13) << (23 - kShift);  // the bucket of 2^-13
  static constexpr int32_t kLast = 127 << (23 - kShift);          // the bucket of 1
  // [0]: below 2^-13; [1 + b - kFirst]: bucket b.
  static constexpr int kEntries = kLast - kFirst + 2;
};
// Filled before main, from encodeSrgb8 (about 53,000 calls); static initializers of other files
// must call encodeSrgb8 instead, as it may not be filled yet when they run.
extern const std::array<uint32_t, SrgbEncodeBuckets::kEntries> kSrgbEncodeTable;

// encodeSrgb8(linear) from kSrgbEncodeTable.
inline uint8_t encodeSrgb8ByTable(float linear) {
  const float c = linear > 0.0f ? (linear < 1.0f ? linear : 1.0f) : 0.0f;
  const int32_t bits = __builtin_bit_cast(int32_t, c);
  const int32_t bucket = (bits >> SrgbEncodeBuckets::kShift) - (SrgbEncodeBuckets::kFirst - 1);
  const uint32_t entry = kSrgbEncodeTable[static_cast<size_t>(bucket > 0 ? bucket : 0)];
  const uint32_t rest = static_cast<uint32_t>(bits) & ((1u << SrgbEncodeBuckets::kShift) - 1);
  return static_cast<uint8_t>((entry & 0xff) + (rest >= (entry >> 8) ? 1 : 0));
}

// Linear RGBA to packed RGBA8 (sRGB RGB, linear alpha), R in the low byte.
uint32_t packSrgba8(float4 linear);

}  // namespace tessera
