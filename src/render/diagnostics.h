// The diagnostics pass (RenderOptions::diagnostics): after the tile stage, separately from it, so
// that the raster and shading kernels are the same code whether diagnostics are asked for or not.
//   - per tile, from the chunks' bins: each binned triangle's depth test at every pixel centre it
//     covers, replayed in submission order (overdraw, tests, passes) and the bin occupancy;
//   - per tile, from the frame's centre ids and depths: material, density, covered fraction,
//     depth range and depth discontinuities.
// Every result is written per pixel or per tile and summed in tile order afterwards, so it is
// the same for any number of workers.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <tessera/render/cpu_renderer.h>

#include <tessera/render/frame.h>
#include <tessera/scene/scene.h>

#include "render/bin.h"
#include "render/clip.h"
#include "render/raster.h"
#include "render/worker_pool.h"

namespace tessera::render {

// One worker's depth buffer for the replayed depth tests.
struct OverdrawScratch {
  alignas(64) float depth[kTileSize * kTileSize];
};

// Per tile, before the sums.
struct TileTests {
  uint64_t tested = 0, passed = 0;
};

// Sizes frame.diagnostics for the frame's size (keeping the memory) and clears its totals.
// `with_pixel_tests`: the overdraw and occupancy buffers too (perspective frames).
void prepareDiagnostics(Frame& frame, bool with_pixel_tests);

// The replayed depth tests of tile `tile` into diagnostics.overdraw and its occupancy into
// diagnostics.tile_triangles. The raster kernel's coverage and depth arithmetic exactly (the
// pixel centres, the top-left rule, z < stored), without its Hi-Z shortcut, which skips only
// tests that would fail: the tests a plain depth-buffered rasterizer makes.
TileTests countTileTests(const std::vector<TriangleChunk>& chunks, size_t chunk_count, int tile,
                         const TileGrid& grid, OverdrawScratch& scratch, Frame& frame);

// Material, density and the tile's occlusion and edges from frame.triangle_id and frame.depth.
// `triangle_bases`: each object's first scene triangle index (ascending).
void measureTile(const Scene& scene, const std::vector<size_t>& triangle_bases, int tile,
                 Frame& frame);

// Each object's first scene triangle index into `bases` (keeping its memory); the scene's
// triangle count.
size_t triangleBases(const Scene& scene, std::vector<size_t>& bases);

// measureTile over every tile, one after another: for a backend that reads its frame's ids and
// depths back (the Vulkan backends), the same measures from the same code as the CPU's.
void measureFrameTiles(const Scene& scene, std::vector<size_t>& triangle_bases, Frame& frame);

// Counts a triangle that setup culled with outcodes c0..c2 and snapped corners v0..v2 under its
// reason, by the cull checks in their order: non-finite, outside the frustum, zero area, facing
// away, no pixel centre in its box.
inline void countCullReason(const SetupContext& ctx, uint32_t c0, uint32_t c1, uint32_t c2,
                            const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2,
                            CullCounts& counts) {
  if ((c0 | c1 | c2) & kNonFinite) {
    ++counts.non_finite;
  } else if (c0 & c1 & c2 & kRejectPlanes) {
    ++counts.frustum;
  } else {
    const int64_t area = signedArea(v0, v1, v2);
    if (area == 0)
      ++counts.degenerate;
    else if (cullsArea(ctx, area))
      ++counts.facing;
    else
      ++counts.no_pixel;
  }
}

// The setup stage's counters of the frame (chunks in order) into frame.diagnostics.counters.
void addSetupCounters(const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                      uint64_t triangles_in, Frame& frame);

// The frame's totals from the per-tile results (and tests, one per tile when measured).
void sumDiagnostics(const std::vector<TileTests>& tests, Frame& frame);

// The pass over every tile, run by the renderer after the tile stage (and the line pass).
class DiagnosticsPass {
 public:
  // `pixel_tests`: replay the chunks' bins (perspective frames); else only the measures from
  // the frame's ids and depths, with the counters `stats` has. The stage times are `stats`' and
  // this pass's own.
  void run(WorkerPool& pool, const std::vector<TriangleChunk>& chunks, size_t chunk_count,
           const Scene& scene, const TileGrid& grid, bool pixel_tests, const PipelineStats& stats,
           Frame& frame);

 private:
  // Made the first time the pass runs, then reused.
  std::vector<std::unique_ptr<OverdrawScratch>> overdraw_;  // one per worker
  std::vector<TileTests> tile_tests_;                       // one per tile
  std::vector<size_t> triangle_bases_;                      // one per object
};

}  // namespace tessera::render
