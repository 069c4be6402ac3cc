#include "render/setup.h"

#include <algorithm>

namespace tessera::render {

bool setupRaster(const SetupContext& ctx, const ScreenVertex& sv0, const ScreenVertex& sv1,
                 const ScreenVertex& sv2, int64_t area, RasterTriangle& raster, RasterWide& wide,
                 TriangleOrientation& o) {
  const ScreenVertex* const v[3] = {&sv0, &sv1, &sv2};

  // Bounding box over pixel centres.
  const PixelBox box = pixelBox(ctx, sv0, sv1, sv2);
  if (box.empty()) return false;
  raster.min_x = static_cast<int16_t>(box.min_x);
  raster.min_y = static_cast<int16_t>(box.min_y);
  raster.max_x = static_cast<int16_t>(box.max_x);
  const int64_t box_w =
      static_cast<int64_t>(std::max({sv0.x, sv1.x, sv2.x})) - std::min({sv0.x, sv1.x, sv2.x});
  const int64_t box_h =
      static_cast<int64_t>(std::max({sv0.y, sv1.y, sv2.y})) - std::min({sv0.y, sv1.y, sv2.y});
  const bool small = smallBox(box_w, box_h, ctx.sample_reach);
  raster.max_y_small = static_cast<uint16_t>(box.max_y | (small ? RasterTriangle::kSmallBit : 0));

  orient(area, o);
  area = area < 0 ? -area : area;
  const ScreenVertex& v0 = *v[o.order[0]];
  const ScreenVertex& v1 = *v[o.order[1]];
  const ScreenVertex& v2 = *v[o.order[2]];

  // Edge k is opposite vertex k: edge 0 = v1->v2, edge 1 = v2->v0, edge 2 = v0->v1.
  makeEdge(v1.x, v1.y, v2.x, v2.y, raster.a[0], raster.b[0], wide.c[0]);
  makeEdge(v2.x, v2.y, v0.x, v0.y, raster.a[1], raster.b[1], wide.c[1]);
  makeEdge(v0.x, v0.y, v1.x, v1.y, raster.a[2], raster.b[2], wide.c[2]);
  // The values at the box's first pixel centre: in the box, so within int32 when small.
  const int64_t px = int64_t{box.min_x} * kSubpixelOne + kSubpixelHalf;
  const int64_t py = int64_t{box.min_y} * kSubpixelOne + kSubpixelHalf;
  for (int k = 0; k < 3; ++k)
    raster.corner[k] =
        small ? static_cast<int32_t>(raster.a[k] * px + raster.b[k] * py + wide.c[k]) : 0;
  // A box of few centres, all missed (missesEveryCentre, on the edges just formed).
  if (testsEveryCentre(ctx, box, box_w, box_h) &&
      edgesMissEveryCentre(raster.a, raster.b, wide.c, box))
    return false;

  // Screen-space planes on the snapped positions, in pixels: lambda_1 = E_20 / area,
  // lambda_2 = E_01 / area. The gradients are (edge coefficient) * 256 / area, exact in the
  // integer part, then one rounding to float.
  const float inv_area = static_cast<float>(static_cast<double>(kSubpixelOne) / area);
  o.l1dx = static_cast<float>(v2.y - v0.y) * inv_area;
  o.l1dy = static_cast<float>(v0.x - v2.x) * inv_area;
  o.l2dx = static_cast<float>(v0.y - v1.y) * inv_area;
  o.l2dy = static_cast<float>(v1.x - v0.x) * inv_area;

  const float scale = 1.0f / static_cast<float>(kSubpixelOne);
  raster.x0 = static_cast<float>(v0.x) * scale;
  raster.y0 = static_cast<float>(v0.y) * scale;
  raster.z0 = v0.z;
  const float dz1 = v1.z - v0.z, dz2 = v2.z - v0.z;
  raster.dzdx = dz1 * o.l1dx + dz2 * o.l2dx;
  raster.dzdy = dz1 * o.l1dy + dz2 * o.l2dy;
  wide.z_min = std::min({v0.z, v1.z, v2.z});
  return true;
}

namespace {

// An unclipped triangle's corners, read from the object's vertices.
struct MeshCorners {
  const MeshVertices& vertices;
  const uint32_t* index;

  const ScreenVertex& screen(int k) const { return vertices.screen[index[k]]; }
  float3 unitNormal(int k) const { return vertices.normal[index[k]]; }  // unit or zero already
  float2 uv(int k) const { return vertices.uv[index[k]]; }
  float2 uv1(int k) const { return vertices.uv1[index[k]]; }
  float3 color(int k) const { return vertices.color[index[k]].xyz(); }
  const float3* lit(int k) const { return vertices.lit ? &vertices.lit[index[k]] : nullptr; }
  float3 world(int k, const float4x4& model) const {
    return (model * float4(vertices.position[index[k]], 1.0f)).xyz();
  }
  // World tangent (a direction: the model's upper 3x3) from the object-space one.
  float4 tangent(int k, const SetupContext& ctx) const {
    const float4 t = ctx.tangents[index[k]];
    return float4((*ctx.model * float4(t.xyz(), 0.0f)).xyz(), t.w * ctx.winding_sign);
  }
};

// A clipped triangle's corners: the clipper's output.
struct ClippedCorners {
  const ScreenVertex* v;
  const VertexAttributes* a;

  const ScreenVertex& screen(int k) const { return v[k]; }
  // Interpolated by the clipper: no longer unit.
  float3 unitNormal(int k) const { return a[k].unit_normal ? a[k].normal : normalize(a[k].normal); }
  float2 uv(int k) const { return a[k].uv; }
  float2 uv1(int k) const { return a[k].uv1; }
  float3 color(int k) const { return a[k].color.xyz(); }
  const float3* lit(int) const { return nullptr; }
  float3 world(int k, const float4x4&) const { return a[k].world; }
  float4 tangent(int k, const SetupContext&) const { return a[k].tangent; }
};

bool isZero(float3 n) {
  return n.x == 0.0f && n.y == 0.0f && n.z == 0.0f;
}

// The perspective-correct barycentric planes (x0 .. sdy); setupBatch does the same eight at a time.
template <typename Corners>
inline __attribute__((always_inline)) void setupShadePlanes(const Corners& corners,
                                                            const TriangleOrientation& o,
                                                            const RasterTriangle& raster,
                                                            ShadeTriangle& shade) {
  const float q0 = corners.screen(o.order[0]).inv_w, q1 = corners.screen(o.order[1]).inv_w,
              q2 = corners.screen(o.order[2]).inv_w;
  shade.x0 = raster.x0;
  shade.y0 = raster.y0;
  shade.inv_w0 = q0;
  shade.p1dx = q1 * o.l1dx;
  shade.p1dy = q1 * o.l1dy;
  shade.p2dx = q2 * o.l2dx;
  shade.p2dy = q2 * o.l2dy;
  shade.sdx = (q1 - q0) * o.l1dx + (q2 - q0) * o.l2dx;
  shade.sdy = (q1 - q0) * o.l1dy + (q2 - q0) * o.l2dy;
}

// The triangle's material: its own where the object has it, else the object's first.
const Material& triangleMaterial(const SetupContext& ctx, uint16_t material) {
  return ctx.object->materials[material < ctx.object->materials.size() ? material : 0];
}

// Corner i's albedo: the base colour, times the vertex colour where the mesh has one.
template <typename Corners>
float3 cornerAlbedo(const SetupContext& ctx, float3 base, const Corners& corners, int i) {
  return ctx.has_color ? base * corners.color(i) : base;
}

// The record's material, id and shading.
void setIdentity(const SetupContext& ctx, const Material& m, uint32_t triangle_id,
                 ShadeTriangle& shade) {
  shade.material = &m;
  shade.triangle_id = triangle_id;
  shade.shading = ctx.shading;
  shade.has_uv = ctx.has_uv && m.albedo != nullptr;
}

// Everything else: material, id, and the corners' colours, normals and UVs. Always inlined into
// its callers: a call costs as much as a corner's work.
template <typename Corners>
inline __attribute__((always_inline)) void setupShadeCornersFrom(
    const SetupContext& ctx, const Corners& corners, const TriangleOrientation& o,
    float3 face_normal, uint32_t triangle_id, uint16_t material, ShadeTriangle& shade,
    ShadeExtras& extras) {
  const Material& m = triangleMaterial(ctx, material);
  const float3 base = m.base_color.xyz();
  // Back faces that are drawn are lit from the viewer's side (two-sided lighting).
  const float flip = o.back_facing ? -1.0f : 1.0f;
  // A zero face normal (not computed: the vertex normals serve) falls back to +Z.
  auto flatNormal = [&] {
    const float3 n = normalize(face_normal) * flip;
    return isZero(n) ? float3{0, 0, flip} : n;
  };
  const auto albedo = [&](int i) { return cornerAlbedo(ctx, base, corners, i); };
  // The vertex normals face the viewer where the face does (flip), unless they point to the other
  // side of the face than its winding does: a mirroring model whose mesh was not turned inside
  // out (SceneGraph's mirrored copies are), whose front faces would else show the normals' back.
  const float normal_flip =
      ctx.winding_sign < 0.0f &&
              dot(corners.unitNormal(0) + corners.unitNormal(1) + corners.unitNormal(2),
                  face_normal) < 0.0f
          ? -flip
          : flip;
  // The vertex's shading normal, facing the viewer; the face's where the vertex has none.
  const auto vertexNormal = [&](int i) {
    const float3 n = corners.unitNormal(i) * normal_flip;
    return isZero(n) ? flatNormal() : n;
  };
  // Only what the shading mode reads is written (shade_kernel.h): normals for Phong and the
  // normal AOV, UVs for textured meshes.
  const LightRig& lights = *ctx.lights;
  // World positions matter only to point and spot lights.
  const bool needs_world = needsWorld(lights, ctx.shading);
  const auto world = [&](int i) { return needs_world ? corners.world(i, *ctx.model) : float3{}; };
  switch (ctx.shading) {
    case Shading::kFlat: {
      const float3 n = flatNormal();
      // The face is lit at its centroid.
      const float3 centre =
          lights.local ? (world(0) + world(1) + world(2)) * (1.0f / 3.0f) : float3{};
      const float3 e = irradiance(lights, n, centre);
      for (int k = 0; k < 3; ++k) {
        if (ctx.want_normals) extras.normal[k] = n;
        shade.color[k] = albedo(o.order[k]) * e;
      }
      break;
    }
    case Shading::kGouraud:
      for (int k = 0; k < 3; ++k) {
        const int i = o.order[k];
        // Facing the viewer, the shading normal is the vertex normal itself (flip = +1), so the
        // vertex stage's irradiance is its irradiance; NaN there marks a zero normal.
        const float3* lit = normal_flip < 0.0f ? nullptr : corners.lit(i);
        if (lit && !std::isnan(lit->x)) {
          if (ctx.want_normals) extras.normal[k] = vertexNormal(i);
          shade.color[k] = albedo(i) * *lit;
        } else {
          const float3 n = vertexNormal(i);
          if (ctx.want_normals) extras.normal[k] = n;
          shade.color[k] = albedo(i) * irradiance(lights, n, world(i));
        }
      }
      break;
    case Shading::kPbr:
      // The base colour (factor x vertex colour); the maps and the BRDF are per pixel.
      for (int k = 0; k < 3; ++k) {
        const int i = o.order[k];
        extras.normal[k] = vertexNormal(i);
        extras.world[k] = world(i);
        shade.color[k] = albedo(i);
        if (ctx.tangents) {
          // Drawn back faces flip the whole frame (normal, tangent and bitangent: the relief
          // seen from behind), as the Khronos sample viewer does.
          const float4 t = corners.tangent(i, ctx);
          extras.tangent[k] = float4(t.xyz() * normal_flip, t.w * normal_flip);
        }
      }
      shade.pbr_flags = static_cast<uint8_t>((ctx.has_uv ? kPbrUv : 0) |
                                             (ctx.has_uv && ctx.tangents ? kPbrTangents : 0));
      break;
    case Shading::kPhong:
    case Shading::kUnlit: {
      // The albedo, lit per pixel (Phong) or not at all.
      const bool normals = writesNormals(ctx.shading, ctx.want_normals);
      const bool positions = writesWorld(lights, ctx.shading);
      for (int k = 0; k < 3; ++k) {
        const int i = o.order[k];
        if (normals) extras.normal[k] = vertexNormal(i);
        if (positions) extras.world[k] = world(i);
        shade.color[k] = albedo(i);
      }
      break;
    }
  }
  if (ctx.has_uv)
    for (int k = 0; k < 3; ++k) extras.uv[k] = corners.uv(o.order[k]);
  if (ctx.uv1)
    for (int k = 0; k < 3; ++k) extras.uv1[k] = corners.uv1(o.order[k]);
  setIdentity(ctx, m, triangle_id, shade);
}

}  // namespace

void setupShade(const SetupContext& ctx, const ScreenVertex v[3], const VertexAttributes a[3],
                const TriangleOrientation& o, const RasterTriangle& raster, float3 face_normal,
                uint32_t triangle_id, uint16_t material, ShadeTriangle& shade,
                ShadeExtras& extras) {
  const ClippedCorners corners{v, a};
  setupShadePlanes(corners, o, raster, shade);
  setupShadeCornersFrom(ctx, corners, o, face_normal, triangle_id, material, shade, extras);
  markSolid(shade);
}

void setupShade(const SetupContext& ctx, const MeshVertices& vertices, const uint32_t index[3],
                const TriangleOrientation& o, const RasterTriangle& raster, float3 face_normal,
                uint32_t triangle_id, uint16_t material, ShadeTriangle& shade,
                ShadeExtras& extras) {
  const MeshCorners corners{vertices, index};
  setupShadePlanes(corners, o, raster, shade);
  setupShadeCornersFrom(ctx, corners, o, face_normal, triangle_id, material, shade, extras);
  markSolid(shade);
}

void setupFlatCorners(const SetupContext& ctx, const MeshVertices& vertices,
                      const uint32_t index[3], const TriangleOrientation& o, uint32_t triangle_id,
                      uint16_t material, ShadeTriangle& shade) {
  const MeshCorners corners{vertices, index};
  const Material& m = triangleMaterial(ctx, material);
  const float3 base = m.base_color.xyz();
  for (int k = 0; k < 3; ++k) shade.color[k] = cornerAlbedo(ctx, base, corners, o.order[k]);
  setIdentity(ctx, m, triangle_id, shade);
}

void setupShadeCorners(const SetupContext& ctx, const MeshVertices& vertices,
                       const uint32_t index[3], const TriangleOrientation& o, float3 face_normal,
                       uint32_t triangle_id, uint16_t material, ShadeTriangle& shade,
                       ShadeExtras& extras) {
  setupShadeCornersFrom(ctx, MeshCorners{vertices, index}, o, face_normal, triangle_id, material,
                        shade, extras);
}

}  // namespace tessera::render
