// Binning: each set-up triangle goes into the bins of the screen tiles its bounding box touches.
// Every chunk of triangles bins into its own ChunkBins (no locks); the rasterizer reads the
// chunks in order, so a tile sees its triangles in submission order.
#pragma once

#include <cstdint>
#include <vector>

#include <tessera/render/diagnostics.h>

#include "render/fixed_point.h"
#include "render/page_pool.h"
#include "render/ray_setup.h"
#include "render/setup.h"

namespace tessera::render {

struct TileGrid {
  int width = 0, height = 0;  // pixels
  int columns = 0, rows = 0;  // tiles

  static TileGrid forViewport(int width, int height) {
    return {width, height, (width + kTileSize - 1) / kTileSize,
            (height + kTileSize - 1) / kTileSize};
  }
  int tileCount() const { return columns * rows; }
};

class ChunkBins {
 public:
  // Empties the bins for a grid of `tile_count` tiles (keeps the memory). `shared`: other cores
  // may have read the lists since they were filled (the renderer has more than one worker).
  // Then every line of the lists is first asked for in write state, all at once: on a host where
  // a line takes hundreds of nanoseconds between cores, the stores that refill the lists would
  // otherwise wait for the other core's copies one line at a time (docs/perf-notes/frame-stages.md,
  // round 6).
  void reset(int tile_count, bool shared = false);
  // Adds triangle `local_index` to every tile its bounding box overlaps. Inline for the common
  // case of a dense mesh: a box inside one tile.
  void add(const TileGrid& grid, const RasterTriangle& triangle, uint32_t local_index) {
    add(grid, PixelBox{triangle.min_x, triangle.min_y, triangle.max_x, triangle.maxY()},
        local_index);
  }
  void add(const TileGrid& grid, const PixelBox& box, uint32_t local_index) {
    const int tx0 = box.min_x >> kTileSizeLog2, tx1 = box.max_x >> kTileSizeLog2;
    const int ty0 = box.min_y >> kTileSizeLog2, ty1 = box.max_y >> kTileSizeLog2;
    if (tx0 == tx1 && ty0 == ty1) {
      push(ty0 * grid.columns + tx0, local_index);
      return;
    }
    addToTiles(grid, tx0, ty0, tx1, ty1, local_index);
  }
  // The tiles given a triangle since the last reset, each once.
  const std::vector<uint32_t>& usedTiles() const { return used_; }
  // The triangles of `tile`, in the order they were added.
  const uint32_t* begin(int tile) const { return tiles_[static_cast<size_t>(tile)].data(); }
  const uint32_t* end(int tile) const {
    const PoolVector<uint32_t>& list = tiles_[static_cast<size_t>(tile)];
    return list.data() + list.size();
  }
  size_t tileCount() const { return tiles_.size(); }
  // Where the list of `tile` is kept (its begin and end), for prefetching.
  const void* listOf(int tile) const { return &tiles_[static_cast<size_t>(tile)]; }
  size_t count(int tile) const { return tiles_[static_cast<size_t>(tile)].size(); }

 private:
  void push(int tile, uint32_t local_index) {
    PoolVector<uint32_t>& list = tiles_[static_cast<size_t>(tile)];
    if (list.empty()) used_.push_back(static_cast<uint32_t>(tile));
    list.push_back(local_index);
  }
  // Adds the triangle to tiles [tx0, tx1] x [ty0, ty1].
  void addToTiles(const TileGrid& grid, int tx0, int ty0, int tx1, int ty1, uint32_t local_index);
  // One list per tile: they keep their capacity from frame to frame, so a frame after warm-up
  // allocates nothing.
  std::vector<PoolVector<uint32_t>> tiles_;
  // The tiles whose lists are not empty. reset empties only these: every tile's list end was
  // read last frame by whichever worker drew the tile, and on a host where a line takes
  // hundreds of nanoseconds between cores, writing all of them cost a mostly culled chunk most
  // of its setup time (docs/perf-notes/frame-stages.md, round 5).
  std::vector<uint32_t> used_;
};

}  // namespace tessera::render

namespace tessera::render {

// The output of setup for one fixed range of the scene's triangles. Two workers set up
// neighbouring chunks at the same time and count into them (size, culled, clipped, the vectors'
// ends): each chunk has lines of its own (128 bytes: the adjacent-line prefetcher pairs lines).
struct alignas(128) TriangleChunk {
  size_t first_triangle = 0;  // scene triangle index range [first, first + count)
  size_t triangle_count = 0;
  // records [0, size) are this frame's; the vectors only grow, so a frame after warm-up neither
  // allocates nor initializes what it then overwrites.
  size_t size = 0;
  PoolVector<RasterTriangle> raster;  // 64-byte aligned (PoolVector): setup streams records in
  PoolVector<RasterWide> wide;        // beside raster, written for large triangles only
  PoolVector<ShadeTriangle> shade;
  PoolVector<ShadeExtras> extras;  // beside shade, written only where the shading reads them
  PoolVector<RayTriangle> ray;     // the nonlinear projections' raster records, beside shade
  // Some record's material may be alphaMode MASK (its ShadeTriangle's material says): the tile
  // raster then looks at each record's (raster_kernel.h's walkTileBins, mask_kernel.h).
  bool any_masked = false;
  // Some record is lit per pixel (Phong, PBR) or the normal AOV is asked for: the tile raster
  // prefetches each record's ShadeExtras normals (and texture coordinates) for the shading pass.
  bool reads_normals = false;
  // And some such record reads its corners' world positions (needsWorld): those are prefetched too.
  bool reads_world = false;
  // Some record may be textured without per-pixel lighting (texturedPlain, mixed_lanes.h): the
  // shading then takes such rows by their runs (row_runs.h), and the tile raster prefetches the
  // records' texture coordinates as it does the normals.
  bool textured_plain = false;
  // Every record is Phong-shaded without an albedo texture (litPlain, one shading): shadeRow's
  // groups of several triangles then evaluate their lights without first looking at each lane's
  // record for that (litAlike). Set by setupChunk; the ray renderer's chunks leave it false.
  bool lit_alike = false;
  // The one material of every record when all are textured without per-pixel lighting
  // (texturedPlain) through it, from objects of one material each; null otherwise. A tile whose
  // chunks all name the same one takes its textured rows' runs without looking at each run's
  // record for that (row_runs.h). Set by setupChunk; the ray renderer's chunks leave it null.
  const Material* textured_alike = nullptr;
  ChunkBins bins;
  // Records whose material is alphaMode BLEND, in submission order: left out of `bins` for the
  // transparent pass (blend.h).
  std::vector<uint32_t> blended;
  size_t culled = 0;
  size_t clipped = 0;
  // Diagnostics: why `culled` were culled (the cull kernel's drops only when count_reasons is
  // set: classifying them costs the setup stage) and the extra pieces of clipped triangles.
  bool count_reasons = false;
  CullCounts cull_reasons;
  size_t clip_splits = 0;
};

// Marks the tiles no chunk's bins touch: tile_empty gets `tiles` entries, 1 for such a tile and 0
// for the others. Returns the chunks' set-up triangles (records this frame), which streamsFrame
// weighs.
inline size_t markEmptyTiles(const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                             size_t tiles, std::vector<uint8_t>& tile_empty) {
  tile_empty.assign(tiles, 1);
  size_t triangles = 0;
  for (size_t c = 0; c < chunk_count; ++c) {
    for (uint32_t tile : chunks[c].bins.usedTiles()) tile_empty[tile] = 0;
    triangles += chunks[c].size;
  }
  return triangles;
}

}  // namespace tessera::render
