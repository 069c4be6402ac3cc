// PNG output. Every writer goes through AtomicFile: the file appears whole or not at all.
#pragma once

#include <cstdint>
#include <filesystem>

#include <tessera/base/expected.h>
#include <tessera/render/frame.h>

namespace tessera::io {

// RGBA8 pixels (R in the low byte, row 0 at the top) to an 8-bit RGB PNG (alpha dropped) or,
// with keep_alpha, an RGBA PNG.
Expected<void> writePngRgba8(const std::filesystem::path& path, int width, int height,
                             const uint32_t* pixels, bool keep_alpha = false);

// 16-bit greyscale PNG (the depth AOV).
Expected<void> writePngGray16(const std::filesystem::path& path, int width, int height,
                              const uint16_t* pixels);

// The AOV encodings of the CLI contract, from a rendered frame:
//   id:     RGB8, value = triangle index + 1 as R + 256 G + 65536 B; 0 = no triangle
//   depth:  16-bit grey of window z (0 = near; 65535 = far or nothing drawn)
//   normal: RGB8 of world normal * 0.5 + 0.5; black where nothing was drawn
//   coverage: 8-bit grey of samples covered / samples (Frame::coverage): an alpha matte
Expected<void> writeIdPng(const std::filesystem::path& path, const Frame& frame);
Expected<void> writeDepthPng(const std::filesystem::path& path, const Frame& frame);
Expected<void> writeNormalPng(const std::filesystem::path& path, const Frame& frame);
Expected<void> writeCoveragePng(const std::filesystem::path& path, const Frame& frame);

}  // namespace tessera::io
