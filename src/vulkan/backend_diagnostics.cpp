#include "vulkan/backend_diagnostics.h"

#include <algorithm>
#include <chrono>

#include "render/diagnostics.h"

namespace tessera::vulkan {

static_assert(kDiagnosticsTileSizeLog2 == render::kTileSizeLog2,
              "the diagnostics passes count occupancy on the CPU's tile grid");

namespace {

// The GPU's per-16x16-tile tests and passes summed into the CPU's 64x64 tiles, which
// sumDiagnostics reads.
std::vector<render::TileTests> testsPerTile(const ComputeDiagnosticsInput& in,
                                            const GpuDiagnosticsLayout& layout,
                                            const FrameDiagnostics& d) {
  std::vector<render::TileTests> tests(d.tileCount());
  constexpr int kPerCpuTile = render::kTileSize / kGpuTileSize;
  for (int gy = 0; gy < in.gpu_tile_rows; ++gy)
    for (int gx = 0; gx < in.gpu_tile_columns; ++gx) {
      const size_t g = static_cast<size_t>(gy) * in.gpu_tile_columns + gx;
      render::TileTests& t =
          tests[static_cast<size_t>(gy / kPerCpuTile) * d.tile_columns + gx / kPerCpuTile];
      t.tested += in.words[layout.tile_tested + g];
      t.passed += in.words[layout.tile_passed + g];
    }
  return tests;
}

}  // namespace

void fillComputeDiagnostics(const Scene& scene, const ComputeDiagnosticsInput& in,
                            std::vector<size_t>& triangle_bases, Frame& frame) {
  const auto start = std::chrono::steady_clock::now();
  render::prepareDiagnostics(frame, in.pixel_tests);
  FrameDiagnostics& d = frame.diagnostics;
  const GpuDiagnosticsLayout layout = GpuDiagnosticsLayout::of(frame.width, frame.height);
  std::vector<render::TileTests> tests;
  if (in.pixel_tests) {
    std::copy_n(in.words + layout.overdraw, d.overdraw.size(), d.overdraw.begin());
    std::copy_n(in.words + layout.occupancy, d.tile_triangles.size(), d.tile_triangles.begin());
    tests = testsPerTile(in, layout, d);
  }
  render::measureFrameTiles(scene, triangle_bases, frame);
  render::sumDiagnostics(tests, frame);

  PipelineCounters& c = d.counters;
  const GpuCounters& g = *in.counters;
  c.triangles_in = in.triangles_in;
  if (in.pixel_tests) {
    const uint32_t* w = in.words;
    c.culled = {w[kDiagInvalid],   w[kDiagNonFinite], w[kDiagFrustum],    w[kDiagDegenerate],
                w[kDiagFacing],    w[kDiagNoPixel],   w[kDiagClippedAway]};
    c.clip_splits = w[kDiagClipSplits];
    c.bin_overflow = in.bin_overflow;
  } else {
    c.culled.no_pixel = g.culled;  // the ray passes do not split their reasons (as the CPU's)
  }
  c.triangles_clipped = g.clipped;
  c.triangles_setup = g.visible;
  d.times = in.times;
  d.times.diagnostics_ms +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void fillRasterDiagnostics(const Scene& scene, uint64_t triangles_in, const StageTimes& times,
                           std::vector<size_t>& triangle_bases, Frame& frame) {
  const auto start = std::chrono::steady_clock::now();
  render::prepareDiagnostics(frame, false);
  FrameDiagnostics& d = frame.diagnostics;
  d.has_setup_counters = false;
  render::measureFrameTiles(scene, triangle_bases, frame);
  render::sumDiagnostics({}, frame);
  d.counters.triangles_in = triangles_in;
  d.times = times;
  d.times.diagnostics_ms +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace tessera::vulkan
