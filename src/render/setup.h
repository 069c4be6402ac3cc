// Triangle setup, in two steps so that culled triangles cost as little as possible:
//   setupRaster: snapped positions -> orientation, cull, bounding box, the fixed-point edge
//                equations with the top-left bias, the depth plane (RasterTriangle: what coverage
//                and depth need);
//   setupShade:  for visible triangles only, the perspective-correct barycentric planes and the
//                vertex attributes (ShadeTriangle: what shading a visible pixel needs).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>

#include <tessera/math/vec.h>
#include <tessera/render/sampling.h>
#include <tessera/scene/scene.h>

#include "render/clip.h"
#include "render/fixed_point.h"
#include "render/lights.h"

namespace tessera::render {

struct ObjectTransforms;  // vertex.h

// A vertex after the perspective divide and the viewport, snapped to the sub-pixel grid.
struct ScreenVertex {
  int32_t x, y;  // window position in 1/256 pixel, y down
  float z;       // window depth in [0, 1]
  float inv_w;   // 1 / clip w
};

// The one place clip space becomes window space: the vertex stage and the clipper both use it,
// so a vertex shared by a clipped and an unclipped triangle snaps to the same point. Snapping
// rounds half to even (lrint in the default rounding mode; roundEven in GLSL).
inline ScreenVertex projectToScreen(float4 clip, float width, float height) {
  const float inv_w = 1.0f / clip.w;
  const float wx = (clip.x * inv_w * 0.5f + 0.5f) * width;
  const float wy = (0.5f - clip.y * inv_w * 0.5f) * height;
  return {static_cast<int32_t>(std::lrint(wx * static_cast<float>(kSubpixelOne))),
          static_cast<int32_t>(std::lrint(wy * static_cast<float>(kSubpixelOne))),
          clip.z * inv_w * 0.5f + 0.5f, inv_w};
}

// What the raster kernel reads of a triangle: 64 bytes, one cache line (the records are 64-byte
// aligned: PoolVector). Edge i covers pixel centre (px, py) (in 1/256 pixel) when
// a*px + b*py + c >= 0, the top-left rule folded into c. A small triangle (every edge value over
// its bounding box, plus 8 pixels right, fits in int32: what most of a mesh is) keeps its edges'
// values at the centre of pixel (min_x, min_y) instead of c; a large one keeps c, and its nearest
// depth for Hi-Z, in a RasterWide beside the record.
struct RasterTriangle {
  int32_t corner[3];  // small: edge i at the centre of pixel (min_x, min_y); large: 0
  int32_t a[3];
  int32_t b[3];
  int16_t min_x, min_y, max_x;  // inclusive pixel bounds, clipped to the viewport
  uint16_t max_y_small;         // max_y, plus kSmallBit for a small triangle
  // Window z at pixel centre (x + 0.5, y + 0.5) = z0 + dzdx * (x + 0.5 - x0) + dzdy * (y + 0.5 -
  // y0)
  float x0, y0, z0, dzdx, dzdy;

  static constexpr uint16_t kSmallBit = 0x8000;
  int maxY() const { return max_y_small & ~kSmallBit; }
  bool small() const { return (max_y_small & kSmallBit) != 0; }
};
static_assert(sizeof(RasterTriangle) == 64);
static_assert(kMaxViewport <= RasterTriangle::kSmallBit, "pixel bounds fit in 15 bits");

// The rest of a large triangle's raster record (written for large ones only).
struct RasterWide {
  int64_t c[3];
  float z_min;  // the nearest depth of the triangle (at a vertex), for Hi-Z
};

struct ShadeTriangle {
  // Laid out so that untextured flat and Gouraud pixels read only the first two cache lines.
  const Material* material;
  uint32_t triangle_id;  // index in the scene's triangle list
  Shading shading;
  bool has_uv;        // sample the albedo texture (the mesh has UVs and the material a texture)
  uint8_t pbr_flags;  // kPbr only: kPbrUv, kPbrTangents (in the padding: the record stays 88 bytes)
  // The corners share one colour (markSolid: setupShade, the ray renderer's setup; markSolid8 for
  // the setup batch's records, whose colours are final only there): interpolateColor gives
  // color[0] at every pixel.
  bool solid;
  // Perspective-correct barycentrics at window point p, with d = p - (x0, y0):
  //   s = inv_w0 + sdx*d.x + sdy*d.y;  b1 = (p1dx*d.x + p1dy*d.y) / s;  b2 = (...) / s;  b0 =
  //   1-b1-b2
  float x0, y0, inv_w0;
  float p1dx, p1dy, p2dx, p2dy, sdx, sdy;
  // Per-vertex colour, interpolated: base colour x vertex colour, already lit for flat (the
  // face's irradiance) and Gouraud (each vertex's); Phong multiplies by the per-pixel lighting.
  float3 color[3];
};

static_assert(sizeof(ShadeTriangle) == 88, "a record is 88 bytes: eight are eleven cache lines");

// Sets shade.solid from its corners' colours, once they are final: the differences of corners 1
// and 2 from corner 0 are all zero, so that c0 + d1 * b1 + d2 * b2 is c0 for any barycentrics.
// Bitwise &, not &&: no branches in the setup of every clipped triangle.
inline void markSolid(ShadeTriangle& shade) {
  const float3 &c0 = shade.color[0], &c1 = shade.color[1], &c2 = shade.color[2];
  shade.solid = (c1.x - c0.x == 0.0f) & (c1.y - c0.y == 0.0f) & (c1.z - c0.z == 0.0f) &
                (c2.x - c0.x == 0.0f) & (c2.y - c0.y == 0.0f) & (c2.z - c0.z == 0.0f);
}

// ShadeTriangle::pbr_flags: the mesh has UVs (the material's maps apply) and tangents (so does its
// normal map).
constexpr uint8_t kPbrUv = 1, kPbrTangents = 2;

// What only Phong, PBR, textured and normal-AOV pixels read, in an array beside the ShadeTriangles:
// records of untextured flat and Gouraud triangles stay 88 bytes, written and read whole.
struct ShadeExtras {
  float3 normal[3];   // world shading normals, facing the viewer for drawn back faces
  float2 uv[3];       // TEXCOORD_0
  float2 uv1[3];      // TEXCOORD_1 (set 0 where the mesh has none): written only when the
                      // object's materials read it (SetupContext::uv1)
  float3 world[3];    // world positions: Phong pixels lit by point and spot lights, PBR pixels
  float4 tangent[3];  // PBR with a normal map: world tangent, w the bitangent's sign (Mesh)
};

struct SetupContext {
  int width = 0, height = 0;
  CullMode cull = CullMode::kBack;
  Shading shading = Shading::kFlat;
  const LightRig* lights = nullptr;  // the frame's (LightRig::prepare)
  const Object* object = nullptr;
  const float4x4* model = nullptr;  // the object's: world positions for point and spot lights
  bool has_uv = false;
  bool has_color = false;
  // Some material of the object reads TEXCOORD_1 (readsTexcoord1) and the mesh has UVs: setup
  // writes ShadeExtras::uv1 from MeshVertices::uv1.
  bool uv1 = false;
  bool want_normals = false;  // the normal AOV is asked for
  // kPbr objects whose materials have a normal map: the mesh's tangents (object space), else null.
  const float4* tangents = nullptr;
  float winding_sign = 1.0f;  // sign of det(model): a mirrored object flips the bitangent
  // How far (1/256 pixel) a sample may lie from its pixel's centre: 0 with one sample at the
  // centre, sampleReach(samples) with MSAA. Boxes then hold every pixel a sample of which may be
  // covered.
  int32_t sample_reach = 0;
};

// The setup context of one object of `scene` on a width x height viewport.
inline SetupContext objectSetupContext(const LightRig& lights, const Object& object,
                                       const float4x4& model, int width, int height,
                                       bool want_normals, int32_t sample_reach) {
  SetupContext ctx;
  ctx.width = width;
  ctx.height = height;
  ctx.cull = object.cull;
  ctx.shading = object.shading;
  ctx.lights = &lights;
  ctx.object = &object;
  ctx.model = &model;
  if (object.mesh) {
    const size_t vertex_count = object.mesh->vertexCount();
    // The Lambert modes read UVs for the albedo texture only (Material): an untextured mesh's
    // UVs are left out, so that its triangles take the plain Gouraud path (plainGouraudFor).
    const bool reads_uv = object.shading == Shading::kPbr ||
                          std::any_of(object.materials.begin(), object.materials.end(),
                                      [](const Material& m) { return m.albedo != nullptr; });
    ctx.has_uv = reads_uv && object.mesh->uvs.size() == vertex_count;
    ctx.has_color = object.mesh->colors.size() == vertex_count;
  }
  ctx.want_normals = want_normals;
  ctx.sample_reach = sample_reach;
  ctx.uv1 = ctx.has_uv && std::any_of(object.materials.begin(), object.materials.end(),
                                      [](const Material& m) { return readsTexcoord1(m); });
  const Mesh* mesh = object.mesh.get();
  if (object.shading == Shading::kPbr && mesh && ctx.has_uv &&
      mesh->tangents.size() == mesh->vertexCount() && mesh->normals.size() == mesh->vertexCount() &&
      std::any_of(object.materials.begin(), object.materials.end(),
                  [](const Material& m) { return m.normal.texture != nullptr; }))
    ctx.tangents = mesh->tangents.data();
  ctx.winding_sign = determinant(upper3x3(model)) < 0.0f ? -1.0f : 1.0f;
  return ctx;
}

// With MSAA, samples lie strictly within half a pixel of the centre (sampling.h).
constexpr int32_t kSampleReach = kSubpixelHalf;

// How far the samples of the n-sample pattern (samplePattern) lie from their pixel's centre, in
// x or y, in 1/256 pixel: what SetupContext::sample_reach takes with MSAA (0 with one sample, at
// the centre). Jitter moves the geometry, not the pattern, so it adds nothing. Half a pixel for
// every count (kSampleReach, the bound) gave boxes pixels no sample of 2x or 4x can reach: on the
// bunny at 1920x1080 with 4x, 5% of the tile raster's instructions
// (docs/perf-notes/msaa-rounds-7-to-11.md).
constexpr int32_t sampleReach(int n) {
  int32_t reach = 0;
  for (const SamplePosition& p : samplePattern(n)) {
    const int32_t dx = p.x - kSubpixelHalf, dy = p.y - kSubpixelHalf;
    reach = std::max({reach, dx < 0 ? -dx : dx, dy < 0 ? -dy : dy});
  }
  return reach;
}
static_assert(sampleReach(1) == 0 && sampleReach(2) == 64 && sampleReach(4) == 96 &&
                  sampleReach(8) == 112 && sampleReach(8) < kSampleReach,
              "the standard patterns' reach: 4/16, 6/16 and 7/16 pixel");

// Whether every edge value the 32-bit raster paths form fits in int32 (RasterTriangle::small):
// an edge value at a point is |a| dx + |b| dy at most from a vertex, with |a| <= box height and
// |b| <= box width (sub-pixels, the snapped vertices' box); the kernels reach up to 7 pixels past
// the box's right end and a row past its bottom. Samples reach `sample_reach` past a pixel centre
// whose pixel reaches `sample_reach` past the box: the box grows by twice that on each side.
inline bool smallBox(int64_t box_w, int64_t box_h, int32_t sample_reach) {
  box_w += 4 * int64_t{sample_reach};
  box_h += 4 * int64_t{sample_reach};
  return box_h * (2 * box_w + 8 * kSubpixelOne) + box_w < (int64_t{1} << 30);
}

// What setupRaster learnt that setupShade needs.
struct TriangleOrientation {
  int order[3];                  // rasterizer vertex k is input vertex order[k] (positive area)
  bool back_facing;              // drawn with its back to the viewer
  float l1dx, l1dy, l2dx, l2dy;  // screen gradients of barycentrics 1 and 2
};

// Twice the signed area on the snapped grid, y down. Counter-clockwise in NDC (front-facing) stays
// counter-clockwise on screen, which with y pointing down gives a negative area. Exact: the
// coordinates are below 2^24, so the products stay below 2^49.
inline int64_t signedArea(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2) {
  return static_cast<int64_t>(v1.x - v0.x) * (v2.y - v0.y) -
         static_cast<int64_t>(v1.y - v0.y) * (v2.x - v0.x);
}

// True when a triangle of this signed area is dropped: degenerate, or facing away per ctx.cull.
// Inline: about half the triangles of a closed mesh stop here, before any other setup work.
inline bool cullsArea(const SetupContext& ctx, int64_t area) {
  const bool back_facing = area > 0;
  return area == 0 || (back_facing && ctx.cull == CullMode::kBack) ||
         (!back_facing && ctx.cull == CullMode::kFront);
}

// The pixels whose centres lie in a triangle's bounding box, clipped to the viewport: inclusive
// bounds, empty when min > max.
struct PixelBox {
  int32_t min_x, min_y, max_x, max_y;
  bool empty() const { return min_x > max_x || min_y > max_y; }
};

// First and last pixel whose centre lies in [lo, hi] (fixed point), clamped to [0, size - 1].
inline void pixelRange(int32_t lo, int32_t hi, int size, int32_t& first, int32_t& last) {
  // The centre of pixel i is i*256 + 128: first = ceil((lo - 128) / 256),
  // last = floor((hi - 128) / 256). Arithmetic shifts floor for negative values too.
  first = -((kSubpixelHalf - lo) >> kSubpixelBits);
  last = (hi - kSubpixelHalf) >> kSubpixelBits;
  first = std::max(first, 0);
  last = std::min(last, size - 1);
}

inline PixelBox pixelBox(const SetupContext& ctx, const ScreenVertex& v0, const ScreenVertex& v1,
                         const ScreenVertex& v2) {
  PixelBox box;
  const int32_t reach = ctx.sample_reach;
  pixelRange(std::min({v0.x, v1.x, v2.x}) - reach, std::max({v0.x, v1.x, v2.x}) + reach, ctx.width,
             box.min_x, box.max_x);
  pixelRange(std::min({v0.y, v1.y, v2.y}) - reach, std::max({v0.y, v1.y, v2.y}) + reach, ctx.height,
             box.min_y, box.max_y);
  return box;
}

// The vertex order and facing of a triangle of this (non-zero) signed area; leaves the gradients.
inline void orient(int64_t area, TriangleOrientation& o) {
  o.back_facing = area > 0;
  // The rasterizer takes positive areas only: front faces are reordered 0, 2, 1.
  o.order[0] = 0;
  o.order[1] = area < 0 ? 2 : 1;
  o.order[2] = area < 0 ? 1 : 2;
}

// Edge from a to b, evaluated at p: (b - a) x (p - a) with y pointing down. Positive inside for
// triangles whose signed area is positive (clockwise as seen on screen).
inline void makeEdge(int32_t ax, int32_t ay, int32_t bx, int32_t by, int32_t& a, int32_t& b,
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

// The most pixel centres a side of a box may hold for setup to test each of them
// (missesEveryCentre), and the most a triangle may span (1/256 pixel) for it: a box is clipped to
// the viewport, and the cull kernel tests such triangles in 32-bit lanes (below 2^14, its edge
// values at the centres stay below 2^30).
constexpr int kFewCentres = 2;
constexpr int32_t kFewCentresSpan = 1 << 14;

// Whether setup tests each pixel centre of `box` (missesEveryCentre): one sample a pixel, at most
// kFewCentres centres a side, and a triangle spanning (span_x, span_y, in 1/256 pixel) less than
// kFewCentresSpan.
inline bool testsEveryCentre(const SetupContext& ctx, const PixelBox& box, int64_t span_x,
                             int64_t span_y) {
  return ctx.sample_reach == 0 && box.max_x - box.min_x < kFewCentres &&
         box.max_y - box.min_y < kFewCentres && span_x < kFewCentresSpan &&
         span_y < kFewCentresSpan;
}

// Whether edges a, b, c (makeEdge's, in setupRaster's order) leave every pixel centre of `box`
// outside: the raster's tests at each.
inline bool edgesMissEveryCentre(const int32_t a[3], const int32_t b[3], const int64_t c[3],
                                 const PixelBox& box) {
  for (int y = box.min_y; y <= box.max_y; ++y)
    for (int x = box.min_x; x <= box.max_x; ++x) {
      const int64_t px = int64_t{x} * kSubpixelOne + kSubpixelHalf;
      const int64_t py = int64_t{y} * kSubpixelOne + kSubpixelHalf;
      bool covered = true;
      for (int k = 0; k < 3; ++k) covered &= a[k] * px + b[k] * py + c[k] >= 0;
      if (covered) return false;
    }
  return true;
}

// Whether a triangle of signed area `area` (not zero) whose box holds at most kFewCentres pixel
// centres a side (and that spans less than kFewCentresSpan: testsEveryCentre) misses all of them,
// at one sample a pixel: the raster's edge tests at each, in setupRaster's vertex order. Such a
// triangle writes nothing, and setup drops it as it drops one whose box holds no centre (counted
// as no_pixel): drawOne and the cull kernel by this test, setupRaster by edgesMissEveryCentre on
// the edges it forms. Meshes of triangles about a pixel in size have many: a third of the dense
// sphere's set-up triangles at 1920x1080, two thirds at 640x480. With MSAA the box reaches the
// samples around the centres (ctx.sample_reach), and nothing is dropped.
inline bool missesEveryCentre(const SetupContext& ctx, const PixelBox& box, const ScreenVertex& s0,
                              const ScreenVertex& s1, const ScreenVertex& s2, int64_t area) {
  const int64_t span_x = std::max({s0.x, s1.x, s2.x}) - std::min({s0.x, s1.x, s2.x});
  const int64_t span_y = std::max({s0.y, s1.y, s2.y}) - std::min({s0.y, s1.y, s2.y});
  if (!testsEveryCentre(ctx, box, span_x, span_y)) return false;
  TriangleOrientation o;
  orient(area, o);
  const ScreenVertex* const s[3] = {&s0, &s1, &s2};
  const ScreenVertex &v0 = *s[o.order[0]], &v1 = *s[o.order[1]], &v2 = *s[o.order[2]];
  const ScreenVertex* const from[3] = {&v1, &v2, &v0};
  const ScreenVertex* const to[3] = {&v2, &v0, &v1};
  int32_t a[3], b[3];
  int64_t c[3];
  for (int k = 0; k < 3; ++k)
    makeEdge(from[k]->x, from[k]->y, to[k]->x, to[k]->y, a[k], b[k], c[k]);
  return edgesMissEveryCentre(a, b, c, box);
}

// The rest of setupRaster for a triangle that cullsArea kept: false when it covers no pixel
// centre's bounding box inside the viewport.
bool setupRaster(const SetupContext& ctx, const ScreenVertex& v0, const ScreenVertex& v1,
                 const ScreenVertex& v2, int64_t area, RasterTriangle& raster, RasterWide& wide,
                 TriangleOrientation& orientation);

// False when the triangle is culled: degenerate, facing away (per ctx.cull) or covering no pixel
// centre's bounding box inside the viewport.
inline bool setupRaster(const SetupContext& ctx, const ScreenVertex v[3], RasterTriangle& raster,
                        RasterWide& wide, TriangleOrientation& orientation) {
  const int64_t area = signedArea(v[0], v[1], v[2]);
  return !cullsArea(ctx, area) &&
         setupRaster(ctx, v[0], v[1], v[2], area, raster, wide, orientation);
}

// One vertex's attributes, as the clipper outputs them.
struct VertexAttributes {
  float3 normal;  // world; zero when the mesh has none
  float2 uv;
  float4 color;
  bool unit_normal;  // `normal` is unit length or zero already (not interpolated by clipping)
  float3 world;      // world position (read only with point or spot lights, and for kPbr)
  float4 tangent{};  // world tangent (read only when SetupContext::tangents is set)
  float2 uv1{};      // read only when SetupContext::uv1
};

// Whether setup writes world positions: point and spot lights, the view vector of kPbr, and the
// shadow maps' lookups of per-pixel shading.
inline bool needsWorld(const LightRig& lights, Shading shading) {
  return lights.local || shading == Shading::kPbr ||
         (lights.shadows != nullptr && shading == Shading::kPhong);
}

// Which ShadeExtras fields setup writes for a triangle shaded `shading` (setup.cpp) and so which
// the shading pass reads: the normals for per-pixel shading (Phong, PBR) and the normal AOV; the
// world positions for per-pixel shading that needsWorld. The tile raster prefetches what these
// say (TriangleChunk::reads_normals, reads_world).
inline bool writesNormals(Shading shading, bool want_normals) {
  return shading == Shading::kPhong || shading == Shading::kPbr || want_normals;
}
inline bool writesWorld(const LightRig& lights, Shading shading) {
  return (shading == Shading::kPhong || shading == Shading::kPbr) && needsWorld(lights, shading);
}

// An object's vertices, indexed by mesh vertex: an unclipped triangle's corners are read from
// here, and only for what its shading mode uses.
struct MeshVertices {
  const ScreenVertex* screen;  // the vertex stage's (VertexBuffer), from the object's first vertex
  const float3* normal;        // world, unit or zero (VertexBuffer)
  const float3* lit;    // VertexBuffer::lit for objects lit in the vertex stage, otherwise null
  const float2* uv;     // read only when ctx.has_uv
  const float4* color;  // read only when ctx.has_color
  const float3* position = nullptr;  // the mesh's (object space); read only with local lights
  const float2* uv1 = nullptr;       // read only when ctx.uv1 (meshUv1: uvs1, else uvs)
};

// MeshVertices::uv1 of an object's mesh: its TEXCOORD_1, or its TEXCOORD_0 where it has none.
inline const float2* meshUv1(const SetupContext& ctx, const Mesh& mesh) {
  if (!ctx.uv1) return nullptr;
  return mesh.uvs1.size() == mesh.vertexCount() ? mesh.uvs1.data() : mesh.uvs.data();
}

// `face_normal` is the world-space geometric normal (flat shading, and vertices without a normal);
// zero when the caller knows it is not needed. Vertices are given in input order.
void setupShade(const SetupContext& ctx, const ScreenVertex v[3], const VertexAttributes a[3],
                const TriangleOrientation& orientation, const RasterTriangle& raster,
                float3 face_normal, uint32_t triangle_id, uint16_t material, ShadeTriangle& shade,
                ShadeExtras& extras);
// The same for an unclipped triangle: its vertices are mesh vertices index[0..2].
void setupShade(const SetupContext& ctx, const MeshVertices& vertices, const uint32_t index[3],
                const TriangleOrientation& orientation, const RasterTriangle& raster,
                float3 face_normal, uint32_t triangle_id, uint16_t material, ShadeTriangle& shade,
                ShadeExtras& extras);

// Whether an unclipped triangle of the object is lit in setup's lanes (SetupBatch::markFlat,
// setupFlatCorners) rather than by setupShadeCorners: flat shading under directional lights only,
// with neither texture coordinates nor the normal AOV (whose extras the lanes do not write).
inline bool flatLitInLanes(const SetupContext& ctx) {
  return ctx.shading == Shading::kFlat && !ctx.lights->local && !ctx.has_uv && !ctx.uv1 &&
         !ctx.want_normals;
}

// setupShadeCorners for such a triangle, but for its light: the corners' albedos (the base colour
// times the vertex colour) in shade.color, and the material, id and shading.
void setupFlatCorners(const SetupContext& ctx, const MeshVertices& vertices,
                      const uint32_t index[3], const TriangleOrientation& o, uint32_t triangle_id,
                      uint16_t material, ShadeTriangle& shade);

// The per-corner half of setupShade for an unclipped triangle (material, id, colours, normals,
// UVs: everything but the barycentric planes x0 .. sdy and the solid flag, which setupBatch
// computes eight triangles at a time; a caller outside the batch marks the flag, markSolid).
// Reads only o.order and o.back_facing.
void setupShadeCorners(const SetupContext& ctx, const MeshVertices& vertices,
                       const uint32_t index[3], const TriangleOrientation& o, float3 face_normal,
                       uint32_t triangle_id, uint16_t material, ShadeTriangle& shade,
                       ShadeExtras& extras);

// Per object: whether plainGouraudCorners applies (Gouraud, lit in the vertex stage, no vertex
// colours or normal AOV), the material when one serves every triangle, and the texture
// coordinates its corners carry (the albedo texture's: SetupContext::has_uv and uv1).
struct PlainGouraud {
  bool applies = false;
  const Material* material = nullptr;  // null: per-triangle materials
  bool uv = false, uv1 = false;
};

inline PlainGouraud plainGouraudFor(const SetupContext& ctx, const MeshVertices& vertices,
                                    bool per_triangle_materials) {
  PlainGouraud plain;
  plain.applies =
      ctx.shading == Shading::kGouraud && vertices.lit && !ctx.has_color && !ctx.want_normals;
  if (!per_triangle_materials) plain.material = &ctx.object->materials[0];
  plain.uv = ctx.has_uv;
  plain.uv1 = ctx.uv1;
  return plain;
}

// setupShadeCorners' most common case, inline: a triangle of a PlainGouraud object facing the
// viewer: each corner's colour is the base colour times the vertex's irradiance (the same
// product setupShadeCorners forms), and its texture coordinates in `extras`. False, with nothing
// written, in any other case (a zero normal's NaN included): call setupShadeCorners.
inline bool plainGouraudCorners(const SetupContext& ctx, const PlainGouraud& plain,
                                const MeshVertices& vertices, const uint32_t index[3],
                                const TriangleOrientation& o, uint32_t triangle_id,
                                uint16_t material, ShadeTriangle& shade, ShadeExtras& extras) {
  if (!plain.applies || o.back_facing) return false;
  // Facing the viewer the signed area is negative (zero is culled), so orient took the corners
  // in the order 0, 2, 1.
  const float3& l0 = vertices.lit[index[0]];
  const float3& l1 = vertices.lit[index[2]];
  const float3& l2 = vertices.lit[index[1]];
  if (std::isnan(l0.x) || std::isnan(l1.x) || std::isnan(l2.x)) return false;
  const std::vector<Material>& materials = ctx.object->materials;
  const Material& m =
      plain.material ? *plain.material : materials[material < materials.size() ? material : 0];
  const float3 base = m.base_color.xyz();
  shade.color[0] = base * l0;
  shade.color[1] = base * l1;
  shade.color[2] = base * l2;
  if (plain.uv) {
    extras.uv[0] = vertices.uv[index[0]];
    extras.uv[1] = vertices.uv[index[2]];
    extras.uv[2] = vertices.uv[index[1]];
  }
  if (plain.uv1) {
    extras.uv1[0] = vertices.uv1[index[0]];
    extras.uv1[1] = vertices.uv1[index[2]];
    extras.uv1[2] = vertices.uv1[index[1]];
  }
  shade.material = &m;
  shade.triangle_id = triangle_id;
  shade.shading = Shading::kGouraud;
  shade.has_uv = plain.uv && m.albedo != nullptr;
  return true;
}

// Unclipped triangles that cullsArea and pixelBox kept, queued for the rest of their setup eight
// at a time (setup_kernel.h): the same values, bit for bit, as setupRaster and setupShade's
// planes. Each input is 64 bytes, so that a lane's fields are two rows of eight 32-bit values.
// The caller fills each lane's shading record but for the planes (nextShade, before push); the
// kernel adds the planes and streams the records out, eight consecutive ones (704 bytes, eleven
// lines) as whole lines.
struct alignas(64) SetupBatch {
  static constexpr int kLanes = 8;
  struct Input {
    ScreenVertex v[3];  // input order
    double area;        // |signed area| (exact: below 2^49)
    int32_t reorder;    // all ones when the signed area is negative: rasterize 0, 2, 1
    uint32_t record;    // where the results go: the chunk's raster and shade records
  };
  Input input[kLanes];
  ShadeTriangle shade[kLanes];  // the lanes' shading records, the planes still to come
  int count = 0;
  // The lanes' extras where the caller stages them (nextExtras: lane l's bit in extras_lanes),
  // written out by the caller after the kernel (chunk_setup.cpp's writeExtras).
  alignas(64) ShadeExtras extras[kLanes];
  uint32_t extras_lanes = 0;
  // Flat faces the kernel lights (setupFlatCorners): lane l's bit; what its world face normal
  // (not normalized) is made of, which the kernel forms eight at a time as chunk_setup.cpp's
  // faceNormal does: the corners' model-space positions (corner[k][axis]: corner k in mesh
  // order) and the object's transforms (its normal matrix and winding sign); the facing's flip
  // (1, or -1 for a drawn back face), and the frame's rig, whose lights are all directional. The
  // lane's record holds the corners' albedos, which the kernel multiplies by the face's
  // irradiance, as setupShadeCorners lights a flat face.
  uint32_t flat_lanes = 0;
  const LightRig* lights = nullptr;
  alignas(32) float corner[3][3][kLanes] = {};
  const ObjectTransforms* object[kLanes] = {};
  alignas(32) float flip[kLanes] = {};

  // The shading record of the lane the next push fills.
  ShadeTriangle& nextShade() { return shade[count]; }
  // Its extras, staged.
  ShadeExtras& nextExtras() {
    extras_lanes |= 1u << count;
    return extras[count];
  }
  // The lanes' records are eight consecutive ones (first, first + 1, ...): the writers then put
  // them out as whole lines where the first starts on one.
  bool consecutive() const {
    if (count != kLanes) return false;
    for (int l = 1; l < kLanes; ++l)
      if (input[l].record != input[0].record + static_cast<uint32_t>(l)) return false;
    return true;
  }
  // Marks the lane the next push fills as a flat face to light: corners p[0..2] (model space, mesh
  // order) of the object of transforms `xf`.
  void markFlat(const float3 p[3], const ObjectTransforms& xf, float facing_flip,
                const LightRig& rig) {
    for (int k = 0; k < 3; ++k) {
      corner[k][0][count] = p[k].x;
      corner[k][1][count] = p[k].y;
      corner[k][2][count] = p[k].z;
    }
    object[count] = &xf;
    flip[count] = facing_flip;
    flat_lanes |= 1u << count;
    lights = &rig;
  }

  void push(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2, int64_t area,
            uint32_t record) {
    input[count++] = {
        {v0, v1, v2}, static_cast<double>(area < 0 ? -area : area), area < 0 ? -1 : 0, record};
  }
  bool full() const { return count == kLanes; }
  // Fills the lanes past `count` with copies of the first, so that every lane computes finite
  // values (they are not stored).
  void padLanes() {
    for (int l = count; l < kLanes; ++l) {
      input[l] = input[0];
      for (int k = 0; k < 3; ++k)
        for (int axis = 0; axis < 3; ++axis) corner[k][axis][l] = corner[k][axis][0];
      flip[l] = flip[0];
    }
  }
};
static_assert(sizeof(SetupBatch::Input) == 64);
static_assert(sizeof(ShadeTriangle) * SetupBatch::kLanes % 64 == 0,
              "eight shading records are whole lines");
static_assert(sizeof(ShadeExtras) * SetupBatch::kLanes % 64 == 0, "eight extras are whole lines");

// Eight consecutive triangles of one object through the cull, eight at a time
// (setup_kernel.h): what the per-triangle checks in setup decide (index range, outcodes,
// cullsArea, pixelBox), with the same integer results.
struct CullGroup {
  static constexpr int kLanes = 8;
  enum Kind : int32_t { kCulled = 0, kVisible = 1, kClip = 2 };
  int32_t kind[kLanes];
  uint32_t kept;        // bit l: lane l's kind is not kCulled
  int32_t cut[kLanes];  // kClip: the outcodes' kCutPlanes bits
  double area[kLanes];  // kVisible: signedArea (exact: below 2^49)
  int32_t min_x[kLanes], min_y[kLanes], max_x[kLanes], max_y[kLanes];  // kVisible: pixelBox
};

}  // namespace tessera::render
