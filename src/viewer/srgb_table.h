// encodeSrgb8 (scene/color.h) by table, for the viewer's per-pixel passes: the same codes, in a
// lookup and one comparison instead of a polynomial.
#pragma once

#include <cstdint>

#include <tessera/scene/color.h>

namespace tessera::viewer {

class SrgbEncodeTable {
 public:
  static const SrgbEncodeTable& instance();

  uint8_t operator()(float linear) const {
    if (!(linear > SrgbEncode::kLinearEnd && linear < 1.0f)) return encodeSrgb8(linear);
    const uint32_t bits = __builtin_bit_cast(uint32_t, linear);
    const uint8_t code = bucket_code_[(bits >> kBucketShift) - kFirstBucket];
    return static_cast<uint8_t>(code + (linear >= threshold_[code + 1] ? 1 : 0));
  }

 private:
  SrgbEncodeTable();

  // A bucket: an exponent and the top 8 bits of the mantissa. Above the linear segment (from
  // 2^-9 up to 1) the curve climbs at most 0.03 codes across one, so a value's code is its
  // bucket's lowest code or the next; the next code's threshold decides. That relies on
  // encodeSrgb8 never going down as the value goes up, which holds for every float in [0, 1]
  // (checked exhaustively when this was written; the viewer's tests check a dense sample).
  static constexpr int kBucketShift = 23 - 8;
  static constexpr uint32_t kFirstBucket = (127u - 9u) << (23 - kBucketShift);  // 2^-9
  static constexpr int kBuckets = 9 << 8;

  uint8_t bucket_code_[kBuckets];
  float threshold_[257];  // [k]: the least value encodeSrgb8 takes to k; [256] = +inf
};

}  // namespace tessera::viewer
