#include <tessera/scene/color.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace tessera {

float srgbToLinear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float linear) {
  return linear <= 0.0031308f ? linear * 12.92f : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

namespace {

struct SrgbDecodeTable {
  std::array<float, 256> decode;
  SrgbDecodeTable() {
    for (int i = 0; i < 256; ++i) decode[i] = srgbToLinear(i / 255.0f);
  }
};

// The exact curve in double precision, in code units.
double exactCode(double linear) {
  return 255.0 *
         (linear <= 0.0031308 ? linear * 12.92 : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055);
}

SrgbEncodeTable makeEncodeTable() {
  SrgbEncodeTable table;
  for (int k = 0; k < SrgbEncodeTable::kBuckets; ++k) {
    const uint32_t start =
        SrgbEncodeTable::kFirstBits + (static_cast<uint32_t>(k) << SrgbEncodeTable::kShift);
    const uint32_t next = start + (1u << SrgbEncodeTable::kShift);
    const double x0 = __builtin_bit_cast(float, start), x1 = __builtin_bit_cast(float, next);
    const double c0 = exactCode(std::min(x0, 1.0)), c1 = exactCode(std::min(x1, 1.0));
    table.offset[k] = static_cast<float>(c0);
    table.slope[k] = static_cast<float>((c1 - c0) / (1u << SrgbEncodeTable::kShift));
  }
  return table;
}

}  // namespace

const float* srgbDecodeTable() {
  static const SrgbDecodeTable t;
  return t.decode.data();
}

const SrgbEncodeTable& srgbEncodeTable() {
  static const SrgbEncodeTable t = makeEncodeTable();
  return t;
}

uint32_t packSrgba8(float4 linear) {
  float a = linear.w > 0.0f ? std::min(linear.w, 1.0f) : 0.0f;
  uint32_t alpha = static_cast<uint32_t>(a * 255.0f + 0.5f);
  return static_cast<uint32_t>(encodeSrgb8(linear.x)) |
         (static_cast<uint32_t>(encodeSrgb8(linear.y)) << 8) |
         (static_cast<uint32_t>(encodeSrgb8(linear.z)) << 16) | (alpha << 24);
}

}  // namespace tessera
