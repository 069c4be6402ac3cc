// The multisampling kernels (msaa.h): combining a tile's sample layers and the exact centre test
// of a mixed pixel's triangles (the rows resolve through fragment_queue.h). Written once against
// eight-lane types and compiled per instruction set (kernels_<isa>.cpp), with the same operations
// per lane, so every variant gives the same bits.
#pragma once

#include <cstdint>
#include <vector>

#include "render/bin.h"
#include "render/mixed_lanes.h"
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
        // The centre's triangle is shaded there (for the normal AOV); where it is not the one
        // every sample holds, the colour comes from the samples' resolve.
        mixed = mixed | ~equal(centre, k0);
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

// The lanes of `lanes` whose pixel centre (columns[l], y) passes the edge tests of their triangle
// (keys; records: each lane's raster record, a valid one in every lane): the exact test, as the
// Vulkan backend's. Small triangles (the pixel lies in the record's box, where their edge values
// fit in int32: RasterTriangle::small) take it in lanes from their records' first ten words,
// loaded eight records at a time and transposed; large ones lane by lane in 64 bits.
TESSERA_LANES_INLINE I32x8 centresCovered(const std::vector<TriangleChunk>& chunks, I32x8 keys,
                                          const RasterTriangle* const records[8], I32x8 lanes,
                                          I32x8 columns, int y) {
  // corner[3], a[3], b[0..1]; then b[2] and min_x | min_y << 16.
  F32x8 w[8], b2, box;
  for (int l = 0; l < 8; ++l) w[l] = load<F32x8>(records[l]);
  transpose8x8(w);
  const float* at8[8];
  for (int l = 0; l < 8; ++l) at8[l] = reinterpret_cast<const float*>(records[l]) + 8;
  loadPairs(at8, b2, box);
  const I32x8 min_x = shiftRight(shiftLeft(bitsOf(box), 16), 16);
  const I32x8 min_y = shiftRight(bitsOf(box), 16);
  const I32x8 dx = (columns - min_x) * splat(kSubpixelOne);
  const I32x8 dy = (splat(y) - min_y) * splat(kSubpixelOne);
  const I32x8 e0 = bitsOf(w[0]) + bitsOf(w[3]) * dx + bitsOf(w[6]) * dy;
  const I32x8 e1 = bitsOf(w[1]) + bitsOf(w[4]) * dx + bitsOf(w[7]) * dy;
  const I32x8 e2 = bitsOf(w[2]) + bitsOf(w[5]) * dx + bitsOf(b2) * dy;
  // A large triangle's corner values are 0 (setup); a small one's are not all 0, as no point lies
  // on all three edges of a triangle with an area (setup drops the others).
  const I32x8 small = ~equal(bitsOf(w[0]) | bitsOf(w[1]) | bitsOf(w[2]), splat(int32_t{0}));
  I32x8 covered = lanes & small & nonNegative(e0 | e1 | e2);
  const I32x8 large = lanes & ~small;
  if (any(large)) {
    alignas(32) int32_t wanted[8], inside[8], column[8];
    alignas(32) uint32_t key[8];
    store(wanted, large);
    store(inside, covered);
    store(column, columns);
    store(key, keys);
    for (int l = 0; l < 8; ++l)
      if (wanted[l] &&
          coversCentre(*records[l], chunks[keyChunk(key[l])].wide[keyLocal(key[l])], column[l], y))
        inside[l] = -1;
    covered = load<I32x8>(inside);
  }
  return covered;
}

// Sample s of row y in pixels: x from the pixel's left edge, y from the top of the image.
TESSERA_LANES_INLINE float sampleX(const MsaaShading& m, int s) {
  return static_cast<float>(m.positions[s].x) * (1.0f / static_cast<float>(kSubpixelOne));
}
TESSERA_LANES_INLINE float sampleY(const MsaaShading& m, int s, int y) {
  return static_cast<float>(y) +
         static_cast<float>(m.positions[s].y) * (1.0f / static_cast<float>(kSubpixelOne));
}

}  // namespace
}  // namespace tessera::render
