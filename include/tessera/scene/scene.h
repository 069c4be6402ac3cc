// The scene: objects (mesh + materials + transform), lights, camera and line lists.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <tessera/math/math.h>
#include <tessera/scene/material.h>
#include <tessera/scene/mesh.h>
#include <tessera/scene/texture.h>

namespace tessera {

enum class Shading : uint8_t {
  kFlat,     // one face normal per triangle
  kGouraud,  // lighting per vertex, interpolated
  kPhong,    // normals interpolated, lighting per pixel
  kUnlit,    // albedo only
};

enum class CullMode : uint8_t { kBack, kFront, kNone };

struct Transform {
  float3 translation{0, 0, 0};
  quat rotation{};
  float3 scale{1, 1, 1};
  // Applied before T * R * S: an instance's world matrix from a scene graph (graph.h), which the
  // TRS above then moves as a whole (a turntable). Unset: the identity.
  std::optional<float4x4> base;

  // T * R * S * base
  float4x4 matrix() const {
    const float4x4 trs = tessera::translation(translation) * toMatrix4(rotation) * scaling(scale);
    return base ? trs * *base : trs;
  }
};

struct MeshClusters;  // clusters.h

struct Object {
  std::shared_ptr<const Mesh> mesh;
  MaterialList materials{Material{}};  // at least one; shared by the instances of a mesh
  Transform transform;
  // The mesh's clusters (clusters.h) for frustum and back-face culling of parts of it; built once
  // per mesh and shared by its instances. Unset, or built for other counts: the object is culled
  // whole by the bounds of its vertices, or not at all.
  std::shared_ptr<const MeshClusters> clusters;
  Shading shading = Shading::kFlat;
  CullMode cull = CullMode::kBack;
  bool show_axes = false;    // draw the object's local X/Y/Z axes (red, green, blue)
  float axes_length = 1.0f;  // their length, in the object's own units
};

// Light travelling along `direction` (world space, from the light towards the scene).
struct DirectionalLight {
  float3 direction{0, 0, -1};
  float3 color{1, 1, 1};  // linear radiance
};

struct Camera {
  float3 position{0, 0, 5};
  float3 target{0, 0, 0};
  float3 up{0, 1, 0};
  float fov_y_degrees = 50.0f;
  float near_z = 0.1f;
  float far_z = 100.0f;
  // A parallel projection instead: `ortho_half_height` units above and below the view axis
  // (glTF's ymag), as wide as the image's aspect makes it; fov_y_degrees is then unused. Near and
  // far are as for the perspective camera (distances along the view axis; near may be 0).
  bool orthographic = false;
  float ortho_half_height = 1.0f;

  // When set, these replace the matrices built from the fields above (custom projections,
  // tests that place vertices directly in clip space).
  std::optional<float4x4> view_override;
  std::optional<float4x4> projection_override;

  float4x4 view() const { return view_override ? *view_override : lookAt(position, target, up); }
  float4x4 projection(float aspect) const {
    if (projection_override) return *projection_override;
    if (orthographic)
      return tessera::orthographic(ortho_half_height * aspect, ortho_half_height, near_z, far_z);
    return perspective(radians(fov_y_degrees), aspect, near_z, far_z);
  }
};

// World-space line segments: points[2i] to points[2i+1] in colors[i] (linear RGB).
struct LineList {
  std::vector<float3> points;
  std::vector<float3> colors;

  void add(float3 a, float3 b, float3 color) {
    points.push_back(a);
    points.push_back(b);
    colors.push_back(color);
  }
};

struct Scene {
  std::vector<Object> objects;
  std::vector<DirectionalLight> lights;
  float3 ambient{0.15f, 0.15f, 0.15f};
  Camera camera;
  float4 background{0.0f, 0.0f, 0.0f, 1.0f};  // linear RGBA
  LineList lines;
  bool show_world_axes = false;
  float world_axes_length = 1.0f;

  size_t triangleCount() const;
  // World-space bounds of every object's finite vertices.
  Bounds bounds() const;
};

// A camera that frames `bounds` from `direction` (pointing from the model to the camera),
// with near and far fitted to the bounds.
Camera frameBounds(const Bounds& bounds, float3 direction, float3 up, float fov_y_degrees,
                   float aspect);

}  // namespace tessera
