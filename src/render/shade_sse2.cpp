// The shading kernel compiled for sse2 (see CMakeLists.txt for this file's flags).
#include "render/shade_kernel.h"

namespace tessera::render {

void shadeTileSse2(const TileVisibility& tile, int tile_index,
                   const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                   const Scene& scene, bool want_normals, uint32_t background, ShadedTile& out) {
  shadeTileKernel(tile, tile_index, chunks, chunk_count, scene, want_normals, background, out);
}

}  // namespace tessera::render
