// The multisampling kernels (msaa.h): combining a tile's sample layers, and resolving the mixed
// pixels of a row sample by sample. Written once against eight-lane types and compiled per
// instruction set (kernels_<isa>.cpp), with the same operations per lane, so every variant gives
// the same bits.
#pragma once

#include <cstdint>
#include <vector>

#include "render/bin.h"
#include "render/msaa.h"
#include "render/shade_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

// SampleTiles::primary, mixed and covered from the sample layers (and the centre layer, when
// `with_centre`).
void combineSamplesKernel(SampleTiles& tiles, int samples, bool with_centre) {
  const TileVisibility& first_layer = *tiles.layers[0];
  TileVisibility& primary = *tiles.primary;
  primary.x0 = first_layer.x0, primary.y0 = first_layer.y0;
  primary.width = first_layer.width, primary.height = first_layer.height;
  const I32x8 empty = splat(static_cast<int32_t>(kEmptyKey));
  const I32x8 zero = splat(int32_t{0});
  for (int ty = 0; ty < primary.height; ++ty) {
    for (int tx = 0; tx < primary.width; tx += 8) {
      const int i = ty * kTileSize + tx;
      const I32x8 k0 = load<I32x8>(first_layer.key + i);
      I32x8 first = k0, mixed = zero;
      I32x8 covered = zero - ~equal(k0, empty);
      for (int s = 1; s < samples; ++s) {
        const I32x8 k = load<I32x8>(tiles.layers[static_cast<size_t>(s)]->key + i);
        mixed = mixed | ~equal(k, k0);
        covered = covered - ~equal(k, empty);
        first = select(equal(first, empty), k, first);
      }
      if (with_centre) {
        const I32x8 centre = load<I32x8>(tiles.layers[static_cast<size_t>(samples)]->key + i);
        first = select(equal(centre, empty), first, centre);
      }
      store(primary.key + i, first);
      store(tiles.mixed + i, mixed);
      store(tiles.covered + i, covered);
    }
  }
}

// Whether the centre of pixel (x, y) passes the triangle's three edge tests (the raster kernel's
// arithmetic: a small triangle from its corner values, a large one from c).
TESSERA_LANES_INLINE bool coversCentre(const RasterTriangle& t, const RasterWide& w, int x, int y) {
  for (int k = 0; k < 3; ++k) {
    const int64_t e =
        t.small() ? t.corner[k] + int64_t{t.a[k]} * ((x - t.min_x) * kSubpixelOne) +
                        int64_t{t.b[k]} * ((y - t.min_y) * kSubpixelOne)
                  : int64_t{t.a[k]} * (int64_t{x} * kSubpixelOne + kSubpixelHalf) +
                        int64_t{t.b[k]} * (int64_t{y} * kSubpixelOne + kSubpixelHalf) + w.c[k];
    if (e < 0) return false;
  }
  return true;
}

// One distinct triangle of a mixed pixel: where it is shaded and how many samples it holds.
struct Fragment {
  const ShadeTriangle* shade;
  const ShadeExtras* extras;
  float x, y;  // the shading point, window coordinates
  int samples;
};

// The distinct triangles of pixel (x, y) (tile index i), in order of first sample, into `out`;
// returns how many, and the count of uncovered samples in `background`.
TESSERA_LANES_INLINE int pixelFragments(const MsaaShading& m, int i, int x, int y,
                                        const std::vector<TriangleChunk>& chunks, Fragment* out,
                                        int& background) {
  uint32_t keys[kMaxSamples];
  for (int s = 0; s < m.samples; ++s) keys[s] = m.tiles->layers[static_cast<size_t>(s)]->key[i];
  int count = 0;
  background = 0;
  for (int s = 0; s < m.samples; ++s) {
    const uint32_t key = keys[s];
    bool seen = false;
    for (int r = 0; r < s && !seen; ++r) seen = keys[r] == key;
    if (seen) continue;
    int held = 0;
    for (int r = s; r < m.samples; ++r) held += keys[r] == key;
    if (key == kEmptyKey) {
      background = held;
      continue;
    }
    const TriangleChunk& chunk = chunks[keyChunk(key)];
    const uint32_t local = keyLocal(key);
    Fragment& f = out[count++];
    f.shade = &chunk.shade[local];
    f.extras = &chunk.extras[local];
    f.samples = held;
    // Sample s is this triangle's first in pattern order, the nearest the centre it holds.
    const bool centre = coversCentre(chunk.raster[local], chunk.wide[local], x, y);
    constexpr float kToPixels = 1.0f / static_cast<float>(kSubpixelOne);
    f.x =
        static_cast<float>(x) + (centre ? 0.5f : static_cast<float>(m.positions[s].x) * kToPixels);
    f.y =
        static_cast<float>(y) + (centre ? 0.5f : static_cast<float>(m.positions[s].y) * kToPixels);
  }
  return count;
}

// Replaces the linear colours of row ty's mixed pixels by their resolve: each distinct triangle
// shaded once, weighted by its samples, uncovered samples the background, over the sample count.
// `plain` (shade.h): fragments are shaded eight at a time from their own records (shadeMixed);
// otherwise one at a time.
void resolveMixedRow(const MsaaShading& m, const TileVisibility& tile, int ty,
                     const std::vector<TriangleChunk>& chunks, const Scene& scene, bool plain,
                     float linear[3][kTileSize]) {
  Fragment fragments[kTileSize * kMaxSamples];
  int first_fragment[kTileSize + 1], background[kTileSize], pixel[kTileSize];
  int pixels = 0, count = 0;
  const int y = tile.y0 + ty;
  for (int tx = 0; tx < tile.width; tx += 8) {
    const int group = ty * kTileSize + tx;
    if (!any(load<I32x8>(m.tiles->mixed + group))) continue;
    for (int l = 0; l < 8 && tx + l < tile.width; ++l) {
      if (m.tiles->mixed[group + l] == 0) continue;
      pixel[pixels] = tx + l;
      first_fragment[pixels] = count;
      count += pixelFragments(m, group + l, tile.x0 + tx + l, y, chunks, fragments + count,
                              background[pixels]);
      ++pixels;
    }
  }
  if (pixels == 0) return;
  first_fragment[pixels] = count;

  // Each fragment's colour.
  alignas(32) float color[3][kTileSize * kMaxSamples + 8];
  if (plain) {
    for (int f = 0; f < count; f += 8) {
      const ShadeTriangle* records[8];
      alignas(32) float px[8], py[8];
      for (int l = 0; l < 8; ++l) {
        const Fragment& from = fragments[f + l < count ? f + l : f];  // the last group: padded
        records[l] = from.shade;
        px[l] = from.x;
        py[l] = from.y;
      }
      const Vec3x8 c = shadeMixed(records, load<F32x8>(px), load<F32x8>(py));
      store(color[0] + f, c.x);
      store(color[1] + f, c.y);
      store(color[2] + f, c.z);
    }
  } else {
    const I32x8 lane0 = equal(iota(), splat(int32_t{0}));
    const F32x8 zero = splat(0.0f);
    for (int f = 0; f < count; ++f) {
      const Fragment& from = fragments[f];
      Vec3x8 c{zero, zero, zero}, normal{zero, zero, zero};
      shadeLanes(*from.shade, *from.extras, scene, false, splat(from.x), from.y, lane0, c, normal);
      color[0][f] = lane(c.x, 0);
      color[1][f] = lane(c.y, 0);
      color[2][f] = lane(c.z, 0);
    }
  }

  // The resolve, pixel by pixel, fragments in order, the background last.
  const float inv_samples = 1.0f / static_cast<float>(m.samples);
  for (int p = 0; p < pixels; ++p) {
    float sum[3] = {0, 0, 0};
    for (int f = first_fragment[p]; f < first_fragment[p + 1]; ++f) {
      const float weight = static_cast<float>(fragments[f].samples);
      for (int c = 0; c < 3; ++c) sum[c] += color[c][f] * weight;
    }
    const float bg_weight = static_cast<float>(background[p]);
    sum[0] += m.background.x * bg_weight;
    sum[1] += m.background.y * bg_weight;
    sum[2] += m.background.z * bg_weight;
    for (int c = 0; c < 3; ++c) linear[c][pixel[p]] = sum[c] * inv_samples;
  }
}

}  // namespace
}  // namespace tessera::render
