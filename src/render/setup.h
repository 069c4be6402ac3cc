// Triangle setup: snap to the sub-pixel grid, orient, cull, build the fixed-point edge equations
// with the top-left bias, the bounding box, the depth plane and the perspective-correct
// barycentric planes. Produces one RasterTriangle (hot: what coverage and depth need) and one
// ShadeTriangle (cold: what shading a visible pixel needs) per visible triangle.
#pragma once

#include <cstdint>

#include <tessera/math/vec.h>
#include <tessera/scene/scene.h>

#include "render/clip.h"

namespace tessera::render {

struct RasterTriangle {
  // Edge i covers pixel centre (px, py) (in 1/256 pixel) when a*px + b*py + c >= 0; the top-left
  // rule is folded into c.
  int64_t c[3];
  int32_t a[3];
  int32_t b[3];
  int32_t min_x, min_y, max_x, max_y;  // inclusive pixel bounds, clipped to the viewport
  // Window z at pixel centre (x + 0.5, y + 0.5) = z0 + dzdx * (x + 0.5 - x0) + dzdy * (y + 0.5 - y0)
  float x0, y0, z0, dzdx, dzdy;
};

struct ShadeTriangle {
  // Perspective-correct barycentrics at window point p, with d = p - (x0, y0):
  //   s = inv_w0 + sdx*d.x + sdy*d.y;  b1 = (p1dx*d.x + p1dy*d.y) / s;  b2 = (...) / s;  b0 = 1-b1-b2
  float x0, y0, inv_w0;
  float p1dx, p1dy, p2dx, p2dy, sdx, sdy;
  float3 normal[3];      // world shading normals, facing the viewer for drawn back faces
  float3 irradiance[3];  // lighting at the vertices (Gouraud)
  float2 uv[3];
  float4 color[3];
  const Material* material;
  uint32_t triangle_id;  // index in the scene's triangle list
  Shading shading;
  bool has_uv;     // sample the albedo texture (the mesh has UVs and the material a texture)
  bool has_color;  // multiply by the interpolated vertex colours
};

struct SetupContext {
  int width = 0, height = 0;
  CullMode cull = CullMode::kBack;
  Shading shading = Shading::kFlat;
  const Scene* scene = nullptr;
  const Object* object = nullptr;
  bool has_uv = false;
  bool has_color = false;
};

enum class SetupResult { kVisible, kCulled };

// Sets up one triangle whose clip-space vertices lie inside the guard band and in front of the
// near plane. `face_normal` is the world-space geometric normal (for flat shading).
SetupResult setupTriangle(const SetupContext& context, const ClipVertex v[3], float3 face_normal,
                          uint32_t triangle_id, uint16_t material, RasterTriangle& raster,
                          ShadeTriangle& shade);

// Lambert irradiance: ambient plus every directional light, for unit normal n.
float3 irradiance(const Scene& scene, float3 n);

}  // namespace tessera::render
