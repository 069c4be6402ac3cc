#include "render/pbr.h"

namespace tessera::render {

float3 pbrBrdf(const PbrSurface& surface, float3 n, float3 v, float3 l) {
  const float nl = dot3(n, l);
  if (!(nl > 0.0f)) return {0.0f, 0.0f, 0.0f};
  const PbrLobes lobes = pbrLobes(surface);
  const float3 r = pbrResponse(lobes, n, v, l, nl, std::fabs(dot3(n, v)));
  return {r.x / kPi, r.y / kPi, r.z / kPi};
}

float3 pbrEnvironment(const PbrLobes& s, const LightRig& rig, float occlusion, float3 n, float3 v,
                      float nv) {
  const float nv_signed = dot3(n, v);
  const float3 r{2.0f * nv_signed * n.x - v.x, 2.0f * nv_signed * n.y - v.y,
                 2.0f * nv_signed * n.z - v.z};
  const Environment& environment = *rig.environment;
  const float3 e_d = environment.diffuse(rig.world_to_environment * n);
  const float3 e_s = environment.specular(rig.world_to_environment * r, s.roughness);
  const float2 ab = splitSumBrdf(nv, s.roughness);
  const float fw = schlickWeight(nv);
  const float f90 = 1.0f - s.roughness;
  float3 out;
  for (int k = 0; k < 3; ++k) {
    const float ks = s.f0[k] + (std::max(f90, s.f0[k]) - s.f0[k]) * fw;
    const float fss_ess = ks * ab.x + ab.y;
    out[k] = occlusion * (e_d[k] * (s.c_diff[k] * (1.0f - fss_ess)) + e_s[k] * fss_ess);
  }
  return out;
}

float3 shadePbr(const LightRig& rig, const PbrSurface& surface, float3 n, float3 p) {
  const PbrLobes lobes = pbrLobes(surface);
  const float3 v = viewVector(rig, p);
  const float nv = std::fabs(dot3(n, v));
  float3 c = rig.environment ? pbrEnvironment(lobes, rig, surface.occlusion, n, v, nv)
                             : pbrAmbient(lobes, rig.ambient, surface.occlusion, nv);
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
