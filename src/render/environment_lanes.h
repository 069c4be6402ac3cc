// The environment light (--hdri) read eight lanes at a time, for the shading code (shade_lanes.h):
// Environment::diffuse, Environment::specular and splitSumBrdf (tessera/scene/environment.h) with
// the same float operations per lane as those scalar functions, so every instruction set gives the
// bits the scalar shading of one pixel gives. The texels are gathered lane by lane; the arithmetic
// around them (the direction's image coordinates, the bilinear and level weights, the spherical
// harmonics) runs on all eight at once.
#pragma once

#include <tessera/scene/environment.h>

#include "render/simd_lanes.h"
#include "render/vec3_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

// As std::clamp(v, lo, hi), through the compares that are one instruction on SSE2 too.
TESSERA_LANES_INLINE F32x8 clampFast8(F32x8 v, float lo, float hi) {
  return blend(maskLess(v, splat(lo)), splat(lo), blend(maskLess(splat(hi), v), splat(hi), v));
}

// As atan2Series.
TESSERA_LANES_INLINE F32x8 atan2Series8(F32x8 y, F32x8 x) {
  const F32x8 zero = splat(0.0f);
  const F32x8 ax = absLanes(x), ay = absLanes(y);
  const I32x8 steep = maskLess(ax, ay);
  const F32x8 big = blend(steep, ay, ax), small = blend(steep, ax, ay);
  const F32x8 a = blend(maskLess(zero, big), small / big, zero);
  const F32x8 s = a * a;
  F32x8 p = splat(kAtanSeries[7]);
  for (int i = 6; i >= 0; --i) p = p * s + splat(kAtanSeries[i]);
  F32x8 r = p * a;
  r = blend(steep, splat(0.5f * kPi) - r, r);
  r = blend(maskLess(x, zero), splat(kPi) - r, r);
  return blend(maskLess(y, zero), negate(r), r);
}

// As sampleEquirect, for the lanes of `finite` (the others are given any direction and give zero).
TESSERA_LANES_INLINE Vec3x8 sampleEquirect8(const EnvironmentImage& image, const Vec3x8& d,
                                            I32x8 finite) {
  const F32x8 zero = splat(0.0f), one = splat(1.0f);
  // equirectUv.
  F32x8 u = atan2Series8(d.x, negate(d.z)) / splat(2.0f * kPi);
  u = blend(maskLess(u, zero), u + one, u);
  const F32x8 y = clampFast8(d.y, -1.0f, 1.0f);
  const F32x8 v = atan2Series8(squareRoot((one - y) * (one + y)), y) / splat(kPi);
  // A lane that is not finite reads texel (0, 0) and gives zero.
  const F32x8 fx = blend(finite, u, zero) * splat(static_cast<float>(image.width)) - splat(0.5f);
  const F32x8 fy =
      clampFast8(blend(finite, v, zero) * splat(static_cast<float>(image.height)) - splat(0.5f),
                 0.0f, static_cast<float>(image.height - 1));
  const F32x8 x_floor = floorLanes(fx), y_floor = floorLanes(fy);
  const F32x8 tx = fx - x_floor, ty = fy - y_floor;
  // u in [0, 1] puts x_floor in [-1, width - 1]: the scalar code's modulo is one add here.
  const I32x8 izero = splat(int32_t{0}), width = splat(int32_t{image.width});
  const I32x8 xi = truncate(x_floor);
  const I32x8 x0 = blend(lessThan(xi, izero), xi + width, xi);
  const I32x8 next = x0 + splat(int32_t{1});
  const I32x8 x1 = blend(lessThan(next, width), next, izero);
  const I32x8 y0 = truncate(y_floor);
  const I32x8 y1 = minimum(y0 + splat(int32_t{1}), splat(int32_t{image.height - 1}));
  const float* texels = &image.texels.front().x;
  const I32x8 three = splat(int32_t{3});
  const I32x8 row0 = y0 * width, row1 = y1 * width;
  const I32x8 corner[4] = {(row0 + x0) * three, (row0 + x1) * three, (row1 + x0) * three,
                           (row1 + x1) * three};
  const F32x8 wx0 = one - tx, wy0 = one - ty;
  F32x8 out[3];
  for (int c = 0; c < 3; ++c) {
    const I32x8 channel = splat(int32_t{c});
    const F32x8 top =
        gather(texels, corner[0] + channel) * wx0 + gather(texels, corner[1] + channel) * tx;
    const F32x8 bottom =
        gather(texels, corner[2] + channel) * wx0 + gather(texels, corner[3] + channel) * tx;
    out[c] = blend(finite, top * wy0 + bottom * ty, zero);
  }
  return {out[0], out[1], out[2]};
}

// The lanes whose three components are finite (x - x is NaN for a NaN or an infinity).
TESSERA_LANES_INLINE I32x8 finiteLanes(const Vec3x8& d) {
  const F32x8 zero = splat(0.0f);
  return maskEqual(d.x - d.x, zero) & maskEqual(d.y - d.y, zero) & maskEqual(d.z - d.z, zero);
}

// As Environment::diffuse.
TESSERA_LANES_INLINE Vec3x8 environmentDiffuse8(const Environment& environment, const Vec3x8& n) {
  const std::array<float3, 9>& sh = environment.irradianceSh();
  const F32x8 b1 = splat(0.488603f), b2 = splat(1.092548f);
  const F32x8 basis[9] = {splat(0.282095f),
                          b1 * n.y,
                          b1 * n.z,
                          b1 * n.x,
                          b2 * n.x * n.y,
                          b2 * n.y * n.z,
                          splat(0.315392f) * (splat(3.0f) * n.z * n.z - splat(1.0f)),
                          b2 * n.x * n.z,
                          splat(0.546274f) * (n.x * n.x - n.y * n.y)};
  const F32x8 zero = splat(0.0f);
  Vec3x8 sum{zero, zero, zero};
  for (int k = 0; k < 9; ++k) {
    sum.x = sum.x + splat(sh[static_cast<size_t>(k)].x) * basis[k];
    sum.y = sum.y + splat(sh[static_cast<size_t>(k)].y) * basis[k];
    sum.z = sum.z + splat(sh[static_cast<size_t>(k)].z) * basis[k];
  }
  // std::max(sum, 0): NaN stays NaN.
  return {blend(maskLess(sum.x, zero), zero, sum.x), blend(maskLess(sum.y, zero), zero, sum.y),
          blend(maskLess(sum.z, zero), zero, sum.z)};
}

// std::fmin(std::fmax(x, 0), 1): a NaN goes to 0.
TESSERA_LANES_INLINE F32x8 unitFmax8(F32x8 x) {
  const F32x8 zero = splat(0.0f), one = splat(1.0f);
  const F32x8 m = blend(maskLess(zero, x), x, zero);
  return blend(maskLess(m, one), m, one);
}

// As Environment::specular: each pair of neighbouring levels that some lane's roughness falls
// between is read for all lanes and kept for those.
TESSERA_LANES_INLINE Vec3x8 environmentSpecular8(const Environment& environment, const Vec3x8& r,
                                                 F32x8 roughness) {
  constexpr int kLevels = Environment::kSpecularLevels;
  const F32x8 lod = unitFmax8(roughness) * splat(static_cast<float>(kLevels - 1));
  const I32x8 lower = minimum(truncate(lod), splat(int32_t{kLevels - 2}));
  const F32x8 t = lod - toFloat(lower), one_minus_t = splat(1.0f) - t;
  const I32x8 finite = finiteLanes(r);
  const F32x8 zero = splat(0.0f);
  Vec3x8 out{zero, zero, zero};
  for (int level = 0; level < kLevels - 1; ++level) {
    const I32x8 here = maskEqual(lower, splat(int32_t{level}));
    if (!any(here)) continue;
    const Vec3x8 a = sampleEquirect8(environment.specularLevel(level), r, finite);
    const Vec3x8 b = sampleEquirect8(environment.specularLevel(level + 1), r, finite);
    out = {blend(here, a.x * one_minus_t + b.x * t, out.x),
           blend(here, a.y * one_minus_t + b.y * t, out.y),
           blend(here, a.z * one_minus_t + b.z * t, out.z)};
  }
  return out;
}

// As splitSumBrdf: x in a, y in b.
TESSERA_LANES_INLINE void splitSumBrdf8(F32x8 n_dot_v, F32x8 roughness, F32x8& a, F32x8& b) {
  constexpr int kSize = kSplitSumTableSize;
  const float* table = &splitSumTable()->x;
  const F32x8 fx = unitFmax8(n_dot_v) * splat(static_cast<float>(kSize - 1));
  const F32x8 fy = unitFmax8(roughness) * splat(static_cast<float>(kSize - 1));
  const I32x8 last = splat(int32_t{kSize - 2});
  const I32x8 x0 = minimum(truncate(fx), last), y0 = minimum(truncate(fy), last);
  const F32x8 tx = fx - toFloat(x0), ty = fy - toFloat(y0);
  const F32x8 one = splat(1.0f);
  const F32x8 wx0 = one - tx, wy0 = one - ty;
  const I32x8 two = splat(int32_t{2});
  const I32x8 i00 = (y0 * splat(int32_t{kSize}) + x0) * two;
  const I32x8 i01 = i00 + two, i10 = i00 + splat(int32_t{2 * kSize}), i11 = i10 + two;
  F32x8 out[2];
  for (int c = 0; c < 2; ++c) {
    const I32x8 channel = splat(int32_t{c});
    const F32x8 top = gather(table, i00 + channel) * wx0 + gather(table, i01 + channel) * tx;
    const F32x8 bottom = gather(table, i10 + channel) * wx0 + gather(table, i11 + channel) * tx;
    out[c] = top * wy0 + bottom * ty;
  }
  a = out[0];
  b = out[1];
}

}  // namespace
}  // namespace tessera::render
