// Radiance .hdr images as environment light (--hdri); OpenEXR ones are handed to exr_loader.cpp.
// stb_image is compiled here a second time, with static linkage and only its HDR decoder, so that
// the textures' decoder (image_loader.cpp) keeps refusing what is not a PNG, JPEG, BMP or TGA file.
#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <tessera/io/image_loader.h>

#include "exr_loader.h"
#include "model_paths.h"

// A second static stb_image, with its HDR decoder only.
#define STBI_ONLY_HDR
#include "stb_image_private.h"

namespace tessera::io {

namespace {

struct StbiFree {
  void operator()(float* pixels) const { stbi_image_free(pixels); }
};

// RGBE reaches 2^120: sums of such values (the irradiance, the prefiltered levels) would be
// infinite. No scene's light is within orders of magnitude of this (the sun is about 1e5).
constexpr float kMaxRadiance = 1e9f;

bool plausibleRadiance(float3 t) {
  return t.x >= 0.0f && t.y >= 0.0f && t.z >= 0.0f && t.x <= kMaxRadiance && t.y <= kMaxRadiance &&
         t.z <= kMaxRadiance;  // false for NaN too
}

// Whether the scanlines of a `width` x `height` RGBE image fit in the bytes after its header.
// stb_image reads zeros past the end of its data, so a truncated file would decode to a silently
// darker light; this walks the run-length encoding (or the flat pixels) the way a decoder does.
bool scanlinesFit(const unsigned char* data, size_t size, int width, int height) {
  // The pixels start after the header's empty line and the resolution line after it.
  const unsigned char* end = data + size;
  const unsigned char* p = data;
  while (p + 1 < end && !(p[0] == '\n' && p[1] == '\n')) ++p;
  p += 2;
  while (p < end && *p != '\n') ++p;
  ++p;
  for (int y = 0; y < height; ++y) {
    const bool rle = width >= 8 && width < 32768 && end - p >= 4 && p[0] == 2 && p[1] == 2 &&
                     ((p[2] << 8) | p[3]) == width;
    if (!rle) {
      if (end - p < 4 * static_cast<ptrdiff_t>(width)) return false;
      p += 4 * static_cast<ptrdiff_t>(width);
      continue;
    }
    p += 4;
    for (int component = 0; component < 4; ++component)
      for (int x = 0; x < width;) {
        if (p >= end) return false;
        const int count = *p++;
        if (count > 128) {
          if (p >= end) return false;
          ++p;
          x += count - 128;
        } else {
          if (count == 0 || end - p < count) return false;
          p += count;
          x += count;
        }
      }
  }
  return p <= end;
}

}  // namespace

Expected<EnvironmentImage> decodeEnvironmentImage(const unsigned char* data, size_t size,
                                                  const std::string& name, uint64_t max_pixels) {
  if (data == nullptr || size == 0) return makeError(name + ": empty file");
  if (size > static_cast<size_t>(INT_MAX))
    return makeError(name + ": " + std::to_string(size) + " bytes, over 2 GiB");
  if (looksLikeExr(data, size)) return decodeExrEnvironment(data, size, name, max_pixels);
  const int length = static_cast<int>(size);
  ImageSize header;
  int channels = 0;
  if (!stbi_is_hdr_from_memory(data, length) ||
      !stbi_info_from_memory(data, length, &header.width, &header.height, &channels))
    return makeError(name +
                     ": not a Radiance .hdr or OpenEXR image (an environment light must be one)");
  if (header.width < 2 || header.height < 1)
    return makeError(name + ": an environment image needs at least 2x1 pixels");
  if (header.pixels() > max_pixels)
    return makeError(texturePixelsOverBudget(name, header, max_pixels));
  if (!scanlinesFit(data, size, header.width, header.height))
    return makeError(name + ": the .hdr image is truncated");
  ImageSize decoded;
  std::unique_ptr<float, StbiFree> pixels(
      stbi_loadf_from_memory(data, length, &decoded.width, &decoded.height, &channels, 3));
  if (!pixels) return makeError(name + ": cannot decode the .hdr image: the data is corrupt");
  if (decoded.width != header.width || decoded.height != header.height)
    return makeError(name + ": the image's header and data disagree about its size");
  EnvironmentImage image;
  image.width = decoded.width;
  image.height = decoded.height;
  image.texels.resize(static_cast<size_t>(decoded.pixels()));
  const float* p = pixels.get();
  for (float3& texel : image.texels) {
    texel = {p[0], p[1], p[2]};
    p += 3;
    // RGBE holds neither: a decoder's mistake would be a silently wrong light.
    if (!plausibleRadiance(texel))
      return makeError(name + ": the .hdr image holds a radiance that is negative, not finite or " +
                       "above " + std::to_string(static_cast<int64_t>(kMaxRadiance)));
  }
  return image;
}

Expected<EnvironmentImage> loadEnvironmentImage(const std::filesystem::path& path,
                                                uint64_t max_pixels) {
  Expected<std::vector<unsigned char>> bytes = readRegularFile(path, kMaxImageFileBytes, "image");
  if (!bytes) return bytes.error();
  return decodeEnvironmentImage(bytes->data(), bytes->size(), path.string(), max_pixels);
}

}  // namespace tessera::io
