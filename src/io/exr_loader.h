// OpenEXR images as environment light (--hdri), beside the Radiance .hdr reader (hdr_loader.cpp).
// Private to tessera_loaders; exr_loader.cpp with OpenEXR (libopenexr-dev), exr_missing.cpp
// without.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <tessera/base/expected.h>
#include <tessera/scene/environment.h>

namespace tessera::io {

// Whether the bytes start with OpenEXR's magic number.
inline bool looksLikeExr(const unsigned char* data, size_t size) {
  return size >= 4 && data[0] == 0x76 && data[1] == 0x2f && data[2] == 0x31 && data[3] == 0x01;
}

// The RGB channels of an OpenEXR image (a missing channel reads as 0, a luminance-only image as
// grey), refused when over `max_pixels` before its pixels are read.
Expected<EnvironmentImage> decodeExrEnvironment(const unsigned char* data, size_t size,
                                                const std::string& name, uint64_t max_pixels);

}  // namespace tessera::io
