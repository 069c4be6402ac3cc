// Tile rasterization into a visibility buffer: for each pixel of a 64x64 tile, the nearest depth
// and the key of the triangle that owns it. Depth passes when z < stored (first wins ties, and
// triangles arrive in submission order, so the result does not depend on the worker count).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <limits>

#include <tessera/render/sampling.h>

#include "render/fixed_point.h"
#include "render/setup.h"

namespace tessera::render {

// A triangle's key: its chunk (the top kChunkKeyBits), a flag the sample layers set
// (kCentreKeyBit) and its index in that chunk's records (the low kLocalKeyBits).
constexpr int kChunkKeyBits = 7;
constexpr uint32_t kMaxChunks = 1u << kChunkKeyBits;
constexpr int kChunkKeyShift = 32 - kChunkKeyBits;
constexpr int kLocalKeyBits = kChunkKeyShift - 1;
// In a multisampled tile's sample layers (msaa.h), set in the keys the layers store where the
// pixel's centre passes the triangle's edge tests (the shading point of a mixed pixel's fragment:
// fragment_queue.h), so that the shading reads the exact test from the key instead of redoing it
// from the raster record. A function of the triangle and the pixel, so the keys of one pixel's
// samples stay equal where their triangle is. Clear in every other key.
constexpr uint32_t kCentreKeyBit = 1u << kLocalKeyBits;
// The all-ones key is empty; a chunk holds fewer than 2^kLocalKeyBits records (16.7 million: a
// chunk is at most 1/128 of the triangles culling keeps, plus the fans of clipped ones), and its
// shading records stay within 2 GiB, so that the shading kernel forms their byte offsets in int32
// lanes.
constexpr uint32_t kMaxTrianglesPerChunk =
    std::min<uint64_t>((1u << kLocalKeyBits) - 1, (uint64_t{1} << 31) / sizeof(ShadeTriangle));
constexpr uint32_t kEmptyKey = 0xffffffffu;

constexpr uint32_t makeKey(uint32_t chunk, uint32_t local) {
  return (chunk << kChunkKeyShift) | local;
}
constexpr uint32_t keyChunk(uint32_t key) {
  return key >> kChunkKeyShift;
}
constexpr uint32_t keyLocal(uint32_t key) {
  return key & ((1u << kLocalKeyBits) - 1);
}

// A tile of depths at infinity: what TileVisibility::clear copies (libc's memcpy takes the
// widest stores the machine has; the loop it replaced was compiled for SSE2's 16 bytes).
inline const std::array<float, kTileSize* kTileSize> kFarDepths = [] {
  std::array<float, kTileSize * kTileSize> far;
  far.fill(std::numeric_limits<float>::infinity());
  return far;
}();

// Room past the last pixel of a tile's arrays: one row, and eight pixels past its end.
constexpr int kTilePadding = kTileSize + 8;

struct TileVisibility {
  int x0 = 0, y0 = 0;         // the tile's first pixel
  int width = 0, height = 0;  // <= kTileSize at the right and bottom borders
  // Row y of the tile starts at y * kTileSize; the padding (kTilePadding) lets the kernels touch
  // eight pixels past the end of a row and the row after the last.
  alignas(64) float depth[kTileSize * kTileSize + kTilePadding];
  alignas(64) uint32_t key[kTileSize * kTileSize + kTilePadding];
  // Hi-Z: an upper bound of the stored depths of each 8x8 block (row-major, 8 blocks a row).
  // A triangle whose nearest depth is not below a block's bound cannot win a pixel there.
  static constexpr int kHiZBlock = 8;
  static constexpr int kHiZBlocksPerRow = kTileSize / kHiZBlock;
  float block_max_depth[kHiZBlocksPerRow * kHiZBlocksPerRow];
  // Some bound above is finite: until then Hi-Z rejects nothing and small triangles skip it
  // (meshes of small triangles alone never tighten a bound).
  bool hiz_bounded = false;

  void clear(int tile_x0, int tile_y0, int tile_width, int tile_height) {
    x0 = tile_x0, y0 = tile_y0, width = tile_width, height = tile_height;
    std::memcpy(depth, kFarDepths.data(), sizeof(float) * kTileSize * kTileSize);
    std::memset(key, 0xff, sizeof(uint32_t) * kTileSize * kTileSize);
    for (float& z : block_max_depth) z = std::numeric_limits<float>::infinity();
    hiz_bounded = false;
  }
};

// Where one sample layer's samples lie: their offset from the pixel centre, in 1/256 pixel and
// in pixels (sampling.h's positions less the centre).
struct SampleShift {
  int32_t dx = 0, dy = 0;
  float pixels_x = 0, pixels_y = 0;
};

// The shift of a sample at `p` (sampling.h: 1/256 pixel within the pixel).
inline SampleShift sampleShift(const SamplePosition& p) {
  const int32_t dx = p.x - kSubpixelHalf, dy = p.y - kSubpixelHalf;
  constexpr float kToPixels = 1.0f / static_cast<float>(kSubpixelOne);
  return {dx, dy, static_cast<float>(dx) * kToPixels, static_cast<float>(dy) * kToPixels};
}

}  // namespace tessera::render
