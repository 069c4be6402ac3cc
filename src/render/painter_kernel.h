// The painter's tile raster (painter.h), compiled per instruction set beside raster_kernel.h:
// the records binned to the tile, slice after slice (back to front), each drawn over what is
// there (DepthRule::kLatest), into one visibility buffer or every sample layer.
#pragma once

#include <vector>

#include "render/painter.h"
#include "render/raster_samples_kernel.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, as raster_kernel.h

// Calls draw(raster, wide, key) for every record binned to the tile, in the painter's order, and
// for a masked one (alphaMode MASK) rasterMasked into the layers (mask_kernel.h). Several layers
// are a multisampled tile's sample layers, whose keys carry the centre flags (kCentreKeyBit); one
// is the one-sample tile, whose keys do not.
template <typename Draw>
TESSERA_LANES_INLINE void walkPainterBins(const std::vector<TriangleChunk>& chunks,
                                          const std::vector<PainterSlice>& slices, int tile_index,
                                          TileVisibility* const* layers, const SampleShift* shifts,
                                          int layer_count, Draw draw) {
  for (const PainterSlice& slice : slices) {
    const uint32_t* end = slice.bins.end(tile_index);
    for (const uint32_t* it = slice.bins.begin(tile_index); it != end; ++it) {
      const TriangleChunk& chunk = chunks[keyChunk(*it)];
      if (chunk.any_masked && isMasked(chunk, keyLocal(*it)))
        rasterMasked<true>(chunk, keyLocal(*it), *it, layers, shifts, layer_count, layer_count > 1);
      else
        draw(chunk.raster[keyLocal(*it)], chunk.wide[keyLocal(*it)], *it);
    }
  }
}

void rasterPainterTileKernel(const std::vector<TriangleChunk>& chunks,
                             const std::vector<PainterSlice>& slices, int tile_index,
                             TileVisibility& tile) {
  TileVisibility* const layers[1] = {&tile};
  const SampleShift centre[1] = {};
  walkPainterBins(chunks, slices, tile_index, layers, centre, 1,
                  [&](const RasterTriangle& t, const RasterWide& w, uint32_t key) {
                    rasterTriangle<DepthRule::kLatest>(t, w, key, tile);
                  });
}

void rasterPainterTileSamplesKernel(const std::vector<TriangleChunk>& chunks,
                                    const std::vector<PainterSlice>& slices, int tile_index,
                                    TileVisibility* const* layers, const SampleShift* shifts,
                                    int layer_count) {
  walkPainterBins(chunks, slices, tile_index, layers, shifts, layer_count,
                  [&](const RasterTriangle& t, const RasterWide& w, uint32_t key) {
                    rasterTriangleSamples<DepthRule::kLatest>(t, w, key, layers, shifts,
                                                              layer_count);
                  });
}

}  // namespace
}  // namespace tessera::render
