#version 460
// Pass 3, setup and cull: one invocation per scene triangle. Trivial reject against the frustum,
// Sutherland-Hodgman clipping against near and far (and the guard band where a triangle leaves
// it), backface culling by the signed area on the snapped grid, fixed-point edge functions with
// 8 sub-pixel bits and the top-left rule, the bounding box, the depth plane and the
// perspective-correct barycentric planes. This is src/render/clip.cpp and src/render/setup.cpp
// operation for operation (precise everywhere: no fused multiply-adds), so coverage is the CPU's
// exactly.
//
// Records: fan piece 0 of triangle t goes to slot t; the other pieces of a clipped triangle go to
// slots triangle_count + extra_base[t] + piece - 1, allocated with one atomic add. Every record
// that survives is appended to the visible list (in any order: the fine raster's atomic min
// makes the result independent of it). A record's key is t << 3 | piece, which orders records as
// the CPU submits them, so equal depths resolve to the same triangle.
//
// TESSERA_FP64 = 1: divisions and the area's reciprocal in double, rounded once to float, as the
// CPU; = 0: in float, for devices without shaderFloat64 (coverage of unclipped triangles is
// still exact; depth and the clipped vertices may differ in the last bit).
//
// TESSERA_DIAGNOSTICS = 1 (RenderOptions::diagnostics): the same setup, and each culled triangle
// counted under its reason (the CPU's countCullReason order) and the clip splits counted, in the
// diagnostics buffer. The variant without it has none of these atomics.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "common.glsl"
#include "records.glsl"
#include "screen.glsl"
#include "shading.glsl"
#include "setup_common.glsl"

#ifndef TESSERA_DIAGNOSTICS
#define TESSERA_DIAGNOSTICS 0
#endif
#if TESSERA_DIAGNOSTICS
#include "diagnostics.glsl"
#define COUNT_DIAGNOSTIC(word, n) atomicAdd(diagnostics_words[word], n)
#else
#define COUNT_DIAGNOSTIC(word, n)
#endif

layout(local_size_x = 64) in;

#if TESSERA_FP64
#define real double
#else
#define real float
#endif

const int kMaxClippedVertices = 9;

float planeDistance(uint plane, vec4 p) {
  precise float d;
  if (plane == kClipNear) d = p.z + p.w;
  else if (plane == kClipFar) d = p.w - p.z;
  else if (plane == kGuardLeft) d = p.x + frame.guard_x * p.w;
  else if (plane == kGuardRight) d = frame.guard_x * p.w - p.x;
  else if (plane == kGuardBottom) d = p.y + frame.guard_y * p.w;
  else d = frame.guard_y * p.w - p.y;
  return d;
}

ClipVertex interpolate(ClipVertex inside, ClipVertex outside, float t) {
  precise vec4 position = inside.position + (outside.position - inside.position) * t;
  precise vec3 weights = inside.weights + (outside.weights - inside.weights) * t;
  return ClipVertex(position, weights);
}

ClipVertex polygon[2][kMaxClippedVertices];

// Clips polygon[0][0..2] against `planes`; the result is polygon[result & 1][0..count), count in
// result >> 1 (0 when nothing is left).
uint clipTriangle(uint planes) {
  const uint order[6] = uint[6](kClipNear, kClipFar, kGuardLeft, kGuardRight, kGuardBottom,
                                kGuardTop);
  int count = 3;
  uint src = 0u;
  for (int p = 0; p < 6; ++p) {
    const uint plane = order[p];
    if ((planes & plane) == 0u) continue;
    const uint dst = 1u - src;
    int out_count = 0;
    for (int i = 0; i < count; ++i) {
      const ClipVertex a = polygon[src][i];
      const ClipVertex b = polygon[src][(i + 1) % count];
      precise float da = planeDistance(plane, a.position);
      precise float db = planeDistance(plane, b.position);
      const bool a_in = da >= 0.0, b_in = db >= 0.0;
      if (a_in) polygon[dst][out_count++] = a;
      if (a_in != b_in) {
        // Always from the inside vertex towards the outside one (see src/render/clip.h).
        precise float a_minus_b = da - db;
        precise float b_minus_a = db - da;
        polygon[dst][out_count++] = a_in ? interpolate(a, b, divideRounded(da, a_minus_b))
                                         : interpolate(b, a, divideRounded(db, b_minus_a));
      }
    }
    count = out_count;
    src = dst;
    if (count < 3) return 0u;
  }
  return (uint(count) << 1) | src;
}

// Edge from a to b: (b - a) x (p - a) with y down; the top-left bias folded into c.
void makeEdge(int ax, int ay, int bx, int by, out int a, out int b, out int64_t c) {
  a = ay - by;
  b = bx - ax;
  c = int64_t(by - ay) * int64_t(ax) - int64_t(bx - ax) * int64_t(ay);
  const int dx = bx - ax, dy = by - ay;
  const bool top_left = dy < 0 || (dy == 0 && dx > 0);
  if (!top_left) c -= 1l;
}

// src/render/setup.cpp, setupRaster then setupShade: true when the triangle is visible.
// sv: the snapped vertices; v: their weights over the source triangle (when clipped).
bool setupTriangle(ScreenVertex sv[3], ClipVertex v[3], TriangleContext ctx,
                   out RasterRecord raster, out ShadeRecord shade) {
  // Signed area on the snapped grid, y down: front faces (counter-clockwise in NDC) are negative.
  int64_t area = int64_t(sv[1].x - sv[0].x) * int64_t(sv[2].y - sv[0].y) -
                 int64_t(sv[1].y - sv[0].y) * int64_t(sv[2].x - sv[0].x);
  if (area == 0l) return false;
  const bool back_facing = area > 0l;
  if ((back_facing && ctx.cull == kCullBack) || (!back_facing && ctx.cull == kCullFront))
    return false;

  // Bounding box over the pixels' sample points (the centres, with one sample): pixel i has
  // points from i*256 + sample_min to i*256 + sample_max, so first = ceil((lo - max) / 256) and
  // last = floor((hi - min) / 256) (arithmetic shifts floor).
  const int lo_x = min(sv[0].x, min(sv[1].x, sv[2].x)), hi_x = max(sv[0].x, max(sv[1].x, sv[2].x));
  const int lo_y = min(sv[0].y, min(sv[1].y, sv[2].y)), hi_y = max(sv[0].y, max(sv[1].y, sv[2].y));
  raster.min_x = max(-((frame.sample_max_x - lo_x) >> kSubpixelBits), 0);
  raster.max_x = min((hi_x - frame.sample_min_x) >> kSubpixelBits, frame.width - 1);
  if (raster.min_x > raster.max_x) return false;
  raster.min_y = max(-((frame.sample_max_y - lo_y) >> kSubpixelBits), 0);
  raster.max_y = min((hi_y - frame.sample_min_y) >> kSubpixelBits, frame.height - 1);
  if (raster.min_y > raster.max_y) return false;

  // The rasterizer takes positive areas only: front faces are reordered 0, 2, 1.
  int order[3] = int[3](0, 1, 2);
  if (area < 0l) {
    order[1] = 2;
    order[2] = 1;
    area = -area;
  }
  const ScreenVertex v0 = sv[order[0]], v1 = sv[order[1]], v2 = sv[order[2]];

  // Edge k is opposite vertex k: edge 0 = v1->v2, edge 1 = v2->v0, edge 2 = v0->v1.
  makeEdge(v1.x, v1.y, v2.x, v2.y, raster.a[0], raster.b[0], raster.c[0]);
  makeEdge(v2.x, v2.y, v0.x, v0.y, raster.a[1], raster.b[1], raster.c[1]);
  makeEdge(v0.x, v0.y, v1.x, v1.y, raster.a[2], raster.b[2], raster.c[2]);
  // One sample a pixel and a box of at most 2 x 2 pixel centres (of a triangle spanning less than
  // 2^14 a side): dropped when every centre is outside (missesEveryCentre, src/render/setup.h),
  // as a box without a centre is.
  if (frame.samples == 1u && raster.max_x - raster.min_x < 2 && raster.max_y - raster.min_y < 2 &&
      hi_x - lo_x < 16384 && hi_y - lo_y < 16384) {
    bool covered = false;
    for (int y = raster.min_y; y <= raster.max_y; ++y)
      for (int x = raster.min_x; x <= raster.max_x; ++x) {
        const int64_t px = int64_t(x) * kSubpixelOne + kSubpixelOne / 2;
        const int64_t py = int64_t(y) * kSubpixelOne + kSubpixelOne / 2;
        bool inside = true;
        for (int k = 0; k < 3; ++k)
          inside = inside &&
                   int64_t(raster.a[k]) * px + int64_t(raster.b[k]) * py + raster.c[k] >= 0l;
        covered = covered || inside;
      }
    if (!covered) return false;
  }

  // Screen-space gradients of barycentrics 1 and 2: (edge coefficient) * 256 / area, the
  // reciprocal rounded once to float from double, as the CPU.
#if TESSERA_FP64
  precise double inv_area_wide = 256.0lf / double(area);
  const float inv_area = float(inv_area_wide);
#else
  precise float inv_area = 256.0 / float(area);
#endif
  precise float l1dx = float(v2.y - v0.y) * inv_area;
  precise float l1dy = float(v0.x - v2.x) * inv_area;
  precise float l2dx = float(v0.y - v1.y) * inv_area;
  precise float l2dy = float(v1.x - v0.x) * inv_area;

  const float scale = 1.0 / float(kSubpixelOne);
  precise float x0 = float(v0.x) * scale;
  precise float y0 = float(v0.y) * scale;
  raster.x0 = x0;
  raster.y0 = y0;
  raster.z0 = v0.z;
  precise float dz1 = v1.z - v0.z, dz2 = v2.z - v0.z;
  precise float dzdx = dz1 * l1dx + dz2 * l2dx;
  precise float dzdy = dz1 * l1dy + dz2 * l2dy;
  raster.dzdx = dzdx;
  raster.dzdy = dzdy;

  const float q0 = v0.inv_w, q1 = v1.inv_w, q2 = v2.inv_w;
  shade.inv_w0 = q0;
  precise float p1dx = q1 * l1dx, p1dy = q1 * l1dy, p2dx = q2 * l2dx, p2dy = q2 * l2dy;
  precise float sdx = (q1 - q0) * l1dx + (q2 - q0) * l2dx;
  precise float sdy = (q1 - q0) * l1dy + (q2 - q0) * l2dy;
  shade.p1dx = p1dx;
  shade.p1dy = p1dy;
  shade.p2dx = p2dx;
  shade.p2dy = p2dy;
  shade.sdx = sdx;
  shade.sdy = sdy;

  setupShadeCorners(ctx, v, order, back_facing, shade);
  return true;
}

#if TESSERA_DIAGNOSTICS
// Why setupTriangle dropped a triangle, by its checks in their order: zero area on the snapped
// grid, facing the culled way, else a bounding box without a pixel centre (or one it misses).
uint cullReason(ScreenVertex sv[3], TriangleContext ctx) {
  const int64_t area = int64_t(sv[1].x - sv[0].x) * int64_t(sv[2].y - sv[0].y) -
                       int64_t(sv[1].y - sv[0].y) * int64_t(sv[2].x - sv[0].x);
  if (area == 0l) return kDiagDegenerate;
  const bool back_facing = area > 0l;
  if ((back_facing && ctx.cull == kCullBack) || (!back_facing && ctx.cull == kCullFront))
    return kDiagFacing;
  return kDiagNoPixel;
}
#endif

void emit(uint slot, RasterRecord raster, ShadeRecord shade) {
  raster_records[slot] = raster;
  shade_records[slot] = shade;
  // alphaMode BLEND: the record is kept for the transparent pass (blend_pass.glsl), out of the
  // bins, the raster and the visibility buffer, as the CPU leaves it out of the z-buffer.
  if ((materials[shade.material].texture_flags & kMaterialBlend) != 0u) return;
  // alphaMode MASK, when the MASK pass runs: that pass commits the record where alpha passes.
  if ((frame.flags & kFrameMaskPass) != 0u &&
      (materials[shade.material].texture_flags & kMaterialMask) != 0u)
    return;
  visible_list[atomicAdd(counters.visible, 1u)] = slot;
}

void main() {
  const uint t = flatWorkgroupIndex() * 64u + gl_LocalInvocationIndex;
  if (t >= frame.triangle_count) return;
  const uint object_index = objectOfTriangle(t);
  const GpuObject object = objects[object_index];
  const uint idx[3] = uint[3](indices[3u * t], indices[3u * t + 1u], indices[3u * t + 2u]);
  if (idx[0] >= object.vertex_count || idx[1] >= object.vertex_count ||
      idx[2] >= object.vertex_count) {
    atomicAdd(counters.culled, 1u);
    COUNT_DIAGNOSTIC(kDiagInvalid, 1u);
    return;
  }

  ClipVertex v[3];
  ScreenVertex sv[3];
  uint codes[3];
  for (int k = 0; k < 3; ++k) {
    const TransformedVertex tv = transformed[object.vertex_base + idx[k]];
    v[k].position = tv.clip;
    v[k].weights = vec3(k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0);
    codes[k] = tv.outcode;
    sv[k] = ScreenVertex(tv.screen.x, tv.screen.y, tv.z, tv.inv_w);
  }
  // Non-finite vertices drop their triangle; so does one wholly outside a frustum plane.
  if (((codes[0] | codes[1] | codes[2]) & kNonFinite) != 0u ||
      (codes[0] & codes[1] & codes[2] & kRejectPlanes) != 0u) {
    atomicAdd(counters.culled, 1u);
    COUNT_DIAGNOSTIC(((codes[0] | codes[1] | codes[2]) & kNonFinite) != 0u ? kDiagNonFinite
                                                                            : kDiagFrustum,
                     1u);
    return;
  }

  TriangleContext ctx = triangleContext(t, object, idx);
  RasterRecord raster;
  ShadeRecord shade;
  const uint cut = (codes[0] | codes[1] | codes[2]) & kCutPlanes;
  if (cut == 0u) {
    ctx.clipped = false;
    if (setupTriangle(sv, v, ctx, raster, shade)) {
      raster.key = t << 3;
      emit(t, raster, shade);
    } else {
      atomicAdd(counters.culled, 1u);
      COUNT_DIAGNOSTIC(cullReason(sv, ctx), 1u);
    }
    return;
  }

  atomicAdd(counters.clipped, 1u);
  ctx.clipped = true;
  polygon[0][0] = v[0];
  polygon[0][1] = v[1];
  polygon[0][2] = v[2];
  const uint clipped = clipTriangle(cut);
  const int count = int(clipped >> 1);
  const uint src = clipped & 1u;
  if (count < 3) {
    atomicAdd(counters.culled, 1u);
    COUNT_DIAGNOSTIC(kDiagClippedAway, 1u);
    return;
  }
  // Pieces 1..count-3 take extra slots. When they do not fit, the counter still records how many
  // were asked for: the host grows the buffer and renders the frame again.
  const uint extra_needed = uint(count - 3);
  uint base = 0u;
  if (extra_needed > 0u) base = atomicAdd(counters.extra, extra_needed);
  extra_base[t] = base;
  bool any_visible = false;
#if TESSERA_DIAGNOSTICS
  uint pieces = 0u;
#endif
  for (int k = 1; k + 1 < count; ++k) {
    const uint piece = uint(k - 1);
    if (piece > 0u && base + piece - 1u >= frame.extra_capacity) continue;
    const ClipVertex fan[3] = ClipVertex[3](polygon[src][0], polygon[src][k], polygon[src][k + 1]);
    const ScreenVertex fan_screen[3] = ScreenVertex[3](projectToScreen(fan[0].position),
                                                       projectToScreen(fan[1].position),
                                                       projectToScreen(fan[2].position));
    if (setupTriangle(fan_screen, fan, ctx, raster, shade)) {
      raster.key = (t << 3) | piece;
      emit(piece == 0u ? t : frame.triangle_count + base + piece - 1u, raster, shade);
      any_visible = true;
#if TESSERA_DIAGNOSTICS
      ++pieces;
#endif
    }
  }
  if (!any_visible) atomicAdd(counters.culled, 1u);
  COUNT_DIAGNOSTIC(any_visible ? kDiagClipSplits : kDiagClippedAway,
                   any_visible ? pieces - 1u : 1u);
}
