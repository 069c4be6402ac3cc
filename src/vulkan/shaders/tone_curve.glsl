// tessera::render::toneMap (src/render/tone.h), its operations in its order: the shaded linear
// colour times `scale` (2^exposure), then the curve (0 none, 1 ACES, 2 Khronos PBR Neutral: the
// order of tessera::ToneMapping). Self-contained GLSL 4.50, shared by shading.glsl (the Vulkan
// backends, through glslc's #include) and the llvmpipe reference of `tessera bench`
// (bench/llvmpipe_programs.cpp, which CMake embeds it into).

float acesFit(float v) {
  precise float r = (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081);
  return r;
}

vec3 toneCurve(vec3 color, float scale, uint curve) {
  precise vec3 c = color * scale;
  if (curve == 0u) return c;
  c = vec3(c.x < 0.0 ? 0.0 : c.x, c.y < 0.0 ? 0.0 : c.y, c.z < 0.0 ? 0.0 : c.z);
  if (curve == 1u) {
    c = c * (1.0 / 0.6);
    precise float x = acesFit((0.59719 * c.x + 0.35458 * c.y) + 0.04823 * c.z);
    precise float y = acesFit((0.07600 * c.x + 0.90834 * c.y) + 0.01566 * c.z);
    precise float z = acesFit((0.02840 * c.x + 0.13383 * c.y) + 0.83777 * c.z);
    precise vec3 o = vec3((1.60475 * x + -0.53108 * y) + -0.07367 * z,
                          (-0.10208 * x + 1.10813 * y) + -0.00605 * z,
                          (-0.00327 * x + -0.07276 * y) + 1.07602 * z);
    return clamp(o, 0.0, 1.0);
  }
  const float lowest = c.y < c.x ? c.y : c.x;
  const float x = c.z < lowest ? c.z : lowest;
  precise float f = x <= 0.08 ? x - (x * x) * (1.0 / 0.16) : 0.04;
  c = c - f;
  const float highest = c.x < c.y ? c.y : c.x;
  const float p = highest < c.z ? c.z : highest;
  if (p <= 0.76) return c;
  const float d = 1.0 - 0.76;
  precise float peak = 1.0 - (d * d) / (p + (d - 0.76));
  precise float g = 1.0 / (0.15 * (p - peak) + 1.0);
  precise float s = (peak / p) * g;
  precise float lift = peak * (1.0 - g);
  return c * s + lift;
}
