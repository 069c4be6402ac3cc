#include "render/setup.h"

#include <algorithm>
#include <cmath>

#include "render/fixed_point.h"

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

int32_t snap(float window_coordinate) {
  return static_cast<int32_t>(std::lround(window_coordinate * kSubpixelOne));
}

// Edge from a to b, evaluated at p: (b - a) x (p - a) with y pointing down. Positive inside for
// triangles whose signed area is positive (clockwise as seen on screen).
void makeEdge(int32_t ax, int32_t ay, int32_t bx, int32_t by, int32_t& a, int32_t& b,
              int64_t& c) {
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
  // centre of pixel i is i*256 + 128: i >= (lo - 128) / 256 rounded up.
  auto floor_div = [](int64_t n, int64_t d) { return n >= 0 ? n / d : -((-n + d - 1) / d); };
  first = static_cast<int32_t>(-floor_div(-(static_cast<int64_t>(lo) - kSubpixelHalf),
                                          kSubpixelOne));
  last = static_cast<int32_t>(floor_div(static_cast<int64_t>(hi) - kSubpixelHalf, kSubpixelOne));
  first = std::max(first, 0);
  last = std::min(last, size - 1);
}

}  // namespace

SetupResult setupTriangle(const SetupContext& ctx, const ClipVertex in[3], float3 face_normal,
                          uint32_t triangle_id, uint16_t material, RasterTriangle& raster,
                          ShadeTriangle& shade) {
  // Perspective divide and viewport.
  float wx[3], wy[3], wz[3], inv_w[3];
  int32_t fx[3], fy[3];
  for (int i = 0; i < 3; ++i) {
    const float4 p = in[i].position;
    inv_w[i] = 1.0f / p.w;
    wx[i] = (p.x * inv_w[i] * 0.5f + 0.5f) * static_cast<float>(ctx.width);
    wy[i] = (0.5f - p.y * inv_w[i] * 0.5f) * static_cast<float>(ctx.height);
    wz[i] = p.z * inv_w[i] * 0.5f + 0.5f;
    fx[i] = snap(wx[i]);
    fy[i] = snap(wy[i]);
  }

  // Signed area on the snapped grid, y down. Counter-clockwise in NDC (front-facing) stays
  // counter-clockwise on screen, which with y pointing down gives a negative area.
  int64_t area = static_cast<int64_t>(fx[1] - fx[0]) * (fy[2] - fy[0]) -
                 static_cast<int64_t>(fy[1] - fy[0]) * (fx[2] - fx[0]);
  if (area == 0) return SetupResult::kCulled;
  const bool back_facing = area > 0;
  if ((back_facing && ctx.cull == CullMode::kBack) ||
      (!back_facing && ctx.cull == CullMode::kFront))
    return SetupResult::kCulled;

  // The rasterizer takes positive areas only: front faces are reordered 0, 2, 1.
  int order[3] = {0, 1, 2};
  if (area < 0) {
    std::swap(order[1], order[2]);
    area = -area;
  }
  const int i0 = order[0], i1 = order[1], i2 = order[2];

  // Bounding box over pixel centres.
  int32_t min_fx = std::min({fx[0], fx[1], fx[2]}), max_fx = std::max({fx[0], fx[1], fx[2]});
  int32_t min_fy = std::min({fy[0], fy[1], fy[2]}), max_fy = std::max({fy[0], fy[1], fy[2]});
  pixelRange(min_fx, max_fx, ctx.width, raster.min_x, raster.max_x);
  pixelRange(min_fy, max_fy, ctx.height, raster.min_y, raster.max_y);
  if (raster.min_x > raster.max_x || raster.min_y > raster.max_y) return SetupResult::kCulled;

  // Edge k is opposite vertex k: edge 0 = v1->v2, edge 1 = v2->v0, edge 2 = v0->v1.
  makeEdge(fx[i1], fy[i1], fx[i2], fy[i2], raster.a[0], raster.b[0], raster.c[0]);
  makeEdge(fx[i2], fy[i2], fx[i0], fy[i0], raster.a[1], raster.b[1], raster.c[1]);
  makeEdge(fx[i0], fy[i0], fx[i1], fy[i1], raster.a[2], raster.b[2], raster.c[2]);

  // Screen-space planes on the snapped positions. lambda_1 = E_20 / area, lambda_2 = E_01 / area.
  const double scale = static_cast<double>(kSubpixelOne);
  const double x0 = fx[i0] / scale, y0 = fy[i0] / scale;
  const double x1 = fx[i1] / scale, y1 = fy[i1] / scale;
  const double x2 = fx[i2] / scale, y2 = fy[i2] / scale;
  const double area_px = static_cast<double>(area) / (scale * scale);
  const double l1dx = (y2 - y0) / area_px, l1dy = (x0 - x2) / area_px;
  const double l2dx = (y0 - y1) / area_px, l2dy = (x1 - x0) / area_px;

  const double z0 = wz[i0], z1 = wz[i1], z2 = wz[i2];
  raster.x0 = static_cast<float>(x0);
  raster.y0 = static_cast<float>(y0);
  raster.z0 = static_cast<float>(z0);
  raster.dzdx = static_cast<float>((z1 - z0) * l1dx + (z2 - z0) * l2dx);
  raster.dzdy = static_cast<float>((z1 - z0) * l1dy + (z2 - z0) * l2dy);

  const double q0 = inv_w[i0], q1 = inv_w[i1], q2 = inv_w[i2];
  shade.x0 = raster.x0;
  shade.y0 = raster.y0;
  shade.inv_w0 = static_cast<float>(q0);
  shade.p1dx = static_cast<float>(q1 * l1dx);
  shade.p1dy = static_cast<float>(q1 * l1dy);
  shade.p2dx = static_cast<float>(q2 * l2dx);
  shade.p2dy = static_cast<float>(q2 * l2dy);
  shade.sdx = static_cast<float>((q1 - q0) * l1dx + (q2 - q0) * l2dx);
  shade.sdy = static_cast<float>((q1 - q0) * l1dy + (q2 - q0) * l2dy);

  // Attributes. Back faces that are drawn are lit from the viewer's side (two-sided lighting).
  const float flip = back_facing ? -1.0f : 1.0f;
  const float3 flat_normal = normalize(face_normal) * flip;
  const float3 flat_irradiance =
      ctx.shading == Shading::kFlat ? irradiance(*ctx.scene, flat_normal) : float3{};
  for (int k = 0; k < 3; ++k) {
    const ClipVertex& v = in[order[k]];
    float3 n = ctx.shading == Shading::kFlat ? flat_normal : normalize(v.normal) * flip;
    if (length(n) == 0.0f) n = flat_normal;
    shade.normal[k] = n;
    shade.uv[k] = v.uv;
    shade.color[k] = v.color;
    shade.irradiance[k] =
        ctx.shading == Shading::kGouraud ? irradiance(*ctx.scene, n) : flat_irradiance;
  }
  shade.material = &ctx.object->materials[material < ctx.object->materials.size() ? material : 0];
  shade.triangle_id = triangle_id;
  shade.shading = ctx.shading;
  shade.has_uv = ctx.has_uv && shade.material->albedo != nullptr;
  shade.has_color = ctx.has_color;
  return SetupResult::kVisible;
}

}  // namespace tessera::render
