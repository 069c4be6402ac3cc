#include "render/shade.h"

#include <algorithm>
#include <cmath>

namespace tessera::render {

Barycentrics barycentricsAt(const ShadeTriangle& t, float x, float y) {
  const float dx = x - t.x0, dy = y - t.y0;
  const float inv_s = 1.0f / (t.inv_w0 + t.sdx * dx + t.sdy * dy);
  const float b1 = (t.p1dx * dx + t.p1dy * dy) * inv_s;
  const float b2 = (t.p2dx * dx + t.p2dy * dy) * inv_s;
  return {1.0f - b1 - b2, b1, b2};
}

namespace {

float2 uvAt(const ShadeExtras& e, const Barycentrics& b) {
  return e.uv[0] * b.b0 + e.uv[1] * b.b1 + e.uv[2] * b.b2;
}

}  // namespace

float3 sampleAlbedo(const ShadeTriangle& t, const ShadeExtras& extras, const Barycentrics& b,
                    float x, float y) {
  const Texture& texture = *t.material->albedo;
  const Sampler& sampler = t.material->sampler;
  const float2 uv = uvAt(extras, b);
  if (sampler.filter != TextureFilter::kTrilinear || texture.mips.empty())
    return texture.sample(uv, sampler).xyz();
  return sampleAlbedo(t, extras, b, barycentricsAt(t, x + 1.0f, y), barycentricsAt(t, x, y + 1.0f));
}

float3 sampleAlbedo(const ShadeTriangle& t, const ShadeExtras& extras, const Barycentrics& b,
                    const Barycentrics& right, const Barycentrics& down) {
  const Texture& texture = *t.material->albedo;
  const Sampler& sampler = t.material->sampler;
  const float2 uv = uvAt(extras, b);
  if (sampler.filter != TextureFilter::kTrilinear || texture.mips.empty())
    return texture.sample(uv, sampler).xyz();
  const float2 size{static_cast<float>(texture.width), static_cast<float>(texture.height)};
  const float2 du = uvAt(extras, right) - uv;
  const float2 dv = uvAt(extras, down) - uv;
  const float2 dx{du.x * size.x, du.y * size.y}, dy{dv.x * size.x, dv.y * size.y};
  const float rho2 = std::max(dx.x * dx.x + dx.y * dx.y, dy.x * dy.x + dy.y * dy.y);
  const float lod = rho2 > 0.0f ? 0.5f * std::log2(rho2) : 0.0f;
  return texture.sampleLod(uv, lod, sampler).xyz();
}

float4 sampleTexture(const Texture& texture, const Sampler& sampler, const ShadeTriangle& t,
                     const ShadeExtras& extras, const Barycentrics& b, float x, float y) {
  if (sampler.filter != TextureFilter::kTrilinear || texture.mips.empty())
    return texture.sample(uvAt(extras, b), sampler);
  return sampleTexture(texture, sampler, extras, b, barycentricsAt(t, x + 1.0f, y),
                       barycentricsAt(t, x, y + 1.0f));
}

float4 sampleTexture(const Texture& texture, const Sampler& sampler, const ShadeExtras& extras,
                     const Barycentrics& b, const Barycentrics& right, const Barycentrics& down) {
  const float2 uv = uvAt(extras, b);
  if (sampler.filter != TextureFilter::kTrilinear || texture.mips.empty())
    return texture.sample(uv, sampler);
  // The level of detail as sampleAlbedo: the larger screen-space footprint in texels.
  const float2 size{static_cast<float>(texture.width), static_cast<float>(texture.height)};
  const float2 du = uvAt(extras, right) - uv;
  const float2 dv = uvAt(extras, down) - uv;
  const float2 dx{du.x * size.x, du.y * size.y}, dy{dv.x * size.x, dv.y * size.y};
  const float rho2 = std::max(dx.x * dx.x + dx.y * dx.y, dy.x * dy.x + dy.y * dy.y);
  const float lod = rho2 > 0.0f ? 0.5f * std::log2(rho2) : 0.0f;
  return texture.sampleLod(uv, lod, sampler);
}

bool plainShading(const Scene& scene, bool want_normals) {
  if (want_normals) return false;
  return std::none_of(scene.objects.begin(), scene.objects.end(), [](const Object& o) {
    const bool textured = o.mesh && !o.mesh->uvs.empty() &&
                          std::any_of(o.materials.begin(), o.materials.end(),
                                      [](const Material& m) { return m.albedo != nullptr; });
    return o.shading == Shading::kPhong || o.shading == Shading::kPbr || textured;
  });
}

}  // namespace tessera::render
