// Eight lanes' interpolation and lights, for the shading kernels (shade_lanes.h, pbr_lanes.h):
// the interpolated attributes, the unit normal and Lambert's irradiance from the frame's LightRig,
// with the same float operations in the same order as lights.h's scalar code, so the same bits.
// Compiled per instruction set (kernels_<isa>.cpp).
#pragma once

#include "render/shade.h"
#include "render/simd_lanes.h"
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

}  // namespace
}  // namespace tessera::render
