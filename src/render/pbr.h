// glTF 2.0's metallic-roughness BRDF (the specification's appendix B), the scalar reference of
// Shading::kPbr. The eight-lane shading (shade_lanes.h: shadePbr8) does these float operations in
// this order, lane by lane, so that both give the same bits.
//
//   alpha  = roughness^2 (perceptual roughness clamped to [kMinRoughness, 1])
//   c_diff = lerp(baseColor, black, metallic)      f0 = lerp(0.04, baseColor, metallic)
//   F      = f0 + (1 - f0) (1 - v.h)^5              (Schlick)
//   D      = alpha^2 X(n.h) / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2)     (Trowbridge-Reitz / GGX)
//   V      = 0.5 / (n.l sqrt((n.v)^2 (1 - alpha^2) + alpha^2) + n.v sqrt((n.l)^2 (1 - alpha^2) +
//            alpha^2))   (Smith's height-correlated masking-shadowing, Heitz 2014, as the Khronos
//            sample viewer; the specification's text writes the separable approximation)
//   f      = (1 - F) c_diff / pi + F D V
//
// Units: tessera's exposure is fixed so that a white Lambert surface lit head-on by a light of
// irradiance E shows E (scene.h: Light). PBR keeps that scale: a light adds pi f E cos(theta), so
// a rough white dielectric looks close to its Lambert shading and the same lights serve both.
//
// Ambient: Scene::ambient is a uniform environment of that irradiance. Its reflection is the
// split-sum's with the directional albedo approximated by Schlick's Fresnel at n.v with a
// roughness-dependent F90 (Fdez-Aguera 2019):
//   Fa = f0 + (max(1 - roughness, f0) - f0) (1 - n.v)^5,   ambient' = ao E_a ((1 - Fa) c_diff + Fa)
// so a white dielectric returns exactly E_a and a smooth metal the environment times its Fresnel.
// Occlusion (the material's ao) darkens this term only, as the Khronos sample viewer does.
#pragma once

#include <algorithm>
#include <cmath>

#include <tessera/math/vec.h>

#include "render/lights.h"

namespace tessera::render {

constexpr float kPi = 3.14159265358979f;
// Below this perceptual roughness D's peak (1 / (pi alpha^2)) loses its float precision near n.h
// = 1.
constexpr float kMinRoughness = 0.03f;
constexpr float kDielectricF0 = 0.04f;

// What a pixel's material gives the BRDF.
struct PbrSurface {
  float3 base_color{1.0f, 1.0f, 1.0f};  // linear: factor x texture x vertex colour
  float metallic = 0.0f;
  float roughness = 1.0f;  // perceptual
  float occlusion = 1.0f;  // ambient only; 1 = none
  float3 emissive{0.0f, 0.0f, 0.0f};
};

// The BRDF's per-pixel constants.
struct PbrLobes {
  float3 c_diff, f0;
  float roughness;  // clamped
  float a2;         // alpha^2 = roughness^4
};

inline PbrLobes pbrLobes(const PbrSurface& s) {
  const float m = std::clamp(s.metallic, 0.0f, 1.0f);
  const float r = std::clamp(s.roughness, kMinRoughness, 1.0f);
  const float alpha = r * r;
  const float dielectric = 1.0f - m;
  const float f0_dielectric = kDielectricF0 * dielectric;
  return {{s.base_color.x * dielectric, s.base_color.y * dielectric, s.base_color.z * dielectric},
          {f0_dielectric + s.base_color.x * m, f0_dielectric + s.base_color.y * m,
           f0_dielectric + s.base_color.z * m},
          r,
          alpha * alpha};
}

// (1 - x)^5, Schlick's weight.
inline float schlickWeight(float x) {
  const float k = 1.0f - x;
  const float k2 = k * k;
  return (k2 * k2) * k;
}

// D, the GGX distribution of microfacet normals (1/sr), with its Heaviside factor.
inline float ggxDistribution(float a2, float nh) {
  const float dd = (nh * nh) * (a2 - 1.0f) + 1.0f;
  return nh > 0.0f ? a2 / ((kPi * dd) * dd) : 0.0f;
}

// V = G / (4 n.l n.v), Smith's height-correlated form; nl > 0, nv >= 0.
inline float smithVisibility(float a2, float nl, float nv) {
  const float one_minus_a2 = 1.0f - a2;
  const float gv = nl * std::sqrt((nv * nv) * one_minus_a2 + a2);
  const float gl = nv * std::sqrt((nl * nl) * one_minus_a2 + a2);
  return 0.5f / (gv + gl);
}

inline float dot3(float3 a, float3 b) {
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}

// pi f(l, v) for unit n, v, l with nl = n.l > 0 and nv = |n.v|: what a light of irradiance E
// (head-on) adds, per unit E cos(theta).
inline float3 pbrResponse(const PbrLobes& s, float3 n, float3 v, float3 l, float nl, float nv) {
  const float hx = l.x + v.x, hy = l.y + v.y, hz = l.z + v.z;
  const float h2 = (hx * hx + hy * hy) + hz * hz;
  // l = -v has no half vector: n.h = v.h = 0, no specular (X(n.h) = 0).
  const float inv_h = h2 > 0.0f ? 1.0f / std::sqrt(h2) : 0.0f;
  const float3 h{hx * inv_h, hy * inv_h, hz * inv_h};
  const float nh = dot3(n, h), vh = dot3(v, h);
  const float fw = schlickWeight(vh);
  const float spec = kPi * (ggxDistribution(s.a2, nh) * smithVisibility(s.a2, nl, nv));
  const float3 f{s.f0.x + (1.0f - s.f0.x) * fw, s.f0.y + (1.0f - s.f0.y) * fw,
                 s.f0.z + (1.0f - s.f0.z) * fw};
  return {(1.0f - f.x) * s.c_diff.x + f.x * spec, (1.0f - f.y) * s.c_diff.y + f.y * spec,
          (1.0f - f.z) * s.c_diff.z + f.z * spec};
}

// The specification's BRDF f(l, v) itself (1/sr; zero below the horizon of l): for the tests.
float3 pbrBrdf(const PbrSurface& surface, float3 n, float3 v, float3 l);

// The ambient term (see the top of this file) for n.v = nv >= 0.
inline float3 pbrAmbient(const PbrLobes& s, float3 ambient, float occlusion, float nv) {
  const float fw = schlickWeight(nv);
  const float f90 = 1.0f - s.roughness;
  const float3 fa{s.f0.x + (std::max(f90, s.f0.x) - s.f0.x) * fw,
                  s.f0.y + (std::max(f90, s.f0.y) - s.f0.y) * fw,
                  s.f0.z + (std::max(f90, s.f0.z) - s.f0.z) * fw};
  return {(occlusion * ambient.x) * ((1.0f - fa.x) * s.c_diff.x + fa.x),
          (occlusion * ambient.y) * ((1.0f - fa.y) * s.c_diff.y + fa.y),
          (occlusion * ambient.z) * ((1.0f - fa.z) * s.c_diff.z + fa.z)};
}

// With an environment (LightRig::environment, --hdri) the uniform ambient gives way to image-based
// light, the split sum of Karis 2013 as the Khronos sample viewer evaluates it: with r = v
// reflected about n, kS = Fa above and (A, B) = splitSumBrdf(n.v, roughness),
//   FssEss = kS A + B,   ambient' = ao (E_d(n) c_diff (1 - FssEss) + E_s(r, roughness) FssEss),
// E_d the environment's irradiance over pi and E_s its GGX-prefiltered radiance
// (environment.h). A white dielectric in a uniform environment of radiance L returns at most L; a
// smooth metal reflects the environment times its split-sum Fresnel.
float3 pbrEnvironment(const PbrLobes& s, const LightRig& rig, float occlusion, float3 n, float3 v,
                      float nv);

// The unit vector from world point p towards the viewer (LightRig::eye).
inline float3 viewVector(const LightRig& rig, float3 p) {
  if (rig.eye_at_infinity) return rig.toward_eye;
  const float3 d{rig.eye.x - p.x, rig.eye.y - p.y, rig.eye.z - p.z};
  const float len2 = (d.x * d.x + d.y * d.y) + d.z * d.z;
  const float inv = len2 > 0.0f ? 1.0f / std::sqrt(len2) : 0.0f;
  return {d.x * inv, d.y * inv, d.z * inv};
}

// A pixel's linear colour: ambient, then every light of the rig in order, then the emission; n is
// the unit shading normal, p the world position.
float3 shadePbr(const LightRig& rig, const PbrSurface& surface, float3 n, float3 p);

}  // namespace tessera::render
