// The display transform (Scene::tone_mapping, Scene::exposure): scales the shaded linear colour by
// 2^exposure, then maps it into [0, 1] with the chosen curve, before the sRGB encode. The scalar
// reference here; the eight lanes (tone_lanes.h) do the same operations in the same order, and the
// Vulkan shaders (shading.glsl's toneMap) the same maths.
#pragma once

#include <cmath>

#include <tessera/math/vec.h>
#include <tessera/scene/scene.h>

namespace tessera::render {

// What the shading reads, prepared once per frame (LightRig::prepare).
struct ToneCurve {
  ToneMapping mapping = ToneMapping::kNone;
  float scale = 1.0f;  // 2^exposure
  bool active() const { return mapping != ToneMapping::kNone || scale != 1.0f; }
  static ToneCurve of(const Scene& scene) {
    // exp2 of a finite exposure (the CLI bounds it to +-20 stops) is exact for whole stops.
    return {scene.tone_mapping, std::exp2(scene.exposure)};
  }
};

// The curves' constants, shared with tone_lanes.h.
struct ToneConstants {
  // ACES: Stephen Hill's fit of the RRT and the sRGB ODT (linear sRGB in, linear sRGB out), after
  // the 1 / 0.6 exposure boost three.js and the Khronos glTF sample viewer apply, so that a mid
  // grey stays near mid grey. Row-major 3x3 matrices.
  static constexpr float kAcesBoost = 1.0f / 0.6f;
  static constexpr float kAcesIn[9] = {0.59719f, 0.35458f, 0.04823f, 0.07600f, 0.90834f,
                                       0.01566f, 0.02840f, 0.13383f, 0.83777f};
  static constexpr float kAcesOut[9] = {1.60475f,  -0.53108f, -0.07367f, -0.10208f, 1.10813f,
                                        -0.00605f, -0.00327f, -0.07276f, 1.07602f};
  static constexpr float kFitA = 0.0245786f, kFitB = 0.000090537f, kFitC = 0.983729f,
                         kFitD = 0.4329510f, kFitE = 0.238081f;
  // Khronos PBR Neutral: F90 = 0.04, compression from Ks = 0.8 - F90, desaturation Kd = 0.15.
  static constexpr float kF90 = 0.04f;
  static constexpr float kStart = 0.8f - 0.04f;
  static constexpr float kDesaturation = 0.15f;
};

inline float acesFit(float v) {
  using K = ToneConstants;
  return (v * (v + K::kFitA) - K::kFitB) / (v * (K::kFitC * v + K::kFitD) + K::kFitE);
}

inline float clampUnit(float v) {
  return v < 0.0f ? 0.0f : (1.0f < v ? 1.0f : v);
}

inline float3 toneAces(float3 c) {
  using K = ToneConstants;
  c = {c.x * K::kAcesBoost, c.y * K::kAcesBoost, c.z * K::kAcesBoost};
  const float* m = K::kAcesIn;
  const float x = acesFit((m[0] * c.x + m[1] * c.y) + m[2] * c.z);
  const float y = acesFit((m[3] * c.x + m[4] * c.y) + m[5] * c.z);
  const float z = acesFit((m[6] * c.x + m[7] * c.y) + m[8] * c.z);
  const float* o = K::kAcesOut;
  return {clampUnit((o[0] * x + o[1] * y) + o[2] * z), clampUnit((o[3] * x + o[4] * y) + o[5] * z),
          clampUnit((o[6] * x + o[7] * y) + o[8] * z)};
}

// The Khronos PBR Neutral specification's formulas: colours up to 0.76 unchanged but for the
// small offset near black; brighter ones compressed towards 1 and desaturated.
inline float3 tonePbrNeutral(float3 c) {
  using K = ToneConstants;
  const float lowest = c.y < c.x ? c.y : c.x;
  const float x = c.z < lowest ? c.z : lowest;
  const float f = x <= 2.0f * K::kF90 ? x - (x * x) * (1.0f / (4.0f * K::kF90)) : K::kF90;
  c = {c.x - f, c.y - f, c.z - f};
  const float highest = c.x < c.y ? c.y : c.x;
  const float p = highest < c.z ? c.z : highest;
  if (p <= K::kStart) return c;
  const float d = 1.0f - K::kStart;
  const float peak = 1.0f - (d * d) / (p + (d - K::kStart));
  const float g = 1.0f / (K::kDesaturation * (p - peak) + 1.0f);
  const float s = (peak / p) * g, lift = peak * (1.0f - g);
  return {c.x * s + lift, c.y * s + lift, c.z * s + lift};
}

// Negative inputs (none from the shading, but a hostile texture or light may) count as 0; NaN
// stays NaN, which the encode writes as 0.
inline float3 toneMap(const ToneCurve& curve, float3 c) {
  c = {c.x * curve.scale, c.y * curve.scale, c.z * curve.scale};
  if (curve.mapping == ToneMapping::kNone) return c;
  c = {c.x < 0.0f ? 0.0f : c.x, c.y < 0.0f ? 0.0f : c.y, c.z < 0.0f ? 0.0f : c.z};
  return curve.mapping == ToneMapping::kAces ? toneAces(c) : tonePbrNeutral(c);
}

}  // namespace tessera::render
