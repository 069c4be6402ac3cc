#include "render/resolve.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include <tessera/scene/color.h>

namespace tessera::render {

void resolveTile(const TileVisibility& tile, const ShadedTile& shaded, uint32_t background,
                 Frame& frame) {
  const bool normals = !frame.normal.empty();
  for (int ty = 0; ty < tile.height; ++ty) {
    const size_t row = static_cast<size_t>(tile.y0 + ty) * frame.width + tile.x0;
    const int t0 = ty * kTileSize;
    std::memcpy(&frame.depth[row], &tile.depth[t0], sizeof(float) * tile.width);
    uint32_t* color = &frame.color[row];
    uint32_t* id = &frame.triangle_id[row];
    for (int tx = 0; tx < tile.width; ++tx) {
      const uint32_t key = tile.key[t0 + tx];
      if (key == kEmptyKey) {
        color[tx] = background;
        id[tx] = kNoTriangle;
        if (normals) frame.normal[row + tx] = float3{};
        continue;
      }
      const float3 c = shaded.color[t0 + tx];
      color[tx] = static_cast<uint32_t>(encodeSrgb8(c.x)) |
                  (static_cast<uint32_t>(encodeSrgb8(c.y)) << 8) |
                  (static_cast<uint32_t>(encodeSrgb8(c.z)) << 16) | 0xff000000u;
      id[tx] = shaded.triangle_id[t0 + tx];
      if (normals) frame.normal[row + tx] = shaded.normal[t0 + tx];
    }
  }
}

void resolveEmptyTile(int x0, int y0, int width, int height, uint32_t background, Frame& frame) {
  const bool normals = !frame.normal.empty();
  for (int y = y0; y < y0 + height; ++y) {
    const size_t row = static_cast<size_t>(y) * frame.width + x0;
    std::fill_n(&frame.color[row], width, background);
    std::fill_n(&frame.depth[row], width, std::numeric_limits<float>::infinity());
    std::fill_n(&frame.triangle_id[row], width, kNoTriangle);
    if (normals) std::fill_n(&frame.normal[row], width, float3{});
  }
}

}  // namespace tessera::render
