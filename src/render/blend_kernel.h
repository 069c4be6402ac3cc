// The transparent pass's tile kernel (blend.h), compiled per instruction set beside the shading
// kernel: each blended triangle binned to the tile, in the back-to-front order, over the pixels
// (or samples) it covers in front of the opaque depth. Coverage and depth are found one pixel at a
// time, as rasterMasked finds them (mask_kernel.h); the covered pixels of a row are shaded eight at
// a time at their centres by shadeLanes (the opaque pixels' shading, so the same colour an opaque
// material would take there), their alpha as MASK reads it (maskedAlpha), and the over operator is
// BlendTile's scalar code. Every variant gives the same bits.
#pragma once

#include <vector>

#include "render/blend.h"
#include "render/mask_kernel.h"
#include "render/shade_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, as shade_kernel.h

// The samples of pixel (x, y) that record t covers in front of the layers' depths: bit i for
// layer i, whose samples lie at shifts[i].
inline uint32_t blendedSamples(const RasterTriangle& t, const RasterWide& w, int x, int y,
                               const TileVisibility* const* layers, const SampleShift* shifts,
                               int samples) {
  uint32_t mask = 0;
  for (int i = 0; i < samples; ++i) {
    const SampleShift& shift = shifts[i];
    if (maskedEdgeAt(t, w, 0, x, y, shift.dx, shift.dy) < 0 ||
        maskedEdgeAt(t, w, 1, x, y, shift.dx, shift.dy) < 0 ||
        maskedEdgeAt(t, w, 2, x, y, shift.dx, shift.dy) < 0)
      continue;
    const float x0 = t.x0 - shift.pixels_x, y0 = t.y0 - shift.pixels_y;
    const float z_row = t.z0 + t.dzdy * (static_cast<float>(y) + 0.5f - y0);
    const float z = z_row + t.dzdx * ((static_cast<float>(x) + 0.5f) - x0);
    const TileVisibility& layer = *layers[i];
    if (z < layer.depth[(y - layer.y0) * kTileSize + (x - layer.x0)]) mask |= 1u << i;
  }
  return mask;
}

// Record `record` of `chunk` over the rows of the tile it covers.
TESSERA_LANES_INLINE void blendRecord(const TriangleChunk& chunk, uint32_t record,
                                      const TileVisibility* const* layers,
                                      const SampleShift* shifts, int samples,
                                      const LightRig& lights, BlendTile& out) {
  const RasterTriangle& t = chunk.raster[record];
  const RasterWide& w = chunk.wide[record];
  const ShadeTriangle& s = chunk.shade[record];
  const ShadeExtras& e = chunk.extras[record];
  const TileVisibility& tile = *layers[0];
  const auto [x_begin, x_end, y_begin, y_end] = tileSpan(t, tile);
  const F32x8 zero = splat(0.0f);
  for (int y = y_begin; y <= y_end; ++y) {
    const float py = static_cast<float>(y) + 0.5f;
    for (int x = x_begin; x <= x_end; x += 8) {
      alignas(32) int32_t lanes[8];
      uint32_t sample_masks[8];
      bool any_lane = false;
      for (int l = 0; l < 8; ++l) {
        sample_masks[l] =
            x + l <= x_end ? blendedSamples(t, w, x + l, y, layers, shifts, samples) : 0;
        lanes[l] = sample_masks[l] ? -1 : 0;
        any_lane |= sample_masks[l] != 0;
      }
      if (!any_lane) continue;
      const F32x8 px = toFloat(splat(x) + iota()) + splat(0.5f);
      Vec3x8 color{zero, zero, zero}, normal{zero, zero, zero};
      shadeLanes(s, e, lights, false, px, py, load<I32x8>(lanes), color, normal);
      alignas(32) float r[8], g[8], b[8];
      store(r, color.x);
      store(g, color.y);
      store(b, color.z);
      for (int l = 0; l < 8; ++l) {
        if (!sample_masks[l]) continue;
        const float alpha = maskedAlpha(s, e, static_cast<float>(x + l) + 0.5f, py);
        const int pixel = (y - tile.y0) * kTileSize + (x + l - tile.x0);
        out.over(pixel, sample_masks[l], float3{r[l], g[l], b[l]}, alpha);
      }
    }
  }
}

void blendTileKernel(const std::vector<TriangleChunk>& chunks, const ChunkBins& bins,
                     int tile_index, const TileVisibility* const* layers, const SampleShift* shifts,
                     int samples, const LightRig& lights, BlendTile& out) {
  const uint32_t* end = bins.end(tile_index);
  for (const uint32_t* it = bins.begin(tile_index); it != end; ++it)
    blendRecord(chunks[keyChunk(*it)], keyLocal(*it), layers, shifts, samples, lights, out);
}

}  // namespace
}  // namespace tessera::render
