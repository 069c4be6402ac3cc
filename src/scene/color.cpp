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

}  // namespace

const float* srgbDecodeTable() {
  static const SrgbDecodeTable t;
  return t.decode.data();
}

const std::array<float, 256> kSrgbDecode = [] {
  std::array<float, 256> values;
  std::copy_n(srgbDecodeTable(), values.size(), values.begin());
  return values;
}();

const std::array<uint32_t, SrgbEncodeBuckets::kEntries> kSrgbEncodeTable = [] {
  using B = SrgbEncodeBuckets;
  std::array<uint32_t, B::kEntries> table{};
  const uint32_t never = 1u << B::kShift;
  table[0] = never << 8;  // code 0
  for (int32_t b = B::kFirst; b <= B::kLast; ++b) {
    const uint32_t first = static_cast<uint32_t>(b) << B::kShift;
    const uint32_t base = encodeSrgb8(__builtin_bit_cast(float, first));
    // The lowest rest of the bucket whose code is above the first's, by bisection; `never` when
    // none is. (1's bucket holds 1 alone: every float above it is clamped to 1.)
    uint32_t lo = 0, hi = never;
    while (b < B::kLast && lo < hi) {
      const uint32_t mid = lo + (hi - lo) / 2;
      if (encodeSrgb8(__builtin_bit_cast(float, first | mid)) > base)
        hi = mid;
      else
        lo = mid + 1;
    }
    table[static_cast<size_t>(1 + b - B::kFirst)] = base | (b < B::kLast ? lo : never) << 8;
  }
  return table;
}();

uint32_t packSrgba8(float4 linear) {
  float a = linear.w > 0.0f ? std::min(linear.w, 1.0f) : 0.0f;
  uint32_t alpha = static_cast<uint32_t>(a * 255.0f + 0.5f);
  return static_cast<uint32_t>(encodeSrgb8(linear.x)) |
         (static_cast<uint32_t>(encodeSrgb8(linear.y)) << 8) |
         (static_cast<uint32_t>(encodeSrgb8(linear.z)) << 16) | (alpha << 24);
}

}  // namespace tessera
