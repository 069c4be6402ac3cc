#include "render/pbr.h"

namespace tessera::render {

float3 pbrBrdf(const PbrSurface& surface, float3 n, float3 v, float3 l) {
  const float nl = dot3(n, l);
  if (!(nl > 0.0f)) return {0.0f, 0.0f, 0.0f};
  const PbrLobes lobes = pbrLobes(surface);
  const float3 r = pbrResponse(lobes, n, v, l, nl, std::fabs(dot3(n, v)));
  return {r.x / kPi, r.y / kPi, r.z / kPi};
}

float3 shadePbr(const LightRig& rig, const PbrSurface& surface, float3 n, float3 p) {
  const PbrLobes lobes = pbrLobes(surface);
  const float3 v = viewVector(rig, p);
  const float nv = std::fabs(dot3(n, v));
  float3 c = pbrAmbient(lobes, rig.ambient, surface.occlusion, nv);
  for (const ShadeLight& light : rig.lights) {
    float3 l;
    float nl, f;
    if (light.type == LightType::kDirectional) {
      l = {-light.direction.x, -light.direction.y, -light.direction.z};
      nl = dot3(n, l);
      f = nl;
    } else {
      const float attenuation = localAttenuation(light, p, l);
      nl = dot3(n, l);
      f = nl * attenuation;
    }
    // As irradiance(): a light adds where its factor is positive (a NaN adds nothing).
    if (!(nl > 0.0f) || !(f > 0.0f)) continue;
    const float3 r = pbrResponse(lobes, n, v, l, nl, nv);
    c = {c.x + r.x * (light.radiance.x * f), c.y + r.y * (light.radiance.y * f),
         c.z + r.z * (light.radiance.z * f)};
  }
  return {c.x + surface.emissive.x, c.y + surface.emissive.y, c.z + surface.emissive.z};
}

}  // namespace tessera::render
