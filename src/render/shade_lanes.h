// Shading of eight lanes at a time, for the shading kernel (shade_kernel.h) and the resolve of
// multisampled pixels (fragment_queue.h, ray_queue.h); written once against eight-lane types
// (simd_lanes.h) and compiled per instruction set (kernels_<isa>.cpp). Each lane does exactly the
// float operations, in exactly the order, that shading one pixel takes, so every variant gives the
// same bits. Texture samples are taken eight lanes at a time (texture_lanes.h); nearest ones, and
// lanes outside its common case, lane by lane through the one sampleAlbedo.
#pragma once

#include <algorithm>
#include <cstddef>

#include <tessera/scene/color.h>

#include "render/environment_lanes.h"
#include "render/pbr.h"
#include "render/shade.h"
#include "render/simd_lanes.h"
#include "render/texture_lanes.h"
#include "render/tone_lanes.h"
#include "render/vec3_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

TESSERA_LANES_INLINE Vec3x8 interpolate(const float3 v[3], F32x8 b0, F32x8 b1, F32x8 b2) {
  return {splat(v[0].x) * b0 + splat(v[1].x) * b1 + splat(v[2].x) * b2,
          splat(v[0].y) * b0 + splat(v[1].y) * b1 + splat(v[2].y) * b2,
          splat(v[0].z) * b0 + splat(v[1].z) * b1 + splat(v[2].z) * b2};
}

// Vertex colours at barycentrics b1, b2 (b0 = 1 - b1 - b2, not read) as c0 + (c1 - c0) b1 +
// (c2 - c0) b2: a triangle whose corners share a colour (every flat-shaded one, and a Gouraud face
// of one normal under directional light) shades to exactly that colour, which shadePlainRow's
// solid groups take without the barycentrics.
TESSERA_LANES_INLINE Vec3x8 interpolateColor(const float3 c[3], F32x8 b1, F32x8 b2) {
  const float3 d1 = c[1] - c[0], d2 = c[2] - c[0];
  return {splat(c[0].x) + splat(d1.x) * b1 + splat(d2.x) * b2,
          splat(c[0].y) + splat(d1.y) * b1 + splat(d2.y) * b2,
          splat(c[0].z) + splat(d1.z) * b1 + splat(d2.z) * b2};
}

// As tessera::normalize: zero for a zero vector.
TESSERA_LANES_INLINE Vec3x8 normalize8(Vec3x8 v) {
  const F32x8 len = squareRoot(v.x * v.x + v.y * v.y + v.z * v.z);
  const F32x8 inv = splat(1.0f) / len;
  const I32x8 nonzero = positive(len);
  const F32x8 zero = splat(0.0f);
  return {select(nonzero, v.x * inv, zero), select(nonzero, v.y * inv, zero),
          select(nonzero, v.z * inv, zero)};
}

// As clamp(v, 0, 1) (std::clamp's comparisons: NaN stays NaN).
TESSERA_LANES_INLINE F32x8 clamp01(F32x8 v) {
  const F32x8 zero = splat(0.0f), one = splat(1.0f);
  return select(lessThan(v, zero), zero, select(lessThan(one, v), one, v));
}

// As render::localFactor (lights.h), lane by lane.
TESSERA_LANES_INLINE F32x8 localFactor8(const ShadeLight& light, const Vec3x8& n, const Vec3x8& p) {
  const Vec3x8 l{splat(light.position.x) - p.x, splat(light.position.y) - p.y,
                 splat(light.position.z) - p.z};
  const F32x8 d2 = (l.x * l.x + l.y * l.y) + l.z * l.z;
  const F32x8 inv_d = splat(1.0f) / squareRoot(d2);
  const Vec3x8 u{l.x * inv_d, l.y * inv_d, l.z * inv_d};
  const F32x8 cos_theta = (n.x * u.x + n.y * u.y) + n.z * u.z;
  const F32x8 window = clamp01(splat(1.0f) - d2 * d2 * splat(light.inv_range4));
  const F32x8 cd =
      splat(0.0f) - ((splat(light.direction.x) * u.x + splat(light.direction.y) * u.y) +
                     splat(light.direction.z) * u.z);
  const F32x8 t = clamp01(cd * splat(light.spot_scale) + splat(light.spot_offset));
  return cos_theta * ((window * (t * t)) / d2);
}

// f times the light's shadow-map visibility (ShadowMaps::visibility, scalar code compiled once:
// the same bits on every instruction set) in the lanes of `lit`; f where the light has no map.
// An unoccluded lane is multiplied by exactly 1. The maps are read lane by lane: callers leave
// out of `lit` the lanes whose colour is not kept.
TESSERA_LANES_INLINE F32x8 shadowed8(const LightRig& rig, const ShadeLight& light, I32x8 lit,
                                     F32x8 f, const Vec3x8& n, const Vec3x8& p) {
  if (!rig.shadows || light.shadow < 0 || !any(lit)) return f;
  alignas(32) float visible[8];
  for (int l = 0; l < 8; ++l)
    visible[l] = lane(lit, l) ? shadowVisibility(*rig.shadows, light.shadow,
                                                 {lane(p.x, l), lane(p.y, l), lane(p.z, l)},
                                                 {lane(n.x, l), lane(n.y, l), lane(n.z, l)})
                              : 1.0f;
  return f * load<F32x8>(visible);
}

// As render::irradiance: ambient plus every light, at world points p (read only when the rig has
// a point or spot light, or shadow maps), times the shadow maps' visibility, which is looked up
// for the lanes of `wanted` only (the others' colour is not kept).
TESSERA_LANES_INLINE Vec3x8 irradiance8(const LightRig& rig, const Vec3x8& n, const Vec3x8& p,
                                        I32x8 wanted) {
  Vec3x8 e{splat(rig.ambient.x), splat(rig.ambient.y), splat(rig.ambient.z)};
  const F32x8 zero = splat(0.0f);
  for (const ShadeLight& light : rig.lights) {
    F32x8 f;
    if (light.type == LightType::kDirectional)
      f = zero - (n.x * splat(light.direction.x) + n.y * splat(light.direction.y) +
                  n.z * splat(light.direction.z));
    else
      f = localFactor8(light, n, p);
    const I32x8 lit = positive(f);
    f = shadowed8(rig, light, lit & wanted, f, n, p);
    e.x = e.x + select(lit, splat(light.radiance.x) * f, zero);
    e.y = e.y + select(lit, splat(light.radiance.y) * f, zero);
    e.z = e.z + select(lit, splat(light.radiance.z) * f, zero);
  }
  return e;
}

// Eight encodeSrgb8s (tessera/scene/color.h), the same operations lane by lane.
TESSERA_LANES_INLINE I32x8 encodeSrgb8x8(F32x8 linear) {
  const F32x8 zero = splat(0.0f), one = splat(1.0f);
  // Clamped to [0, 1], NaN to 0: (x > 0 ? x : 0), then (< 1 ? : 1).
  const F32x8 c = lowerOf(upperOf(linear, zero), one);
  const I32x8 bits = bitsOf(c);
  // Lanes on the linear segment compute the curve too (from c's exponent, which may be below
  // -9 there: the index is clamped to the table) and take the line.
  const I32x8 e9 = shiftRight(bits, 23) - splat(int32_t{127 - 9});
  const I32x8 index = maximum(e9, splat(int32_t{0}));
  const F32x8 x = fromBits((bits & splat(int32_t{0x7fffff})) | splat(int32_t{0x3f800000})) - one;
  const float* k = SrgbEncode::kPoly;
  const F32x8 p =
      (((splat(k[4]) * x + splat(k[3])) * x + splat(k[2])) * x + splat(k[1])) * x + splat(k[0]);
  F32x8 curve = lookup16(SrgbEncode::kScale, index) * p - splat(SrgbEncode::kOffset);
  curve = lowerOf(curve, splat(255.0f));
  const F32x8 code = select(lessThan(splat(SrgbEncode::kLinearEnd), c), curve,
                            c * splat(SrgbEncode::kLinearFactor));
  return truncate(code + splat(0.5f));
}

#if defined(TESSERA_LANES16)
// encodeSrgb8x8 for sixteen lanes, the same operations.
TESSERA_LANES_INLINE I32x16 encodeSrgb8x16(F32x16 linear) {
  const F32x16 zero = splat16(0.0f), one = splat16(1.0f);
  const F32x16 c = lowerOf16(upperOf16(linear, zero), one);
  const I32x16 bits = reinterpret_cast<I32x16>(c);
  const I32x16 e9 = (bits >> 23) - (127 - 9);
  const I32x16 index = e9 > 0 ? e9 : 0;
  const F32x16 x = reinterpret_cast<F32x16>((bits & 0x7fffff) | 0x3f800000) - one;
  const float* k = SrgbEncode::kPoly;
  const F32x16 p =
      (((splat16(k[4]) * x + splat16(k[3])) * x + splat16(k[2])) * x + splat16(k[1])) * x +
      splat16(k[0]);
  F32x16 curve = lookup16x16(SrgbEncode::kScale, index) * p - splat16(SrgbEncode::kOffset);
  curve = lowerOf16(curve, splat16(255.0f));
  const F32x16 code = SrgbEncode::kLinearEnd < c ? curve : c * splat16(SrgbEncode::kLinearFactor);
  return truncate16(code + splat16(0.5f));
}
#endif

// The albedo of the lanes of `mask` at barycentrics b0, b1, b2 through sampleTexture8; `footprint`
// gives the barycentrics at the next pixel centres right and down (false: it cannot, and trilinear
// filtering is left to the caller). False, with nothing computed, when the caller must sample lane
// by lane.
template <typename Footprint>
TESSERA_LANES_INLINE bool sampleAlbedo8(const ShadeTriangle& t, const ShadeExtras& e, I32x8 mask,
                                        F32x8 b0, F32x8 b1, F32x8 b2, Footprint footprint,
                                        Vec3x8& albedo) {
  const Material& m = *t.material;
  const Texture& texture = *m.albedo;
  if (!texture8Applies(texture, m.sampler)) return false;
  // The corners in the sampler's set.
  const BroadcastFields corners{&uvSet(e, m.sampler)->x};
  const Uv8 uv = uvAt8(corners, b0, b1, b2);
  Uv8 right = uv, down = uv;
  if (needsLod(texture, m.sampler)) {
    Vec3x8 br, bd;
    if (!footprint(br, bd)) return false;
    right = uvAt8(corners, br.x, br.y, br.z);
    down = uvAt8(corners, bd.x, bd.y, bd.z);
  }
  F32x8 out[4];
  if (!sampleTexture8(texture, m.sampler, mask, uv, right, down, 3, out)) return false;
  albedo = {out[0], out[1], out[2]};
  return true;
}

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

// Shades the lanes of `mask` from triangle t at barycentrics b0, b1, b2, into `color` and, when
// asked, `normal`; the other lanes keep what they hold. When the eight-lane texture filter does not
// take the lanes, they get their albedo from albedo_lane(l, Barycentrics) one at a time;
// footprint(right, down) gives the barycentrics at the next pixel centres right and down for the
// eight-lane filter's level of detail (false: it has none, and the lanes go one at a time). PBR
// maps come from texture_lane(l, Barycentrics, texture, sampler).
template <typename AlbedoLane, typename Footprint, typename TextureLane>
TESSERA_LANES_INLINE void shadeLanesAt(const ShadeTriangle& t, const ShadeExtras& e,
                                       const LightRig& lights, bool want_normals, F32x8 b0,
                                       F32x8 b1, F32x8 b2, I32x8 mask, Vec3x8& color,
                                       Vec3x8& normal, AlbedoLane albedo_lane, Footprint footprint,
                                       TextureLane texture_lane) {
  Vec3x8 c = interpolateColor(t.color, b1, b2);
  Vec3x8 albedo;
  if (t.has_uv && sampleAlbedo8(t, e, mask, b0, b1, b2, footprint, albedo)) {
    c = {c.x * albedo.x, c.y * albedo.y, c.z * albedo.z};
  } else if (t.has_uv) {
    for (int l = 0; l < 8; ++l) {
      if (!lane(mask, l)) continue;
      const float3 a = albedo_lane(l, Barycentrics{lane(b0, l), lane(b1, l), lane(b2, l)});
      setLane(c.x, l, lane(c.x, l) * a.x);
      setLane(c.y, l, lane(c.y, l) * a.y);
      setLane(c.z, l, lane(c.z, l) * a.z);
    }
  }
  if (t.shading == Shading::kPbr) {
    Vec3x8 n;
    c = shadePbrLanes(t, e, lights, b0, b1, b2, mask, c, n, texture_lane);
    if (want_normals)
      normal = {select(mask, n.x, normal.x), select(mask, n.y, normal.y),
                select(mask, n.z, normal.z)};
  } else if (t.shading == Shading::kPhong || (want_normals && t.shading != Shading::kFlat)) {
    const Vec3x8 n = normalize8(interpolate(e.normal, b0, b1, b2));
    if (t.shading == Shading::kPhong) {
      const Vec3x8 p = lights.local || lights.shadows ? interpolate(e.world, b0, b1, b2) : Vec3x8{};
      const Vec3x8 e = irradiance8(lights, n, p, mask);
      c = {c.x * e.x, c.y * e.y, c.z * e.z};
    }
    if (want_normals)
      normal = {select(mask, n.x, normal.x), select(mask, n.y, normal.y),
                select(mask, n.z, normal.z)};
  } else if (want_normals) {
    normal = {select(mask, splat(e.normal[0].x), normal.x),
              select(mask, splat(e.normal[0].y), normal.y),
              select(mask, splat(e.normal[0].z), normal.z)};
  }
  if (lights.tone.active()) toneMap8(lights.tone, c.x, c.y, c.z);
  color = {select(mask, c.x, color.x), select(mask, c.y, color.y), select(mask, c.z, color.z)};
}

// Triangle t's barycentrics (b.x, b.y, b.z) at pixel centres (x, y), exactly as barycentricsAt.
TESSERA_LANES_INLINE void barycentrics8(const ShadeTriangle& t, F32x8 x, float y, Vec3x8& b) {
  const F32x8 dx = x - splat(t.x0);
  const float dy = y - t.y0;
  const F32x8 inv_s = splat(1.0f) / (splat(t.inv_w0) + splat(t.sdx) * dx + splat(t.sdy * dy));
  b.y = (splat(t.p1dx) * dx + splat(t.p1dy * dy)) * inv_s;
  b.z = (splat(t.p2dx) * dx + splat(t.p2dy * dy)) * inv_s;
  b.x = splat(1.0f) - b.y - b.z;
}

// Whether the lights of a Phong pixel can wait for finishPhong8: no world positions (no point or
// spot light, no shadow maps) and no normal AOV.
TESSERA_LANES_INLINE bool phongDeferrable(const LightRig& lights, bool want_normals) {
  return !want_normals && !lights.local && !lights.shadows;
}

// An untextured Phong triangle t's work at pixel centres (px, py) up to the lights (shadeLanes'
// operations): its interpolated vertex colour and interpolated (not yet unit) normal.
TESSERA_LANES_INLINE void phongInputs(const ShadeTriangle& t, const ShadeExtras& e, F32x8 px,
                                      float py, Vec3x8& color, Vec3x8& normal) {
  Vec3x8 b;
  barycentrics8(t, px, py, b);
  color = interpolateColor(t.color, b.y, b.z);
  normal = interpolate(e.normal, b.x, b.y, b.z);
}

// The rest of a Phong pixel's shading (phongDeferrable): the normal made unit, the lights, the
// tone curve; shadeLanes' and shadeLitMixed's operations, so the same bits.
TESSERA_LANES_INLINE Vec3x8 finishPhong8(const LightRig& lights, const Vec3x8& color,
                                         const Vec3x8& normal) {
  const Vec3x8 e = irradiance8(lights, normalize8(normal), Vec3x8{}, splat(int32_t{0}));
  Vec3x8 c{color.x * e.x, color.y * e.y, color.z * e.z};
  if (lights.tone.active()) toneMap8(lights.tone, c.x, c.y, c.z);
  return c;
}

#if defined(TESSERA_LANES16)
// finishPhong8 for two groups side by side in sixteen lanes (AVX-512), the same operations per
// lane, without a tone curve: on this host a division or square root of sixteen lanes takes
// about as long as one of eight. c and n: the colours' and normals' x, y, z.
TESSERA_LANES_INLINE void finishPhong16(const LightRig& lights, F32x16 c[3], const F32x16 n[3]) {
  const F32x16 zero = splat16(0.0f);
  const F32x16 len = reinterpret_cast<F32x16>(_mm512_maskz_sqrt_ps(
      0xffff, reinterpret_cast<__m512>((n[0] * n[0] + n[1] * n[1]) + n[2] * n[2])));
  const F32x16 inv = splat16(1.0f) / len;
  const auto nonzero = len > zero;
  const F32x16 u[3] = {nonzero ? n[0] * inv : zero, nonzero ? n[1] * inv : zero,
                       nonzero ? n[2] * inv : zero};
  F32x16 e[3] = {splat16(lights.ambient.x), splat16(lights.ambient.y), splat16(lights.ambient.z)};
  for (const ShadeLight& light : lights.lights) {
    const F32x16 f = zero - (u[0] * splat16(light.direction.x) + u[1] * splat16(light.direction.y) +
                             u[2] * splat16(light.direction.z));
    const auto lit = f > zero;
    e[0] = e[0] + (lit ? splat16(light.radiance.x) * f : zero);
    e[1] = e[1] + (lit ? splat16(light.radiance.y) * f : zero);
    e[2] = e[2] + (lit ? splat16(light.radiance.z) * f : zero);
  }
  for (int k = 0; k < 3; ++k) c[k] = c[k] * e[k];
}
#endif

// The colour of an untextured flat, Gouraud or unlit triangle (its interpolated vertex colours)
// at pixel centres (px, py): shadeLanes' operations for such a triangle without a tone curve.
TESSERA_LANES_INLINE Vec3x8 shadePlainLanes(const ShadeTriangle& t, F32x8 px, float py) {
  Vec3x8 b;
  barycentrics8(t, px, py, b);
  return interpolateColor(t.color, b.y, b.z);
}

// Shades the lanes of `mask` (pixel centres px, py) from triangle t, into `color` and, when
// asked, `normal`; the other lanes keep what they hold.
TESSERA_LANES_INLINE void shadeLanes(const ShadeTriangle& t, const ShadeExtras& e,
                                     const LightRig& lights, bool want_normals, F32x8 px, float py,
                                     I32x8 mask, Vec3x8& color, Vec3x8& normal) {
  // At (px, py) and, for a level of detail, at the next pixel centres right and down.
  auto barycentrics = [&](F32x8 x, float y, Vec3x8& b) { barycentrics8(t, x, y, b); };
  Vec3x8 b;
  barycentrics(px, py, b);
  shadeLanesAt(
      t, e, lights, want_normals, b.x, b.y, b.z, mask, color, normal,
      [&](int l, const Barycentrics& at) { return sampleAlbedo(t, e, at, lane(px, l), py); },
      [&](Vec3x8& right, Vec3x8& down) {
        barycentrics(px + splat(1.0f), py, right);
        barycentrics(px, py + 1.0f, down);
        return true;
      },
      [&](int l, const Barycentrics& at, const Texture& texture, const Sampler& sampler) {
        return sampleTexture(texture, sampler, t, e, at, lane(px, l), py);
      });
}

// Stores eight pixels' colours at column tx of a row's linear colours and, when asked, their
// normals at pixel i of the tile.
TESSERA_LANES_INLINE void storeShadedGroup(const Vec3x8& color, const Vec3x8& normal,
                                           bool want_normals, int tx, int i,
                                           float linear[3][kTileSize], ShadedTile& out) {
  store(linear[0] + tx, color.x);
  store(linear[1] + tx, color.y);
  store(linear[2] + tx, color.z);
  if (want_normals) {
    store(out.normal_x + i, normal.x);
    store(out.normal_y + i, normal.y);
    store(out.normal_z + i, normal.z);
  }
}

// A group of eight pixels as shadePlainRow leaves it for the encode: kNoSolid, encode its linear
// colours; kSolidEmpty, no pixel covered; else the sRGB of every covered pixel (alpha 0xff, so
// never either of the two).
constexpr uint32_t kNoSolid = 0, kSolidEmpty = 1;

// Eight pixels' linear colours to sRGB, packed with an alpha of 0xff.
TESSERA_LANES_INLINE I32x8 encodeRgba8x8(F32x8 r, F32x8 g, F32x8 b) {
  return encodeSrgb8x8(r) | shiftLeft(encodeSrgb8x8(g), 8) | shiftLeft(encodeSrgb8x8(b), 16) |
         splat(static_cast<int32_t>(0xff000000u));
}

// The encoded colour of every pixel of a triangle whose corners share a colour (interpolateColor
// gives exactly that colour), by encodeShadedRow's operations; kNoSolid for any other triangle.
TESSERA_LANES_INLINE uint32_t solidRgba(const ShadeTriangle& t) {
  if (!t.solid) return kNoSolid;
  const float3& c = t.color[0];
  return static_cast<uint32_t>(lane(encodeRgba8x8(splat(c.x), splat(c.y), splat(c.z)), 0));
}

// Encodes row ty of the tile's linear colours to sRGB into out.rgba (or the frame's row at
// out.direct), whole; the background where no triangle is. `solid` (or null) gives
// shadePlainRow's groups of one solid triangle, which take their colour from it.
TESSERA_LANES_INLINE void encodeShadedRow(const TileVisibility& tile, int ty,
                                          const float linear[3][kTileSize], const uint32_t solid[],
                                          uint32_t background, ShadedTile& out) {
  uint32_t* const row = out.direct ? out.direct + static_cast<size_t>(ty) * out.direct_stride
                                   : out.rgba + ty * kTileSize;
#if defined(TESSERA_LANES16)
  const I32x16 fill = splat16(static_cast<int32_t>(background));  // the encode's width
  // Sixteen pixels a step (the rows are kTileSize wide, a multiple of 16).
  for (int tx = 0; tx < tile.width; tx += 16) {
    const int i = ty * kTileSize + tx;
    const I32x16 covered = load<I32x16>(tile.key + i) != static_cast<int32_t>(kEmptyKey);
    if (!_mm512_test_epi32_mask(reinterpret_cast<__m512i>(covered),
                                reinterpret_cast<__m512i>(covered))) {
      store(row + tx, fill);
      continue;
    }
    I32x16 rgba;
    if (solid && solid[tx / 8] != kNoSolid && solid[tx / 8 + 1] != kNoSolid) {
      rgba = reinterpret_cast<I32x16>(
          _mm512_mask_blend_epi32(0xff00, _mm512_set1_epi32(static_cast<int>(solid[tx / 8])),
                                  _mm512_set1_epi32(static_cast<int>(solid[tx / 8 + 1]))));
    } else {
      rgba = encodeSrgb8x16(load<F32x16>(linear[0] + tx)) |
             encodeSrgb8x16(load<F32x16>(linear[1] + tx)) << 8 |
             encodeSrgb8x16(load<F32x16>(linear[2] + tx)) << 16 | static_cast<int32_t>(0xff000000u);
    }
    store(row + tx, covered ? rgba : fill);
  }
#else
  const I32x8 empty = splat(static_cast<int32_t>(kEmptyKey));
  const I32x8 fill = splat(static_cast<int32_t>(background));
  for (int tx = 0; tx < tile.width; tx += 8) {
    const int i = ty * kTileSize + tx;
    const I32x8 covered = ~equal(load<I32x8>(tile.key + i), empty);
    if (!any(covered)) {
      store(row + tx, fill);
      continue;
    }
    const I32x8 rgba = solid && solid[tx / 8] != kNoSolid
                           ? splat(static_cast<int32_t>(solid[tx / 8]))
                           : encodeRgba8x8(load<F32x8>(linear[0] + tx), load<F32x8>(linear[1] + tx),
                                           load<F32x8>(linear[2] + tx));
    store(row + tx, select(covered, rgba, fill));
  }
#endif
}

}  // namespace
}  // namespace tessera::render
