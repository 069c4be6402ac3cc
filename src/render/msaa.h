// Multisampling in the tile stage: one visibility layer per sample (raster_kernel.h's
// rasterSample), then per pixel the key the shading kernel shades at the centre and whether the
// pixel's samples hold different triangles, which the shading kernels (of both renderers) then
// resolve fragment by fragment (fragment_queue.h).
//
// A pixel whose samples all hold one triangle is shaded once at its centre, as with one sample:
// the centre lies in the convex hull of every standard pattern, so inside that triangle. A mixed
// pixel shades each distinct triangle once, at the centre when the centre passes the triangle's
// edge tests and otherwise at the first of its samples in pattern order (nearest the centre
// first), weights it by the samples it holds, gives uncovered samples the background, and
// averages in linear light.
#pragma once

#include <array>
#include <memory>

#include <tessera/math/vec.h>
#include <tessera/render/sampling.h>

#include "render/raster.h"

namespace tessera::render {

// One worker's sample layers and what the combine step derives from them.
struct SampleTiles {
  // layers[0 .. samples - 1]: the samples, in pattern order; layers[samples]: the pixel centres,
  // rasterized when an AOV or the line pass needs them (the same bits as one sample gives).
  std::array<std::unique_ptr<TileVisibility>, kMaxSamples + 1> layers;
  // The key the shading kernel shades at each pixel's centre: the centre layer's where it is
  // covered (so the normal AOV is the centre's), else the first covered sample's; empty where
  // neither is. Only its keys are used.
  std::unique_ptr<TileVisibility> primary = std::make_unique<TileVisibility>();
  // Per pixel (tile layout): all ones where the samples hold different keys, or the centre layer
  // another key than the samples (its colour is then the samples' resolve); the number of covered
  // samples.
  alignas(64) int32_t mixed[kTileSize * kTileSize + kTilePadding];
  alignas(64) int32_t covered[kTileSize * kTileSize + kTilePadding];

  TileVisibility& layer(int i) {
    if (!layers[static_cast<size_t>(i)])
      layers[static_cast<size_t>(i)] = std::make_unique<TileVisibility>();
    return *layers[static_cast<size_t>(i)];
  }
};

// What the shading kernel needs to resolve mixed pixels.
struct MsaaShading {
  const SampleTiles* tiles = nullptr;
  int samples = 1;
  const SamplePosition* positions = nullptr;  // samplePattern(samples)
  float3 background{};                        // linear
};

}  // namespace tessera::render
