// Albedo textures: 8-bit RGBA texels; base colour textures hold sRGB-encoded values and are
// decoded to linear when sampled (the decode is exact: a 256-entry table).
#pragma once

#include <cstdint>
#include <vector>

#include <tessera/math/vec.h>

namespace tessera {

enum class TextureFilter { kNearest, kBilinear };
enum class TextureWrap { kRepeat, kClamp };

struct Sampler {
  TextureFilter filter = TextureFilter::kBilinear;
  TextureWrap wrap = TextureWrap::kRepeat;
};

struct Texture {
  int width = 0;
  int height = 0;
  std::vector<uint32_t> texels;  // RGBA8, R in the low byte, row 0 at the top (v = 1 is row 0)
  bool srgb = true;              // texels are sRGB-encoded colour (decode to linear on sampling)

  // Linear RGBA at texture coordinate `uv` (OpenGL convention: v = 0 is the bottom row).
  float4 sample(float2 uv, const Sampler& sampler) const;
};

}  // namespace tessera
