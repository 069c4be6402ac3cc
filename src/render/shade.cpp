#include "render/shade.h"

namespace tessera::render {

ShadedPixel shadePixel(const ShadeTriangle& t, const Scene& scene, float x, float y) {
  // Perspective-correct barycentrics from the 1/w-weighted planes.
  const float dx = x - t.x0, dy = y - t.y0;
  const float s = t.inv_w0 + t.sdx * dx + t.sdy * dy;
  const float inv_s = 1.0f / s;
  const float b1 = (t.p1dx * dx + t.p1dy * dy) * inv_s;
  const float b2 = (t.p2dx * dx + t.p2dy * dy) * inv_s;
  const float b0 = 1.0f - b1 - b2;

  const Object& object = scene.objects[t.object];
  const Material& material = object.materials[t.material < object.materials.size() ? t.material : 0];

  float4 albedo = material.base_color;
  albedo = albedo * (t.color[0] * b0 + t.color[1] * b1 + t.color[2] * b2);
  if (material.albedo && t.has_uv) {
    const float2 uv = t.uv[0] * b0 + t.uv[1] * b1 + t.uv[2] * b2;
    albedo = albedo * material.albedo->sample(uv, material.sampler);
  }

  ShadedPixel out;
  switch (t.shading) {
    case Shading::kFlat: out.normal = t.normal[0]; break;
    default: out.normal = normalize(t.normal[0] * b0 + t.normal[1] * b1 + t.normal[2] * b2); break;
  }

  float3 light{1, 1, 1};
  switch (t.shading) {
    case Shading::kFlat: light = t.irradiance[0]; break;  // lit once, in setup
    case Shading::kPhong: light = irradiance(scene, out.normal); break;
    case Shading::kGouraud:
      light = t.irradiance[0] * b0 + t.irradiance[1] * b1 + t.irradiance[2] * b2;
      break;
    case Shading::kUnlit: break;
  }
  out.color = float4{albedo.xyz() * light, albedo.w};
  return out;
}

}  // namespace tessera::render
