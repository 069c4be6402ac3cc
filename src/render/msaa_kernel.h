// The multisampling kernels (msaa.h): combining a tile's sample layers, and the exact centre test
// of a mixed pixel's triangles read from the layers' keys (kCentreKeyBit; the rows resolve through
// fragment_queue.h). Written once against eight-lane types and compiled per instruction set
// (kernels_<isa>.cpp), with the same operations per lane, so every variant gives the same bits.
#pragma once

#include <cstdint>
#include <vector>

#include "render/bin.h"
#include "render/mixed_lanes.h"
#include "render/msaa.h"
#include "render/shade_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

// The lanes of `lanes` whose pixel centre passes the edge tests of their triangle: the centre
// flags of their sample layer keys (kCentreKeyBit), the raster kernels' exact test (the Vulkan
// backend's).
TESSERA_LANES_INLINE I32x8 centresCovered(I32x8 keys, I32x8 lanes) {
  const I32x8 bit = splat(static_cast<int32_t>(kCentreKeyBit));
  return lanes & equal(keys & bit, bit);
}

// A sample layer's keys without their centre flags (not of empty lanes).
TESSERA_LANES_INLINE I32x8 unflagged(I32x8 keys) {
  return keys & splat(static_cast<int32_t>(~kCentreKeyBit));
}

// SampleTiles::primary, mixed and covered from the sample layers (and the centre layer, when
// `with_centre`).
TESSERA_LANES_INLINE void combineSamples(SampleTiles& tiles, int samples, bool with_centre) {
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
      // Without the sample layers' centre flags: the shading compares these keys across pixels.
      store(primary.key + i, select(equal(first, empty), first, unflagged(first)));
      store(tiles.mixed + i, mixed);
      store(tiles.covered + i, covered);
    }
  }
}
void combineSamplesKernel(SampleTiles& tiles, int samples, bool with_centre) {
  if (with_centre)
    combineSamples(tiles, samples, true);
  else
    withSampleCount(
        samples, [&](int n) __attribute__((always_inline)) { combineSamples(tiles, n, false); });
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
