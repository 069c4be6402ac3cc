// The shading kernel compiled for scalar (see CMakeLists.txt for this file's flags).
#define TESSERA_SIMD_SCALAR 1
#include "render/shade_kernel.h"

namespace tessera::render {

void shadeTileScalar(const TileVisibility& tile, int tile_index,
                   const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                   const Scene& scene, bool want_normals, uint32_t background, ShadedTile& out) {
  shadeTileKernel(tile, tile_index, chunks, chunk_count, scene, want_normals, background, out);
}

}  // namespace tessera::render
