// Fixed-point conventions of the rasterizer, in one place.
//
// Window coordinates are snapped to 8 sub-pixel bits (1/256 pixel), as Direct3D, Vulkan,
// llvmpipe and dEQP do. Where it overflows:
//   - vertices are kept within the guard band [-kGuardBandPixels, viewport + kGuardBandPixels]
//     by clipping, and viewports are at most kMaxViewport, so a snapped coordinate is below
//     2^15 pixels = 2^23 sub-pixel units in magnitude;
//   - an edge coefficient (a difference of two coordinates) is below 2^24;
//   - an edge value (coefficient * coordinate + constant) is below 2^49: int64 always suffices.
#pragma once

#include <cstdint>

namespace tessera::render {

constexpr int kSubpixelBits = 8;
constexpr int32_t kSubpixelOne = 1 << kSubpixelBits;  // one pixel in fixed point
constexpr int32_t kSubpixelHalf = kSubpixelOne / 2;   // pixel centres are at +0.5
constexpr int kMaxViewport = 16384;                   // largest width or height
constexpr float kGuardBandPixels = 16384.0f;          // beyond the viewport on each side

// Tiles of the binning rasterizer: one worker owns a tile at a time.
constexpr int kTileSizeLog2 = 6;
constexpr int kTileSize = 1 << kTileSizeLog2;  // 64x64 pixels: depth + id stay in L1/L2

}  // namespace tessera::render
