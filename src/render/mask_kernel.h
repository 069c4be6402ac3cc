// alphaMode MASK in the tile raster (raster_kernel.h, painter_kernel.h): a triangle whose
// material is masked is drawn pixel by pixel, or sample by sample with MSAA, and each pixel or
// sample it covers keeps it only where its alpha (the base colour's alpha times the albedo
// texture's, read as the shading reads the albedo) is at least the material's alpha_cutoff, as
// glTF says. With several samples per pixel each sample takes its own alpha: the cut's edge is
// anti-aliased as alpha-to-coverage would make it, from the texture itself rather than a dither.
// Scalar (one pixel at a time) and the same operations on every instruction set: masked triangles
// are few (foliage, fences), and the image must not depend on the kernel variant.
#pragma once

#include <cstdint>

#include "render/bin.h"
#include "render/msaa.h"
#include "render/raster.h"
#include "render/shade.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, as raster_kernel.h

// Whether record `record` of `chunk` is drawn by rasterMasked: its material is alphaMode MASK.
inline bool isMasked(const TriangleChunk& chunk, uint32_t record) {
  return chunk.shade[record].material->alpha_mode == AlphaMode::kMask;
}

// Edge k of record t at the point (dx, dy) sub-pixels from the centre of pixel (x, y): the same
// integer as the record's edge function there (a * px + b * py + c), for a small record from its
// corner values, for a large one from its wide record's c.
inline int64_t maskedEdgeAt(const RasterTriangle& t, const RasterWide& w, int k, int x, int y,
                            int32_t dx, int32_t dy) {
  if (t.small())
    return t.corner[k] + int64_t{t.a[k]} * (int64_t{x - t.min_x} * kSubpixelOne + dx) +
           int64_t{t.b[k]} * (int64_t{y - t.min_y} * kSubpixelOne + dy);
  return int64_t{t.a[k]} * (int64_t{x} * kSubpixelOne + kSubpixelHalf + dx) +
         int64_t{t.b[k]} * (int64_t{y} * kSubpixelOne + kSubpixelHalf + dy) + w.c[k];
}

// The pixels of record t's box inside the tile: [x_begin, x_end] x [y_begin, y_end].
struct TileSpan {
  int x_begin, x_end, y_begin, y_end;
};
inline TileSpan tileSpan(const RasterTriangle& t, const TileVisibility& tile) {
  return {std::max<int>(t.min_x, tile.x0),
          std::min(static_cast<int>(t.max_x), tile.x0 + tile.width - 1),
          std::max<int>(t.min_y, tile.y0), std::min(t.maxY(), tile.y0 + tile.height - 1)};
}

// The triangle's alpha at window point (px, py): base colour alpha times the albedo's.
inline float maskedAlpha(const ShadeTriangle& s, const ShadeExtras& e, float px, float py) {
  const Material& m = *s.material;
  float alpha = m.base_color.w;
  if (s.has_uv && m.albedo) {
    const Barycentrics b = barycentricsAt(s, px, py);
    alpha = alpha * sampleTexture(*m.albedo, m.sampler, s, e, b, px, py).w;
  }
  return alpha;
}

// Record `record` of `chunk` (masked) into each of the layers, layer i with its samples at
// shifts[i]; one layer at the pixel centres (a zero shift) without MSAA. The depth is formed as
// rasterSample and depthTestRow8 form it, so a masked triangle meets its neighbours as an opaque
// one would. `flag_centres` (sample layers): the keys get kCentreKeyBit where the pixel's centre
// passes the edge tests, as the opaque walks give it.
template <bool kLatest>
void rasterMasked(const TriangleChunk& chunk, uint32_t record, uint32_t key,
                  TileVisibility* const* layers, const SampleShift* shifts, int layer_count,
                  bool flag_centres) {
  const RasterTriangle& t = chunk.raster[record];
  const RasterWide& w = chunk.wide[record];
  const ShadeTriangle& s = chunk.shade[record];
  const ShadeExtras& e = chunk.extras[record];
  const auto [x_begin, x_end, y_begin, y_end] = tileSpan(t, *layers[0]);
  const float cutoff = s.material->alpha_cutoff;
  for (int i = 0; i < layer_count; ++i) {
    const SampleShift& shift = shifts[i];
    const float x0 = t.x0 - shift.pixels_x, y0 = t.y0 - shift.pixels_y;
    TileVisibility& layer = *layers[i];
    for (int y = y_begin; y <= y_end; ++y) {
      const float z_row = t.z0 + t.dzdy * (static_cast<float>(y) + 0.5f - y0);
      for (int x = x_begin; x <= x_end; ++x) {
        if (maskedEdgeAt(t, w, 0, x, y, shift.dx, shift.dy) < 0 ||
            maskedEdgeAt(t, w, 1, x, y, shift.dx, shift.dy) < 0 ||
            maskedEdgeAt(t, w, 2, x, y, shift.dx, shift.dy) < 0)
          continue;
        const float z = z_row + t.dzdx * ((static_cast<float>(x) + 0.5f) - x0);
        const int at = (y - layer.y0) * kTileSize + (x - layer.x0);
        if (!kLatest && !(z < layer.depth[at])) continue;
        const float px = static_cast<float>(x) + 0.5f + shift.pixels_x;
        const float py = static_cast<float>(y) + 0.5f + shift.pixels_y;
        if (!(maskedAlpha(s, e, px, py) >= cutoff)) continue;
        layer.depth[at] = z;
        layer.key[at] = flag_centres && maskedEdgeAt(t, w, 0, x, y, 0, 0) >= 0 &&
                                maskedEdgeAt(t, w, 1, x, y, 0, 0) >= 0 &&
                                maskedEdgeAt(t, w, 2, x, y, 0, 0) >= 0
                            ? key | kCentreKeyBit
                            : key;
      }
    }
  }
}

}  // namespace
}  // namespace tessera::render
