// Shading: once per visible pixel of a tile, from the triangle that owns it in the visibility
// buffer, into the tile's final colours (and world normals when asked).
//
// The shading kernel walks the tile in pixel order, eight pixels of a row at a time, and evaluates
// each triangle owning some of them once for the eight; colours are encoded to sRGB right there.
// Like the raster kernel it is written once (shade_kernel.h) and compiled per instruction set.
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
  alignas(64) uint32_t rgba[kSize];   // the final colour: sRGB-encoded, or the background
  alignas(64) float normal_x[kSize];  // world shading normal; filled only when asked
  alignas(64) float normal_y[kSize];
  alignas(64) float normal_z[kSize];
  // Where the shading's encode (encodeShadedRow) puts the colour when not null: the frame's pixel
  // at the tile's origin, its rows `direct_stride` pixels apart. rgba is then left alone and
  // resolveTile copies no colour. The tile stage sets it for every tile (directColour in
  // cpu_renderer.cpp).
  uint32_t* direct = nullptr;
  size_t direct_stride = 0;
};

struct Barycentrics {
  float b0, b1, b2;
};

// The corners' texture coordinates in the set `sampler` reads (Sampler::texcoord): ShadeExtras::uv
// or uv1 (which setup writes for every object whose materials read set 1).
inline const float2* uvSet(const ShadeExtras& e, const Sampler& sampler) {
  return sampler.texcoord == 1 ? e.uv1 : e.uv;
}

// Perspective-correct barycentrics at window point (x, y) from the 1/w-weighted planes.
Barycentrics barycentricsAt(const ShadeTriangle& t, float x, float y);

// Whether reading `texture` through `sampler` takes a level of detail: trilinear filtering of a
// texture with mip levels.
inline bool needsLod(const Texture& texture, const Sampler& sampler) {
  return sampler.filter == TextureFilter::kTrilinear && !texture.mips.empty();
}

// The coefficients of lodLog2's series: 2 / ln 2 times 1, 1/3, 1/5, 1/7.
inline constexpr float kLodLog2Series[4] = {2.8853900817779268f, 0.9617966939259756f,
                                            0.5770780163555854f, 0.4121985831111324f};
// log2 x for the level of detail, within 2e-5 for finite x > 0 (and 128 for +inf); one definition
// that the eight-lane path repeats operation for operation (std::log2 has none in vector form).
float lodLog2(float x);
// The level of detail of a texture of width x height texels where the texture coordinates move
// from uv to uv_right and uv_down at the next pixel centres: log2 of the longer screen axis's
// footprint in texels (the OpenGL specification's scale factor rho, 8.14.1).
float textureLod(float2 uv, float2 uv_right, float2 uv_down, float width, float height);

// `texture` read through `sampler` at uv, the texture coordinates at this pixel before the
// sampler's transform; uv_right and uv_down (the same at the next pixel centres) give the level of
// detail where needsLod. Every map of a material is read through this.
float4 sampleTexture(const Texture& texture, const Sampler& sampler, float2 uv, float2 uv_right,
                     float2 uv_down);

// The albedo texture of `t` at window point (x, y), with barycentrics b there. Trilinear
// filtering takes its level of detail from the UVs at the next pixel centres right and down.
float3 sampleAlbedo(const ShadeTriangle& t, const ShadeExtras& extras, const Barycentrics& b,
                    float x, float y);
// The same with the barycentrics at the next pixel centres right and down given (the nonlinear
// projections, whose barycentrics come from rays).
float3 sampleAlbedo(const ShadeTriangle& t, const ShadeExtras& extras, const Barycentrics& b,
                    const Barycentrics& right, const Barycentrics& down);

// Any texture of t's material (`texture` read through `sampler`: the PBR maps) at barycentrics b,
// RGBA as the texture holds it (linear; sRGB textures decoded): in the sampler's UV set, through
// its KHR_texture_transform. The same filtering and level of detail as sampleAlbedo, from the
// barycentrics at window point (x, y)'s neighbours or those given.
float4 sampleTexture(const Texture& texture, const Sampler& sampler, const ShadeTriangle& t,
                     const ShadeExtras& extras, const Barycentrics& b, float x, float y);
float4 sampleTexture(const Texture& texture, const Sampler& sampler, const ShadeExtras& extras,
                     const Barycentrics& b, const Barycentrics& right, const Barycentrics& down);

// True when every pixel's colour is its triangle's interpolated vertex colours: no object is
// textured, Phong- or PBR-shaded and the normal AOV is not asked for.
bool plainShading(const Scene& scene, bool want_normals);

// `plain`: plainShading(scene, want_normals).
// `msaa`: null with one sample; otherwise the tile's sample layers, whose mixed pixels are
// resolved sample by sample (msaa.h) where `tile` (SampleTiles::primary) is shaded at centres.
using ShadeTileFn = void (*)(const TileVisibility& tile, const std::vector<TriangleChunk>& chunks,
                             size_t chunk_count, const LightRig& lights, bool want_normals,
                             bool plain, uint32_t background, const struct MsaaShading* msaa,
                             ShadedTile& out);

// shade_kernel.h; one variant per instruction set (kernels.h). Shades every pixel of the tile that
// has a triangle and encodes it to sRGB; the background where no triangle is.

}  // namespace tessera::render
