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

// The 8-bit encode without a table per value, so that SIMD lanes need no gather. Above the linear
// segment (12.92 x up to 0.0031308), a value is c = m * 2^e with m in [1, 2) and e in [-9, 0], and
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

// Linear RGBA to packed RGBA8 (sRGB RGB, linear alpha), R in the low byte.
uint32_t packSrgba8(float4 linear);

}  // namespace tessera
