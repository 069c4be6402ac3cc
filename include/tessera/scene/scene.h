// The scene: objects (mesh + materials + transform), lights, camera and line lists.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <tessera/math/math.h>
#include <tessera/scene/environment.h>
#include <tessera/scene/material.h>
#include <tessera/scene/mesh.h>
#include <tessera/scene/texture.h>

namespace tessera {

enum class Shading : uint8_t {
  kFlat,     // one face normal per triangle
  kGouraud,  // lighting per vertex, interpolated
  kPhong,    // normals interpolated, lighting per pixel
  kUnlit,    // albedo only
  // glTF's metallic-roughness BRDF per pixel (render/pbr.h): every map and factor of the Material,
  // view-dependent. The Vulkan backends draw it too (docs/vulkan-features.md).
  kPbr,
};

enum class CullMode : uint8_t { kBack, kFront, kNone };

struct Transform {
  float3 translation{0, 0, 0};
  quat rotation{};
  float3 scale{1, 1, 1};
  // Applied before T * R * S: an instance's world matrix from a scene graph (graph.h), which the
  // TRS above then moves as a whole (a turntable). Unset: the identity.
  std::optional<float4x4> base;

  // T * R * S, in closed form: the rotation's columns scaled, the translation beside them (the
  // same bits as the three 4x4 products, which add and multiply by nothing but 0 and 1).
  float4x4 trs() const {
    const float3x3 r = toMatrix3(rotation);
    float4x4 m;
    m.col[0] = float4{r.col[0] * scale.x, 0.0f};
    m.col[1] = float4{r.col[1] * scale.y, 0.0f};
    m.col[2] = float4{r.col[2] * scale.z, 0.0f};
    m.col[3] = float4{translation, 1.0f};
    return m;
  }
  // The same T, R and S as `other` (a turntable turns every instance alike).
  bool sameTrs(const Transform& other) const {
    return translation == other.translation && rotation.x == other.rotation.x &&
           rotation.y == other.rotation.y && rotation.z == other.rotation.z &&
           rotation.w == other.rotation.w && scale == other.scale;
  }

  // T * R * S * base
  float4x4 matrix() const { return withBase(trs()); }
  // `trs` (this transform's trs()) times base.
  float4x4 withBase(const float4x4& trs) const { return base ? trs * *base : trs; }
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

// A punctual light, as glTF's KHR_lights_punctual defines it, in world space.
//
// Units (the extension's): `intensity` is in lux for a directional light and in candela for point
// and spot lights. tessera's exposure is fixed: a surface's linear colour is albedo x irradiance,
// where irradiance is in lux with no 1/pi, so a white directional light of intensity 1 shining
// straight onto a surface gives the surface its albedo. A point or spot light at distance d gives
// color * intensity / d^2 (the inverse-square law), times the range window and the cone:
//   range > 0:  clamp(1 - (d / range)^4, 0, 1)  (the extension's recommended window); 0: none
//   spot:       t = clamp((cos(angle to the axis) - cos(outer)) / max(0.001, cos(inner) -
//               cos(outer)), 0, 1), times t (the extension's smooth angular falloff, squared)
// Every light contributes color * intensity * attenuation * max(0, cos(incidence)), summed, plus
// Scene::ambient. Lights are the same on every backend and every shading mode: flat lights the
// face at its centroid, Gouraud each vertex, Phong each pixel.
enum class LightType : uint8_t { kDirectional, kPoint, kSpot };

struct Light {
  // Directional and spot: the direction the light travels (from the light towards the scene; for
  // glTF, the node's -Z). Ignored for point lights. Unit length.
  float3 direction{0, 0, -1};
  float3 color{1, 1, 1};  // linear RGB, multiplied by intensity
  LightType type = LightType::kDirectional;
  float3 position{0, 0, 0};       // point and spot: world position
  float intensity = 1.0f;         // lux (directional) or candela (point, spot)
  float range = 0.0f;             // point and spot: 0 = infinite
  float inner_cone = 0.0f;        // spot: radians, 0 <= inner < outer <= pi / 2
  float outer_cone = 0.7853982f;  // spot: radians (the extension's default, pi / 4)

  static Light directional(float3 direction, float3 color, float intensity = 1.0f) {
    return {direction, color, LightType::kDirectional, {}, intensity};
  }
  static Light point(float3 position, float3 color, float intensity, float range = 0.0f) {
    return {{0, 0, -1}, color, LightType::kPoint, position, intensity, range};
  }
  static Light spot(float3 position, float3 direction, float3 color, float intensity,
                    float inner_cone, float outer_cone, float range = 0.0f) {
    return {direction, color, LightType::kSpot, position, intensity, range, inner_cone, outer_cone};
  }
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

// World-space points (a point cloud, a mesh's vertices without faces): positions[i] in colors[i]
// when `colors` has one per position, else all in the scene's point colour
// (RenderOptions::points). Drawn by the point pass (render/point_pass.h) after the triangles,
// depth-tested and writing depth.
struct PointList {
  std::vector<float3> positions;
  // Empty, or one per position: packed sRGB RGBA8 (R in the low byte, alpha 255; packSrgba8 of a
  // linear colour), as point clouds carry 8-bit colours: the point pass draws them without
  // converting 10 million colours a frame, and they take a third of the memory of linear floats.
  std::vector<uint32_t> colors;

  size_t size() const { return positions.size(); }
  bool empty() const { return positions.empty(); }
};

// The display transform of the shaded colours, before the sRGB encode (--tone-mapping,
// src/render/tone.h): none clips at 1; ACES is Stephen Hill's fit of the ACES RRT and sRGB ODT;
// Khronos PBR Neutral keeps base colours as authored up to 0.76 and compresses the highlights.
enum class ToneMapping : uint8_t { kNone, kAces, kPbrNeutral };

struct Scene {
  std::vector<Object> objects;
  std::vector<Light> lights;
  float3 ambient{0.15f, 0.15f, 0.15f};  // linear irradiance added to every light (see Light)
  Camera camera;
  float4 background{0.0f, 0.0f, 0.0f, 1.0f};  // linear RGBA
  // Image-based light around the scene (--hdri), prepared once per image; null: none. With
  // environment_background the image replaces `background` behind the triangles, seen along
  // each pixel's view ray (compositeEnvironment).
  std::shared_ptr<const Environment> environment;
  bool environment_background = false;
  // World directions into the environment image's frame (whose up is +Y): a model with another up
  // axis sees its sky above it.
  float3x3 world_to_environment;  // identity unless set
  // Applied to every shaded surface and to the environment background, not to the plain
  // background colour, lines or points (display colours already).
  ToneMapping tone_mapping = ToneMapping::kNone;
  float exposure = 0.0f;  // stops: the shaded radiance is scaled by 2^exposure first
  LineList lines;
  PointList points;
  bool show_world_axes = false;
  float world_axes_length = 1.0f;

  size_t triangleCount() const;
  // World-space bounds of every object's finite vertices, the points and the line end points.
  Bounds bounds() const;
};

// A camera that frames `bounds` from `direction` (pointing from the model to the camera),
// with near and far fitted to the bounds.
Camera frameBounds(const Bounds& bounds, float3 direction, float3 up, float fov_y_degrees,
                   float aspect);

}  // namespace tessera
