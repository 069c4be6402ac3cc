// Texture and image decoding (stb_image: PNG, JPEG, BMP, TGA).
#pragma once

#include <filesystem>

#include <tessera/base/expected.h>
#include <tessera/scene/texture.h>

namespace tessera::io {

// Decodes an image file to RGBA8 texels with its mip chain (generateMipmaps). `srgb` marks the
// texels as sRGB-encoded colour.
// Refuses images over 16384 pixels on a side.
Expected<Texture> loadTexture(const std::filesystem::path& path, bool srgb = true);

// Decodes an image held in memory (glTF buffers, data: URIs); `name` is used in messages.
Expected<Texture> decodeTexture(const unsigned char* data, size_t size, const std::string& name,
                                bool srgb = true);

}  // namespace tessera::io
