#include <tessera/viewer/diagnostic_view.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include <tessera/render/heatmap.h>

namespace tessera::viewer {

DiagnosticView toggleTileHeatmap(DiagnosticView view) {
  return view == DiagnosticView::kTileHeatmap ? DiagnosticView::kOff : DiagnosticView::kTileHeatmap;
}

DiagnosticView nextAnalysisView(DiagnosticView view) {
  switch (view) {
    case DiagnosticView::kTileField:
      return DiagnosticView::kDensity;
    case DiagnosticView::kDensity:
      return DiagnosticView::kOff;
    default:
      return DiagnosticView::kTileField;
  }
}

namespace {

const char* viewName(DiagnosticView view) {
  switch (view) {
    case DiagnosticView::kTileHeatmap:
      return "tile heatmap";
    case DiagnosticView::kTileField:
      return "tile field";
    case DiagnosticView::kDensity:
      return "density";
    default:
      return "";
  }
}

uint32_t toCount(float v, float scale) {
  return std::isfinite(v) ? static_cast<uint32_t>(std::lround(std::max(v, 0.0f) * scale)) : 0u;
}

}  // namespace

DiagnosticPicture diagnosticPicture(const Frame& frame, DiagnosticView view,
                                    const std::string& backend) {
  DiagnosticPicture picture;
  if (view == DiagnosticView::kOff) return picture;
  const FrameDiagnostics& d = frame.diagnostics;
  const std::string name = viewName(view);
  if (!d.valid) {
    picture.caption = name + ": not available on this backend (" + backend + ")";
    return picture;
  }
  const int w = frame.width, h = frame.height;
  const std::string tile = std::to_string(d.tile_size) + "x" + std::to_string(d.tile_size);
  std::vector<uint32_t> counts;
  std::optional<uint32_t> top;
  if (view == DiagnosticView::kTileHeatmap) {
    if (d.tile_triangles.empty()) {
      picture.caption = name + ": not available in this projection (perspective only)";
      return picture;
    }
    counts = spreadTiles(d, d.tile_triangles, w, h);
    const uint32_t most = *std::max_element(d.tile_triangles.begin(), d.tile_triangles.end());
    picture.caption = name + ": triangles binned per " + tile + " tile, 0 (black) to " +
                      std::to_string(most) + " (yellow)";
  } else if (view == DiagnosticView::kTileField) {
    std::vector<uint32_t> percent(d.tile_covered.size());
    for (size_t t = 0; t < percent.size(); ++t) percent[t] = toCount(d.tile_covered[t], 100.0f);
    counts = spreadTiles(d, percent, w, h);
    top = 100;
    picture.caption = name + ": covered fraction per " + tile + " tile, 0 to 100 %";
  } else {
    counts.resize(d.density.size());
    for (size_t p = 0; p < counts.size(); ++p) counts[p] = toCount(d.density[p], 1000.0f);
    const uint32_t most = counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end());
    char range[32];
    std::snprintf(range, sizeof range, "%.3f", most / 1000.0);
    picture.caption =
        name + ": Material::density per pixel, 0 to " + range + " (legend in thousandths)";
  }
  picture.pixels = heatmapImage(w, h, counts, top);
  return picture;
}

}  // namespace tessera::viewer
