// Frame validation: the CRC-32 of an image's pixels, reading a reference PNG back, and a
// per-pixel comparison with a difference image. Used by `tessera render --crc/--reference`,
// `cube`, `bench` and the viewer's F5/F6.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <tessera/base/expected.h>

namespace tessera::io {

// RGBA8 pixels as everywhere in tessera: R in the low byte, row 0 at the top.
struct Rgba8Image {
  int width = 0, height = 0;
  std::vector<uint32_t> pixels;
};

// zlib's crc32 (the PNG/gzip polynomial) of the bytes R, G, B, A of each pixel, rows top to
// bottom: the same number Python's zlib.crc32 gives for the image's RGBA bytes.
uint32_t crc32Rgba8(const uint32_t* pixels, int width, int height);

// Eight lower-case hex digits, as printed by the CLI and the viewer.
std::string crc32Hex(uint32_t crc);

// Decodes a PNG of any colour type and depth to RGBA8 (16-bit channels keep their high byte;
// no gamma correction). Errors name the path: missing, not a PNG, corrupt, over 16384 a side.
Expected<Rgba8Image> readPngRgba8(const std::filesystem::path& path);

// A pixel differs when its largest channel difference (R, G, B; alpha is not compared) exceeds
// this: the tolerance the vulkan backend is held to against cpu, so that rounding differences
// alone never count.
constexpr int kDifferingChannelTolerance = 2;

struct ImageComparison {
  // The metric: percent (0..100) of pixels whose largest channel difference exceeds
  // kDifferingChannelTolerance.
  double differing_percent = 0;
  int64_t differing_pixels = 0;
  int max_channel_difference = 0;  // 0..255, over all pixels
  // Where they differ, amplified: the reference dimmed to a quarter in grey, pixels differing
  // within the tolerance in yellow, beyond it in red brightening with the difference.
  Rgba8Image difference;
};

// Compares two images of the same size (a caller's bug otherwise).
ImageComparison compareRgba8(const Rgba8Image& image, const Rgba8Image& reference);

}  // namespace tessera::io
