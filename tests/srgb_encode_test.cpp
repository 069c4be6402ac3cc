// The 8-bit sRGB encode by table (kSrgbEncodeTable, scene/color.h) and the shading kernels'
// encode of every instruction set this CPU runs give encodeSrgb8's code for every float of
// [2^-13, 1], the range the table's buckets cover, and for the values around and beyond it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <limits>
#include <vector>

#include <tessera/scene/color.h>

#include "render/kernels.h"

using namespace tessera;
using namespace tessera::render;

namespace {

constexpr uint32_t kFirstBits = static_cast<uint32_t>(SrgbEncodeBuckets::kFirst)
                                << SrgbEncodeBuckets::kShift;  // 2^-13
constexpr uint32_t kOneBits = 0x3f800000u;

float fromBits(uint32_t bits) {
  return __builtin_bit_cast(float, bits);
}

// Values outside the buckets' range: the clamps, NaN, and a sample of what lies below 2^-13.
std::vector<float> edgeValues() {
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> v = {0.0f,
                          -0.0f,
                          -1.0f,
                          -inf,
                          inf,
                          2.0f,
                          1.0f,
                          std::nextafter(1.0f, 2.0f),
                          std::numeric_limits<float>::quiet_NaN(),
                          std::numeric_limits<float>::denorm_min(),
                          fromBits(kFirstBits - 1),
                          fromBits(kFirstBits),
                          SrgbEncode::kLinearEnd};
  for (uint32_t bits = 0; bits < kFirstBits; bits += 65521) v.push_back(fromBits(bits));
  return v;
}

TEST(SrgbEncodeTable, GivesEncodeSrgb8sCodeForEveryFloatOfItsRange) {
  int changes = 0;
  uint8_t previous = 0;
  for (uint32_t bits = kFirstBits; bits <= kOneBits; ++bits) {
    const float v = fromBits(bits);
    const uint8_t want = encodeSrgb8(v);
    const uint8_t got = encodeSrgb8ByTable(v);
    if (got != want)
      FAIL() << "value " << v << " (bits " << bits << "): " << int(got) << ", want " << int(want);
    changes += want != previous;
    previous = want;
  }
  EXPECT_EQ(changes, 255);  // every code from 0 to 255 is reached, in order
  for (float v : edgeValues()) EXPECT_EQ(encodeSrgb8ByTable(v), encodeSrgb8(v)) << v;
  EXPECT_EQ(encodeSrgb8ByTable(0.5f), 188);
  EXPECT_EQ(encodeSrgb8ByTable(7.0f), 255);
  EXPECT_EQ(encodeSrgb8ByTable(std::numeric_limits<float>::quiet_NaN()), 0);
}

TEST(SrgbEncodeTable, EveryInstructionSetsKernelGivesEncodeSrgb8sCodes) {
  std::vector<Isa> isas;
  for (Isa isa : {Isa::kScalar, Isa::kSse2, Isa::kAvx2, Isa::kAvx512}) {
    if (isa <= detectIsa())
      isas.push_back(isa);
    else
      std::cout << "srgb_encode_test: " << isaName(isa) << " not run, this CPU lacks it\n";
  }
  // Every float of the range, a block at a time, through each kernel.
  constexpr size_t kBlock = size_t{1} << 20;
  std::vector<float> values(kBlock);
  std::vector<uint8_t> want(kBlock), got(kBlock);
  for (uint64_t start = kFirstBits; start <= kOneBits; start += kBlock) {
    for (size_t i = 0; i < kBlock; ++i) {
      const uint64_t bits = start + i;
      values[i] = bits <= kOneBits ? fromBits(static_cast<uint32_t>(bits)) : 0.5f;
      want[i] = encodeSrgb8(values[i]);
    }
    for (Isa isa : isas) {
      // The scalar and SSE2 kernels repeat encodeSrgb8's own operations (no gather to read a
      // table with), and the scalar one takes 40 ns a value: one block in 64 for them.
      if (isa < Isa::kAvx2 && (start - kFirstBits) / kBlock % 64 != 0) continue;
      kernelsFor(isa).encode_srgb(values.data(), kBlock, got.data());
      if (std::memcmp(got.data(), want.data(), kBlock) == 0) continue;
      for (size_t i = 0; i < kBlock; ++i)
        ASSERT_EQ(int(got[i]), int(want[i])) << isaName(isa) << ": value " << values[i];
    }
  }
  std::vector<float> edges = edgeValues();
  edges.resize((edges.size() + 15) / 16 * 16, 0.25f);
  std::vector<uint8_t> codes(edges.size());
  for (Isa isa : isas) {
    kernelsFor(isa).encode_srgb(edges.data(), edges.size(), codes.data());
    for (size_t i = 0; i < edges.size(); ++i)
      EXPECT_EQ(int(codes[i]), int(encodeSrgb8(edges[i]))) << isaName(isa) << ": " << edges[i];
  }
  EXPECT_FALSE(isas.empty());
}

}  // namespace
