// glTF 2.0's metallic-roughness BRDF itself (render/pbr.h): the lobes, Schlick's weight, pi f(l, v)
// and the uniform ambient's reflection, with the CPU's float operations in the same order
// (precise: no fused multiply-adds). Self-contained GLSL 4.50, shared by two programs: pbr.glsl
// (the Vulkan backends, through glslc's #include) and the llvmpipe reference of `tessera bench`
// (bench/llvmpipe_programs.cpp, which CMake embeds it into), so that both draw the same formulas.

const float kPi = 3.14159265358979;
const float kMinRoughness = 0.03;  // render/pbr.h: kMinRoughness
const float kDielectricF0 = 0.04;

// The BRDF's per-pixel constants (render::PbrLobes).
struct PbrLobes {
  vec3 c_diff, f0;
  float roughness;  // clamped
  float a2;         // alpha^2 = roughness^4
};

// std::clamp(v, lo, hi): NaN stays NaN.
float clampAsCpu(float v, float lo, float hi) { return v < lo ? lo : (hi < v ? hi : v); }

float dot3(vec3 a, vec3 b) {
  precise float d = (a.x * b.x + a.y * b.y) + a.z * b.z;
  return d;
}

// render::pbrLobes
PbrLobes pbrLobes(vec3 base, float metallic, float roughness) {
  const float m = clampAsCpu(metallic, 0.0, 1.0);
  const float r = clampAsCpu(roughness, kMinRoughness, 1.0);
  precise float alpha = r * r;
  precise float dielectric = 1.0 - m;
  precise float f0_dielectric = kDielectricF0 * dielectric;
  precise vec3 c_diff = base * dielectric;
  precise vec3 f0 = vec3(f0_dielectric) + base * m;
  precise float a2 = alpha * alpha;
  return PbrLobes(c_diff, f0, r, a2);
}

// (1 - x)^5, Schlick's weight.
float schlickWeight(float x) {
  precise float k = 1.0 - x;
  precise float k2 = k * k;
  precise float w = (k2 * k2) * k;
  return w;
}

// render::pbrResponse: pi f(l, v) for unit n, v, l with nl = n.l > 0 and nv = |n.v|.
vec3 pbrResponse(PbrLobes s, vec3 n, vec3 v, vec3 l, float nl, float nv) {
  precise float hx = l.x + v.x, hy = l.y + v.y, hz = l.z + v.z;
  precise float h2 = (hx * hx + hy * hy) + hz * hz;
  // l = -v has no half vector: no specular.
  precise float inv_h = h2 > 0.0 ? 1.0 / sqrt(h2) : 0.0;
  precise vec3 h = vec3(hx * inv_h, hy * inv_h, hz * inv_h);
  const float nh = dot3(n, h), vh = dot3(v, h);
  const float fw = schlickWeight(vh);
  // GGX (Trowbridge-Reitz) distribution with its Heaviside factor.
  precise float dd = (nh * nh) * (s.a2 - 1.0) + 1.0;
  precise float d = nh > 0.0 ? s.a2 / ((kPi * dd) * dd) : 0.0;
  // Smith's height-correlated visibility (Heitz 2014).
  precise float one_minus_a2 = 1.0 - s.a2;
  precise float gv = nl * sqrt((nv * nv) * one_minus_a2 + s.a2);
  precise float gl = nv * sqrt((nl * nl) * one_minus_a2 + s.a2);
  precise float spec = kPi * (d * (0.5 / (gv + gl)));
  precise vec3 f = s.f0 + (vec3(1.0) - s.f0) * fw;
  precise vec3 r = (vec3(1.0) - f) * s.c_diff + f * spec;
  return r;
}

// render::pbrAmbient: the uniform ambient's reflection, Schlick's Fresnel at n.v with a
// roughness-dependent F90 (Fdez-Aguera 2019); occlusion darkens this term only.
vec3 pbrAmbient(PbrLobes s, vec3 ambient, float occlusion, float nv) {
  const float fw = schlickWeight(nv);
  precise float f90 = 1.0 - s.roughness;
  // std::max(f90, f0): f90 < f0 ? f0 : f90.
  const vec3 f90v = vec3(f90 < s.f0.x ? s.f0.x : f90, f90 < s.f0.y ? s.f0.y : f90,
                         f90 < s.f0.z ? s.f0.z : f90);
  precise vec3 fa = s.f0 + (f90v - s.f0) * fw;
  precise vec3 r = (ambient * occlusion) * ((vec3(1.0) - fa) * s.c_diff + fa);
  return r;
}
