// Texture and image decoding (stb_image: PNG, JPEG, BMP, TGA; Radiance .hdr for environments).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include <tessera/base/expected.h>
#include <tessera/scene/environment.h>
#include <tessera/scene/texture.h>

namespace tessera::io {

// Decoded pixels of one texture unless the caller says otherwise: 8192 x 8192, as
// LoadBudget's default.
constexpr uint64_t kDefaultMaxTexturePixels = uint64_t{1} << 26;

struct ImageSize {
  int width = 0, height = 0;
  uint64_t pixels() const { return uint64_t(width) * uint64_t(height); }
};

// The size an encoded image says it decodes to, from its header alone.
Expected<ImageSize> readImageSize(const unsigned char* data, size_t size, const std::string& name);

// Decodes an image file to RGBA8 texels with its mip chain (generateMipmaps). `srgb` marks the
// texels as sRGB-encoded colour. The file is read only if it is a regular file (a FIFO or a
// directory is refused, never waited on); an image over `max_pixels` is refused before it is
// decoded, with a message naming --max-texture-pixels.
Expected<Texture> loadTexture(const std::filesystem::path& path, bool srgb = true,
                              uint64_t max_pixels = kDefaultMaxTexturePixels);

// Decodes an image held in memory (glTF buffers, data: URIs); `name` is used in messages.
Expected<Texture> decodeTexture(const unsigned char* data, size_t size, const std::string& name,
                                bool srgb = true, uint64_t max_pixels = kDefaultMaxTexturePixels);

// Decodes a Radiance .hdr file (RGBE, as HDRI sites publish equirectangular environments) or an
// OpenEXR one (when built with OpenEXR) to linear radiance, for --hdri; refused like a texture over
// `max_pixels`, and when it is neither or holds a value that is not a finite radiance.
Expected<EnvironmentImage> loadEnvironmentImage(const std::filesystem::path& path,
                                                uint64_t max_pixels = kDefaultMaxTexturePixels);
Expected<EnvironmentImage> decodeEnvironmentImage(const unsigned char* data, size_t size,
                                                  const std::string& name,
                                                  uint64_t max_pixels = kDefaultMaxTexturePixels);

// The message for an image over the per-texture budget.
std::string texturePixelsOverBudget(const std::string& name, ImageSize size, uint64_t max_pixels);

}  // namespace tessera::io
