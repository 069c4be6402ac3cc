// Shading: once per visible pixel of a tile, from the triangle that owns it in the visibility
// buffer, into a tile of linear colours (and world normals when asked).
#pragma once

#include <vector>

#include <tessera/math/vec.h>
#include <tessera/scene/scene.h>

#include "render/bin.h"
#include "render/raster.h"
#include "render/setup.h"

namespace tessera::render {

struct ShadedTile {
  alignas(64) float3 color[kTileSize * kTileSize];        // linear RGB; unset where no triangle
  alignas(64) uint32_t triangle_id[kTileSize * kTileSize];  // scene triangle index + 1
  alignas(64) float3 normal[kTileSize * kTileSize];       // filled only when asked
};

// Shades window point (x, y) (a pixel centre) of triangle `t`; writes the shading normal to
// *normal when it is not null.
float3 shadePixel(const ShadeTriangle& t, const Scene& scene, float x, float y, float3* normal);

// Shades every pixel of the tile that has a triangle. Walks the tile's triangles in bin order
// (so the setup records are read in the order they were written, not at random) and shades the
// pixels each one owns.
void shadeTile(const TileVisibility& tile, int tile_index, const std::vector<TriangleChunk>& chunks,
               size_t chunk_count, const Scene& scene, bool want_normals, ShadedTile& out);

}  // namespace tessera::render
