#include <tessera/io/image_loader.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

// stb_image is compiled here only, with static linkage, so another translation unit (a glTF
// loader bundling its own copy) cannot collide with it. Only the formats textures come in are
// built: less code that a hostile file can reach.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_ONLY_BMP
#define STBI_ONLY_TGA
// A second line of defence behind the explicit stbi_info check below.
#define STBI_MAX_DIMENSIONS 16384
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#pragma GCC diagnostic ignored "-Wpedantic"
#include <stb_image.h>
#pragma GCC diagnostic pop

namespace tessera::io {

namespace {

constexpr int kMaxTextureSide = STBI_MAX_DIMENSIONS;

struct StbiFree {
  void operator()(stbi_uc* pixels) const { stbi_image_free(pixels); }
};
using StbiPixels = std::unique_ptr<stbi_uc, StbiFree>;

struct FileClose {
  void operator()(FILE* file) const { std::fclose(file); }
};

std::string failureReason() {
  const char* reason = stbi_failure_reason();
  return reason ? reason : "unknown error";
}

Expected<void> checkDimensions(int width, int height, const std::string& name) {
  if (width <= 0 || height <= 0)
    return makeError(name + ": image has no pixels (" + std::to_string(width) + "x" +
                     std::to_string(height) + ")");
  if (width > kMaxTextureSide || height > kMaxTextureSide)
    return makeError(name + ": image is " + std::to_string(width) + "x" + std::to_string(height) +
                     ", over the limit of " + std::to_string(kMaxTextureSide) +
                     " pixels on a side");
  return {};
}

// stb's header scan fails with "too large" when STBI_MAX_DIMENSIONS trips inside it (PNG does).
Error headerError(const std::string& name) {
  std::string reason = failureReason();
  if (reason == "too large")
    return makeError(name + ": image is over the limit of " + std::to_string(kMaxTextureSide) +
                     " pixels on a side");
  return makeError(name + ": not a readable PNG, JPEG, BMP or TGA image (" + reason + ")");
}

Expected<Texture> toTexture(StbiPixels pixels, int width, int height, bool srgb,
                            const std::string& name) {
  if (!pixels) return makeError(name + ": cannot decode the image (" + failureReason() + ")");
  if (Expected<void> dims = checkDimensions(width, height, name); !dims) return dims.error();
  Texture texture;
  texture.width = width;
  texture.height = height;
  texture.srgb = srgb;
  const size_t count = static_cast<size_t>(width) * static_cast<size_t>(height);
  texture.texels.resize(count);
  const stbi_uc* p = pixels.get();
  for (size_t i = 0; i < count; ++i, p += 4)
    texture.texels[i] = static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 |
                        static_cast<uint32_t>(p[2]) << 16 | static_cast<uint32_t>(p[3]) << 24;
  // Every loaded texture gets its mip chain, for trilinear filtering (a third more memory).
  generateMipmaps(texture);
  return texture;
}

}  // namespace

Expected<Texture> loadTexture(const std::filesystem::path& path, bool srgb) {
  const std::string name = path.string();
  std::unique_ptr<FILE, FileClose> file(std::fopen(name.c_str(), "rb"));
  if (!file) return makeError(name + ": cannot open: " + std::strerror(errno));
  int width = 0, height = 0, channels = 0;
  // The header alone: a huge image is refused before anything is allocated for it.
  if (!stbi_info_from_file(file.get(), &width, &height, &channels)) return headerError(name);
  if (Expected<void> dims = checkDimensions(width, height, name); !dims) return dims.error();
  StbiPixels pixels(stbi_load_from_file(file.get(), &width, &height, &channels, 4));
  return toTexture(std::move(pixels), width, height, srgb, name);
}

Expected<Texture> decodeTexture(const unsigned char* data, size_t size, const std::string& name,
                                bool srgb) {
  if (data == nullptr || size == 0) return makeError(name + ": empty image");
  if (size > static_cast<size_t>(INT_MAX))
    return makeError(name + ": image data is " + std::to_string(size) + " bytes, over 2 GiB");
  const int length = static_cast<int>(size);
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(data, length, &width, &height, &channels)) return headerError(name);
  if (Expected<void> dims = checkDimensions(width, height, name); !dims) return dims.error();
  StbiPixels pixels(stbi_load_from_memory(data, length, &width, &height, &channels, 4));
  return toTexture(std::move(pixels), width, height, srgb, name);
}

}  // namespace tessera::io
