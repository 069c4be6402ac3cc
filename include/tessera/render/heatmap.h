// Diagnostic values as pictures for people: an inferno colour ramp with a labelled legend, and
// per-tile values spread over the pixels of their tiles. `tessera render --aov *-heatmap` and the
// viewer's diagnostic views (Shift+F1, F11) draw with these, so both show the same picture.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <tessera/render/diagnostics.h>

namespace tessera {

// Inferno (matplotlib) at t in [0, 1]: black (0, 0, 4) through purple and orange to pale yellow
// (252, 255, 164). RGBA8, R in the low byte, alpha 255.
uint32_t infernoColor(float t);

// The heatmap picture of per-pixel counts (width x height of them): the inferno ramp from 0
// (black) to `top` (pale yellow; counts above it are clamped), by default the largest count,
// with a legend strip along the bottom labelled 0 and `top` (left out on pictures too small to
// label). RGBA8 pixels, row 0 at the top.
std::vector<uint32_t> heatmapImage(int width, int height, const std::vector<uint32_t>& counts,
                                   std::optional<uint32_t> top = std::nullopt);

// The height of heatmapImage's legend strip on a width x height picture (0: too small to label).
int heatmapLegendHeight(int width, int height);

// A per-tile array of `d` (tile_columns x tile_rows, row-major) as a width x height per-pixel
// array: every pixel holds its tile's value.
template <typename T>
std::vector<T> spreadTiles(const FrameDiagnostics& d, const std::vector<T>& tiles, int width,
                           int height) {
  std::vector<T> out(static_cast<size_t>(width) * static_cast<size_t>(height));
  for (int y = 0; y < height; ++y) {
    const size_t row = static_cast<size_t>(y / d.tile_size) * d.tile_columns;
    for (int x = 0; x < width; ++x)
      out[static_cast<size_t>(y) * width + x] = tiles[row + x / d.tile_size];
  }
  return out;
}

}  // namespace tessera
