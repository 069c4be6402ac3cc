#include "render/raster.h"

#include <algorithm>

namespace tessera::render {

void rasterTriangle(const RasterTriangle& t, uint32_t key, TileVisibility& tile) {
  const int x_begin = std::max(t.min_x, tile.x0);
  const int x_end = std::min(t.max_x, tile.x0 + tile.width - 1);
  const int y_begin = std::max(t.min_y, tile.y0);
  const int y_end = std::min(t.max_y, tile.y0 + tile.height - 1);
  if (x_begin > x_end || y_begin > y_end) return;

  // Edge values at the centre of the first pixel of the first row, then stepped by whole pixels.
  const int64_t px = static_cast<int64_t>(x_begin) * kSubpixelOne + kSubpixelHalf;
  const int64_t py = static_cast<int64_t>(y_begin) * kSubpixelOne + kSubpixelHalf;
  int64_t row[3], step_x[3], step_y[3];
  for (int k = 0; k < 3; ++k) {
    row[k] = t.a[k] * px + t.b[k] * py + t.c[k];
    step_x[k] = static_cast<int64_t>(t.a[k]) * kSubpixelOne;
    step_y[k] = static_cast<int64_t>(t.b[k]) * kSubpixelOne;
  }

  for (int y = y_begin; y <= y_end; ++y) {
    int64_t e0 = row[0], e1 = row[1], e2 = row[2];
    const float dy = static_cast<float>(y) + 0.5f - t.y0;
    const float z_row = t.z0 + t.dzdy * dy;
    float* depth = tile.depth + (y - tile.y0) * kTileSize - tile.x0;
    uint32_t* keys = tile.key + (y - tile.y0) * kTileSize - tile.x0;
    for (int x = x_begin; x <= x_end; ++x) {
      if ((e0 | e1 | e2) >= 0) {
        const float z = z_row + t.dzdx * (static_cast<float>(x) + 0.5f - t.x0);
        if (z < depth[x]) {
          depth[x] = z;
          keys[x] = key;
        }
      }
      e0 += step_x[0];
      e1 += step_x[1];
      e2 += step_x[2];
    }
    for (int k = 0; k < 3; ++k) row[k] += step_y[k];
  }
}

}  // namespace tessera::render
