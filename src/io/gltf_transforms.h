// Small maths for glTF node transforms, in double: node matrices compose over deep hierarchies.
// Private to tessera_io.
#pragma once

#include <array>
#include <cmath>
#include <limits>

#include <tessera/math/vec.h>

namespace tessera::io::gltf {

struct Matrix {
  std::array<double, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // column-major
  double at(int row, int column) const { return m[static_cast<size_t>(column * 4 + row)]; }
  double& at(int row, int column) { return m[static_cast<size_t>(column * 4 + row)]; }
};

inline Matrix operator*(const Matrix& a, const Matrix& b) {
  Matrix r;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      double sum = 0;
      for (int k = 0; k < 4; ++k) sum += a.at(row, k) * b.at(k, c);
      r.at(row, c) = sum;
    }
  return r;
}

inline double determinant3(const Matrix& a) {
  return a.at(0, 0) * (a.at(1, 1) * a.at(2, 2) - a.at(1, 2) * a.at(2, 1)) -
         a.at(0, 1) * (a.at(1, 0) * a.at(2, 2) - a.at(1, 2) * a.at(2, 0)) +
         a.at(0, 2) * (a.at(1, 0) * a.at(2, 1) - a.at(1, 1) * a.at(2, 0));
}

// The cofactor matrix of the upper 3x3, det * inverse transpose: it maps normals as the inverse
// transpose does, up to scale, and still works for a singular matrix.
inline std::array<double, 9> normalMatrix(const Matrix& a) {
  auto cofactor = [&](int r, int c) {
    const int r0 = r == 0 ? 1 : 0, r1 = r == 2 ? 1 : 2;
    const int c0 = c == 0 ? 1 : 0, c1 = c == 2 ? 1 : 2;
    const double minor = a.at(r0, c0) * a.at(r1, c1) - a.at(r0, c1) * a.at(r1, c0);
    return ((r + c) % 2 == 0) ? minor : -minor;
  };
  // A mirroring matrix has a negative determinant: the sign keeps normals pointing outward.
  const double sign = determinant3(a) < 0 ? -1.0 : 1.0;
  std::array<double, 9> n{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) n[static_cast<size_t>(c * 3 + r)] = sign * cofactor(r, c);
  return n;
}

inline float toFloat(double value) {
  // Beyond float's range becomes infinite rather than undefined.
  if (std::isnan(value)) return std::numeric_limits<float>::quiet_NaN();
  constexpr double kMax = std::numeric_limits<float>::max();
  if (value > kMax) return std::numeric_limits<float>::infinity();
  if (value < -kMax) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);
}

inline float3 transformPoint(const Matrix& a, float3 p) {
  double out[3];
  for (int r = 0; r < 3; ++r)
    out[r] = a.at(r, 0) * p.x + a.at(r, 1) * p.y + a.at(r, 2) * p.z + a.at(r, 3);
  return {toFloat(out[0]), toFloat(out[1]), toFloat(out[2])};
}

inline float3 transformNormal(const std::array<double, 9>& n, float3 v) {
  double out[3];
  for (int r = 0; r < 3; ++r)
    out[r] = n[static_cast<size_t>(r)] * v.x + n[static_cast<size_t>(3 + r)] * v.y +
             n[static_cast<size_t>(6 + r)] * v.z;
  const double len = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
  if (!(len > 0) || !std::isfinite(len)) return {0, 0, 0};
  return {toFloat(out[0] / len), toFloat(out[1] / len), toFloat(out[2] / len)};
}

}  // namespace tessera::io::gltf
