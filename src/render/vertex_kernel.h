// The vertex stage's kernel (vertex.h), written once against eight-lane types (simd_lanes.h) and
// compiled per instruction set (kernels_<isa>.cpp), eight vertices at a time; the AVX-512 variant
// takes sixteen at a time where it can (transformVertexBlock16, the same operations per lane).
//
// What it computes is defined here and nowhere else. For each vertex, with p its position and n
// its normal, every lane does exactly these float operations in this order (no FMA: tessera_core
// builds with -ffp-contract=off), so every variant gives the same bits:
//   clip    = MVP * p, each row summed left to right: ((m0 * p.x + m1 * p.y) + m2 * p.z) + m3.
//   outcode = the clip.h planes the clip position is outside of, by strict comparisons against
//             -w, w and the guard band's factor * w; only kNonFinite when a coordinate is NaN or
//             infinite.
//   screen  = projectToScreen(clip, width, height) (setup.h); stored for every vertex, valid
//             where the outcode has no kCutPlanes bit.
//   normal  = normalize(normal_matrix * n) (vec.h): v * (1 / |v|), zero unless |v| > 0; zero for
//             a mesh without normals.
//   lit     = irradiance(rig, normal, -) (lights.h; directional lights only), NaN where the normal
//   is zero; only
//             when lighting is given (Gouraud objects lit per vertex).
// The Vulkan transform pass (src/vulkan/shaders/transform.comp) mirrors this.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>

#include "render/simd_lanes.h"
#include "render/vertex.h"

namespace tessera::render {
namespace {  // one private copy per translation unit, each compiled for its instruction set

static_assert(sizeof(float3) == 12 && sizeof(ScreenVertex) == 16,
              "the loads and stores below assume packed float3 and 16-byte ScreenVertex");

struct Float3x8 {
  F32x8 x, y, z;
};

// Eight float3 p[0..7] as lanes of x, y and z. Reads p[7] as 16 bytes: p[8] must exist.
TESSERA_LANES_INLINE Float3x8 loadFloat3x8(const float3* p) {
  F32x8 rows[4];  // rows[r]: p[r] in lanes 0-3, p[r + 4] in lanes 4-7 (each with a spare float)
  for (int r = 0; r < 4; ++r) rows[r] = load2x4<F32x8>(&p[r], &p[r + 4]);
  transpose4x4Halves(rows);
  return {rows[0], rows[1], rows[2]};
}

// Writes exactly p[0..7]: vertices are stored in order as 16 bytes, each one's spare float landing
// on the next one's x before that is stored; the last one as 12 bytes, so nothing past p[7] (a
// neighbouring job's vertex) is touched.
TESSERA_LANES_INLINE void storeFloat3x8(float3* p, const Float3x8& v) {
  F32x8 rows[4] = {v.x, v.y, v.z, v.z};
  transpose4x4Halves(rows);  // rows[r]: p[r] in lanes 0-3, p[r + 4] in lanes 4-7
  char* out = reinterpret_cast<char*>(p);
  for (int r = 0; r < 4; ++r) std::memcpy(out + 12 * r, &rows[r], 16);
  for (int r = 0; r < 3; ++r)
    std::memcpy(out + 12 * (r + 4), reinterpret_cast<const char*>(&rows[r]) + 16, 16);
  std::memcpy(out + 12 * 7, reinterpret_cast<const char*>(&rows[3]) + 16, 12);
}

// The call's constants as lanes.
struct VertexConstants {
  F32x8 mvp[4][4];     // [column][row]
  F32x8 normal[3][3];  // [column][row]
  F32x8 guard_x, guard_y;
  F32x8 width, height;
};

// Where one block of eight vertices goes (into the VertexBuffer, or a staging block for the tail).
struct VertexBlockOut {
  float *clip_x, *clip_y, *clip_z, *clip_w;
  uint16_t* outcode;
  ScreenVertex* screen;
  float3* normal;
  float3* lit;  // null: not lit
};

TESSERA_LANES_INLINE I32x8 planeBit(I32x8 outside, uint32_t bit) {
  return outside & splat(static_cast<int32_t>(bit));
}

// NaN and infinities have an all-ones exponent; the finite floats are those whose magnitude bits
// are at most FLT_MAX's.
TESSERA_LANES_INLINE I32x8 finiteMask(F32x8 a) {
  return maskLessOrEqual(bitsOf(a) & splat(0x7fffffff), splat(0x7f7fffff));
}

// Vertices positions[0..7] (and normals[0..7], null for none); both are read one float past the
// eighth vertex.
TESSERA_LANES_INLINE void transformVertexBlock(const float3* positions, const float3* normals,
                                               const VertexConstants& k,
                                               const VertexLighting* lighting,
                                               const VertexBlockOut& out) {
  // Clip position.
  const Float3x8 p = loadFloat3x8(positions);
  F32x8 clip[4];
  for (int r = 0; r < 4; ++r)
    clip[r] = k.mvp[0][r] * p.x + k.mvp[1][r] * p.y + k.mvp[2][r] * p.z + k.mvp[3][r];
  const F32x8 x = clip[0], y = clip[1], z = clip[2], w = clip[3];
  store(out.clip_x, x);
  store(out.clip_y, y);
  store(out.clip_z, z);
  store(out.clip_w, w);

  // Outcode (clip.h).
  const F32x8 neg_w = negate(w);
  const F32x8 gx = k.guard_x * w, gy = k.guard_y * w;
  const I32x8 code =
      planeBit(maskLess(z, neg_w), kClipNear) | planeBit(maskLess(w, z), kClipFar) |
      planeBit(maskLess(x, neg_w), kClipLeft) | planeBit(maskLess(w, x), kClipRight) |
      planeBit(maskLess(y, neg_w), kClipBottom) | planeBit(maskLess(w, y), kClipTop) |
      planeBit(maskLess(x, negate(gx)), kGuardLeft) | planeBit(maskLess(gx, x), kGuardRight) |
      planeBit(maskLess(y, negate(gy)), kGuardBottom) | planeBit(maskLess(gy, y), kGuardTop);
  const I32x8 all_finite = finiteMask(x) & finiteMask(y) & finiteMask(z) & finiteMask(w);
  storeU16(out.outcode, blend(all_finite, code, splat(static_cast<int32_t>(kNonFinite))));

  // Screen position (projectToScreen), for every lane: a cut vertex's is never read, and its NaN
  // or out-of-range values convert without trapping.
  const F32x8 half = splat(0.5f);
  const F32x8 inv_w = splat(1.0f) / w;
  const F32x8 wx = (x * inv_w * half + half) * k.width;
  const F32x8 wy = (half - y * inv_w * half) * k.height;
  const F32x8 subpixel = splat(static_cast<float>(kSubpixelOne));
  F32x8 screen[4] = {fromBits(roundToInt(wx * subpixel)), fromBits(roundToInt(wy * subpixel)),
                     z * inv_w * half + half, inv_w};
  transpose4x4Halves(screen);  // screen[r]: vertex r in lanes 0-3, vertex r + 4 in lanes 4-7
  for (int r = 0; r < 4; ++r) store2x4(&out.screen[r], &out.screen[r + 4], screen[r]);

  // World normal.
  const F32x8 zero = splat(0.0f);
  Float3x8 n{zero, zero, zero};
  if (normals) {
    const Float3x8 m = loadFloat3x8(normals);
    const Float3x8 v{k.normal[0][0] * m.x + k.normal[1][0] * m.y + k.normal[2][0] * m.z,
                     k.normal[0][1] * m.x + k.normal[1][1] * m.y + k.normal[2][1] * m.z,
                     k.normal[0][2] * m.x + k.normal[1][2] * m.y + k.normal[2][2] * m.z};
    const F32x8 len = squareRoot(v.x * v.x + v.y * v.y + v.z * v.z);
    const F32x8 inv_len = splat(1.0f) / len;
    const I32x8 nonzero = maskPositive(len);
    n = {blend(nonzero, v.x * inv_len, zero), blend(nonzero, v.y * inv_len, zero),
         blend(nonzero, v.z * inv_len, zero)};
  }
  storeFloat3x8(out.normal, n);

  if (!lighting) return;
  // Irradiance (setup.h). A light adds only where it faces the vertex: selecting e itself
  // elsewhere, not e + 0, keeps an ambient of -0 as the scalar loop does.
  Float3x8 e{splat(lighting->ambient.x), splat(lighting->ambient.y), splat(lighting->ambient.z)};
  for (const ShadeLight& light : lighting->lights) {
    const F32x8 cos_theta = negate(n.x * splat(light.direction.x) + n.y * splat(light.direction.y) +
                                   n.z * splat(light.direction.z));
    const I32x8 facing = maskPositive(cos_theta);
    e.x = blend(facing, e.x + splat(light.radiance.x) * cos_theta, e.x);
    e.y = blend(facing, e.y + splat(light.radiance.y) * cos_theta, e.y);
    e.z = blend(facing, e.z + splat(light.radiance.z) * cos_theta, e.z);
  }
  const I32x8 zero_normal = maskEqual(n.x, zero) & maskEqual(n.y, zero) & maskEqual(n.z, zero);
  const F32x8 nan = splat(std::numeric_limits<float>::quiet_NaN());
  storeFloat3x8(out.lit, {blend(zero_normal, nan, e.x), blend(zero_normal, nan, e.y),
                          blend(zero_normal, nan, e.z)});
}

#if defined(TESSERA_LANES16)
// Where a vector register holds sixteen floats (the AVX-512 variant), sixteen vertices a step:
// transformVertexBlock's operations, lane for lane and in its order, so the same bits with half
// the instructions.
struct Float3x16 {
  F32x16 x, y, z;
};

// p[0..15] (exactly 48 floats) as lanes of x, y and z.
TESSERA_LANES_INLINE Float3x16 loadFloat3x16(const float3* p) {
  F32x16 v[3];
  std::memcpy(v, p, sizeof v);
  const F32x16 x01 =
      __builtin_shufflevector(v[0], v[1], 0, 3, 6, 9, 12, 15, 18, 21, 24, 27, 30, 0, 0, 0, 0, 0);
  const F32x16 y01 =
      __builtin_shufflevector(v[0], v[1], 1, 4, 7, 10, 13, 16, 19, 22, 25, 28, 31, 0, 0, 0, 0, 0);
  const F32x16 z01 =
      __builtin_shufflevector(v[0], v[1], 2, 5, 8, 11, 14, 17, 20, 23, 26, 29, 0, 0, 0, 0, 0, 0);
  return {__builtin_shufflevector(x01, v[2], 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 17, 20, 23, 26, 29),
          __builtin_shufflevector(y01, v[2], 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 18, 21, 24, 27, 30),
          __builtin_shufflevector(z01, v[2], 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 16, 19, 22, 25, 28, 31)};
}

// Writes exactly p[0..15].
TESSERA_LANES_INLINE void storeFloat3x16(float3* p, const Float3x16& v) {
  const F32x16 xy0 =
      __builtin_shufflevector(v.x, v.y, 0, 16, 0, 1, 17, 0, 2, 18, 0, 3, 19, 0, 4, 20, 0, 5);
  const F32x16 xy1 =
      __builtin_shufflevector(v.x, v.y, 21, 0, 6, 22, 0, 7, 23, 0, 8, 24, 0, 9, 25, 0, 10, 26);
  const F32x16 xy2 =
      __builtin_shufflevector(v.x, v.y, 0, 11, 27, 0, 12, 28, 0, 13, 29, 0, 14, 30, 0, 15, 31, 0);
  const F32x16 out[3] = {
      __builtin_shufflevector(xy0, v.z, 0, 1, 16, 3, 4, 17, 6, 7, 18, 9, 10, 19, 12, 13, 20, 15),
      __builtin_shufflevector(xy1, v.z, 0, 21, 2, 3, 22, 5, 6, 23, 8, 9, 24, 11, 12, 25, 14, 15),
      __builtin_shufflevector(xy2, v.z, 26, 1, 2, 27, 4, 5, 28, 7, 8, 29, 10, 11, 30, 13, 14, 31)};
  std::memcpy(p, out, sizeof out);
}

TESSERA_LANES_INLINE I32x16 planeBit16(I32x16 outside, uint32_t bit) {
  return outside & static_cast<int32_t>(bit);
}

TESSERA_LANES_INLINE I32x16 finiteMask16(F32x16 a) {
  return (reinterpret_cast<I32x16>(a) & 0x7fffffff) <= 0x7f7fffff;
}

// transformVertexBlock for positions[0..15] (and normals[0..15], null for none), read exactly.
TESSERA_LANES_INLINE void transformVertexBlock16(const float3* positions, const float3* normals,
                                                 const VertexConstants& k,
                                                 const VertexLighting* lighting,
                                                 const VertexBlockOut& out) {
  auto s = [](F32x8 lanes) { return splat16(lane(lanes, 0)); };
  const Float3x16 p = loadFloat3x16(positions);
  F32x16 clip[4];
  for (int r = 0; r < 4; ++r)
    clip[r] = s(k.mvp[0][r]) * p.x + s(k.mvp[1][r]) * p.y + s(k.mvp[2][r]) * p.z + s(k.mvp[3][r]);
  const F32x16 x = clip[0], y = clip[1], z = clip[2], w = clip[3];
  std::memcpy(out.clip_x, &x, sizeof x);
  std::memcpy(out.clip_y, &y, sizeof y);
  std::memcpy(out.clip_z, &z, sizeof z);
  std::memcpy(out.clip_w, &w, sizeof w);

  const F32x16 neg_w = -w;
  const F32x16 gx = s(k.guard_x) * w, gy = s(k.guard_y) * w;
  const I32x16 code = planeBit16(z < neg_w, kClipNear) | planeBit16(w < z, kClipFar) |
                      planeBit16(x < neg_w, kClipLeft) | planeBit16(w < x, kClipRight) |
                      planeBit16(y < neg_w, kClipBottom) | planeBit16(w < y, kClipTop) |
                      planeBit16(x < -gx, kGuardLeft) | planeBit16(gx < x, kGuardRight) |
                      planeBit16(y < -gy, kGuardBottom) | planeBit16(gy < y, kGuardTop);
  const I32x16 all_finite = finiteMask16(x) & finiteMask16(y) & finiteMask16(z) & finiteMask16(w);
  typedef uint16_t U16x16 __attribute__((vector_size(32)));
  const U16x16 codes = __builtin_convertvector(
      all_finite ? code : I32x16{} + static_cast<int32_t>(kNonFinite), U16x16);
  std::memcpy(out.outcode, &codes, sizeof codes);

  const F32x16 half = splat16(0.5f);
  const F32x16 inv_w = splat16(1.0f) / w;
  const F32x16 wx = (x * inv_w * half + half) * s(k.width);
  const F32x16 wy = (half - y * inv_w * half) * s(k.height);
  const F32x16 subpixel = splat16(static_cast<float>(kSubpixelOne));
  const F32x16 sx = reinterpret_cast<F32x16>(roundToInt16(wx * subpixel));
  const F32x16 sy = reinterpret_cast<F32x16>(roundToInt16(wy * subpixel));
  const F32x16 sz = z * inv_w * half + half;
  // Sixteen (x, y, z, w) records: pairs, then vertices four at a time.
  const F32x16 xy_low =
      __builtin_shufflevector(sx, sy, 0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23);
  const F32x16 xy_high =
      __builtin_shufflevector(sx, sy, 8, 24, 9, 25, 10, 26, 11, 27, 12, 28, 13, 29, 14, 30, 15, 31);
  const F32x16 zw_low =
      __builtin_shufflevector(sz, inv_w, 0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23);
  const F32x16 zw_high = __builtin_shufflevector(sz, inv_w, 8, 24, 9, 25, 10, 26, 11, 27, 12, 28,
                                                 13, 29, 14, 30, 15, 31);
  const F32x16 screen[4] = {__builtin_shufflevector(xy_low, zw_low, 0, 1, 16, 17, 2, 3, 18, 19, 4,
                                                    5, 20, 21, 6, 7, 22, 23),
                            __builtin_shufflevector(xy_low, zw_low, 8, 9, 24, 25, 10, 11, 26, 27,
                                                    12, 13, 28, 29, 14, 15, 30, 31),
                            __builtin_shufflevector(xy_high, zw_high, 0, 1, 16, 17, 2, 3, 18, 19, 4,
                                                    5, 20, 21, 6, 7, 22, 23),
                            __builtin_shufflevector(xy_high, zw_high, 8, 9, 24, 25, 10, 11, 26, 27,
                                                    12, 13, 28, 29, 14, 15, 30, 31)};
  std::memcpy(out.screen, screen, sizeof screen);

  const F32x16 zero{};
  Float3x16 n{zero, zero, zero};
  if (normals) {
    const Float3x16 m = loadFloat3x16(normals);
    const Float3x16 v{s(k.normal[0][0]) * m.x + s(k.normal[1][0]) * m.y + s(k.normal[2][0]) * m.z,
                      s(k.normal[0][1]) * m.x + s(k.normal[1][1]) * m.y + s(k.normal[2][1]) * m.z,
                      s(k.normal[0][2]) * m.x + s(k.normal[1][2]) * m.y + s(k.normal[2][2]) * m.z};
    const F32x16 squared = v.x * v.x + v.y * v.y + v.z * v.z;
    F32x16 len;
    for (int l = 0; l < 16; ++l) len[l] = __builtin_sqrtf(squared[l]);  // one vector sqrt
    const F32x16 inv_len = splat16(1.0f) / len;
    const I32x16 nonzero = zero < len;
    n = {nonzero ? v.x * inv_len : zero, nonzero ? v.y * inv_len : zero,
         nonzero ? v.z * inv_len : zero};
  }
  storeFloat3x16(out.normal, n);

  if (!lighting) return;
  Float3x16 e{splat16(lighting->ambient.x), splat16(lighting->ambient.y),
              splat16(lighting->ambient.z)};
  for (const ShadeLight& light : lighting->lights) {
    const F32x16 cos_theta = -(n.x * splat16(light.direction.x) + n.y * splat16(light.direction.y) +
                               n.z * splat16(light.direction.z));
    const I32x16 facing = zero < cos_theta;
    e.x = facing ? e.x + splat16(light.radiance.x) * cos_theta : e.x;
    e.y = facing ? e.y + splat16(light.radiance.y) * cos_theta : e.y;
    e.z = facing ? e.z + splat16(light.radiance.z) * cos_theta : e.z;
  }
  const I32x16 zero_normal = (n.x == zero) & (n.y == zero) & (n.z == zero);
  const F32x16 nan = splat16(std::numeric_limits<float>::quiet_NaN());
  storeFloat3x16(out.lit,
                 {zero_normal ? nan : e.x, zero_normal ? nan : e.y, zero_normal ? nan : e.z});
}
#endif

// TransformVerticesFn (kernels.h).
void transformVerticesKernel(const Mesh& mesh, const ObjectTransforms& transforms,
                             const ViewportTransform& viewport, const VertexLighting* lighting,
                             size_t first, size_t count, VertexBuffer& out) {
  VertexConstants k;
  for (int c = 0; c < 4; ++c) {
    const float4 column = transforms.model_view_projection.col[c];
    k.mvp[c][0] = splat(column.x), k.mvp[c][1] = splat(column.y);
    k.mvp[c][2] = splat(column.z), k.mvp[c][3] = splat(column.w);
  }
  for (int c = 0; c < 3; ++c) {
    const float3 column = transforms.normal_matrix.col[c];
    k.normal[c][0] = splat(column.x), k.normal[c][1] = splat(column.y);
    k.normal[c][2] = splat(column.z);
  }
  k.guard_x = splat(viewport.guard.x_factor), k.guard_y = splat(viewport.guard.y_factor);
  k.width = splat(viewport.width), k.height = splat(viewport.height);

  const size_t vertex_count = mesh.positions.size();
  const bool has_normals = mesh.normals.size() == vertex_count;
  const float3* positions = mesh.positions.data();
  const float3* normals = has_normals ? mesh.normals.data() : nullptr;
  const size_t end = first + count;
  size_t i = first;
#if defined(TESSERA_LANES16)
  // Sixteen at a time where they fit (these read exactly their sixteen vertices).
  for (; i + 16 <= end; i += 16) {
    const size_t o = transforms.vertex_base + i;
    transformVertexBlock16(
        positions + i, normals ? normals + i : nullptr, k, lighting,
        {&out.clip_x[o], &out.clip_y[o], &out.clip_z[o], &out.clip_w[o], &out.outcode[o],
         &out.screen[o], &out.normal[o], lighting ? &out.lit[o] : nullptr});
  }
#endif
  // Whole blocks straight from the mesh while the 16-byte load of the eighth vertex stays inside
  // it (i + 8 < vertex_count).
  for (; i + 8 <= end && i + 8 < vertex_count; i += 8) {
    const size_t o = transforms.vertex_base + i;
    transformVertexBlock(
        positions + i, normals ? normals + i : nullptr, k, lighting,
        {&out.clip_x[o], &out.clip_y[o], &out.clip_z[o], &out.clip_w[o], &out.outcode[o],
         &out.screen[o], &out.normal[o], lighting ? &out.lit[o] : nullptr});
  }
  // The rest (at most eight vertices, normally fewer) through a staging block, so that it takes
  // the same code path; the padding lanes compute on zeros and are dropped.
  if (i == end) return;
  const size_t rest = end - i;
  float3 p[9] = {}, m[9] = {};  // one spare vertex for the over-read
  std::copy_n(positions + i, rest, p);
  if (normals) std::copy_n(normals + i, rest, m);
  float clip_x[8], clip_y[8], clip_z[8], clip_w[8];
  uint16_t outcode[8];
  ScreenVertex screen[8];
  float3 normal[8], lit[8];
  transformVertexBlock(p, normals ? m : nullptr, k, lighting,
                       {clip_x, clip_y, clip_z, clip_w, outcode, screen, normal, lit});
  const size_t o = transforms.vertex_base + i;
  std::copy_n(clip_x, rest, &out.clip_x[o]);
  std::copy_n(clip_y, rest, &out.clip_y[o]);
  std::copy_n(clip_z, rest, &out.clip_z[o]);
  std::copy_n(clip_w, rest, &out.clip_w[o]);
  std::copy_n(outcode, rest, &out.outcode[o]);
  std::copy_n(screen, rest, &out.screen[o]);
  std::copy_n(normal, rest, &out.normal[o]);
  if (lighting) std::copy_n(lit, rest, &out.lit[o]);
}

}  // namespace
}  // namespace tessera::render
