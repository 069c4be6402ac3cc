// The scene's lights as the shading reads them (tessera/scene/scene.h: Light): radiance and the
// spot cone's constants computed once per frame, so that no pixel takes a cosine. One scalar
// irradiance here (setup: flat faces, Gouraud vertices); the eight-lane one for Phong pixels
// (shade_lanes.h) does the same float operations in the same order, lane by lane.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <tessera/math/mat.h>
#include <tessera/math/vec.h>
#include <tessera/scene/scene.h>

#include "render/tone.h"

namespace tessera::render {

class ShadowMaps;  // shadow_map.h
// ShadowMaps::visibility, for the kernels (which then need not see shadow_map.h): compiled once.
float shadowVisibility(const ShadowMaps& maps, int shadow, float3 p, float3 n);

struct ShadeLight {
  LightType type;
  float3 direction;  // directional, spot: unit, the way the light travels
  float3 radiance;   // color * intensity
  float3 position;   // point, spot
  float inv_range4;  // 1 / range^4; 0: no range window
  // Spot: t = clamp(dot(direction, -l) * spot_scale + spot_offset, 0, 1), attenuation t * t
  // (KHR_lights_punctual's recommended form). Point: scale 0, offset 1.
  float spot_scale, spot_offset;
  int shadow = -1;  // this light's maps in LightRig::shadows (ShadowMaps::visibility); -1: none
};

// The spot's cone constants, as KHR_lights_punctual's implementation note writes them.
inline void spotConstants(float inner_cone, float outer_cone, float& scale, float& offset) {
  const float cos_outer = std::cos(outer_cone);
  scale = 1.0f / std::max(0.001f, std::cos(inner_cone) - cos_outer);
  offset = -cos_outer * scale;
}

inline ShadeLight shadeLight(const Light& light) {
  ShadeLight s{
      light.type, light.direction, light.color * light.intensity, light.position, 0.0f, 0.0f, 1.0f};
  if (light.type != LightType::kDirectional && light.range > 0.0f) {
    const float r2 = light.range * light.range;
    s.inv_range4 = 1.0f / (r2 * r2);
  }
  if (light.type == LightType::kSpot)
    spotConstants(light.inner_cone, light.outer_cone, s.spot_scale, s.spot_offset);
  return s;
}

// Reused frame to frame: preparing allocates nothing once the vector has grown to the count.
struct LightRig {
  float3 ambient{0, 0, 0};
  std::vector<ShadeLight> lights;
  bool local = false;  // a point or spot light: shading needs world positions
  // The viewer, for view-dependent shading (Shading::kPbr): the camera's position, or for a
  // parallel projection the unit direction towards it (eye_at_infinity).
  float3 eye{0, 0, 0};
  float3 toward_eye{0, 0, 1};
  bool eye_at_infinity = false;
  // Image-based light (Scene::environment, --hdri): PBR pixels take it in place of `ambient`.
  const Environment* environment = nullptr;
  float3x3 world_to_environment;
  ToneCurve tone;  // applied to every shaded colour (tone.h)
  // This frame's shadow maps (RenderOptions::shadows; ShadowMaps::build sets it); null: none.
  // Per-pixel shading then takes world positions (setup.h: needsWorld).
  const ShadowMaps* shadows = nullptr;

  void prepare(const Scene& scene) {
    ambient = scene.ambient;
    tone = ToneCurve::of(scene);
    environment =
        scene.environment && !scene.environment->empty() ? scene.environment.get() : nullptr;
    world_to_environment = scene.world_to_environment;
    // The camera's frame in world space: the inverse view matrix's last two columns. A
    // projection whose w does not depend on z (m(3, 3) != 0) is a parallel one.
    const float4x4 camera = inverse(scene.camera.view());
    eye = camera.col[3].xyz();
    toward_eye = normalize(camera.col[2].xyz());
    eye_at_infinity = scene.camera.projection(1.0f)(3, 3) != 0.0f;
    lights.clear();
    local = false;
    shadows = nullptr;
    for (const Light& light : scene.lights) {
      lights.push_back(shadeLight(light));
      local = local || light.type != LightType::kDirectional;
    }
  }
};

// What a point or spot light gives a surface at p with unit normal n, per unit radiance: the
// incidence cosine times 1 / d^2, the range window and the cone; zero (or a NaN the caller's
// `> 0` test drops) where it does not reach. The lanes (shade_lanes.h) do these operations in
// this order.
inline float localFactor(const ShadeLight& light, float3 n, float3 p) {
  const float3 l = light.position - p;
  const float d2 = (l.x * l.x + l.y * l.y) + l.z * l.z;
  const float inv_d = 1.0f / std::sqrt(d2);
  const float3 u{l.x * inv_d, l.y * inv_d, l.z * inv_d};
  const float cos_theta = (n.x * u.x + n.y * u.y) + n.z * u.z;
  const float window = std::clamp(1.0f - d2 * d2 * light.inv_range4, 0.0f, 1.0f);
  const float cd = -((light.direction.x * u.x + light.direction.y * u.y) + light.direction.z * u.z);
  const float t = std::clamp(cd * light.spot_scale + light.spot_offset, 0.0f, 1.0f);
  return cos_theta * ((window * (t * t)) / d2);
}

// What a point or spot light gives a surface at p per unit radiance before the incidence cosine
// (1 / d^2, the range window and the cone), and in `u` the unit direction from p to the light:
// localFactor is (n.u) times this, with the same operations.
inline float localAttenuation(const ShadeLight& light, float3 p, float3& u) {
  const float3 l = light.position - p;
  const float d2 = (l.x * l.x + l.y * l.y) + l.z * l.z;
  const float inv_d = 1.0f / std::sqrt(d2);
  u = {l.x * inv_d, l.y * inv_d, l.z * inv_d};
  const float window = std::clamp(1.0f - d2 * d2 * light.inv_range4, 0.0f, 1.0f);
  const float cd = -((light.direction.x * u.x + light.direction.y * u.y) + light.direction.z * u.z);
  const float t = std::clamp(cd * light.spot_scale + light.spot_offset, 0.0f, 1.0f);
  return (window * (t * t)) / d2;
}

// Lambert irradiance at world point p with unit normal n: ambient plus every light. The vertex
// kernel (vertex_kernel.h) lights Gouraud vertices with the directional lights' operations, eight
// at a time, when the rig has no local light.
inline float3 irradiance(const LightRig& rig, float3 n, float3 p) {
  float3 e = rig.ambient;
  for (const ShadeLight& light : rig.lights) {
    if (light.type == LightType::kDirectional) {
      const float cos_theta = -dot(n, light.direction);
      if (cos_theta > 0.0f) e += light.radiance * cos_theta;
    } else {
      const float f = localFactor(light, n, p);
      if (f > 0.0f) e += light.radiance * f;
    }
  }
  return e;
}

}  // namespace tessera::render
