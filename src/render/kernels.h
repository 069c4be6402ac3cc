// The per-instruction-set kernels (vertex, setup, raster, shading) and the run-time choice between
// them. Each kernel is written once (vertex_kernel.h, setup_kernel.h, raster_kernel.h,
// shade_kernel.h) and compiled once per instruction set (kernels_<isa>.cpp); every variant
// produces the same bits.
#pragma once

#include <tessera/render/cpu_renderer.h>

#include "render/blend.h"
#include "render/msaa.h"
#include "render/painter.h"
#include "render/raster.h"
#include "render/ray_setup.h"
#include "render/setup.h"
#include "render/shade.h"
#include "render/vertex.h"

namespace tessera::render {

enum class Isa { kScalar, kSse2, kAvx2, kAvx512 };

// The best one this CPU runs.
Isa detectIsa();
// The one CpuRenderer runs at `level`: that one where this CPU has it, else the best it has.
Isa isaFor(SimdLevel level);
const char* isaName(Isa isa);

// Rasterizes the triangles binned to `tile_index`, chunk by chunk in submission order, into the
// tile's visibility buffer (raster_kernel.h).
using RasterTileFn = void (*)(const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                              int tile_index, TileVisibility& tile);

// The same into several layers, layer i with its samples at shifts[i] (raster_kernel.h).
using RasterTileSamplesFn = void (*)(const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                                     int tile_index, TileVisibility* const* layers,
                                     const SampleShift* shifts, int layer_count);

// SampleTiles' primary keys, mixed pixels and covered counts from its layers (msaa_kernel.h).
using CombineSamplesFn = void (*)(SampleTiles& tiles, int samples, bool with_centre);

// Sets up the queued triangles of a batch into their chunk's records (setup_kernel.h).
// `sample_reach`: SetupContext::sample_reach.
using SetupBatchFn = void (*)(SetupBatch& batch, int width, int height, int32_t sample_reach,
                              RasterTriangle* raster, RasterWide* wide, ShadeTriangle* shade);

// Culls the eight triangles whose vertex indices are indices[0..23] (setup_kernel.h). False, with
// nothing written, when an index is not below vertex_count: the caller takes them one at a time.
using CullGroupFn = bool (*)(const uint32_t* indices, size_t vertex_count,
                             const ScreenVertex* screen, const uint16_t* outcodes, int width,
                             int height, CullMode cull, int32_t sample_reach, CullGroup& out);

// The nonlinear projections' tile raster: every triangle binned to the tile (TriangleChunk::ray),
// in submission order, into the visibility buffer at the rays of `layer` (ray_kernel.h).
using RasterRayTileFn = void (*)(const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                                 int tile_index, const RayLayer& layer, int width, RayDepth depth,
                                 TileVisibility& tile);
// Their shading: the tile's visible pixels at their centre rays, mixed pixels resolved from the
// sample rays when `msaa` is given, then the sRGB encode (ray_kernel.h).
using ShadeRayTileFn = void (*)(const TileVisibility& tile,
                                const std::vector<TriangleChunk>& chunks, size_t chunk_count,
                                const LightRig& lights, bool want_normals, uint32_t background,
                                const RayTable& rays, const MsaaShading* msaa, ShadedTile& out);

// The painter's raster (painter_kernel.h): the records binned to the tile in `slices`, slice
// after slice, each drawn over what is there; into one layer or several, as the two above.
using RasterPainterTileFn = void (*)(const std::vector<TriangleChunk>& chunks,
                                     const std::vector<PainterSlice>& slices, int tile_index,
                                     TileVisibility& tile);
using RasterPainterTileSamplesFn = void (*)(const std::vector<TriangleChunk>& chunks,
                                            const std::vector<PainterSlice>& slices, int tile_index,
                                            TileVisibility* const* layers,
                                            const SampleShift* shifts, int layer_count);

// The transparent pass over one resolved tile (blend_kernel.h): the blended records binned to the
// tile in `bins`, in order, over the samples of `layers` (their opaque depths; one layer at the
// pixel centres without MSAA, whose samples lie at shifts[i]) into `out`.
using BlendTileFn = void (*)(const std::vector<TriangleChunk>& chunks, const ChunkBins& bins,
                             int tile_index, const TileVisibility* const* layers,
                             const SampleShift* shifts, int samples, const LightRig& lights,
                             BlendTile& out);

// The sRGB codes of `count` linear values (a multiple of 16) by the shading kernel's encode
// (shade_kernel.h), for the tests.
using EncodeSrgbFn = void (*)(const float* linear, size_t count, uint8_t* codes);

// Every kernel compiled for one instruction set.
struct Kernels {
  TransformVerticesFn transform_vertices;   // vertex_kernel.h
  CullGroupFn cull_group;                   // setup_kernel.h
  SetupBatchFn setup_batch;                 // setup_kernel.h
  RasterTileFn raster_tile;                 // raster_kernel.h
  ShadeTileFn shade_tile;                   // shade_kernel.h
  RasterTileSamplesFn raster_tile_samples;  // raster_kernel.h
  CombineSamplesFn combine_samples;         // msaa_kernel.h
  RasterRayTileFn raster_ray_tile;          // ray_kernel.h
  ShadeRayTileFn shade_ray_tile;            // ray_kernel.h
  RasterPainterTileFn raster_painter_tile;  // painter_kernel.h
  RasterPainterTileSamplesFn raster_painter_tile_samples;
  BlendTileFn blend_tile;    // blend_kernel.h
  EncodeSrgbFn encode_srgb;  // shade_kernel.h
};

Kernels kernelsFor(Isa isa);

// The table of the kernels compiled in this translation unit (kernels_<isa>.cpp, which includes
// every *_kernel.h), in Kernels' order: one list for the four instruction sets.
#define TESSERA_KERNELS_OF_THIS_ISA                                                                \
  Kernels {                                                                                        \
    transformVerticesKernel, cullGroupKernel, setupBatchKernel, rasterTileKernel, shadeTileKernel, \
        rasterTileSamplesKernel, combineSamplesKernel, rasterRayTileKernel, shadeRayTileKernel,    \
        rasterPainterTileKernel, rasterPainterTileSamplesKernel, blendTileKernel, encodeSrgbKernel \
  }

// One table per instruction set, defined in kernels_<isa>.cpp.
extern const Kernels kKernelsScalar;
extern const Kernels kKernelsSse2;
extern const Kernels kKernelsAvx2;
extern const Kernels kKernelsAvx512;

}  // namespace tessera::render
