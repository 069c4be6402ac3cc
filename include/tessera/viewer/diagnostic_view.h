// The viewer's diagnostic views (Shift+F1, F11): pictures of Frame::diagnostics shown instead of
// the rendered image. Read only frame.diagnostics, so every backend that fills it gets the views;
// one that does not gets a line saying so, never a wrong picture. No SDL: unit-tested.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tessera/render/frame.h>

namespace tessera::viewer {

// One view at a time: Shift+F1 and F11 replace each other's view.
enum class DiagnosticView {
  kOff,
  kTileHeatmap,  // Shift+F1: triangles binned into each tile (occupancy), inferno ramp
  kTileField,    // F11, first: each tile's covered fraction, 0 to 100 %
  kDensity,      // F11, second: each pixel's Material::density
};

// Shift+F1: the tile heatmap, or off when it is shown.
DiagnosticView toggleTileHeatmap(DiagnosticView view);
// F11: off -> tile field -> density -> off; from the tile heatmap, the tile field.
DiagnosticView nextAnalysisView(DiagnosticView view);
// Whether the frame needs RenderOptions::diagnostics for the view (off: nothing is measured).
inline bool needsDiagnostics(DiagnosticView view) {
  return view != DiagnosticView::kOff;
}

struct DiagnosticPicture {
  // RGBA8, the frame's size, row 0 at the top; empty: show the rendered frame (view off, or
  // the backend or projection gave no data for the view).
  std::vector<uint32_t> pixels;
  std::string caption;  // the overlay's line: what the colours mean, or why there is no picture
};

// The picture of `view` from frame.diagnostics (heatmap.h's inferno ramp and legend, the same as
// `tessera render --aov occupancy-heatmap` for the tile heatmap). `backend`: its name, for the
// "not available" caption.
DiagnosticPicture diagnosticPicture(const Frame& frame, DiagnosticView view,
                                    const std::string& backend);

}  // namespace tessera::viewer
