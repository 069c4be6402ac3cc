#include <tessera/io/validation.h>

#include <spng.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <system_error>

namespace tessera::io {
namespace {

constexpr uint32_t kMaxSide = 16384;

struct SpngDeleter {
  void operator()(spng_ctx* ctx) const { spng_ctx_free(ctx); }
};
struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

uint8_t channel(uint32_t pixel, int c) {
  return static_cast<uint8_t>(pixel >> (8 * c));
}

uint32_t packRgba(uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
  return uint32_t{r} | uint32_t{g} << 8 | uint32_t{b} << 16 | uint32_t{a} << 24;
}

// The difference image's pixel for one compared pair.
uint32_t differencePixel(uint32_t reference, int largest) {
  if (largest > kDifferingChannelTolerance) {
    // x8 makes a difference of 16/255 full red; the floor keeps 3/255 plainly visible.
    return packRgba(static_cast<uint8_t>(std::clamp(96 + largest * 8, 0, 255)), 0, 0, 255);
  }
  if (largest > 0) return packRgba(96, 96, 0, 255);
  const int grey =
      (channel(reference, 0) * 54 + channel(reference, 1) * 183 + channel(reference, 2) * 19) >>
      10;  // Rec. 709 luma / 4
  const auto g = static_cast<uint8_t>(grey);
  return packRgba(g, g, g, 255);
}

}  // namespace

uint32_t crc32Rgba8(const uint32_t* pixels, int width, int height) {
  TESSERA_CHECK(width >= 0 && height >= 0) << width << "x" << height;
  const size_t count = static_cast<size_t>(width) * static_cast<size_t>(height);
  uLong crc = ::crc32_z(0L, Z_NULL, 0);
  // Bytes by shifts, a row at a time: "R in the low byte" is a property of the value, whatever
  // the host's byte order.
  std::vector<Bytef> row(static_cast<size_t>(width) * 4);
  for (size_t start = 0; start < count; start += static_cast<size_t>(width)) {
    for (size_t x = 0; x < static_cast<size_t>(width); ++x)
      for (int c = 0; c < 4; ++c) row[4 * x + c] = channel(pixels[start + x], c);
    crc = ::crc32_z(crc, row.data(), row.size());
  }
  return static_cast<uint32_t>(crc);
}

std::string crc32Hex(uint32_t crc) {
  char text[9];
  std::snprintf(text, sizeof text, "%08x", crc);
  return text;
}

Expected<Rgba8Image> readPngRgba8(const std::filesystem::path& path) {
  // Appended, not "'" + ...: GCC 12's -Wrestrict misfires on operator+(const char*, string&&).
  std::string name = "'";
  name += path.string();
  name += "'";
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) return makeError(name + ": " + std::generic_category().message(errno));
  std::unique_ptr<spng_ctx, SpngDeleter> ctx(spng_ctx_new(0));
  if (!ctx) return makeError(name + ": out of memory");
  spng_set_image_limits(ctx.get(), kMaxSide, kMaxSide);
  spng_set_chunk_limits(ctx.get(), 64u << 20, 64u << 20);
  spng_set_png_file(ctx.get(), file.get());
  spng_ihdr ihdr{};
  if (int code = spng_get_ihdr(ctx.get(), &ihdr)) {
    if (code == SPNG_ESIGNATURE || code == SPNG_IO_EOF)
      return makeError(name + " is not a PNG file");
    return makeError(name + ": not a valid PNG (" + spng_strerror(code) + ")");
  }
  size_t size = 0;
  if (int code = spng_decoded_image_size(ctx.get(), SPNG_FMT_RGBA8, &size))
    return makeError(name + ": " + spng_strerror(code));
  std::vector<uint8_t> bytes(size);
  if (int code = spng_decode_image(ctx.get(), bytes.data(), size, SPNG_FMT_RGBA8, SPNG_DECODE_TRNS))
    return makeError(name + ": corrupt PNG (" + spng_strerror(code) + ")");
  Rgba8Image image;
  image.width = static_cast<int>(ihdr.width);
  image.height = static_cast<int>(ihdr.height);
  image.pixels.resize(size / 4);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = packRgba(bytes[4 * i], bytes[4 * i + 1], bytes[4 * i + 2], bytes[4 * i + 3]);
  return image;
}

ImageComparison compareRgba8(const Rgba8Image& image, const Rgba8Image& reference) {
  TESSERA_CHECK(image.width == reference.width && image.height == reference.height)
      << image.width << "x" << image.height << " against " << reference.width << "x"
      << reference.height;
  ImageComparison result;
  result.difference.width = image.width;
  result.difference.height = image.height;
  result.difference.pixels.resize(image.pixels.size());
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    int largest = 0;
    for (int c = 0; c < 3; ++c)
      largest = std::max(largest,
                         std::abs(channel(image.pixels[i], c) - channel(reference.pixels[i], c)));
    result.max_channel_difference = std::max(result.max_channel_difference, largest);
    if (largest > kDifferingChannelTolerance) ++result.differing_pixels;
    result.difference.pixels[i] = differencePixel(reference.pixels[i], largest);
  }
  if (!image.pixels.empty())
    result.differing_percent = 100.0 * static_cast<double>(result.differing_pixels) /
                               static_cast<double>(image.pixels.size());
  return result;
}

}  // namespace tessera::io
