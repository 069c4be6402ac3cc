// Small fixed-size vectors: float2, float3, float4, int2. Header-only.
#pragma once

#include <algorithm>
#include <cmath>

namespace tessera {

struct float2 {
  float x = 0, y = 0;
  constexpr float2() = default;
  constexpr float2(float x_, float y_) : x(x_), y(y_) {}
  constexpr float operator[](int i) const { return i == 0 ? x : y; }
};

struct float3 {
  float x = 0, y = 0, z = 0;
  constexpr float3() = default;
  constexpr float3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  constexpr explicit float3(float s) : x(s), y(s), z(s) {}
  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};

struct float4 {
  float x = 0, y = 0, z = 0, w = 0;
  constexpr float4() = default;
  constexpr float4(float x_, float y_, float z_, float w_) : x(x_), y(y_), z(z_), w(w_) {}
  constexpr float4(float3 v, float w_) : x(v.x), y(v.y), z(v.z), w(w_) {}
  constexpr float3 xyz() const { return {x, y, z}; }
  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : (i == 2 ? z : w)); }
  constexpr float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : (i == 2 ? z : w)); }
};

struct int2 {
  int x = 0, y = 0;
};

// float2
constexpr float2 operator+(float2 a, float2 b) {
  return {a.x + b.x, a.y + b.y};
}
constexpr float2 operator-(float2 a, float2 b) {
  return {a.x - b.x, a.y - b.y};
}
constexpr float2 operator*(float2 a, float s) {
  return {a.x * s, a.y * s};
}
constexpr float2 operator*(float s, float2 a) {
  return a * s;
}

// float3
constexpr float3 operator+(float3 a, float3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
constexpr float3 operator-(float3 a, float3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
constexpr float3 operator-(float3 a) {
  return {-a.x, -a.y, -a.z};
}
constexpr float3 operator*(float3 a, float3 b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
constexpr float3 operator*(float3 a, float s) {
  return {a.x * s, a.y * s, a.z * s};
}
constexpr float3 operator*(float s, float3 a) {
  return a * s;
}
constexpr float3 operator/(float3 a, float s) {
  return {a.x / s, a.y / s, a.z / s};
}
constexpr float3& operator+=(float3& a, float3 b) {
  return a = a + b;
}
constexpr float3& operator-=(float3& a, float3 b) {
  return a = a - b;
}
constexpr float3& operator*=(float3& a, float s) {
  return a = a * s;
}
constexpr bool operator==(float3 a, float3 b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

constexpr float dot(float3 a, float3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr float3 cross(float3 a, float3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(float3 a) {
  return std::sqrt(dot(a, a));
}
// Returns the zero vector for a zero-length input rather than NaNs.
inline float3 normalize(float3 a) {
  float len = length(a);
  return len > 0.0f ? a * (1.0f / len) : float3{};
}
constexpr float3 min(float3 a, float3 b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
constexpr float3 max(float3 a, float3 b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
inline bool isFinite(float3 a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

// float4
constexpr float4 operator+(float4 a, float4 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w};
}
constexpr float4 operator-(float4 a, float4 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z, a.w - b.w};
}
constexpr float4 operator*(float4 a, float4 b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z, a.w * b.w};
}
constexpr float4 operator*(float4 a, float s) {
  return {a.x * s, a.y * s, a.z * s, a.w * s};
}
constexpr float4 operator*(float s, float4 a) {
  return a * s;
}
constexpr float dot(float4 a, float4 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w;
}
constexpr bool operator==(float4 a, float4 b) {
  return a.x == b.x && a.y == b.y && a.z == b.z && a.w == b.w;
}

constexpr float lerp(float a, float b, float t) {
  return a + (b - a) * t;
}
constexpr float3 lerp(float3 a, float3 b, float t) {
  return a + (b - a) * t;
}
constexpr float4 lerp(float4 a, float4 b, float t) {
  return a + (b - a) * t;
}

constexpr float kPi = 3.14159265358979323846f;
constexpr float radians(float degrees) {
  return degrees * (kPi / 180.0f);
}

}  // namespace tessera
