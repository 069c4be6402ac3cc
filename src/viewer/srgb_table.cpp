#include "srgb_table.h"

#include <limits>

namespace tessera::viewer {

const SrgbEncodeTable& SrgbEncodeTable::instance() {
  static const SrgbEncodeTable table;
  return table;
}

SrgbEncodeTable::SrgbEncodeTable() {
  for (int i = 0; i < kBuckets; ++i)
    bucket_code_[i] = encodeSrgb8(
        __builtin_bit_cast(float, (kFirstBucket + static_cast<uint32_t>(i)) << kBucketShift));
  // Each threshold by bisection over the float bit patterns of [0, 1] (ordered as the values).
  threshold_[0] = 0.0f;
  threshold_[256] = std::numeric_limits<float>::infinity();
  for (int k = 1; k < 256; ++k) {
    uint32_t lo = 0, hi = __builtin_bit_cast(uint32_t, 1.0f);  // encode(hi) = 255 >= k
    while (lo < hi) {
      const uint32_t mid = lo + (hi - lo) / 2;
      if (encodeSrgb8(__builtin_bit_cast(float, mid)) >= k)
        hi = mid;
      else
        lo = mid + 1;
    }
    threshold_[k] = __builtin_bit_cast(float, lo);
  }
}

}  // namespace tessera::viewer
