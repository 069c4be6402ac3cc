// Frame diagnostics: what the pipeline did to draw a frame, per pixel, per tile and in total
// (RenderOptions::diagnostics). docs/stats.md describes every field; docs/rendering.md the AOVs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tessera {

// Why triangles were dropped before setup (each input triangle is counted under one reason).
struct CullCounts {
  uint64_t invalid = 0;       // a vertex index past the mesh's vertices
  uint64_t non_finite = 0;    // a NaN or infinite vertex
  uint64_t frustum = 0;       // wholly outside one plane of the view frustum
  uint64_t degenerate = 0;    // zero signed area after snapping to the sub-pixel grid
  uint64_t facing = 0;        // back-facing (or front-facing) and culled by Object::cull
  uint64_t no_pixel = 0;      // a bounding box that holds no pixel centre of the viewport
  uint64_t clipped_away = 0;  // clipped, and no piece of it survived
  // In an instance or a cluster culled before the vertex stage (RenderOptions::frustum_cull):
  // wholly outside the frustum, or (clusters) wholly facing away.
  uint64_t skipped = 0;
  uint64_t total() const {
    return invalid + non_finite + frustum + degenerate + facing + no_pixel + clipped_away + skipped;
  }
};

// Totals of one frame. triangles_in == culled.total() + triangles_setup - clip_splits.
struct PipelineCounters {
  uint64_t triangles_in = 0;
  CullCounts culled;
  uint64_t triangles_clipped = 0;  // input triangles that went through the clipper
  uint64_t clip_splits = 0;        // setup records beyond one per clipped triangle (fan pieces)
  uint64_t triangles_setup = 0;    // setup records (clipped pieces counted one by one)
  uint64_t triangles_binned = 0;   // bin entries: a record counts once per tile it is binned to
  uint64_t bin_overflow = 0;       // entries that did not fit a bin (the CPU's bins grow: 0)
  uint64_t pixels_tested = 0;      // depth tests at pixel centres (the sum of the overdraw AOV)
  uint64_t pixels_passed = 0;      // of those, the ones that passed (z < stored)
  uint64_t pixels_shaded = 0;      // pixels whose centre shows a triangle (each shaded once)
  uint64_t tiles = 0;
  uint64_t tiles_empty = 0;  // no triangle binned
  uint64_t tiles_full = 0;   // every pixel centre inside the image covered
  // Culled before the vertex stage (RenderOptions::frustum_cull), not in triangles_in's sum:
  // instances wholly outside the frustum, clusters outside it, clusters wholly facing away, and
  // the triangles those held.
  uint64_t instances_culled = 0;
  uint64_t clusters_culled = 0;
  uint64_t clusters_facing = 0;
  uint64_t triangles_skipped = 0;
};

// Wall-clock milliseconds of each stage of the frame.
struct StageTimes {
  double vertex_ms = 0, setup_ms = 0, tiles_ms = 0, lines_ms = 0;
  double diagnostics_ms = 0;  // the diagnostics pass itself (not in the others)
};

// A pixel pair whose window depths differ by more than this (or of which one shows no
// triangle) is a depth discontinuity: the tile-edges diagnostic counts them.
constexpr float kEdgeDepthThreshold = 0.01f;

struct FrameDiagnostics {
  bool valid = false;  // filled by the last render
  // Per pixel (Frame's size, row 0 at the top).
  std::vector<uint32_t> overdraw;  // depth tests at the pixel centre (empty: not available)
  std::vector<uint32_t> material;  // material index + 1 of the triangle shown; 0 = none
  std::vector<float> density;      // Material::density of the triangle shown; 0 = none
  // Per tile of tile_size x tile_size pixels, row-major, tile_columns x tile_rows.
  int tile_size = 0, tile_columns = 0, tile_rows = 0;
  std::vector<uint32_t> tile_triangles;  // occupancy: triangles binned into the tile (empty: n/a)
  std::vector<float> tile_covered;       // covered pixel centres / pixels of the tile in the image
  std::vector<float> tile_depth_min;     // of the covered pixels; NaN when none is covered
  std::vector<float> tile_depth_max;
  std::vector<uint32_t> tile_edges;  // neighbour pairs (right, below) across a depth discontinuity
  PipelineCounters counters;
  StageTimes times;
  bool has_pixel_tests = false;  // overdraw, occupancy and the pixel/bin counters were measured
  // The cull reasons, the clip counts and the setup records were measured (not by the
  // vulkan-raster backend, whose setup is the driver's: docs/stats.md).
  bool has_setup_counters = false;

  size_t tileCount() const { return static_cast<size_t>(tile_columns) * tile_rows; }
};

}  // namespace tessera
