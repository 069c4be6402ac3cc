// The raster kernel compiled for sse2 (see CMakeLists.txt for this file's flags).
#include "render/raster_kernel.h"

namespace tessera::render {

void rasterTriangleSse2(const RasterTriangle& triangle, uint32_t key, TileVisibility& tile) {
  rasterTriangleKernel(triangle, key, tile);
}

}  // namespace tessera::render
