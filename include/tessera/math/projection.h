// Camera and projection matrices, OpenGL conventions: right-handed, camera looks down -Z.
// Header-only.
#pragma once

#include <cmath>

#include <tessera/math/mat.h>
#include <tessera/math/vec.h>

namespace tessera {

// View matrix of a camera at `eye` looking at `target`. When `up` is parallel to the view
// direction another up vector is chosen, so the result is always a valid rotation.
inline float4x4 lookAt(float3 eye, float3 target, float3 up) {
  float3 f = normalize(target - eye);
  if (length(f) == 0.0f) f = {0, 0, -1};
  float3 s = cross(f, up);
  if (length(s) < 1e-6f * std::max(length(up), 1e-30f)) {
    // Looking along the up vector: pick the world axis least aligned with the view direction.
    float3 alt = std::fabs(f.y) < 0.9f ? float3{0, 1, 0} : float3{0, 0, 1};
    s = cross(f, alt);
  }
  s = normalize(s);
  float3 u = cross(s, f);
  float4x4 m;
  m(0, 0) = s.x, m(0, 1) = s.y, m(0, 2) = s.z, m(0, 3) = -dot(s, eye);
  m(1, 0) = u.x, m(1, 1) = u.y, m(1, 2) = u.z, m(1, 3) = -dot(u, eye);
  m(2, 0) = -f.x, m(2, 1) = -f.y, m(2, 2) = -f.z, m(2, 3) = dot(f, eye);
  return m;
}

// OpenGL perspective: view z in [-near, -far] maps to NDC z in [-1, 1]. fov_y in radians.
inline float4x4 perspective(float fov_y, float aspect, float near_z, float far_z) {
  float f = 1.0f / std::tan(fov_y * 0.5f);
  float4x4 m;
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = (far_z + near_z) / (near_z - far_z);
  m(2, 3) = 2.0f * far_z * near_z / (near_z - far_z);
  m(3, 2) = -1.0f;
  m(3, 3) = 0.0f;
  return m;
}

// OpenGL orthographic projection, symmetric about the view axis: x in [-half_width, half_width]
// and y in [-half_height, half_height] map to NDC [-1, 1], view z in [-near, -far] to [-1, 1];
// w stays 1.
inline float4x4 orthographic(float half_width, float half_height, float near_z, float far_z) {
  float4x4 m;
  m(0, 0) = 1.0f / half_width;
  m(1, 1) = 1.0f / half_height;
  m(2, 2) = 2.0f / (near_z - far_z);
  m(2, 3) = (far_z + near_z) / (near_z - far_z);
  return m;
}

// Zero-to-one perspective (Vulkan/D3D depth range): view z in [-near, -far] maps to NDC z in
// [0, 1]. Y is not flipped: the viewport does that, as for the OpenGL form.
inline float4x4 perspectiveZeroToOne(float fov_y, float aspect, float near_z, float far_z) {
  float f = 1.0f / std::tan(fov_y * 0.5f);
  float4x4 m;
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = far_z / (near_z - far_z);
  m(2, 3) = far_z * near_z / (near_z - far_z);
  m(3, 2) = -1.0f;
  m(3, 3) = 0.0f;
  return m;
}

// Maps NDC (x, y in [-1, 1], z in [-1, 1]) to window coordinates: pixel (0, 0) top-left, y down,
// z in [0, 1] with 0 at the near plane.
struct Viewport {
  float width = 1, height = 1;

  constexpr float3 toWindow(float3 ndc) const {
    return {(ndc.x * 0.5f + 0.5f) * width, (0.5f - ndc.y * 0.5f) * height, ndc.z * 0.5f + 0.5f};
  }
  // The same mapping as a matrix (for the GL form).
  constexpr float4x4 matrix() const {
    float4x4 m;
    m(0, 0) = 0.5f * width, m(0, 3) = 0.5f * width;
    m(1, 1) = -0.5f * height, m(1, 3) = 0.5f * height;
    m(2, 2) = 0.5f, m(2, 3) = 0.5f;
    return m;
  }
};

}  // namespace tessera
