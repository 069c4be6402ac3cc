#include <tessera/scene/texture.h>

#include <cmath>

#include <tessera/scene/color.h>

namespace tessera {

namespace {

int wrapCoord(int i, int size, TextureWrap wrap) {
  if (wrap == TextureWrap::kClamp) return i < 0 ? 0 : (i >= size ? size - 1 : i);
  int m = i % size;
  return m < 0 ? m + size : m;
}

float4 texelLinear(const Texture& t, int x, int y) {
  uint32_t c = t.texels[static_cast<size_t>(y) * t.width + x];
  float a = static_cast<float>(c >> 24) / 255.0f;
  if (t.srgb)
    return {decodeSrgb8(c & 0xff), decodeSrgb8((c >> 8) & 0xff), decodeSrgb8((c >> 16) & 0xff), a};
  return {static_cast<float>(c & 0xff) / 255.0f, static_cast<float>((c >> 8) & 0xff) / 255.0f,
          static_cast<float>((c >> 16) & 0xff) / 255.0f, a};
}

// Keeps float-to-int conversions defined for huge or non-finite coordinates.
float sanitize(float v) { return std::isfinite(v) ? std::fmod(v, 65536.0f) : 0.0f; }

}  // namespace

float4 Texture::sample(float2 uv, const Sampler& sampler) const {
  if (width <= 0 || height <= 0) return {1, 1, 1, 1};
  // Texel space: x right, y down from the top row (v = 1 is the top edge).
  float fx = sanitize(uv.x) * width;
  float fy = (1.0f - sanitize(uv.y)) * height;
  if (sampler.filter == TextureFilter::kNearest) {
    int x = wrapCoord(static_cast<int>(std::floor(fx)), width, sampler.wrap);
    int y = wrapCoord(static_cast<int>(std::floor(fy)), height, sampler.wrap);
    return texelLinear(*this, x, y);
  }
  // Bilinear between the four nearest texel centres, in linear space.
  float sx = fx - 0.5f, sy = fy - 0.5f;
  float x0f = std::floor(sx), y0f = std::floor(sy);
  float tx = sx - x0f, ty = sy - y0f;
  int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);
  int xa = wrapCoord(x0, width, sampler.wrap), xb = wrapCoord(x0 + 1, width, sampler.wrap);
  int ya = wrapCoord(y0, height, sampler.wrap), yb = wrapCoord(y0 + 1, height, sampler.wrap);
  float4 top = lerp(texelLinear(*this, xa, ya), texelLinear(*this, xb, ya), tx);
  float4 bottom = lerp(texelLinear(*this, xa, yb), texelLinear(*this, xb, yb), tx);
  return lerp(top, bottom, ty);
}

}  // namespace tessera
