// Unit quaternions for rotation. Header-only.
#pragma once

#include <cmath>

#include <tessera/math/mat.h>
#include <tessera/math/vec.h>

namespace tessera {

struct quat {
  float x = 0, y = 0, z = 0, w = 1;  // identity by default

  static quat fromAxisAngle(float3 axis, float angle_radians) {
    float3 n = normalize(axis);
    float s = std::sin(angle_radians * 0.5f);
    return {n.x * s, n.y * s, n.z * s, std::cos(angle_radians * 0.5f)};
  }
};

// Hamilton product: (a * b) rotates by b first, then by a.
constexpr quat operator*(quat a, quat b) {
  return {
      a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
      a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}

inline quat normalize(quat q) {
  float len = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (len == 0.0f) return {};
  float s = 1.0f / len;
  return {q.x * s, q.y * s, q.z * s, q.w * s};
}

// Euler angles in radians, composed as Rz * Ry * Rx: X is applied first, then Y, then Z.
inline quat fromEuler(float3 angles) {
  return quat::fromAxisAngle({0, 0, 1}, angles.z) * quat::fromAxisAngle({0, 1, 0}, angles.y) *
         quat::fromAxisAngle({1, 0, 0}, angles.x);
}

constexpr float3x3 toMatrix3(quat q) {
  float xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
  float xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
  float wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
  float3x3 m;
  m.col[0] = {1 - 2 * (yy + zz), 2 * (xy + wz), 2 * (xz - wy)};
  m.col[1] = {2 * (xy - wz), 1 - 2 * (xx + zz), 2 * (yz + wx)};
  m.col[2] = {2 * (xz + wy), 2 * (yz - wx), 1 - 2 * (xx + yy)};
  return m;
}

constexpr float4x4 toMatrix4(quat q) {
  float3x3 r = toMatrix3(q);
  float4x4 m;
  for (int c = 0; c < 3; ++c) m.col[c] = float4{r.col[c], 0.0f};
  return m;
}

constexpr float3 rotate(quat q, float3 v) {
  return toMatrix3(q) * v;
}

}  // namespace tessera
