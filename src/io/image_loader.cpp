#include <tessera/io/image_loader.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model_paths.h"

// stb_image for textures: only the formats they come in.
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_ONLY_BMP
#define STBI_ONLY_TGA
#include "stb_image_private.h"

namespace tessera::io {

namespace {

struct StbiFree {
  void operator()(stbi_uc* pixels) const { stbi_image_free(pixels); }
};
using StbiPixels = std::unique_ptr<stbi_uc, StbiFree>;

// stb_image's failure reasons in tessera's words.
std::string failureReason() {
  const char* reason = stbi_failure_reason();
  const std::string text = reason ? reason : "";
  if (text == "unknown image type") return "not a PNG, JPEG, BMP or TGA file";
  if (text == "outofmem") return "out of memory";
  if (text == "too large") return "its size is out of range";
  if (text.empty()) return "the data is corrupt";
  return "corrupt data (" + text + ")";
}

// A PNG's size from its IHDR chunk. stb_image's header scan refuses a PNG whose size it would not
// decode and then says "unknown image type"; this says how big it claims to be.
std::optional<ImageSize> pngHeaderSize(const unsigned char* data, size_t size) {
  static const unsigned char kSignature[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (size < 24 || std::memcmp(data, kSignature, 8) != 0 || std::memcmp(data + 12, "IHDR", 4) != 0)
    return std::nullopt;
  auto big_endian = [&](size_t at) {
    return uint32_t{data[at]} << 24 | uint32_t{data[at + 1]} << 16 | uint32_t{data[at + 2]} << 8 |
           uint32_t{data[at + 3]};
  };
  const uint32_t width = big_endian(16), height = big_endian(20);
  if (width == 0 || height == 0 || width > INT_MAX || height > INT_MAX) return std::nullopt;
  return ImageSize{static_cast<int>(width), static_cast<int>(height)};
}

std::string pixelCount(uint64_t pixels) {
  if (pixels >= 10'000'000) return std::to_string(pixels / 1'000'000) + " million pixels";
  return std::to_string(pixels) + " pixels";
}

Expected<void> checkSize(ImageSize size, uint64_t max_pixels, const std::string& name) {
  if (size.width <= 0 || size.height <= 0)
    return makeError(name + ": image has no pixels (" + std::to_string(size.width) + "x" +
                     std::to_string(size.height) + ")");
  if (size.pixels() > max_pixels) return makeError(texturePixelsOverBudget(name, size, max_pixels));
  return {};
}

Expected<Texture> toTexture(StbiPixels pixels, ImageSize size, bool srgb, const std::string& name) {
  if (!pixels) return makeError(name + ": cannot decode the image: " + failureReason());
  Texture texture;
  texture.width = size.width;
  texture.height = size.height;
  texture.srgb = srgb;
  const size_t count = static_cast<size_t>(size.pixels());
  texture.texels.resize(count);
  const stbi_uc* p = pixels.get();
  for (size_t i = 0; i < count; ++i, p += 4)
    texture.texels[i] = static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 |
                        static_cast<uint32_t>(p[2]) << 16 | static_cast<uint32_t>(p[3]) << 24;
  pixels.reset();
  // Every loaded texture gets its mip chain, for trilinear filtering (a third more memory).
  generateMipmaps(texture);
  return texture;
}

}  // namespace

std::string texturePixelsOverBudget(const std::string& name, ImageSize size, uint64_t max_pixels) {
  return name + ": image is " + std::to_string(size.width) + "x" + std::to_string(size.height) +
         " (" + pixelCount(size.pixels()) + "), over the budget of " + pixelCount(max_pixels) +
         " per texture; raise it with --max-texture-pixels or --memory-limit";
}

Expected<ImageSize> readImageSize(const unsigned char* data, size_t size, const std::string& name) {
  if (data == nullptr || size == 0) return makeError(name + ": empty image");
  if (size > static_cast<size_t>(INT_MAX))
    return makeError(name + ": image data is " + std::to_string(size) + " bytes, over 2 GiB");
  ImageSize image;
  int channels = 0;
  if (stbi_info_from_memory(data, static_cast<int>(size), &image.width, &image.height, &channels))
    return image;
  if (std::optional<ImageSize> png = pngHeaderSize(data, size)) return *png;
  return makeError(name + ": not a readable PNG, JPEG, BMP or TGA image: " + failureReason());
}

Expected<Texture> loadTexture(const std::filesystem::path& path, bool srgb, uint64_t max_pixels) {
  Expected<std::vector<unsigned char>> bytes = readRegularFile(path, kMaxImageFileBytes, "image");
  if (!bytes) return bytes.error();
  return decodeTexture(bytes->data(), bytes->size(), path.string(), srgb, max_pixels);
}

Expected<Texture> decodeTexture(const unsigned char* data, size_t size, const std::string& name,
                                bool srgb, uint64_t max_pixels) {
  // The header alone first: an image over the budget is refused before anything is allocated.
  Expected<ImageSize> header = readImageSize(data, size, name);
  if (!header) return header.error();
  if (Expected<void> ok = checkSize(*header, max_pixels, name); !ok) return ok.error();
  ImageSize decoded;
  int channels = 0;
  StbiPixels pixels(stbi_load_from_memory(data, static_cast<int>(size), &decoded.width,
                                          &decoded.height, &channels, 4));
  if (pixels && (decoded.width != header->width || decoded.height != header->height))
    return makeError(name + ": the image's header and data disagree about its size");
  Expected<Texture> texture = toTexture(std::move(pixels), decoded, srgb, name);
  if (texture) texture->source_channels = channels;
  return texture;
}

}  // namespace tessera::io
