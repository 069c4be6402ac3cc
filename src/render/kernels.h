// The per-instruction-set kernels of the tile stage (raster and shading), and the run-time choice
// between them. Each kernel is written once (raster_kernel.h, shade_kernel.h) and compiled once
// per instruction set (kernels_<isa>.cpp); every variant produces the same bits.
#pragma once

#include "render/raster.h"
#include "render/shade.h"

namespace tessera::render {

enum class Isa { kScalar, kSse2, kAvx2, kAvx512 };

// The best one this CPU runs.
Isa detectIsa();
const char* isaName(Isa isa);

struct TileKernels {
  RasterTriangleFn raster_triangle;
  ShadeTileFn shade_tile;
};

TileKernels tileKernels(Isa isa);

// One table per instruction set, defined in kernels_<isa>.cpp.
extern const TileKernels kTileKernelsScalar;
extern const TileKernels kTileKernelsSse2;
extern const TileKernels kTileKernelsAvx2;
extern const TileKernels kTileKernelsAvx512;

}  // namespace tessera::render
