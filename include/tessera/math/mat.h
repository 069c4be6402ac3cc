// 3x3 and 4x4 matrices, column-major storage, column-vector convention: v' = M * v,
// composed right to left (MVP = P * V * M). Header-only.
#pragma once

#include <cmath>
#include <type_traits>

#include <tessera/math/vec.h>

namespace tessera {

struct float3x3 {
  float3 col[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};  // identity by default

  constexpr float operator()(int row, int column) const { return col[column][row]; }
  constexpr float& operator()(int row, int column) { return col[column][row]; }
};

struct float4x4 {
  float4 col[4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};  // identity

  constexpr float operator()(int row, int column) const { return col[column][row]; }
  constexpr float& operator()(int row, int column) { return col[column][row]; }
  static constexpr float4x4 identity() { return {}; }
};

constexpr float3 operator*(const float3x3& m, float3 v) {
  return m.col[0] * v.x + m.col[1] * v.y + m.col[2] * v.z;
}
constexpr float4 operator*(const float4x4& m, float4 v) {
  return m.col[0] * v.x + m.col[1] * v.y + m.col[2] * v.z + m.col[3] * v.w;
}
constexpr float3x3 operator*(const float3x3& a, const float3x3& b) {
  float3x3 r;
  for (int c = 0; c < 3; ++c) r.col[c] = a * b.col[c];
  return r;
}
constexpr float4x4 operator*(const float4x4& a, const float4x4& b) {
  float4x4 r;
  if (std::is_constant_evaluated()) {
    for (int c = 0; c < 4; ++c) r.col[c] = a * b.col[c];
    return r;
  }
  // Four lanes at a time (a scene of 10,000 instances makes two products each a frame): the
  // same products and sums in the same order as `a * b.col[c]`, so the same bits.
  typedef float Lanes __attribute__((vector_size(16)));
  Lanes ac[4];
  __builtin_memcpy(ac, a.col, sizeof ac);
  for (int c = 0; c < 4; ++c) {
    const float4 v = b.col[c];
    const Lanes column = ac[0] * v.x + ac[1] * v.y + ac[2] * v.z + ac[3] * v.w;
    __builtin_memcpy(static_cast<void*>(&r.col[c]), &column, sizeof column);
  }
  return r;
}

constexpr float3x3 transpose(const float3x3& m) {
  float3x3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = m(j, i);
  return r;
}
constexpr float4x4 transpose(const float4x4& m) {
  float4x4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r(i, j) = m(j, i);
  return r;
}

constexpr float determinant(const float3x3& m) {
  return dot(m.col[0], cross(m.col[1], m.col[2]));
}

// Inverse of a 3x3 matrix; a singular matrix yields the zero matrix.
constexpr float3x3 inverse(const float3x3& m) {
  float det = determinant(m);
  float3x3 r;
  if (det == 0.0f) {
    r.col[0] = r.col[1] = r.col[2] = float3{};
    return r;
  }
  // Rows of the inverse are the cross products of the columns, divided by the determinant.
  float3 r0 = cross(m.col[1], m.col[2]) / det;
  float3 r1 = cross(m.col[2], m.col[0]) / det;
  float3 r2 = cross(m.col[0], m.col[1]) / det;
  return transpose(float3x3{{r0, r1, r2}});
}

constexpr float3x3 upper3x3(const float4x4& m) {
  return float3x3{{m.col[0].xyz(), m.col[1].xyz(), m.col[2].xyz()}};
}

// General 4x4 inverse by cofactors; a singular matrix yields the zero matrix.
inline float4x4 inverse(const float4x4& m) {
  const float* a = &m.col[0].x;
  float inv[16];
  inv[0] = a[5] * a[10] * a[15] - a[5] * a[11] * a[14] - a[9] * a[6] * a[15] + a[9] * a[7] * a[14] +
           a[13] * a[6] * a[11] - a[13] * a[7] * a[10];
  inv[4] = -a[4] * a[10] * a[15] + a[4] * a[11] * a[14] + a[8] * a[6] * a[15] -
           a[8] * a[7] * a[14] - a[12] * a[6] * a[11] + a[12] * a[7] * a[10];
  inv[8] = a[4] * a[9] * a[15] - a[4] * a[11] * a[13] - a[8] * a[5] * a[15] + a[8] * a[7] * a[13] +
           a[12] * a[5] * a[11] - a[12] * a[7] * a[9];
  inv[12] = -a[4] * a[9] * a[14] + a[4] * a[10] * a[13] + a[8] * a[5] * a[14] -
            a[8] * a[6] * a[13] - a[12] * a[5] * a[10] + a[12] * a[6] * a[9];
  inv[1] = -a[1] * a[10] * a[15] + a[1] * a[11] * a[14] + a[9] * a[2] * a[15] -
           a[9] * a[3] * a[14] - a[13] * a[2] * a[11] + a[13] * a[3] * a[10];
  inv[5] = a[0] * a[10] * a[15] - a[0] * a[11] * a[14] - a[8] * a[2] * a[15] + a[8] * a[3] * a[14] +
           a[12] * a[2] * a[11] - a[12] * a[3] * a[10];
  inv[9] = -a[0] * a[9] * a[15] + a[0] * a[11] * a[13] + a[8] * a[1] * a[15] - a[8] * a[3] * a[13] -
           a[12] * a[1] * a[11] + a[12] * a[3] * a[9];
  inv[13] = a[0] * a[9] * a[14] - a[0] * a[10] * a[13] - a[8] * a[1] * a[14] + a[8] * a[2] * a[13] +
            a[12] * a[1] * a[10] - a[12] * a[2] * a[9];
  inv[2] = a[1] * a[6] * a[15] - a[1] * a[7] * a[14] - a[5] * a[2] * a[15] + a[5] * a[3] * a[14] +
           a[13] * a[2] * a[7] - a[13] * a[3] * a[6];
  inv[6] = -a[0] * a[6] * a[15] + a[0] * a[7] * a[14] + a[4] * a[2] * a[15] - a[4] * a[3] * a[14] -
           a[12] * a[2] * a[7] + a[12] * a[3] * a[6];
  inv[10] = a[0] * a[5] * a[15] - a[0] * a[7] * a[13] - a[4] * a[1] * a[15] + a[4] * a[3] * a[13] +
            a[12] * a[1] * a[7] - a[12] * a[3] * a[5];
  inv[14] = -a[0] * a[5] * a[14] + a[0] * a[6] * a[13] + a[4] * a[1] * a[14] - a[4] * a[2] * a[13] -
            a[12] * a[1] * a[6] + a[12] * a[2] * a[5];
  inv[3] = -a[1] * a[6] * a[11] + a[1] * a[7] * a[10] + a[5] * a[2] * a[11] - a[5] * a[3] * a[10] -
           a[9] * a[2] * a[7] + a[9] * a[3] * a[6];
  inv[7] = a[0] * a[6] * a[11] - a[0] * a[7] * a[10] - a[4] * a[2] * a[11] + a[4] * a[3] * a[10] +
           a[8] * a[2] * a[7] - a[8] * a[3] * a[6];
  inv[11] = -a[0] * a[5] * a[11] + a[0] * a[7] * a[9] + a[4] * a[1] * a[11] - a[4] * a[3] * a[9] -
            a[8] * a[1] * a[7] + a[8] * a[3] * a[5];
  inv[15] = a[0] * a[5] * a[10] - a[0] * a[6] * a[9] - a[4] * a[1] * a[10] + a[4] * a[2] * a[9] +
            a[8] * a[1] * a[6] - a[8] * a[2] * a[5];
  float det = a[0] * inv[0] + a[1] * inv[4] + a[2] * inv[8] + a[3] * inv[12];
  float4x4 r;
  float* out = &r.col[0].x;
  float scale = det != 0.0f ? 1.0f / det : 0.0f;
  for (int i = 0; i < 16; ++i) out[i] = inv[i] * scale;
  return r;
}

// The matrix that transforms normals: inverse transpose of the upper 3x3.
inline float3x3 normalMatrix(const float4x4& model) {
  return transpose(inverse(upper3x3(model)));
}

constexpr float4x4 translation(float3 t) {
  float4x4 m;
  m.col[3] = float4{t, 1.0f};
  return m;
}
constexpr float4x4 scaling(float3 s) {
  float4x4 m;
  m(0, 0) = s.x;
  m(1, 1) = s.y;
  m(2, 2) = s.z;
  return m;
}

}  // namespace tessera
