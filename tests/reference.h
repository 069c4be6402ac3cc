// Reference images: tests/reference/<name>.png, compared with a stated tolerance. Run a test with
// TESSERA_UPDATE_REFERENCES=1 to (re)write its references instead of comparing; review the new
// images before committing them.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "decode.h"

namespace tessera::test {

struct Tolerance {
  int max_channel_difference = 2;  // per 8-bit channel
  int max_differing_pixels = 0;    // pixels over that difference
};

// Compares the PNG at `actual_path` with the reference `name`; in update mode copies it there.
inline void expectMatchesReference(const std::string& actual_path, const std::string& name,
                                   Tolerance tolerance) {
  const std::filesystem::path reference =
      std::filesystem::path(TESSERA_REFERENCE_DIR) / (name + ".png");
  if (const char* update = std::getenv("TESSERA_UPDATE_REFERENCES"); update && *update == '1') {
    std::filesystem::create_directories(reference.parent_path());
    std::filesystem::copy_file(actual_path, reference,
                               std::filesystem::copy_options::overwrite_existing);
    std::printf("updated reference %s\n", reference.c_str());
    return;
  }
  DecodedPng want, got;
  ASSERT_TRUE(decodePng(reference.string(), want))
      << "missing reference " << reference << " (run with TESSERA_UPDATE_REFERENCES=1)";
  ASSERT_TRUE(decodePng(actual_path, got)) << actual_path;
  ASSERT_EQ(want.width, got.width);
  ASSERT_EQ(want.height, got.height);
  ASSERT_EQ(want.channels, got.channels);
  int differing = 0, worst = 0;
  for (int y = 0; y < want.height; ++y)
    for (int x = 0; x < want.width; ++x) {
      int d = 0;
      for (int c = 0; c < want.channels; ++c)
        d = std::max(d, std::abs(static_cast<int>(want.at(x, y, c)) - got.at(x, y, c)));
      worst = std::max(worst, d);
      differing += d > tolerance.max_channel_difference;
    }
  EXPECT_LE(differing, tolerance.max_differing_pixels)
      << name << ": " << differing << " pixels differ by more than "
      << tolerance.max_channel_difference << " (worst " << worst << ")";
}

}  // namespace tessera::test
