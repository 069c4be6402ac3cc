// makeOccupancyHeatmap(): tile occupancy as an image.
#include <tessera/vulkan/vulkan_backend.h>

#include <algorithm>
#include <cmath>

namespace tessera::vulkan {

namespace {

uint32_t packRgb(float r, float g, float b) {
  auto byte = [](float v) {
    return static_cast<uint32_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
  };
  return byte(r) | (byte(g) << 8) | (byte(b) << 16) | (255u << 24);
}

// t in [0, 1]: dark blue, blue, green, yellow, white.
uint32_t ramp(float t) {
  struct Stop {
    float t, r, g, b;
  };
  constexpr Stop kStops[] = {{0.0f, 0.05f, 0.05f, 0.35f},
                             {0.25f, 0.1f, 0.3f, 1.0f},
                             {0.5f, 0.1f, 0.8f, 0.3f},
                             {0.75f, 1.0f, 0.9f, 0.1f},
                             {1.0f, 1.0f, 1.0f, 1.0f}};
  for (size_t i = 1; i < std::size(kStops); ++i) {
    if (t <= kStops[i].t) {
      const Stop& a = kStops[i - 1];
      const Stop& b = kStops[i];
      const float u = (t - a.t) / (b.t - a.t);
      return packRgb(a.r + (b.r - a.r) * u, a.g + (b.g - a.g) * u, a.b + (b.b - a.b) * u);
    }
  }
  return packRgb(1, 1, 1);
}

}  // namespace

std::vector<uint32_t> makeOccupancyHeatmap(const TileOccupancy& occupancy, int width, int height) {
  std::vector<uint32_t> image(static_cast<size_t>(std::max(width, 0)) * std::max(height, 0),
                              packRgb(0, 0, 0));
  if (occupancy.entries.empty() || occupancy.tile_size <= 0) return image;
  const uint32_t most = *std::max_element(occupancy.entries.begin(), occupancy.entries.end());
  const float scale = most > 0 ? 1.0f / static_cast<float>(most) : 0.0f;
  const int size = occupancy.tile_size;
  for (int y = 0; y < height; ++y) {
    const int ty = y / size;
    for (int x = 0; x < width; ++x) {
      const int tx = x / size;
      if (tx >= occupancy.columns || ty >= occupancy.rows) continue;
      const uint32_t count = occupancy.entries[static_cast<size_t>(ty) * occupancy.columns + tx];
      if (count == 0) continue;
      uint32_t color = ramp(static_cast<float>(count) * scale);
      // A darker one-pixel border shows the tile grid.
      if (x % size == 0 || y % size == 0) color = (color >> 1) & 0x7f7f7fu;
      image[static_cast<size_t>(y) * width + x] = color | (255u << 24);
    }
  }
  return image;
}

}  // namespace tessera::vulkan
