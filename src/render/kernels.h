// The per-instruction-set kernels of the tile stage (raster and shading) and of the vertex stage,
// and the run-time choice between them. Each kernel is written once (raster_kernel.h,
// shade_kernel.h, vertex_kernel.h) and compiled once per instruction set (kernels_<isa>.cpp);
// every variant produces the same bits.
#pragma once

#include "render/raster.h"
#include "render/setup.h"
#include "render/shade.h"
#include "render/vertex.h"

namespace tessera::render {

enum class Isa { kScalar, kSse2, kAvx2, kAvx512 };

// The best one this CPU runs.
Isa detectIsa();
const char* isaName(Isa isa);

// Rasterizes the triangles binned to `tile_index`, chunk by chunk in submission order, into the
// tile's visibility buffer (raster_kernel.h).
using RasterTileFn = void (*)(const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                              int tile_index, TileVisibility& tile);

struct TileKernels {
  RasterTileFn raster_tile;
  ShadeTileFn shade_tile;
  TransformVerticesFn transform_vertices;  // the vertex stage's, not a tile's (vertex_kernel.h)
};

TileKernels tileKernels(Isa isa);

// Sets up the queued triangles of a batch into their chunk's records (setup_kernel.h).
using SetupBatchFn = void (*)(const SetupBatch& batch, int width, int height,
                              RasterTriangle* raster, ShadeTriangle* shade);
struct SetupKernels {
  SetupBatchFn setup_batch;
};
SetupKernels setupKernels(Isa isa);
extern const SetupKernels kSetupKernelsScalar;
extern const SetupKernels kSetupKernelsSse2;
extern const SetupKernels kSetupKernelsAvx2;
extern const SetupKernels kSetupKernelsAvx512;

// One table per instruction set, defined in kernels_<isa>.cpp.
extern const TileKernels kTileKernelsScalar;
extern const TileKernels kTileKernelsSse2;
extern const TileKernels kTileKernelsAvx2;
extern const TileKernels kTileKernelsAvx512;

}  // namespace tessera::render
