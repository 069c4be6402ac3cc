// The raster kernel compiled for scalar (see CMakeLists.txt for this file's flags).
#define TESSERA_RASTER_SCALAR 1
#include "render/raster_kernel.h"

namespace tessera::render {

void rasterTriangleScalar(const RasterTriangle& triangle, uint32_t key, TileVisibility& tile) {
  rasterTriangleKernel(triangle, key, tile);
}

}  // namespace tessera::render
