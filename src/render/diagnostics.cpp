#include "render/diagnostics.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace tessera::render {

namespace {

// The tile's rectangle in pixels.
struct TileRect {
  int x0, y0, width, height;
};

TileRect tileRect(const TileGrid& grid, int tile) {
  const int tx = tile % grid.columns, ty = tile / grid.columns;
  const int x0 = tx * kTileSize, y0 = ty * kTileSize;
  return {x0, y0, std::min(kTileSize, grid.width - x0), std::min(kTileSize, grid.height - y0)};
}

// Edge k at the centre of pixel (x, y), as the raster kernel forms it: a small triangle's from
// its box corner (smallEdgeAt), a large one's from its 64-bit constant (edgeAt).
int64_t edgeValue(const RasterTriangle& t, const RasterWide& w, int k, int x, int y) {
  if (t.small())
    return t.corner[k] + static_cast<int64_t>(t.a[k]) * ((x - t.min_x) * kSubpixelOne) +
           static_cast<int64_t>(t.b[k]) * ((y - t.min_y) * kSubpixelOne);
  return t.a[k] * (static_cast<int64_t>(x) * kSubpixelOne + kSubpixelHalf) +
         t.b[k] * (static_cast<int64_t>(y) * kSubpixelOne + kSubpixelHalf) + w.c[k];
}

// Window z at the centre of (x, y): rowDepth plus depthAcross8, in the same order (the core is
// built without contraction, so these are the kernel's bits).
float depthAt(const RasterTriangle& t, int x, int y) {
  const float z_row = t.z0 + t.dzdy * (static_cast<float>(y) + 0.5f - t.y0);
  return z_row + t.dzdx * ((static_cast<float>(x) + 0.5f) - t.x0);
}

}  // namespace

void prepareDiagnostics(Frame& frame, bool with_pixel_tests) {
  FrameDiagnostics& d = frame.diagnostics;
  const size_t n = frame.pixelCount();
  const TileGrid grid = TileGrid::forViewport(frame.width, frame.height);
  d.tile_size = kTileSize;
  d.tile_columns = grid.columns;
  d.tile_rows = grid.rows;
  const size_t tiles = d.tileCount();
  d.overdraw.assign(with_pixel_tests ? n : 0, 0);
  d.tile_triangles.assign(with_pixel_tests ? tiles : 0, 0);
  d.material.resize(n);
  d.density.resize(n);
  d.tile_covered.resize(tiles);
  d.tile_depth_min.resize(tiles);
  d.tile_depth_max.resize(tiles);
  d.tile_edges.resize(tiles);
  d.counters = {};
  d.has_pixel_tests = with_pixel_tests;
  d.has_setup_counters = true;
  d.valid = true;
}

TileTests countTileTests(const std::vector<TriangleChunk>& chunks, size_t chunk_count, int tile,
                         const TileGrid& grid, OverdrawScratch& scratch, Frame& frame) {
  const TileRect r = tileRect(grid, tile);
  std::fill_n(scratch.depth, kTileSize * kTileSize, std::numeric_limits<float>::infinity());
  uint32_t* overdraw = frame.diagnostics.overdraw.data();
  TileTests counts;
  uint32_t binned = 0;
  for (size_t c = 0; c < chunk_count; ++c) {
    const TriangleChunk& chunk = chunks[c];
    binned += static_cast<uint32_t>(chunk.bins.count(tile));
    for (const uint32_t* it = chunk.bins.begin(tile); it != chunk.bins.end(tile); ++it) {
      const RasterTriangle& t = chunk.raster[*it];
      const RasterWide& w = chunk.wide[*it];
      const int x_begin = std::max<int>(t.min_x, r.x0);
      const int x_end = std::min<int>(t.max_x, r.x0 + r.width - 1);
      const int y_begin = std::max<int>(t.min_y, r.y0);
      const int y_end = std::min<int>(t.maxY(), r.y0 + r.height - 1);
      for (int y = y_begin; y <= y_end; ++y) {
        for (int x = x_begin; x <= x_end; ++x) {
          if (edgeValue(t, w, 0, x, y) < 0 || edgeValue(t, w, 1, x, y) < 0 ||
              edgeValue(t, w, 2, x, y) < 0)
            continue;
          ++overdraw[static_cast<size_t>(y) * frame.width + x];
          ++counts.tested;
          const float z = depthAt(t, x, y);
          float& stored = scratch.depth[(y - r.y0) * kTileSize + (x - r.x0)];
          if (z < stored) {
            stored = z;
            ++counts.passed;
          }
        }
      }
    }
  }
  frame.diagnostics.tile_triangles[static_cast<size_t>(tile)] = binned;
  return counts;
}

void measureTile(const Scene& scene, const std::vector<size_t>& triangle_bases, int tile,
                 Frame& frame) {
  FrameDiagnostics& d = frame.diagnostics;
  const TileRect r = tileRect(TileGrid::forViewport(frame.width, frame.height), tile);
  // The material of scene triangle `id - 1`: its object's, as setup picks it (an index past the
  // object's materials takes the first).
  auto materialIndex = [&](uint32_t id, size_t& object) -> uint32_t {
    const size_t triangle = id - 1;
    object = static_cast<size_t>(
        std::upper_bound(triangle_bases.begin(), triangle_bases.end(), triangle) -
        triangle_bases.begin() - 1);
    const Object& o = scene.objects[object];
    const std::vector<uint16_t>& per_triangle = o.mesh->triangle_materials;
    const size_t local = triangle - triangle_bases[object];
    const uint32_t m = local < per_triangle.size() ? per_triangle[local] : 0;
    return m < o.materials.size() ? m : 0;
  };
  size_t covered = 0;
  uint32_t edges = 0;
  float z_min = std::numeric_limits<float>::infinity(), z_max = -z_min;
  auto isEdge = [&](size_t p, size_t q) {
    const bool p_drawn = frame.triangle_id[p] != kNoTriangle;
    if (p_drawn != (frame.triangle_id[q] != kNoTriangle)) return true;
    return p_drawn && std::fabs(frame.depth[p] - frame.depth[q]) > kEdgeDepthThreshold;
  };
  for (int y = r.y0; y < r.y0 + r.height; ++y) {
    for (int x = r.x0; x < r.x0 + r.width; ++x) {
      const size_t p = static_cast<size_t>(y) * frame.width + x;
      const uint32_t id = frame.triangle_id[p];
      if (x + 1 < frame.width) edges += isEdge(p, p + 1);
      if (y + 1 < frame.height) edges += isEdge(p, p + static_cast<size_t>(frame.width));
      if (id == kNoTriangle) {
        d.material[p] = 0;
        d.density[p] = 0.0f;
        continue;
      }
      size_t object = 0;
      const uint32_t m = materialIndex(id, object);
      d.material[p] = m + 1;
      d.density[p] = scene.objects[object].materials[m].density;
      ++covered;
      z_min = std::min(z_min, frame.depth[p]);
      z_max = std::max(z_max, frame.depth[p]);
    }
  }
  const size_t t = static_cast<size_t>(tile);
  d.tile_covered[t] = static_cast<float>(covered) / static_cast<float>(r.width * r.height);
  d.tile_depth_min[t] = covered ? z_min : std::numeric_limits<float>::quiet_NaN();
  d.tile_depth_max[t] = covered ? z_max : std::numeric_limits<float>::quiet_NaN();
  d.tile_edges[t] = edges;
}

size_t triangleBases(const Scene& scene, std::vector<size_t>& bases) {
  bases.clear();
  size_t triangles = 0;
  for (const Object& object : scene.objects) {
    bases.push_back(triangles);
    triangles += object.mesh ? object.mesh->triangleCount() : 0;
  }
  return triangles;
}

void measureFrameTiles(const Scene& scene, std::vector<size_t>& triangle_bases, Frame& frame) {
  triangleBases(scene, triangle_bases);
  const int tiles = static_cast<int>(frame.diagnostics.tileCount());
  for (int tile = 0; tile < tiles; ++tile) measureTile(scene, triangle_bases, tile, frame);
}

void addSetupCounters(const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                      uint64_t triangles_in, Frame& frame) {
  PipelineCounters& c = frame.diagnostics.counters;
  c.triangles_in = triangles_in;
  for (size_t i = 0; i < chunk_count; ++i) {
    const TriangleChunk& chunk = chunks[i];
    const CullCounts& r = chunk.cull_reasons;
    c.culled.invalid += r.invalid;
    c.culled.non_finite += r.non_finite;
    c.culled.frustum += r.frustum;
    c.culled.degenerate += r.degenerate;
    c.culled.facing += r.facing;
    c.culled.no_pixel += r.no_pixel;
    c.culled.clipped_away += r.clipped_away;
    c.triangles_clipped += chunk.clipped;
    c.clip_splits += chunk.clip_splits;
    c.triangles_setup += chunk.size;
  }
}

void sumDiagnostics(const std::vector<TileTests>& tests, Frame& frame) {
  FrameDiagnostics& d = frame.diagnostics;
  PipelineCounters& c = d.counters;
  c.tiles = d.tileCount();
  for (size_t t = 0; t < c.tiles; ++t) {
    c.tiles_full += d.tile_covered[t] == 1.0f;
    if (d.has_pixel_tests) {
      c.triangles_binned += d.tile_triangles[t];
      c.tiles_empty += d.tile_triangles[t] == 0;
      c.pixels_tested += tests[t].tested;
      c.pixels_passed += tests[t].passed;
    } else {
      c.tiles_empty += d.tile_covered[t] == 0.0f;
    }
  }
  for (uint32_t m : d.material) c.pixels_shaded += m != 0;
}

void DiagnosticsPass::run(WorkerPool& pool, const std::vector<TriangleChunk>& chunks,
                          size_t chunk_count, const Scene& scene, const TileGrid& grid,
                          bool pixel_tests, const PipelineStats& stats, Frame& frame) {
  const auto start = std::chrono::steady_clock::now();
  prepareDiagnostics(frame, pixel_tests);
  const size_t triangles = triangleBases(scene, triangle_bases_);
  tile_tests_.assign(static_cast<size_t>(grid.tileCount()), {});
  while (overdraw_.size() < static_cast<size_t>(pool.size()))
    overdraw_.push_back(std::make_unique<OverdrawScratch>());
  pool.parallelFor(tile_tests_.size(), [&](size_t tile, int worker) {
    if (pixel_tests)
      tile_tests_[tile] = countTileTests(chunks, chunk_count, static_cast<int>(tile), grid,
                                         *overdraw_[static_cast<size_t>(worker)], frame);
    measureTile(scene, triangle_bases_, static_cast<int>(tile), frame);
  });
  sumDiagnostics(tile_tests_, frame);
  PipelineCounters& c = frame.diagnostics.counters;
  c.instances_culled = stats.instances_culled;
  c.clusters_culled = stats.clusters_culled;
  c.clusters_facing = stats.clusters_facing;
  c.triangles_skipped = stats.triangles_skipped;
  c.culled.skipped = stats.triangles_skipped;
  if (pixel_tests) {
    addSetupCounters(chunks, chunk_count, triangles, frame);
  } else {
    c.triangles_in = stats.triangles_in;
    c.culled.no_pixel = stats.triangles_culled;  // RayRenderer does not split its reasons
    c.triangles_setup = stats.triangles_setup;
  }
  frame.diagnostics.times = {
      stats.vertex_ms, stats.setup_ms, stats.tiles_ms, stats.lines_ms,
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count()};
}

}  // namespace tessera::render
