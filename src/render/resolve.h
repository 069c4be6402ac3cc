// Resolve: write a shaded tile (colour already sRGB-encoded by the shading kernel) and the AOVs
// (triangle id, depth, normal) into the frame.
#pragma once

#include <vector>

#include <tessera/render/frame.h>
#include <tessera/scene/scene.h>

#include "render/bin.h"
#include "render/raster.h"
#include "render/shade.h"

namespace tessera::render {

// Whether a frame of `pixels` pixels drawing `triangles` set-up triangles has its colour written
// past the caches (streaming stores) rather than through them: when the colour and the triangles'
// records would take more than half the last-level cache (kUnknownCacheFrameBytes where Linux
// does not say its size). A frame that fits stays in the cache, where the next frame's writes and
// the image encoder find it; a larger one would evict what the tiles read. Measured on the 2-core
// AMD EPYC with its 32 MB L3 (docs/perf-notes/frame-passes.md, 2026-12-04, sixth session): through
// the caches the cube at 1920x1080 took 19% less time and the textured sphere 7% less, the bunny
// the same; the dense sphere's million triangles took 2% more, and scenes at 3840x2160 up to 10%
// more.
constexpr size_t kUnknownCacheFrameBytes = size_t{4} << 20;
bool streamsFrame(size_t pixels, size_t triangles);

// Whether the background of a frame's empty tiles is written past the caches: when the frame
// streams (streamsFrame), or when its colour is more than kStreamedBackgroundBytes. Nothing of the
// renderer reads those pixels again, and a fill in streaming stores of whole lines costs no read
// of the lines it replaces: on the 2-core Intel Xeon (docs/perf-notes/frame-passes.md, 2026-12-05,
// "The empty tiles' background streamed") a 4K fill took 1.6 ms streamed against 3.0-3.7 ms through
// the caches, and the textured sphere's 4K frame 8.39 -> 6.94 ms, where the last-level cache the
// system reports (300 MB, shared with other machines) kept the frame from streaming.
constexpr size_t kStreamedBackgroundBytes = size_t{4} << 20;
bool streamsBackground(size_t pixels, size_t triangles);

// The triangle ids come from the keys through the chunks' records. `stream`: streamsFrame.
void resolveTile(const TileVisibility& tile, const ShadedTile& shaded,
                 const std::vector<TriangleChunk>& chunks, bool stream, Frame& frame);

// The coverage AOV of the tile's pixels: with one sample (`covered` null) 255 where the tile's key
// is a triangle's; with `samples`, covered[i] of them covered: (covered * 255 + samples / 2) /
// samples.
void resolveCoverage(const TileVisibility& tile, const int32_t* covered, int samples, Frame& frame);

// A tile no triangle touches: background colour, no id, depth +inf (and zero normals and
// coverage). `stream`: streamsBackground.
void resolveEmptyTile(int x0, int y0, int width, int height, uint32_t background, bool stream,
                      Frame& frame);

// Tile `tile` of `grid`, empty (tile_empty[tile], from markEmptyTiles): the first tile of a run of
// empty tiles along its row fills the whole run, row by row across it (resolveEmptyTile: long runs
// of stores instead of 64-pixel pieces); the run's other tiles leave it to that one.
void resolveEmptyRun(const TileGrid& grid, const std::vector<uint8_t>& tile_empty, int tile,
                     uint32_t background, bool stream, Frame& frame);

}  // namespace tessera::render
