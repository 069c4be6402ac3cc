// Shading: once per visible pixel of a tile, from the triangle that owns it in the visibility
// buffer, into a tile of linear colours (and world normals when asked).
//
// shadeTile walks the triangles that won pixels when the tile was rasterized, in bin order (so the
// setup records are read in the order they were written, not at random), and shades the pixels
// each one still owns, eight at a time. Like
// the raster kernel it is written once (shade_kernel.h) and compiled per instruction set.
#pragma once

#include <vector>

#include <tessera/math/vec.h>
#include <tessera/scene/scene.h>

#include "render/bin.h"
#include "render/raster.h"
#include "render/setup.h"

namespace tessera::render {

// Structure of arrays, laid out like TileVisibility (row y at y * kTileSize, padded).
struct ShadedTile {
  static constexpr int kSize = kTileSize * kTileSize + kTilePadding;
  alignas(64) float red[kSize];  // linear RGB; unset where no triangle
  alignas(64) float green[kSize];
  alignas(64) float blue[kSize];
  alignas(64) uint32_t rgba[kSize];         // the final colour: sRGB-encoded, or the background
  alignas(64) uint32_t triangle_id[kSize];  // scene triangle index + 1
  alignas(64) float normal_x[kSize];        // world shading normal; filled only when asked
  alignas(64) float normal_y[kSize];
  alignas(64) float normal_z[kSize];
};

struct Barycentrics {
  float b0, b1, b2;
};

// Perspective-correct barycentrics at window point (x, y) from the 1/w-weighted planes.
Barycentrics barycentricsAt(const ShadeTriangle& t, float x, float y);

// The albedo texture of `t` at window point (x, y), with barycentrics b there. Trilinear
// filtering takes its level of detail from the UVs at the next pixel centres right and down.
float3 sampleAlbedo(const ShadeTriangle& t, const Barycentrics& b, float x, float y);

// `drawn` lists the keys of the triangles that may own pixels of the tile (the raster kernel's
// output), in raster order.
using ShadeTileFn = void (*)(const TileVisibility& tile, const uint32_t* drawn, size_t drawn_count,
                             const std::vector<TriangleChunk>& chunks, const Scene& scene,
                             bool want_normals, uint32_t background, ShadedTile& out);

// shade_kernel.h; one variant per instruction set (kernels.h). Shades every pixel of the tile that
// has a triangle, then encodes the tile to sRGB (the background where no triangle is).

}  // namespace tessera::render
