// Albedo textures: 8-bit RGBA texels; base colour textures hold sRGB-encoded values and are
// decoded to linear when sampled (the decode is exact: a 256-entry table).
#pragma once

#include <cstdint>
#include <vector>

#include <tessera/math/vec.h>

namespace tessera {

// kTrilinear: bilinear in the two mip levels around the level of detail the pixel's screen-space
// UV footprint asks for, blended (falls back to kBilinear on a texture without mip levels).
enum class TextureFilter { kNearest, kBilinear, kTrilinear };
enum class TextureWrap { kRepeat, kClamp };

// KHR_texture_transform: uv' = T(offset) * R(rotation) * S(scale) * uv, in the extension's
// convention (rotation in radians, counter-clockwise in UV space with v pointing down the image).
struct TextureTransform {
  float2 offset{0.0f, 0.0f};
  float rotation = 0.0f;
  float2 scale{1.0f, 1.0f};
  bool identity() const {
    return offset.x == 0.0f && offset.y == 0.0f && rotation == 0.0f && scale.x == 1.0f &&
           scale.y == 1.0f;
  }
};

// How a material reads one of its textures: glTF's sampler, and its textureInfo's texture
// coordinate set and transform.
struct Sampler {
  TextureFilter filter = TextureFilter::kTrilinear;
  TextureWrap wrap = TextureWrap::kRepeat;
  TextureTransform transform;  // identity unless the file says KHR_texture_transform
  int texcoord = 0;            // TEXCOORD_<n>
};

struct TextureLevel {
  int width = 0;
  int height = 0;
  std::vector<uint32_t> texels;  // RGBA8, R in the low byte, row 0 at the top
};

struct Texture {
  int width = 0;
  int height = 0;
  std::vector<uint32_t> texels;    // RGBA8, R in the low byte, row 0 at the top (v = 1 is row 0)
  bool srgb = true;                // texels are sRGB-encoded colour (decode to linear on sampling)
  int source_channels = 0;  // the image file's channels (1 grey ... 4 RGBA); 0: not from a file
  std::vector<TextureLevel> mips;  // levels 1, 2, ... down to 1x1 (generateMipmaps); may be empty

  // Linear RGBA at texture coordinate `uv` (OpenGL convention: v = 0 is the bottom row), from
  // level 0 (kTrilinear samples level 0 bilinearly).
  float4 sample(float2 uv, const Sampler& sampler) const;
  // The same at level of detail `lod` (0 = full size, 1 = half size, ...): kTrilinear blends the
  // two levels around it; the other filters use the nearest level.
  float4 sampleLod(float2 uv, float lod, const Sampler& sampler) const;
  int levelCount() const { return 1 + static_cast<int>(mips.size()); }
};

// Fills texture.mips with a box-filtered chain (averaged in linear light for sRGB textures) down
// to 1x1. Odd sizes round down; each level's texel averages the 2x2 (or fewer) texels above it.
void generateMipmaps(Texture& texture);

}  // namespace tessera
