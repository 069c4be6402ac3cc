// Eight rays at a time for the nonlinear projections' tile stage (ray_kernel.h) and their
// multisampled resolve (ray_queue.h): edge values, coverage and barycentrics of rays against a
// triangle's edge planes (ray_setup.h), and the shading of a ray group. Written once against
// eight-lane types and compiled per instruction set with the same operations per lane, so every
// variant gives the same bits.
#pragma once

#include <vector>

#include <tessera/render/projection.h>
#include <tessera/scene/scene.h>

#include "render/bin.h"
#include "render/mixed_lanes.h"
#include "render/ray_setup.h"
#include "render/shade_lanes.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

struct Ray8 {
  F32x8 x, y, z;
};

TESSERA_LANES_INLINE Ray8 loadRays(const RayLayer& layer, size_t at) {
  return {load<F32x8>(layer.x.data() + at), load<F32x8>(layer.y.data() + at),
          load<F32x8>(layer.z.data() + at)};
}

// E_k of eight rays, as dotRay.
TESSERA_LANES_INLINE F32x8 edgeValue(const RayTriangle& t, int k, const Ray8& d) {
  return (d.x * splat(t.n[k][0]) + d.y * splat(t.n[k][1])) + d.z * splat(t.n[k][2]);
}

TESSERA_LANES_INLINE I32x8 lessOrEqualF(F32x8 a, F32x8 b) {
  return lessThan(a, b) | equal(a, b);
}

// The barycentrics of eight rays' hits, as rayBarycentrics.
TESSERA_LANES_INLINE void rayBarycentrics8(const RayTriangle& t, const Ray8& d, F32x8& b0,
                                           F32x8& b1, F32x8& b2) {
  const F32x8 e0 = edgeValue(t, 0, d), e1 = edgeValue(t, 1, d), e2 = edgeValue(t, 2, d);
  const F32x8 inv_s = splat(1.0f) / ((e0 + e1) + e2);
  b1 = e1 * inv_s;
  b2 = e2 * inv_s;
  b0 = splat(1.0f) - b1 - b2;
}

float3 rayAt(const RayLayer& layer, size_t at) {
  return {layer.x[at], layer.y[at], layer.z[at]};
}

// What shading a tile reads of the frame's rays.
struct RayShading {
  const LightRig& lights;
  const std::vector<TriangleChunk>& chunks;
  const RayTable& rays;
  int width, height;

  // Shades the lanes of `mask` from triangle `key` at the rays d (pixels x .. x + 7 of row y);
  // lanes the eight-lane texture filter does not take find their level of detail from the centre
  // rays of the next pixels right and down (or left and up at the image's edge).
  TESSERA_LANES_INLINE void shade(uint32_t key, const Ray8& d, int x, int y, I32x8 mask,
                                  bool want_normals, Vec3x8& color, Vec3x8& normal) const {
    const TriangleChunk& chunk = chunks[keyChunk(key)];
    const ShadeTriangle& t = chunk.shade[keyLocal(key)];
    const ShadeExtras& e = chunk.extras[keyLocal(key)];
    const RayTriangle& r = chunk.ray[keyLocal(key)];
    F32x8 b0, b1, b2;
    rayBarycentrics8(r, d, b0, b1, b2);
    // The barycentrics at the centre rays of the next pixels right and down of pixel x + l (or
    // left and up at the image's edge: a one-pixel-wide image has no neighbour, the pixel itself).
    auto neighbours = [&](int l, Barycentrics& br, Barycentrics& bd) {
      const int px = x + l;
      const int right = px + 1 < width ? px + 1 : std::max(px - 1, 0);
      const int down = y + 1 < height ? y + 1 : std::max(y - 1, 0);
      const size_t w = static_cast<size_t>(width);
      rayBarycentrics(r, rayAt(rays.centre(), static_cast<size_t>(y) * w + right), br.b0, br.b1,
                      br.b2);
      rayBarycentrics(r, rayAt(rays.centre(), static_cast<size_t>(down) * w + px), bd.b0, bd.b1,
                      bd.b2);
    };
    shadeLanesAt(
        t, e, lights, want_normals, b0, b1, b2, mask, color, normal,
        [&](int l, const Barycentrics& b) {
          Barycentrics br, bd;
          neighbours(l, br, bd);
          return sampleAlbedo(t, e, b, br, bd);
        },
        [](Vec3x8&, Vec3x8&) { return false; },
        [&](int l, const Barycentrics& b, const Texture& texture, const Sampler& sampler) {
          Barycentrics br, bd;
          neighbours(l, br, bd);
          return sampleTexture(texture, sampler, e, b, br, bd);
        });
  }
};

// Each chunk's first shading, extra and ray records, for laneRecords.
struct RayRecords {
  const ShadeTriangle* shade[kMaxChunks];
  const ShadeExtras* extras[kMaxChunks];
  const RayTriangle* ray[kMaxChunks];

  RayRecords(const std::vector<TriangleChunk>& chunks, size_t chunk_count) {
    for (size_t c = 0; c < chunk_count; ++c) {
      shade[c] = chunks[c].shade.data();
      extras[c] = chunks[c].extras.data();
      ray[c] = chunks[c].ray.data();
    }
  }
};

// Whether a pixel of triangle t is its interpolated vertex colours alone (untextured, lit per
// vertex or unlit).
TESSERA_LANES_INLINE bool rayPlain(const ShadeTriangle& t) {
  return !t.has_uv && t.shading != Shading::kPhong && t.shading != Shading::kPbr;
}

// Whether eight rays of several triangles, triangle t among them, may take shadeRaysOnce.
TESSERA_LANES_INLINE bool rayBatchable(const ShadeTriangle& t) {
  return rayPlain(t) || texturedPlain(t) || litPlain(t);
}

// The triangles' edge values at rays d, as edgeValue with each lane's own normals (n: corners9's
// layout of RayTriangle::n).
TESSERA_LANES_INLINE void edgeValues(const F32x8 n[9], const Ray8& d, F32x8 e[3]) {
  for (int k = 0; k < 3; ++k) e[k] = (d.x * n[3 * k] + d.y * n[3 * k + 1]) + d.z * n[3 * k + 2];
}

// The lanes whose ray d passes through their triangle (n: edge normals as edgeValues takes them;
// owner[k]: all ones where the triangle's edge k owns rays exactly on it): E_k > 0, or E_k == 0
// on an owned edge, for every k, and a positive sum (ray_setup.h's coverage rule, the Vulkan
// backend's rayCovers).
TESSERA_LANES_INLINE I32x8 raysCover(const F32x8 n[9], const I32x8 owner[3], const Ray8& d) {
  const F32x8 zero = splat(0.0f);
  F32x8 e[3];
  edgeValues(n, d, e);
  I32x8 covered = lessThan(zero, (e[0] + e[1]) + e[2]);
  for (int k = 0; k < 3; ++k)
    covered = covered & (lessThan(zero, e[k]) | (equal(e[k], zero) & owner[k]));
  return covered;
}

// The edge normals of the lanes' triangles (laneRecords' rays), in corners9's layout.
TESSERA_LANES_INLINE void rayNormals(const RayTriangle* const rays[8], F32x8 n[9]) {
  const float* at[8];
  for (int l = 0; l < 8; ++l) at[l] = &rays[l]->n[0][0];
  corners9(at, n);
}

// Eight rays d of several triangles (k: each lane's; n: their edge normals; lanes outside `valid`
// hold a valid lane's triangle) shaded in one evaluation, each lane from its own triangle's records
// loaded eight at a time: where all are rayPlain (interpolateColor), all textured alike without
// per-pixel lighting or a level of detail (filterTexturedGroup), or all lit per pixel alike
// (shadeLitAt). RayShading::shade's operations per lane (rayBarycentrics8's barycentrics), so the
// same bits. False, with `color` untouched, otherwise: the caller shades triangle by triangle.
TESSERA_LANES_INLINE bool shadeRaysOnce(const RayRecords& records, const LaneKeys& k,
                                        const F32x8 n[9], const Ray8& d, I32x8 valid,
                                        const LightRig& lights, Vec3x8& color) {
  const ShadeTriangle* lanes[8];
  laneRecords(k, records.shade, lanes);
  const ShadeTriangle& t = *lanes[0];
  const Material* material = t.material;
  bool plain = true, textured = texturedPlain(t);
  for (int l = 0; l < 8; ++l) {
    plain = plain && rayPlain(*lanes[l]);
    textured = textured && texturedPlain(*lanes[l]) && lanes[l]->material == material;
  }
  textured = textured && texture8Applies(*material->albedo, material->sampler) &&
             !needsLod(*material->albedo, material->sampler);
  const bool lit = !plain && !textured && litAlike(lanes);
  if (!plain && !textured && !lit) return false;
  F32x8 e[3], f[kPlainFields];
  edgeValues(n, d, e);
  const F32x8 inv_s = splat(1.0f) / ((e[0] + e[1]) + e[2]);
  const F32x8 b1 = e[1] * inv_s, b2 = e[2] * inv_s;
  const F32x8 b0 = splat(1.0f) - b1 - b2;
  loadPlainFields(lanes, f);
  if (plain) {
    Vec3x8 c = plainColor(f, b1, b2);
    if (lights.tone.active()) toneMap8(lights.tone, c.x, c.y, c.z);
    color = c;
    return true;
  }
  const ShadeExtras* extras[8];
  laneRecords(k, records.extras, extras);
  if (lit) {
    color = shadeLitAt(t, f, extras, valid, lights, b0, b1, b2);
    return true;
  }
  F32x8 corner[8];
  uvCorners8(extras, material->sampler.texcoord, corner);
  TexturedGroup group;
  group.uv = uvAt8(corner, b0, b1, b2);
  group.color = plainColor(f, b1, b2);
  group.covered = valid;
  group.material = material;
  return filterTexturedGroup(group, lights, color);
}

// Eight centre rays d (the lanes of `covered`, whose keys name several triangles, `first` a
// covered lane's): shadeRaysOnce from each lane's records, zero outside `covered`.
TESSERA_LANES_INLINE bool shadeRayMixed(const RayRecords& records, const LightRig& lights,
                                        I32x8 keys, I32x8 covered, uint32_t first, const Ray8& d,
                                        Vec3x8& color) {
  const LaneKeys k = laneKeys(keys, covered, first);
  const RayTriangle* rays[8];
  laneRecords(k, records.ray, rays);
  F32x8 n[9];
  rayNormals(rays, n);
  Vec3x8 c;
  if (!shadeRaysOnce(records, k, n, d, covered, lights, c)) return false;
  const F32x8 zero = splat(0.0f);
  color = {select(covered, c.x, zero), select(covered, c.y, zero), select(covered, c.z, zero)};
  return true;
}

}  // namespace
}  // namespace tessera::render
