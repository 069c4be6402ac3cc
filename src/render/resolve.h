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

// The triangle ids come from the keys through the chunks' records.
void resolveTile(const TileVisibility& tile, const ShadedTile& shaded,
                 const std::vector<TriangleChunk>& chunks, Frame& frame);

// The coverage AOV of the tile's pixels: with one sample (`covered` null) 255 where the tile's key
// is a triangle's; with `samples`, covered[i] of them covered: (covered * 255 + samples / 2) /
// samples.
void resolveCoverage(const TileVisibility& tile, const int32_t* covered, int samples, Frame& frame);

// A tile no triangle touches: background colour, no id, depth +inf (and zero normals and
// coverage).
void resolveEmptyTile(int x0, int y0, int width, int height, uint32_t background, Frame& frame);

}  // namespace tessera::render
