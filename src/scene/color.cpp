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

uint32_t packSrgba8(float4 linear) {
  float a = linear.w > 0.0f ? std::min(linear.w, 1.0f) : 0.0f;
  uint32_t alpha = static_cast<uint32_t>(a * 255.0f + 0.5f);
  return static_cast<uint32_t>(encodeSrgb8(linear.x)) |
         (static_cast<uint32_t>(encodeSrgb8(linear.y)) << 8) |
         (static_cast<uint32_t>(encodeSrgb8(linear.z)) << 16) | (alpha << 24);
}

}  // namespace tessera
