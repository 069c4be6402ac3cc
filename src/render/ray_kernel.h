// The tile stage of the nonlinear projections (ray_setup.h): coverage and depth by each pixel's
// ray, shading from the ray's barycentrics. Compiled once, for the baseline instruction set (not
// per ISA): the image of a nonlinear mode is the same bits whatever SIMD level is asked for.
#pragma once

#include <vector>

#include <tessera/render/projection.h>
#include <tessera/scene/scene.h>

#include "render/bin.h"
#include "render/msaa.h"
#include "render/raster.h"
#include "render/shade.h"

namespace tessera::render {

// How a hit's distance along its ray becomes depth: (t - near) * inv_range, kept in [0, 1].
struct RayDepth {
  float near = 0.1f;
  float inv_range = 1.0f;
};

// Every triangle binned to the tile (the chunks' RayTriangle records), in submission order, into
// the visibility buffer, at the rays of `layer` (a width-wide image's).
void rasterRayTile(const std::vector<TriangleChunk>& chunks, size_t chunk_count, int tile_index,
                   const RayLayer& layer, int width, RayDepth depth, TileVisibility& tile);

// Shades the tile's visible pixels at their centre rays (shade_lanes.h), resolves mixed pixels
// from the sample rays when `msaa` is given (the contract of msaa.h: a triangle is shaded at the
// centre ray when that ray passes through it, else at its first sample's), and encodes to sRGB.
void shadeRayTile(const TileVisibility& tile, const std::vector<TriangleChunk>& chunks,
                  size_t chunk_count, const Scene& scene, bool want_normals, uint32_t background,
                  const RayTable& rays, const MsaaShading* msaa, ShadedTile& out);

}  // namespace tessera::render
