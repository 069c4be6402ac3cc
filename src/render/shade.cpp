#include "render/shade.h"

#include "render/tone.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tessera::render {

Barycentrics barycentricsAt(const ShadeTriangle& t, float x, float y) {
  const float dx = x - t.x0, dy = y - t.y0;
  const float inv_s = 1.0f / (t.inv_w0 + t.sdx * dx + t.sdy * dy);
  const float b1 = (t.p1dx * dx + t.p1dy * dy) * inv_s;
  const float b2 = (t.p2dx * dx + t.p2dy * dy) * inv_s;
  return {1.0f - b1 - b2, b1, b2};
}

namespace {

float2 uvAt(const float2 uv[3], const Barycentrics& b) {
  return uv[0] * b.b0 + uv[1] * b.b1 + uv[2] * b.b2;
}

}  // namespace

float lodLog2(float x) {
  // x = m 2^e with m in [1, 2): log2 x = e + log2 m, and log2 m = 2 atanh(s) / ln 2 with
  // s = (m - 1) / (m + 1) in [0, 1/3), its odd series to s^7 (error below 2e-5). The eight-lane
  // path (shade_lanes.h: lodLog2x8) does the same operations.
  int32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const int32_t e = (bits >> 23) - 127;
  const int32_t mantissa_bits = (bits & 0x7fffff) | 0x3f800000;
  float m;
  std::memcpy(&m, &mantissa_bits, sizeof m);
  const float s = (m - 1.0f) / (m + 1.0f);
  const float s2 = s * s;
  const float* k = kLodLog2Series;
  const float p = ((k[3] * s2 + k[2]) * s2 + k[1]) * s2 + k[0];
  return static_cast<float>(e) + s * p;
}

float textureLod(float2 uv, float2 uv_right, float2 uv_down, float width, float height) {
  const float2 du = uv_right - uv;
  const float2 dv = uv_down - uv;
  const float2 dx{du.x * width, du.y * height}, dy{dv.x * width, dv.y * height};
  const float rho2 = std::max(dx.x * dx.x + dx.y * dx.y, dy.x * dy.x + dy.y * dy.y);
  return rho2 > 0.0f ? 0.5f * lodLog2(rho2) : 0.0f;
}

float4 sampleTexture(const Texture& texture, const Sampler& sampler, float2 uv, float2 uv_right,
                     float2 uv_down) {
  const bool moved = !sampler.transform.identity();
  const UvAffine affine = moved ? sampler.transform.affine() : UvAffine{};
  const float2 at = moved ? affine.apply(uv) : uv;
  if (!needsLod(texture, sampler)) return texture.sample(at, sampler);
  const float2 right = moved ? affine.apply(uv_right) : uv_right;
  const float2 down = moved ? affine.apply(uv_down) : uv_down;
  const float lod = textureLod(at, right, down, static_cast<float>(texture.width),
                               static_cast<float>(texture.height));
  return texture.sampleLod(at, lod, sampler);
}

float3 sampleAlbedo(const ShadeTriangle& t, const ShadeExtras& extras, const Barycentrics& b,
                    float x, float y) {
  const Texture& texture = *t.material->albedo;
  const Sampler& sampler = t.material->sampler;
  if (!needsLod(texture, sampler)) {
    const float2 uv = uvAt(uvSet(extras, sampler), b);
    return sampleTexture(texture, sampler, uv, uv, uv).xyz();
  }
  return sampleAlbedo(t, extras, b, barycentricsAt(t, x + 1.0f, y), barycentricsAt(t, x, y + 1.0f));
}

float3 sampleAlbedo(const ShadeTriangle& t, const ShadeExtras& extras, const Barycentrics& b,
                    const Barycentrics& right, const Barycentrics& down) {
  const float2* uv = uvSet(extras, t.material->sampler);
  return sampleTexture(*t.material->albedo, t.material->sampler, uvAt(uv, b), uvAt(uv, right),
                       uvAt(uv, down))
      .xyz();
}

float4 sampleTexture(const Texture& texture, const Sampler& sampler, const ShadeTriangle& t,
                     const ShadeExtras& extras, const Barycentrics& b, float x, float y) {
  if (!needsLod(texture, sampler)) {
    const float2 uv = uvAt(uvSet(extras, sampler), b);
    return sampleTexture(texture, sampler, uv, uv, uv);
  }
  return sampleTexture(texture, sampler, extras, b, barycentricsAt(t, x + 1.0f, y),
                       barycentricsAt(t, x, y + 1.0f));
}

float4 sampleTexture(const Texture& texture, const Sampler& sampler, const ShadeExtras& extras,
                     const Barycentrics& b, const Barycentrics& right, const Barycentrics& down) {
  // The sampler's set, then the albedo's sampling (its transform and level of detail).
  const float2* uv = uvSet(extras, sampler);
  return sampleTexture(texture, sampler, uvAt(uv, b), uvAt(uv, right), uvAt(uv, down));
}

bool plainShading(const Scene& scene, bool want_normals) {
  // The plain paths interpolate vertex colours only; the tone curve is shadeLanesAt's.
  if (want_normals || ToneCurve::of(scene).active()) return false;
  return std::none_of(scene.objects.begin(), scene.objects.end(), [](const Object& o) {
    const bool textured = o.mesh && !o.mesh->uvs.empty() &&
                          std::any_of(o.materials.begin(), o.materials.end(),
                                      [](const Material& m) { return m.albedo != nullptr; });
    return o.shading == Shading::kPhong || o.shading == Shading::kPbr || textured;
  });
}

}  // namespace tessera::render
