// kPbr's image-based light (Scene::environment, --hdri): the CPU's render::pbrEnvironment
// (src/render/pbr.cpp) and tessera::Environment's diffuse() and specular() and splitSumBrdf
// (src/scene/environment.cpp), the same operations in the same order, on the environment block the
// host puts in the texel buffer (gpu_types.h: GpuEnvironmentBlock). The GPU's atan and acos may
// round differently from the C library's, which moves a sample by a fraction of a texel at most.
// Included by pbr.glsl.

const uint kEnvironmentSh = 0u;
const uint kEnvironmentMatrix = 27u;
const uint kEnvironmentLevels = 36u;
const uint kEnvironmentSplitSum = 54u;
const int kSpecularLevels = 6;  // Environment::kSpecularLevels
const int kSplitSumTableSize = 32;

float environmentFloat(uint i) { return uintBitsToFloat(texels[frame.environment - 1u + i]); }
vec3 environmentVec3(uint i) {
  return vec3(environmentFloat(i), environmentFloat(i + 1u), environmentFloat(i + 2u));
}

// world_to_environment * d (float3x3 * float3: the columns summed in order).
vec3 toEnvironment(vec3 d) {
  precise vec3 r = environmentVec3(kEnvironmentMatrix) * d.x +
                   environmentVec3(kEnvironmentMatrix + 3u) * d.y +
                   environmentVec3(kEnvironmentMatrix + 6u) * d.z;
  return r;
}

// Environment::diffuse: the irradiance over pi at unit normal n, from its SH coefficients.
vec3 environmentDiffuse(vec3 d) {
  precise float basis[9] = float[9](
      0.282095, 0.488603 * d.y, 0.488603 * d.z, 0.488603 * d.x, 1.092548 * d.x * d.y,
      1.092548 * d.y * d.z, 0.315392 * (3.0 * d.z * d.z - 1.0), 1.092548 * d.x * d.z,
      0.546274 * (d.x * d.x - d.y * d.y));
  precise vec3 sum = vec3(0.0);
  for (int k = 0; k < 9; ++k) sum = sum + environmentVec3(kEnvironmentSh + 3u * uint(k)) * basis[k];
  return vec3(sum.x < 0.0 ? 0.0 : sum.x, sum.y < 0.0 ? 0.0 : sum.y, sum.z < 0.0 ? 0.0 : sum.z);
}

// sampleEquirect: bilinear in level `level` of the specular chain, wrapping around horizontally.
vec3 sampleEquirect(int level, vec3 d) {
  const uint h = kEnvironmentLevels + 3u * uint(level);
  const uint offset = texels[frame.environment - 1u + h];
  const int width = int(texels[frame.environment + h]);
  const int height = int(texels[frame.environment + h + 1u]);
  // equirectUv
  precise float u = atan(d.x, -d.z) / (2.0 * kPi);
  if (u < 0.0) u = u + 1.0;
  precise float v = acos(clamp(d.y, -1.0, 1.0)) / kPi;
  if (isinf(u) || isnan(u) || isinf(v) || isnan(v)) return vec3(0.0);
  precise float fx = u * float(width) - 0.5;
  precise float fy_raw = v * float(height) - 0.5;
  const float fy = clamp(fy_raw, 0.0, float(height - 1));
  const float x_floor = floor(fx), y_floor = floor(fy);
  precise float tx = fx - x_floor, ty = fy - y_floor;
  // ((x % w) + w) % w without % of a negative operand.
  const int xi = int(x_floor);
  const int x0 = xi >= 0 ? xi % width : (width - 1 - ((-1 - xi) % width));
  const int x1 = (x0 + 1) % width;
  const int y0 = int(y_floor), y1 = min(y0 + 1, height - 1);
  const uint row0 = offset + 3u * uint(y0 * width), row1 = offset + 3u * uint(y1 * width);
  const vec3 a = vec3(uintBitsToFloat(texels[row0 + 3u * uint(x0)]),
                      uintBitsToFloat(texels[row0 + 3u * uint(x0) + 1u]),
                      uintBitsToFloat(texels[row0 + 3u * uint(x0) + 2u]));
  const vec3 b = vec3(uintBitsToFloat(texels[row0 + 3u * uint(x1)]),
                      uintBitsToFloat(texels[row0 + 3u * uint(x1) + 1u]),
                      uintBitsToFloat(texels[row0 + 3u * uint(x1) + 2u]));
  const vec3 c = vec3(uintBitsToFloat(texels[row1 + 3u * uint(x0)]),
                      uintBitsToFloat(texels[row1 + 3u * uint(x0) + 1u]),
                      uintBitsToFloat(texels[row1 + 3u * uint(x0) + 2u]));
  const vec3 e = vec3(uintBitsToFloat(texels[row1 + 3u * uint(x1)]),
                      uintBitsToFloat(texels[row1 + 3u * uint(x1) + 1u]),
                      uintBitsToFloat(texels[row1 + 3u * uint(x1) + 2u]));
  precise vec3 top = a * (1.0 - tx) + b * tx;
  precise vec3 bottom = c * (1.0 - tx) + e * tx;
  precise vec3 r = top * (1.0 - ty) + bottom * ty;
  return r;
}

// Environment::specular: between the two levels of the chain around the roughness.
vec3 environmentSpecular(vec3 r, float roughness) {
  precise float lod = min(max(roughness, 0.0), 1.0) * float(kSpecularLevels - 1);
  const int lower = min(int(lod), kSpecularLevels - 2);
  precise float t = lod - float(lower);
  precise vec3 s = sampleEquirect(lower, r) * (1.0 - t) + sampleEquirect(lower + 1, r) * t;
  return s;
}

vec2 splitSumEntry(int x, int y) {
  const uint i = kEnvironmentSplitSum + 2u * uint(y * kSplitSumTableSize + x);
  return vec2(environmentFloat(i), environmentFloat(i + 1u));
}

// splitSumBrdf: bilinear in the split-sum table.
vec2 splitSumBrdf(float n_dot_v, float roughness) {
  precise float fx = min(max(n_dot_v, 0.0), 1.0) * float(kSplitSumTableSize - 1);
  precise float fy = min(max(roughness, 0.0), 1.0) * float(kSplitSumTableSize - 1);
  const int x0 = min(int(fx), kSplitSumTableSize - 2);
  const int y0 = min(int(fy), kSplitSumTableSize - 2);
  precise float tx = fx - float(x0), ty = fy - float(y0);
  precise vec2 top = splitSumEntry(x0, y0) * (1.0 - tx) + splitSumEntry(x0 + 1, y0) * tx;
  precise vec2 bottom =
      splitSumEntry(x0, y0 + 1) * (1.0 - tx) + splitSumEntry(x0 + 1, y0 + 1) * tx;
  precise vec2 r = top * (1.0 - ty) + bottom * ty;
  return r;
}

// render::pbrEnvironment: the split sum (Karis 2013) with the ambient term's Fresnel kS:
// ao (E_d(n) c_diff (1 - FssEss) + E_s(r, roughness) FssEss), FssEss = kS A + B.
vec3 pbrEnvironment(PbrLobes s, float occlusion, vec3 n, vec3 v, float nv) {
  const float nv_signed = dot3(n, v);
  precise vec3 r = vec3(2.0 * nv_signed * n.x - v.x, 2.0 * nv_signed * n.y - v.y,
                        2.0 * nv_signed * n.z - v.z);
  const vec3 e_d = environmentDiffuse(toEnvironment(n));
  const vec3 e_s = environmentSpecular(toEnvironment(r), s.roughness);
  const vec2 ab = splitSumBrdf(nv, s.roughness);
  const float fw = schlickWeight(nv);
  precise float f90 = 1.0 - s.roughness;
  const vec3 f90v = vec3(f90 < s.f0.x ? s.f0.x : f90, f90 < s.f0.y ? s.f0.y : f90,
                         f90 < s.f0.z ? s.f0.z : f90);
  precise vec3 ks = s.f0 + (f90v - s.f0) * fw;
  precise vec3 fss_ess = ks * ab.x + ab.y;
  precise vec3 out_color =
      (e_d * (s.c_diff * (vec3(1.0) - fss_ess)) + e_s * fss_ess) * occlusion;
  return out_color;
}
