#include "render/setup.h"

#include <algorithm>

namespace tessera::render {

float3 irradiance(const Scene& scene, float3 n) {
  float3 e = scene.ambient;
  for (const DirectionalLight& light : scene.lights) {
    float cos_theta = -dot(n, light.direction);
    if (cos_theta > 0.0f) e += light.color * cos_theta;
  }
  return e;
}

namespace {

// Edge from a to b, evaluated at p: (b - a) x (p - a) with y pointing down. Positive inside for
// triangles whose signed area is positive (clockwise as seen on screen).
void makeEdge(int32_t ax, int32_t ay, int32_t bx, int32_t by, int32_t& a, int32_t& b, int64_t& c) {
  a = ay - by;
  b = bx - ax;
  c = static_cast<int64_t>(by - ay) * ax - static_cast<int64_t>(bx - ax) * ay;
  // Top-left rule (y down, interior on the right of a->b): a top edge is horizontal and runs to
  // +x; a left edge runs up (dy < 0). Centres exactly on other edges are not covered.
  const int32_t dx = bx - ax, dy = by - ay;
  const bool top_left = dy < 0 || (dy == 0 && dx > 0);
  if (!top_left) c -= 1;
}

// First and last pixel whose centre lies in [lo, hi] (fixed point), clamped to [0, size - 1].
void pixelRange(int32_t lo, int32_t hi, int size, int32_t& first, int32_t& last) {
  // The centre of pixel i is i*256 + 128: first = ceil((lo - 128) / 256),
  // last = floor((hi - 128) / 256). Arithmetic shifts floor for negative values too.
  first = -((kSubpixelHalf - lo) >> kSubpixelBits);
  last = (hi - kSubpixelHalf) >> kSubpixelBits;
  first = std::max(first, 0);
  last = std::min(last, size - 1);
}

}  // namespace

bool setupRaster(const SetupContext& ctx, const ScreenVertex v[3], RasterTriangle& raster,
                 TriangleOrientation& o) {
  // Signed area on the snapped grid, y down. Counter-clockwise in NDC (front-facing) stays
  // counter-clockwise on screen, which with y pointing down gives a negative area.
  int64_t area = static_cast<int64_t>(v[1].x - v[0].x) * (v[2].y - v[0].y) -
                 static_cast<int64_t>(v[1].y - v[0].y) * (v[2].x - v[0].x);
  if (area == 0) return false;
  o.back_facing = area > 0;
  if ((o.back_facing && ctx.cull == CullMode::kBack) ||
      (!o.back_facing && ctx.cull == CullMode::kFront))
    return false;

  // Bounding box over pixel centres.
  const int32_t min_fx = std::min({v[0].x, v[1].x, v[2].x}),
                max_fx = std::max({v[0].x, v[1].x, v[2].x});
  const int32_t min_fy = std::min({v[0].y, v[1].y, v[2].y}),
                max_fy = std::max({v[0].y, v[1].y, v[2].y});
  pixelRange(min_fx, max_fx, ctx.width, raster.min_x, raster.max_x);
  if (raster.min_x > raster.max_x) return false;
  pixelRange(min_fy, max_fy, ctx.height, raster.min_y, raster.max_y);
  if (raster.min_y > raster.max_y) return false;
  // An edge value at a point of the box is |a| dx + |b| dy at most, with |a| <= box height and
  // |b| <= box width (sub-pixels); the kernel also evaluates up to 7 pixels past the right end.
  // Below 2^30 the 32-bit path cannot overflow.
  const int64_t box_w = static_cast<int64_t>(max_fx) - min_fx;
  const int64_t box_h = static_cast<int64_t>(max_fy) - min_fy;
  raster.small = box_h * (2 * box_w + 8 * kSubpixelOne) + box_w < (int64_t{1} << 30);

  // The rasterizer takes positive areas only: front faces are reordered 0, 2, 1.
  o.order[0] = 0, o.order[1] = 1, o.order[2] = 2;
  if (area < 0) {
    o.order[1] = 2, o.order[2] = 1;
    area = -area;
  }
  const ScreenVertex& v0 = v[o.order[0]];
  const ScreenVertex& v1 = v[o.order[1]];
  const ScreenVertex& v2 = v[o.order[2]];

  // Edge k is opposite vertex k: edge 0 = v1->v2, edge 1 = v2->v0, edge 2 = v0->v1.
  makeEdge(v1.x, v1.y, v2.x, v2.y, raster.a[0], raster.b[0], raster.c[0]);
  makeEdge(v2.x, v2.y, v0.x, v0.y, raster.a[1], raster.b[1], raster.c[1]);
  makeEdge(v0.x, v0.y, v1.x, v1.y, raster.a[2], raster.b[2], raster.c[2]);

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
  raster.z_min = std::min({v0.z, v1.z, v2.z});
  return true;
}

void setupShade(const SetupContext& ctx, const ScreenVertex v[3], const VertexAttributes a[3],
                const TriangleOrientation& o, const RasterTriangle& raster, float3 face_normal,
                uint32_t triangle_id, uint16_t material, ShadeTriangle& shade) {
  const float q0 = v[o.order[0]].inv_w, q1 = v[o.order[1]].inv_w, q2 = v[o.order[2]].inv_w;
  shade.x0 = raster.x0;
  shade.y0 = raster.y0;
  shade.inv_w0 = q0;
  shade.p1dx = q1 * o.l1dx;
  shade.p1dy = q1 * o.l1dy;
  shade.p2dx = q2 * o.l2dx;
  shade.p2dy = q2 * o.l2dy;
  shade.sdx = (q1 - q0) * o.l1dx + (q2 - q0) * o.l2dx;
  shade.sdy = (q1 - q0) * o.l1dy + (q2 - q0) * o.l2dy;

  const Material& m = ctx.object->materials[material < ctx.object->materials.size() ? material : 0];
  const float3 base = m.base_color.xyz();
  // Back faces that are drawn are lit from the viewer's side (two-sided lighting).
  const float flip = o.back_facing ? -1.0f : 1.0f;
  // A zero face normal (not computed: the vertex normals serve) falls back to +Z.
  float3 flat_normal = normalize(face_normal) * flip;
  if (flat_normal.x == 0.0f && flat_normal.y == 0.0f && flat_normal.z == 0.0f)
    flat_normal = float3{0, 0, flip};
  const float3 flat_irradiance =
      ctx.shading == Shading::kFlat ? irradiance(*ctx.scene, flat_normal) : float3(1.0f);
  const bool keep_normals = ctx.shading == Shading::kPhong || ctx.want_normals;
  for (int k = 0; k < 3; ++k) {
    const VertexAttributes& va = a[o.order[k]];
    float3 n = flat_normal;
    if (ctx.shading != Shading::kFlat) {
      // The vertex stage's normals are unit already; clipped vertices' are interpolated.
      n = (va.unit_normal ? va.normal : normalize(va.normal)) * flip;
      if (n.x == 0.0f && n.y == 0.0f && n.z == 0.0f) n = flat_normal;
    }
    if (keep_normals) shade.normal[k] = n;
    if (ctx.has_uv) shade.uv[k] = va.uv;
    const float3 albedo = ctx.has_color ? base * va.color.xyz() : base;
    shade.color[k] =
        albedo * (ctx.shading == Shading::kGouraud ? irradiance(*ctx.scene, n) : flat_irradiance);
  }
  shade.material = &m;
  shade.triangle_id = triangle_id;
  shade.shading = ctx.shading;
  shade.has_uv = ctx.has_uv && m.albedo != nullptr;
}

}  // namespace tessera::render
