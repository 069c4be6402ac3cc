// The batched half of triangle setup, written once against eight-lane types (simd_lanes.h) and
// compiled per instruction set (kernels_<isa>.cpp): eight queued triangles (SetupBatch) at a time
// get what setupRaster computes and setupShade's barycentric planes. Each lane runs exactly the
// integer and IEEE operations of those functions, in the same order (the core builds with
// -ffp-contract=off), so the records hold the same bytes.
#pragma once

#include <cstddef>

#include "render/setup.h"
#include "render/simd_lanes.h"
#include "render/vec3_lanes.h"
#include "render/vertex.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

// The raster records are written as two rows of eight 32-bit values; these are the rows.
static_assert(offsetof(RasterTriangle, corner) == 0 && offsetof(RasterTriangle, a) == 12 &&
                  offsetof(RasterTriangle, b) == 24 && offsetof(RasterTriangle, min_x) == 36 &&
                  offsetof(RasterTriangle, min_y) == 38 && offsetof(RasterTriangle, max_x) == 40 &&
                  offsetof(RasterTriangle, max_y_small) == 42 &&
                  offsetof(RasterTriangle, x0) == 44 && offsetof(RasterTriangle, y0) == 48 &&
                  offsetof(RasterTriangle, z0) == 52 && offsetof(RasterTriangle, dzdx) == 56 &&
                  offsetof(RasterTriangle, dzdy) == 60 && sizeof(RasterTriangle) == 64,
              "setupBatchKernel writes RasterTriangle as two rows of eight 32-bit values");
static_assert(offsetof(ShadeTriangle, p1dx) == offsetof(ShadeTriangle, x0) + 3 * sizeof(float) &&
                  offsetof(ShadeTriangle, sdx) == offsetof(ShadeTriangle, x0) + 7 * sizeof(float) &&
                  offsetof(ShadeTriangle, sdy) == offsetof(ShadeTriangle, x0) + 8 * sizeof(float),
              "setupBatchKernel writes ShadeTriangle::x0 .. sdx as one row");

struct ScreenVertex8 {
  I32x8 x, y;
  F32x8 z, inv_w;
};

struct Edge8 {
  I32x8 a, b;
  F64x8 c;  // exact: below 2^48
};

// makeEdge's top-left rule for an edge running (dx, dy), lane by lane: -1 off the rule, else 0
// (what makeEdge subtracts from c).
TESSERA_LANES_INLINE I32x8 offTopLeft(I32x8 dx, I32x8 dy) {
  const I32x8 zero = splat(int32_t{0});
  return nonNegative(dy) & ~(equal(dy, zero) & ~lessOrEqual(dx, zero));
}

// As makeEdge (setup.h). c is computed in double lanes: exact, since the coordinates are below
// 2^23 in magnitude and their differences below 2^24, the products stay below 2^47.
TESSERA_LANES_INLINE Edge8 makeEdge8(const ScreenVertex8& p, const ScreenVertex8& q) {
  const I32x8 dx = q.x - p.x, dy = q.y - p.y;
  const F64x8 c = toDouble(dy) * toDouble(p.x) - toDouble(dx) * toDouble(p.y);
  // Off the top-left rule c - 1: the mask's -1 added as a double.
  return {p.y - q.y, dx, c + toDouble(offTopLeft(dx, dy))};
}

TESSERA_LANES_INLINE ScreenVertex8 selectVertex(I32x8 mask, const ScreenVertex8& a,
                                                const ScreenVertex8& b) {
  return {select(mask, a.x, b.x), select(mask, a.y, b.y), select(mask, a.z, b.z),
          select(mask, a.inv_w, b.inv_w)};
}

// As pixelRange (setup.h), lane by lane.
TESSERA_LANES_INLINE void pixelRange8(I32x8 lo, I32x8 hi, int size, I32x8& first, I32x8& last) {
  const I32x8 zero = splat(int32_t{0});
  first = maximum(zero - shiftRight(splat(kSubpixelHalf) - lo, kSubpixelBits), zero);
  last = minimum(shiftRight(hi - splat(kSubpixelHalf), kSubpixelBits), splat(size - 1));
}

struct ScreenPoint8 {
  I32x8 x, y;  // 1/256 pixel
};

// Lanes whose three edges leave each centre of a box of at most 2 x 2 pixel centres outside: the
// box's first centre p, and `across` and `down` (0 or 1) more to the right and below. Edge k runs
// from[k] -> to[k]; its value is makeEdge's (setup.h), (b - a) x (p - a) less 1 off the top-left
// rule, stepped by -dy * 256 a pixel right and dx * 256 a pixel down. In 32-bit lanes: exact for
// the lanes of `few` (spanning less than kFewCentresSpan, so the values stay below 2^30); the
// others compute on zeros.
static_assert(kFewCentres == 2, "missesEveryCentre8 tests a box of at most 2 x 2 centres");
TESSERA_LANES_INLINE I32x8 missesEveryCentre8(const ScreenPoint8 from[3], const ScreenPoint8 to[3],
                                              const ScreenPoint8& p, I32x8 few, I32x8 across,
                                              I32x8 down) {
  const I32x8 zero = splat(int32_t{0});
  I32x8 first = zero, right = zero, below = zero, last = zero;  // the sign: some edge misses
  for (int k = 0; k < 3; ++k) {
    const I32x8 dx = (to[k].x - from[k].x) & few, dy = (to[k].y - from[k].y) & few;
    const I32x8 e =
        dx * ((p.y - from[k].y) & few) - dy * ((p.x - from[k].x) & few) + offTopLeft(dx, dy);
    const I32x8 step_x = (zero - shiftLeft(dy, kSubpixelBits)) & (zero - across);
    const I32x8 step_y = shiftLeft(dx, kSubpixelBits) & (zero - down);
    first = first | e;
    right = right | (e + step_x);
    below = below | (e + step_y);
    last = last | ((e + step_x) + step_y);
  }
  return ~nonNegative(first) & ~nonNegative(right) & ~nonNegative(below) & ~nonNegative(last);
}

// The cull of eight consecutive triangles (CullGroup), lane by lane as setup's per-triangle checks:
// outcodes (a non-finite vertex or all three outside one frustum plane drop the triangle; one
// outside a cut plane sends it to the clipper), then cullsArea on signedArea, then pixelBox and
// missesEveryCentre.
bool cullGroupKernel(const uint32_t* indices, size_t vertex_count, const ScreenVertex* screen,
                     const uint16_t* outcodes, int width, int height, CullMode cull,
                     int32_t sample_reach, CullGroup& out) {
  // Indices as int32 lanes: a count below 2^31 keeps the comparison unsigned in effect.
  if (vertex_count > 0x7fffffffu) return false;
  const I32x8 count = splat(static_cast<int32_t>(vertex_count));
  I32x8 bad = splat(int32_t{0});
  for (int k = 0; k < 3; ++k) {
    const I32x8 index = load<I32x8>(indices + 8 * k);
    bad = bad | ~nonNegative(index) | ~lessThan(index, count);
  }
  if (any(bad)) return false;

  // Each lane's three screen vertices, (x, y, z, inv_w) each, transposed into lanes: vertices 0
  // and 1 a row a lane, vertex 2 of lanes l and l + 4 a row.
  F32x8 rows01[8], rows2[4];
  alignas(32) int32_t code_any[8], code_all[8];
  for (int l = 0; l < CullGroup::kLanes; ++l) {
    const uint32_t i0 = indices[3 * l], i1 = indices[3 * l + 1], i2 = indices[3 * l + 2];
    rows01[l] = load2x4<F32x8>(&screen[i0], &screen[i1]);
    const uint32_t c0 = outcodes[i0], c1 = outcodes[i1], c2 = outcodes[i2];
    code_any[l] = static_cast<int32_t>(c0 | c1 | c2);
    code_all[l] = static_cast<int32_t>(c0 & c1 & c2);
  }
  for (int l = 0; l < CullGroup::kLanes / 2; ++l)
    rows2[l] = load2x4<F32x8>(&screen[indices[3 * l + 2]], &screen[indices[3 * (l + 4) + 2]]);
  transpose8x8(rows01);
  transpose4x4Halves(rows2);  // rows2[k]: field k of vertex 2, lanes 0-3 then 4-7

  const I32x8 zero = splat(int32_t{0});
  const I32x8 any_code = load<I32x8>(code_any), all_code = load<I32x8>(code_all);
  const I32x8 dropped = ~equal(any_code & splat(static_cast<int32_t>(kNonFinite)), zero) |
                        ~equal(all_code & splat(static_cast<int32_t>(kRejectPlanes)), zero);
  const I32x8 cut = any_code & splat(static_cast<int32_t>(kCutPlanes));
  const I32x8 whole = ~dropped & equal(cut, zero);
  const I32x8 clip = ~dropped & ~whole;

  // Screen positions are valid only where no cut plane is crossed: the other lanes compute on
  // zeros (and are not used).
  const I32x8 x0 = select(whole, bitsOf(rows01[0]), zero),
              y0 = select(whole, bitsOf(rows01[1]), zero);
  const I32x8 x1 = select(whole, bitsOf(rows01[4]), zero),
              y1 = select(whole, bitsOf(rows01[5]), zero);
  const I32x8 x2 = select(whole, bitsOf(rows2[0]), zero),
              y2 = select(whole, bitsOf(rows2[1]), zero);
  // signedArea in double lanes: exact, the differences are below 2^24 and the products below
  // 2^48.
  const F64x8 area = toDouble(x1 - x0) * toDouble(y2 - y0) - toDouble(y1 - y0) * toDouble(x2 - x0);
  const I32x8 positive = lessThan(splat(0.0), area), negative = lessThan(area, splat(0.0));
  // cullsArea.
  const I32x8 culled = ~(positive | negative) |
                       (positive & splat(int32_t{cull == CullMode::kBack ? -1 : 0})) |
                       (negative & splat(int32_t{cull == CullMode::kFront ? -1 : 0}));
  // pixelBox.
  I32x8 min_x, max_x, min_y, max_y;
  const I32x8 reach = splat(sample_reach);
  const I32x8 lo_x = minimum(minimum(x0, x1), x2), hi_x = maximum(maximum(x0, x1), x2);
  const I32x8 lo_y = minimum(minimum(y0, y1), y2), hi_y = maximum(maximum(y0, y1), y2);
  pixelRange8(lo_x - reach, hi_x + reach, width, min_x, max_x);
  pixelRange8(lo_y - reach, hi_y + reach, height, min_y, max_y);
  const I32x8 empty = lessThan(max_x, min_x) | lessThan(max_y, min_y);
  I32x8 visible = whole & ~culled & ~empty;
  // missesEveryCentre (setup.h), at one sample a pixel.
  if (sample_reach == 0) {
    const I32x8 across = max_x - min_x, down = max_y - min_y;
    const I32x8 one = splat(int32_t{kFewCentres - 1}), span = splat(kFewCentresSpan);
    const I32x8 few = visible & lessOrEqual(across, one) & lessOrEqual(down, one) &
                      lessThan(hi_x - lo_x, span) & lessThan(hi_y - lo_y, span);
    if (any(few)) {
      // setupRaster's vertex order (front faces, of negative area, take the corners 0, 2, 1) and
      // edges (edge 0 = v1 -> v2, 1 = v2 -> v0, 2 = v0 -> v1).
      const ScreenPoint8 v0{x0, y0}, v1{select(negative, x2, x1), select(negative, y2, y1)},
          v2{select(negative, x1, x2), select(negative, y1, y2)};
      const ScreenPoint8 from[3] = {v1, v2, v0}, to[3] = {v2, v0, v1};
      const ScreenPoint8 centre{shiftLeft(min_x, kSubpixelBits) + splat(kSubpixelHalf),
                                shiftLeft(min_y, kSubpixelBits) + splat(kSubpixelHalf)};
      visible = visible & ~(few & missesEveryCentre8(from, to, centre, few, across, down));
    }
  }

  store(out.kind, (visible & splat(int32_t{CullGroup::kVisible})) |
                      (clip & splat(int32_t{CullGroup::kClip})));
  out.kept = laneBits(visible | clip);
  store(out.cut, cut);
  store(out.area, area);
  store(out.min_x, min_x);
  store(out.min_y, min_y);
  store(out.max_x, max_x);
  store(out.max_y, max_y);
  return true;
}

// The world face normals (not normalized) of the batch's flat faces, as chunk_setup.cpp's
// faceNormal forms each (the same bits): normal_matrix * cross(p1 - p0, p2 - p0) * winding_sign,
// the matrix times a vector column by column (mat.h). One object's transforms in every flat lane
// are broadcast; lanes of several objects (a batch across an object's end) read each lane's.
TESSERA_LANES_INLINE Vec3x8 flatFaceNormals(const SetupBatch& batch) {
  const auto corner = [&](int k, int axis) { return load<F32x8>(batch.corner[k][axis]); };
  const F32x8 ax = corner(1, 0) - corner(0, 0), ay = corner(1, 1) - corner(0, 1),
              az = corner(1, 2) - corner(0, 2);
  const F32x8 bx = corner(2, 0) - corner(0, 0), by = corner(2, 1) - corner(0, 1),
              bz = corner(2, 2) - corner(0, 2);
  const F32x8 cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
  // The other lanes (not flat, or past the count) take the first flat lane's object.
  const ObjectTransforms* const shared = batch.object[__builtin_ctz(batch.flat_lanes)];
  bool one_object = true;
  for (int l = 0; l < batch.count; ++l)
    one_object &= !(batch.flat_lanes >> l & 1u) || batch.object[l] == shared;
  F32x8 m[3][3], w;  // m[column][row]
  if (one_object) {
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) m[c][r] = splat(shared->normal_matrix.col[c][r]);
    w = splat(shared->winding_sign);
  } else {
    alignas(32) float lanes[10][SetupBatch::kLanes];  // the matrix by columns, then the sign
    for (int l = 0; l < SetupBatch::kLanes; ++l) {
      const ObjectTransforms& own = batch.flat_lanes >> l & 1u ? *batch.object[l] : *shared;
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) lanes[3 * c + r][l] = own.normal_matrix.col[c][r];
      lanes[9][l] = own.winding_sign;
    }
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) m[c][r] = load<F32x8>(lanes[3 * c + r]);
    w = load<F32x8>(lanes[9]);
  }
  return {(m[0][0] * cx + m[1][0] * cy + m[2][0] * cz) * w,
          (m[0][1] * cx + m[1][1] * cy + m[2][1] * cz) * w,
          (m[0][2] * cx + m[1][2] * cy + m[2][2] * cz) * w};
}

// The batch's flat faces (SetupBatch::flat_lanes) lit as setupShadeCorners lights a flat face,
// operation for operation (the same bits): the face normal (flatFaceNormals) normalized (vec.h:
// zero where its length is not positive) and flipped, +Z times the flip where that leaves it zero;
// the ambient plus each directional light's radiance times its cosine where that is positive;
// each corner's albedo times that irradiance.
TESSERA_LANES_INLINE void lightFlatFaces(SetupBatch& batch) {
  const LightRig& rig = *batch.lights;
  const Vec3x8 face = flatFaceNormals(batch);
  const F32x8 fx = face.x, fy = face.y, fz = face.z, flip = load<F32x8>(batch.flip);
  const F32x8 zero = splat(0.0f);
  const F32x8 length = squareRoot(fx * fx + fy * fy + fz * fz);
  const I32x8 positive = lessThan(zero, length);
  const F32x8 inverse = splat(1.0f) / length;
  F32x8 nx = select(positive, fx * inverse, zero) * flip;
  F32x8 ny = select(positive, fy * inverse, zero) * flip;
  F32x8 nz = select(positive, fz * inverse, zero) * flip;
  const I32x8 degenerate = equal(nx, zero) & equal(ny, zero) & equal(nz, zero);
  nx = select(degenerate, zero, nx);
  ny = select(degenerate, zero, ny);
  nz = select(degenerate, flip, nz);
  F32x8 ex = splat(rig.ambient.x), ey = splat(rig.ambient.y), ez = splat(rig.ambient.z);
  for (const ShadeLight& light : rig.lights) {
    const float3 d = light.direction, r = light.radiance;
    const F32x8 cos_theta = zero - (nx * splat(d.x) + ny * splat(d.y) + nz * splat(d.z));
    const I32x8 lit = lessThan(zero, cos_theta);
    ex = select(lit, ex + splat(r.x) * cos_theta, ex);
    ey = select(lit, ey + splat(r.y) * cos_theta, ey);
    ez = select(lit, ez + splat(r.z) * cos_theta, ez);
  }
  alignas(32) float e[3][SetupBatch::kLanes];
  store(e[0], ex);
  store(e[1], ey);
  store(e[2], ez);
  for (int l = 0; l < batch.count; ++l) {
    if (!(batch.flat_lanes >> l & 1u)) continue;
    for (float3& c : batch.shade[l].color) c = c * float3{e[0][l], e[1][l], e[2][l]};
  }
}

// markSolid (setup.h) for the batch's lanes, eight at a time: the same test of the same floats.
static_assert(offsetof(ShadeTriangle, color) + 8 * sizeof(float) <= sizeof(ShadeTriangle),
              "markSolid8 reads eight floats from color[0]");
TESSERA_LANES_INLINE void markSolid8(SetupBatch& batch) {
  F32x8 c[8];  // c[3 k + i]: component i of corner k (the last, c2.z, apart)
  alignas(32) float last[SetupBatch::kLanes];
  for (int l = 0; l < SetupBatch::kLanes; ++l) {
    c[l] = load<F32x8>(&batch.shade[l].color[0].x);
    last[l] = batch.shade[l].color[2].z;
  }
  transpose8x8(c);
  const F32x8 zero = splat(0.0f);
  const I32x8 solid = equal(c[3] - c[0], zero) & equal(c[4] - c[1], zero) &
                      equal(c[5] - c[2], zero) & equal(c[6] - c[0], zero) &
                      equal(c[7] - c[1], zero) & equal(load<F32x8>(last) - c[2], zero);
  alignas(32) int32_t flags[SetupBatch::kLanes];
  store(flags, solid);
  for (int l = 0; l < batch.count; ++l) batch.shade[l].solid = flags[l] != 0;
}

// The triangles' bounding boxes over pixel centres (reaching samples `sample_reach` from them),
// and smallBox's test (setup.h) lane by lane, in double lanes (exact: below 2^50).
struct PixelBox8 {
  I32x8 min_x, max_x, min_y, max_y, small;
};
TESSERA_LANES_INLINE PixelBox8 pixelBox8(const ScreenVertex8 in[3], int width, int height,
                                         int32_t sample_reach) {
  const I32x8 min_fx = minimum(minimum(in[0].x, in[1].x), in[2].x);
  const I32x8 max_fx = maximum(maximum(in[0].x, in[1].x), in[2].x);
  const I32x8 min_fy = minimum(minimum(in[0].y, in[1].y), in[2].y);
  const I32x8 max_fy = maximum(maximum(in[0].y, in[1].y), in[2].y);
  PixelBox8 box;
  const I32x8 sample = splat(sample_reach);
  pixelRange8(min_fx - sample, max_fx + sample, width, box.min_x, box.max_x);
  pixelRange8(min_fy - sample, max_fy + sample, height, box.min_y, box.max_y);
  const I32x8 grow = splat(4 * sample_reach);
  const I32x8 box_w = max_fx - min_fx + grow, box_h = max_fy - min_fy + grow;
  const F64x8 reach =
      toDouble(box_h) * toDouble(box_w + box_w + splat(8 * kSubpixelOne)) + toDouble(box_w);
  box.small = lessThan(reach, splat(0x1p30));
  return box;
}

// The batch's staged shading records (final) written to shade[record], streamed.
TESSERA_LANES_INLINE void streamShadeRecords(const SetupBatch& batch, ShadeTriangle* shade) {
  // The shading records go out streamed too. Setup writes over last frame's records, which the
  // other worker's shading pass read: on a host where a line takes hundreds of nanoseconds
  // between cores, ordinary stores waited on every line (docs/perf-notes/frame-stages.md, round 5).
  // Eight consecutive records starting on a line (the usual full batch) are eleven whole lines.
  char* const out = reinterpret_cast<char*>(&shade[batch.input[0].record]);
  if (batch.consecutive() && (reinterpret_cast<uintptr_t>(out) & 63) == 0) {
    const char* in = reinterpret_cast<const char*>(batch.shade);
    for (size_t offset = 0; offset < sizeof batch.shade; offset += 32)
      storeStreaming(out + offset, load<F32x8>(in + offset));
  } else {
    for (int l = 0; l < batch.count; ++l)
      streamCopy(&shade[batch.input[l].record], &batch.shade[l], sizeof(ShadeTriangle));
  }
}

// The large triangles' (lanes outside `small`) edge constants and least depth, beside their raster
// records in wide[record].
TESSERA_LANES_INLINE void storeWideRecords(const SetupBatch& batch, I32x8 small, const Edge8& e0,
                                           const Edge8& e1, const Edge8& e2, F32x8 z_min,
                                           RasterWide* wide) {
  alignas(64) int64_t c[3][8];
  store(c[0], exactInt64(e0.c));
  store(c[1], exactInt64(e1.c));
  store(c[2], exactInt64(e2.c));
  for (int l = 0; l < batch.count; ++l) {
    if (lane(small, l)) continue;
    RasterWide& w = wide[batch.input[l].record];
    for (int k = 0; k < 3; ++k) w.c[k] = c[k][l];
    w.z_min = lane(z_min, l);
  }
}

// Sets up the batch's first `count` lanes into raster[record] (and wide[record] for large
// triangles) and shade[record]: the lane's staged shading record (batch.shade) with the planes
// added (the other lanes must hold copies of a real triangle: they are computed, not stored).
// The records are written with streaming stores: the caller fences (_mm_sfence) before another
// thread reads them.
void setupBatchKernel(SetupBatch& batch, int width, int height, int32_t sample_reach,
                      RasterTriangle* raster, RasterWide* wide, ShadeTriangle* shade) {
  // Each input is two rows of eight 32-bit values: v0 v1, then v2 area reorder record.
  F32x8 rows01[8], rows2[8];
  for (int l = 0; l < SetupBatch::kLanes; ++l) {
    rows01[l] = load<F32x8>(&batch.input[l].v[0]);
    rows2[l] = load<F32x8>(&batch.input[l].v[2]);
  }
  transpose8x8(rows01);
  transpose8x8(rows2);
  const ScreenVertex8 in[3] = {{bitsOf(rows01[0]), bitsOf(rows01[1]), rows01[2], rows01[3]},
                               {bitsOf(rows01[4]), bitsOf(rows01[5]), rows01[6], rows01[7]},
                               {bitsOf(rows2[0]), bitsOf(rows2[1]), rows2[2], rows2[3]}};
  const I32x8 reorder = bitsOf(rows2[6]);
  const F64x8 area = loadStrided(&batch.input[0].area, sizeof(SetupBatch::Input));

  const PixelBox8 box = pixelBox8(in, width, height, sample_reach);
  const I32x8 min_x = box.min_x, max_x = box.max_x, min_y = box.min_y, max_y = box.max_y;
  const I32x8 small = box.small;

  // Positive area: front faces are reordered 0, 2, 1.
  const ScreenVertex8& v0 = in[0];
  const ScreenVertex8 v1 = selectVertex(reorder, in[2], in[1]);
  const ScreenVertex8 v2 = selectVertex(reorder, in[1], in[2]);
  const Edge8 e0 = makeEdge8(v1, v2), e1 = makeEdge8(v2, v0), e2 = makeEdge8(v0, v1);

  const F32x8 inv_area = toFloat(splat(static_cast<double>(kSubpixelOne)) / area);
  const F32x8 l1dx = toFloat(v2.y - v0.y) * inv_area;
  const F32x8 l1dy = toFloat(v0.x - v2.x) * inv_area;
  const F32x8 l2dx = toFloat(v0.y - v1.y) * inv_area;
  const F32x8 l2dy = toFloat(v1.x - v0.x) * inv_area;

  const F32x8 scale = splat(1.0f / static_cast<float>(kSubpixelOne));
  const F32x8 x0 = toFloat(v0.x) * scale, y0 = toFloat(v0.y) * scale;
  const F32x8 dz1 = v1.z - v0.z, dz2 = v2.z - v0.z;
  const F32x8 dzdx = dz1 * l1dx + dz2 * l2dx;
  const F32x8 dzdy = dz1 * l1dy + dz2 * l2dy;
  // std::min({z0, z1, z2}): the first of the smallest.
  F32x8 z_min = v0.z;
  z_min = select(lessThan(v1.z, z_min), v1.z, z_min);
  z_min = select(lessThan(v2.z, z_min), v2.z, z_min);

  // setupShade's planes.
  const F32x8 q0 = v0.inv_w, q1 = v1.inv_w, q2 = v2.inv_w;
  const F32x8 sdy = (q1 - q0) * l1dy + (q2 - q0) * l2dy;

  // Small triangles: the edge values at the centre of pixel (min_x, min_y), as setupRaster forms
  // them (in double lanes: exact, below 2^50; within int32 for a small triangle).
  const F64x8 px = toDouble(shiftLeft(min_x, kSubpixelBits) + splat(kSubpixelHalf));
  const F64x8 py = toDouble(shiftLeft(min_y, kSubpixelBits) + splat(kSubpixelHalf));
  const I32x8 zero = splat(int32_t{0});
  auto corner = [&](const Edge8& e) {
    return select(small, low32(exactInt64(toDouble(e.a) * px + toDouble(e.b) * py + e.c)), zero);
  };
  const I32x8 box_min = (min_x & splat(int32_t{0xffff})) | shiftLeft(min_y, 16);
  const I32x8 box_max =
      (max_x & splat(int32_t{0xffff})) |
      shiftLeft(max_y | (small & splat(static_cast<int32_t>(RasterTriangle::kSmallBit))), 16);

  // Lane l of vector k becomes field k of record l.
  F32x8 raster_edges[8] = {floatsOf(corner(e0)), floatsOf(corner(e1)), floatsOf(corner(e2)),
                           floatsOf(e0.a),       floatsOf(e1.a),       floatsOf(e2.a),
                           floatsOf(e0.b),       floatsOf(e1.b)};
  F32x8 raster_rest[8] = {
      floatsOf(e2.b), floatsOf(box_min), floatsOf(box_max), x0, y0, v0.z, dzdx, dzdy};
  F32x8 shade_planes[8] = {x0,        y0,        q0,        q1 * l1dx,
                           q1 * l1dy, q2 * l2dx, q2 * l2dy, (q1 - q0) * l1dx + (q2 - q0) * l2dx};
  transpose8x8(raster_edges);
  transpose8x8(raster_rest);
  transpose8x8(shade_planes);
  for (int l = 0; l < batch.count; ++l) {
    const uint32_t record = batch.input[l].record;
    char* const r = reinterpret_cast<char*>(&raster[record]);
    // Streaming: setup writes some 2 MB of raster records a frame (the bunny at 1080p) that only
    // the tile stage reads, after every chunk is done. Records are 64 bytes in 64-byte aligned
    // storage (PoolVector), so each is two aligned 32-byte stores: one whole line.
    storeStreaming(r, raster_edges[l]);
    storeStreaming(r + 32, raster_rest[l]);
    char* const s = reinterpret_cast<char*>(&batch.shade[l]);
    store(s + offsetof(ShadeTriangle, x0), shade_planes[l]);
    batch.shade[l].sdy = lane(sdy, l);
  }
  if (batch.flat_lanes != 0) lightFlatFaces(batch);
  markSolid8(batch);  // the colours are final
  streamShadeRecords(batch, shade);
  // Large triangles (few) keep c and z_min beside the record.
  if (any(~small)) storeWideRecords(batch, small, e0, e1, e2, z_min, wide);
}

}  // namespace
}  // namespace tessera::render
