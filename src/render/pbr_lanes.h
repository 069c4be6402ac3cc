// glTF's metallic-roughness shading of eight lanes at a time (render/pbr.h's BRDF, the
// material's maps, the environment light), for the shading kernels (shade_lanes.h): each lane
// does the same float operations as render/pbr.h's scalar code, so the same bits. Compiled per
// instruction set (kernels_<isa>.cpp).
#pragma once

#include "render/environment_lanes.h"
#include "render/light_lanes.h"
#include "render/pbr.h"
#include "render/shade.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

// The metallic-roughness BRDF of render/pbr.h, lane by lane with the same operations.

struct PbrLobes8 {
  Vec3x8 c_diff, f0;
  F32x8 roughness, a2;
};

// As pbrLobes.
TESSERA_LANES_INLINE PbrLobes8 pbrLobes8(const Vec3x8& base, F32x8 metallic, F32x8 roughness) {
  const F32x8 m = clampLanes(metallic, 0.0f, 1.0f);
  const F32x8 r = clampLanes(roughness, kMinRoughness, 1.0f);
  const F32x8 alpha = r * r;
  const F32x8 dielectric = splat(1.0f) - m;
  const F32x8 f0_dielectric = splat(kDielectricF0) * dielectric;
  return {{base.x * dielectric, base.y * dielectric, base.z * dielectric},
          {f0_dielectric + base.x * m, f0_dielectric + base.y * m, f0_dielectric + base.z * m},
          r,
          alpha * alpha};
}

// As schlickWeight.
TESSERA_LANES_INLINE F32x8 schlickWeight8(F32x8 x) {
  const F32x8 k = splat(1.0f) - x;
  const F32x8 k2 = k * k;
  return (k2 * k2) * k;
}

// As pbrResponse.
TESSERA_LANES_INLINE Vec3x8 pbrResponse8(const PbrLobes8& s, const Vec3x8& n, const Vec3x8& v,
                                         const Vec3x8& l, F32x8 nl, F32x8 nv) {
  const F32x8 zero = splat(0.0f), one = splat(1.0f);
  const F32x8 hx = l.x + v.x, hy = l.y + v.y, hz = l.z + v.z;
  const F32x8 h2 = (hx * hx + hy * hy) + hz * hz;
  const F32x8 inv_h = select(positive(h2), one / squareRoot(h2), zero);
  const Vec3x8 h{hx * inv_h, hy * inv_h, hz * inv_h};
  const F32x8 nh = dot8(n, h), vh = dot8(v, h);
  const F32x8 fw = schlickWeight8(vh);
  // ggxDistribution and smithVisibility.
  const F32x8 dd = (nh * nh) * (s.a2 - one) + one;
  const F32x8 d = select(positive(nh), s.a2 / ((splat(kPi) * dd) * dd), zero);
  const F32x8 one_minus_a2 = one - s.a2;
  const F32x8 gv = nl * squareRoot((nv * nv) * one_minus_a2 + s.a2);
  const F32x8 gl = nv * squareRoot((nl * nl) * one_minus_a2 + s.a2);
  const F32x8 spec = splat(kPi) * (d * (splat(0.5f) / (gv + gl)));
  const Vec3x8 f{s.f0.x + (one - s.f0.x) * fw, s.f0.y + (one - s.f0.y) * fw,
                 s.f0.z + (one - s.f0.z) * fw};
  return {(one - f.x) * s.c_diff.x + f.x * spec, (one - f.y) * s.c_diff.y + f.y * spec,
          (one - f.z) * s.c_diff.z + f.z * spec};
}

// As pbrAmbient.
TESSERA_LANES_INLINE Vec3x8 pbrAmbient8(const PbrLobes8& s, float3 ambient, F32x8 occlusion,
                                        F32x8 nv) {
  const F32x8 one = splat(1.0f);
  const F32x8 fw = schlickWeight8(nv);
  const F32x8 f90 = one - s.roughness;
  // std::max(f90, f0): f90 < f0 ? f0 : f90.
  auto fa = [&](F32x8 f0) { return f0 + (select(lessThan(f90, f0), f0, f90) - f0) * fw; };
  const Vec3x8 a{fa(s.f0.x), fa(s.f0.y), fa(s.f0.z)};
  return {(occlusion * splat(ambient.x)) * ((one - a.x) * s.c_diff.x + a.x),
          (occlusion * splat(ambient.y)) * ((one - a.y) * s.c_diff.y + a.y),
          (occlusion * splat(ambient.z)) * ((one - a.z) * s.c_diff.z + a.z)};
}

// As pbrEnvironment.
TESSERA_LANES_INLINE Vec3x8 pbrEnvironment8(const PbrLobes8& s, const LightRig& rig,
                                            F32x8 occlusion, const Vec3x8& n, const Vec3x8& v,
                                            F32x8 nv) {
  const F32x8 one = splat(1.0f), two_nv = splat(2.0f) * dot8(n, v);
  const Vec3x8 r{two_nv * n.x - v.x, two_nv * n.y - v.y, two_nv * n.z - v.z};
  // float3x3 * float3: the columns times the components, summed left to right.
  const float3x3& m = rig.world_to_environment;
  auto turn = [&m](const Vec3x8& d) -> Vec3x8 {
    return {(splat(m.col[0].x) * d.x + splat(m.col[1].x) * d.y) + splat(m.col[2].x) * d.z,
            (splat(m.col[0].y) * d.x + splat(m.col[1].y) * d.y) + splat(m.col[2].y) * d.z,
            (splat(m.col[0].z) * d.x + splat(m.col[1].z) * d.y) + splat(m.col[2].z) * d.z};
  };
  const Environment& environment = *rig.environment;
  const Vec3x8 e_d = environmentDiffuse8(environment, turn(n));
  const Vec3x8 e_s = environmentSpecular8(environment, turn(r), s.roughness);
  F32x8 ab_x, ab_y;
  splitSumBrdf8(nv, s.roughness, ab_x, ab_y);
  const F32x8 fw = schlickWeight8(nv);
  const F32x8 f90 = one - s.roughness;
  auto lobe = [&](F32x8 f0, F32x8 c_diff, F32x8 diffuse, F32x8 specular) {
    // std::max(f90, f0): f90 < f0 ? f0 : f90.
    const F32x8 ks = f0 + (blend(maskLess(f90, f0), f0, f90) - f0) * fw;
    const F32x8 fss_ess = ks * ab_x + ab_y;
    return occlusion * (diffuse * (c_diff * (one - fss_ess)) + specular * fss_ess);
  };
  return {lobe(s.f0.x, s.c_diff.x, e_d.x, e_s.x), lobe(s.f0.y, s.c_diff.y, e_d.y, e_s.y),
          lobe(s.f0.z, s.c_diff.z, e_d.z, e_s.z)};
}

// As viewVector.
TESSERA_LANES_INLINE Vec3x8 viewVector8(const LightRig& rig, const Vec3x8& p) {
  if (rig.eye_at_infinity)
    return {splat(rig.toward_eye.x), splat(rig.toward_eye.y), splat(rig.toward_eye.z)};
  const Vec3x8 d{splat(rig.eye.x) - p.x, splat(rig.eye.y) - p.y, splat(rig.eye.z) - p.z};
  const F32x8 len2 = (d.x * d.x + d.y * d.y) + d.z * d.z;
  const F32x8 inv = select(positive(len2), splat(1.0f) / squareRoot(len2), splat(0.0f));
  return {d.x * inv, d.y * inv, d.z * inv};
}

// As localAttenuation (lights.h).
TESSERA_LANES_INLINE F32x8 localAttenuation8(const ShadeLight& light, const Vec3x8& p, Vec3x8& u) {
  const Vec3x8 l{splat(light.position.x) - p.x, splat(light.position.y) - p.y,
                 splat(light.position.z) - p.z};
  const F32x8 d2 = (l.x * l.x + l.y * l.y) + l.z * l.z;
  const F32x8 inv_d = splat(1.0f) / squareRoot(d2);
  u = {l.x * inv_d, l.y * inv_d, l.z * inv_d};
  const F32x8 window = clamp01(splat(1.0f) - d2 * d2 * splat(light.inv_range4));
  const F32x8 cd = negate((splat(light.direction.x) * u.x + splat(light.direction.y) * u.y) +
                          splat(light.direction.z) * u.z);
  const F32x8 t = clamp01(cd * splat(light.spot_scale) + splat(light.spot_offset));
  return (window * (t * t)) / d2;
}

// As shadePbr: ambient, every light in order, then the emission; shadow maps are looked up for
// the lanes of `wanted` only (irradiance8).
TESSERA_LANES_INLINE Vec3x8 shadePbr8(const LightRig& rig, const PbrLobes8& s, F32x8 occlusion,
                                      const Vec3x8& emissive, const Vec3x8& n, const Vec3x8& p,
                                      I32x8 wanted) {
  const Vec3x8 v = viewVector8(rig, p);
  const F32x8 nv = absLanes(dot8(n, v));
  Vec3x8 c = rig.environment ? pbrEnvironment8(s, rig, occlusion, n, v, nv)
                             : pbrAmbient8(s, rig.ambient, occlusion, nv);
  for (const ShadeLight& light : rig.lights) {
    Vec3x8 l;
    F32x8 nl, f;
    if (light.type == LightType::kDirectional) {
      l = {splat(-light.direction.x), splat(-light.direction.y), splat(-light.direction.z)};
      nl = dot8(n, l);
      f = nl;
    } else {
      const F32x8 attenuation = localAttenuation8(light, p, l);
      nl = dot8(n, l);
      f = nl * attenuation;
    }
    const I32x8 lit = positive(nl) & positive(f);
    if (!any(lit)) continue;
    f = shadowed8(rig, light, lit & wanted, f, n, p);
    const Vec3x8 r = pbrResponse8(s, n, v, l, nl, nv);
    c = {select(lit, c.x + r.x * (splat(light.radiance.x) * f), c.x),
         select(lit, c.y + r.y * (splat(light.radiance.y) * f), c.y),
         select(lit, c.z + r.z * (splat(light.radiance.z) * f), c.z)};
  }
  return {c.x + emissive.x, c.y + emissive.y, c.z + emissive.z};
}

// One map of the material for the lanes of `mask`, lane by lane through texture_lane(l,
// Barycentrics, texture, sampler) (shade.h: sampleTexture); the other lanes hold `fill`.
template <typename TextureLane>
TESSERA_LANES_INLINE void sampleMap(const TextureSlot& slot, I32x8 mask, F32x8 b0, F32x8 b1,
                                    F32x8 b2, float4 fill, F32x8 out[4], TextureLane texture_lane) {
  alignas(32) float texel[4][8];
  for (int l = 0; l < 8; ++l) {
    const float4 t = lane(mask, l)
                         ? texture_lane(l, Barycentrics{lane(b0, l), lane(b1, l), lane(b2, l)},
                                        *slot.texture, slot.sampler)
                         : fill;
    texel[0][l] = t.x, texel[1][l] = t.y, texel[2][l] = t.z, texel[3][l] = t.w;
  }
  for (int c = 0; c < 4; ++c) out[c] = load<F32x8>(texel[c]);
}

// The shading normal of a PBR pixel: the interpolated normal n, perturbed by the material's
// normal map in the tangent frame (the tangent made orthogonal to n, the bitangent cross(n, t) *
// w, as glTF defines TANGENT): normalize(t x' + b y' + n z') with (x', y', z') = (2 texel - 1)
// scaled by normal_scale in x and y.
template <typename TextureLane>
TESSERA_LANES_INLINE Vec3x8 normalMapped(const ShadeTriangle& t, const ShadeExtras& e, I32x8 mask,
                                         F32x8 b0, F32x8 b1, F32x8 b2, const Vec3x8& n,
                                         TextureLane texture_lane) {
  const Material& m = *t.material;
  Vec3x8 tangent{splat(0.0f), splat(0.0f), splat(0.0f)};
  for (int k = 0; k < 3; ++k) {
    const F32x8 b = k == 0 ? b0 : (k == 1 ? b1 : b2);
    tangent = {tangent.x + splat(e.tangent[k].x) * b, tangent.y + splat(e.tangent[k].y) * b,
               tangent.z + splat(e.tangent[k].z) * b};
  }
  const F32x8 tn = dot8(n, tangent);
  tangent = normalize8({tangent.x - n.x * tn, tangent.y - n.y * tn, tangent.z - n.z * tn});
  const F32x8 w = splat(e.tangent[0].w < 0.0f ? -1.0f : 1.0f);
  const Vec3x8 bitangent{(n.y * tangent.z - n.z * tangent.y) * w,
                         (n.z * tangent.x - n.x * tangent.z) * w,
                         (n.x * tangent.y - n.y * tangent.x) * w};
  F32x8 texel[4];
  sampleMap(m.normal, mask, b0, b1, b2, float4{0.5f, 0.5f, 1.0f, 1.0f}, texel, texture_lane);
  const F32x8 one = splat(1.0f), two = splat(2.0f), scale = splat(m.normal_scale);
  const F32x8 x = (texel[0] * two - one) * scale, y = (texel[1] * two - one) * scale;
  const F32x8 z = texel[2] * two - one;
  return normalize8({(tangent.x * x + bitangent.x * y) + n.x * z,
                     (tangent.y * x + bitangent.y * y) + n.y * z,
                     (tangent.z * x + bitangent.z * y) + n.z * z});
}

// A PBR pixel's colour from its base colour c (factor x vertex colour x base colour texture):
// the material's metallic-roughness (G, B), occlusion (R) and emissive maps and factors, the
// normal map, then the BRDF under every light. `n` gets the shading normal.
template <typename TextureLane>
TESSERA_LANES_INLINE Vec3x8 shadePbrLanes(const ShadeTriangle& t, const ShadeExtras& e,
                                          const LightRig& lights, F32x8 b0, F32x8 b1, F32x8 b2,
                                          I32x8 mask, const Vec3x8& c, Vec3x8& n,
                                          TextureLane texture_lane) {
  const Material& m = *t.material;
  const bool maps = (t.pbr_flags & kPbrUv) != 0;
  n = normalize8(interpolate(e.normal, b0, b1, b2));
  if (maps && m.normal && (t.pbr_flags & kPbrTangents))
    n = normalMapped(t, e, mask, b0, b1, b2, n, texture_lane);
  F32x8 metallic = splat(m.metallic), roughness = splat(m.roughness), occlusion = splat(1.0f);
  F32x8 texel[4];
  if (maps && m.metallic_roughness) {
    sampleMap(m.metallic_roughness, mask, b0, b1, b2, float4{1, 1, 1, 1}, texel, texture_lane);
    roughness = roughness * texel[1];
    metallic = metallic * texel[2];
  }
  if (maps && m.occlusion) {
    // glTF: 1 + strength (R - 1).
    sampleMap(m.occlusion, mask, b0, b1, b2, float4{1, 1, 1, 1}, texel, texture_lane);
    occlusion = splat(1.0f) + splat(m.occlusion_strength) * (texel[0] - splat(1.0f));
  }
  Vec3x8 emissive{splat(m.emissive_factor.x), splat(m.emissive_factor.y),
                  splat(m.emissive_factor.z)};
  if (maps && m.emissive) {
    sampleMap(m.emissive, mask, b0, b1, b2, float4{1, 1, 1, 1}, texel, texture_lane);
    emissive = {emissive.x * texel[0], emissive.y * texel[1], emissive.z * texel[2]};
  }
  const Vec3x8 p = interpolate(e.world, b0, b1, b2);
  return shadePbr8(lights, pbrLobes8(c, metallic, roughness), occlusion, emissive, n, p, mask);
}

}  // namespace
}  // namespace tessera::render
