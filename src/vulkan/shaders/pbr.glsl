// glTF 2.0's metallic-roughness BRDF (Shading::kPbr) for both Vulkan backends: the CPU's
// src/render/pbr.h (scalar reference) and src/render/shade_lanes.h (shadePbrLanes, normalMapped)
// with the same float operations in the same order (precise: no fused multiply-adds). The maths
// and its sources are described at the top of pbr.h; the environment's in environment.glsl; the
// shadow maps' in shadow.glsl. Included by shading.glsl; needs what it defines.

#include "pbr_brdf.glsl"

#include "environment.glsl"

// render::viewVector: the unit vector from world point p towards the viewer.
vec3 viewVector(vec3 p) {
  if (frame.eye.w != 0.0) return frame.toward_eye.xyz;
  precise vec3 d = frame.eye.xyz - p;
  precise float len2 = (d.x * d.x + d.y * d.y) + d.z * d.z;
  precise float inv = len2 > 0.0 ? 1.0 / sqrt(len2) : 0.0;
  precise vec3 v = d * inv;
  return v;
}

// render::localAttenuation: a point or spot light's 1 / d^2, range window and cone at p, and in u
// the unit direction from p to the light.
float localAttenuation(Light light, vec3 p, out vec3 u) {
  precise vec3 l = light.position.xyz - p;
  precise float d2 = (l.x * l.x + l.y * l.y) + l.z * l.z;
  precise float inv_d = 1.0 / sqrt(d2);
  precise vec3 unit = l * inv_d;
  u = unit;
  precise float window = clamp(1.0 - d2 * d2 * light.color.w, 0.0, 1.0);
  const vec3 d = light.direction.xyz;
  precise float cd = -((d.x * unit.x + d.y * unit.y) + d.z * unit.z);
  precise float t = clamp(cd * light.position.w + light.spot.x, 0.0, 1.0);
  precise float a = (window * (t * t)) / d2;
  return a;
}

// render::shadePbr: ambient, every light in order, then the emission; n the unit shading normal,
// p the world position.
vec3 shadePbr(PbrLobes s, float occlusion, vec3 emissive, vec3 n, vec3 p) {
  const vec3 v = viewVector(p);
  const float nv = abs(dot3(n, v));
  precise vec3 c = frame.environment != 0u ? pbrEnvironment(s, occlusion, n, v, nv)
                                            : pbrAmbient(s, frame.ambient.xyz, occlusion, nv);
  for (uint i = 0u; i < frame.light_count; ++i) {
    const Light light = lights[i];
    vec3 l;
    float nl, f;
    if (light.direction.w == 0.0) {
      l = -light.direction.xyz;
      nl = dot3(n, l);
      f = nl;
    } else {
      const float attenuation = localAttenuation(light, p, l);
      nl = dot3(n, l);
      precise float lit = nl * attenuation;
      f = lit;
    }
    if (!(nl > 0.0 && f > 0.0)) continue;
    // Times the light's shadow maps' visibility (shadow.glsl; 1 without maps).
    precise float shadowed = f * shadowVisibility(i, p, n);
    const vec3 r = pbrResponse(s, n, v, l, nl, nv);
    c = c + r * (light.color.xyz * shadowed);
  }
  precise vec3 result = c + emissive;
  return result;
}

// ---- the material's maps ----

// A point's UVs and those at the next pixels right and down (the trilinear level of detail), in
// set 0 (TEXCOORD_0) and set 1 (TEXCOORD_1).
struct UvFootprint {
  vec2 uv, right, down;
  vec2 uv1, right1, down1;
};

// Map `map` of a material (render::sampleTexture for a TextureSlot): in the map's own set, through
// its own KHR_texture_transform; trilinear samplers take their level of detail from the footprint.
vec4 sampleMap(GpuMaterial m, int map, UvFootprint f) {
  const TextureRef t = m.maps[map];
  const bool set1 = (t.flags & kTextureSet1) != 0u;
  const vec2 uv = transformMapUv(m, map, set1 ? f.uv1 : f.uv);
  const bool trilinear = (t.flags & kTextureTrilinear) != 0u;
  float lod = 0.0;
  if (trilinear) {
    const vec2 right = transformMapUv(m, map, set1 ? f.right1 : f.right);
    const vec2 down = transformMapUv(m, map, set1 ? f.down1 : f.down);
    const vec2 size = vec2(float(t.width), float(t.height));
    precise vec2 du = right - uv;
    precise vec2 dv = down - uv;
    precise vec2 dx = du * size, dy = dv * size;
    precise float rx = dx.x * dx.x + dx.y * dx.y;
    precise float ry = dy.x * dy.x + dy.y * dy.y;
    const float rho2 = rx < ry ? ry : rx;
    precise float level_of_detail = rho2 > 0.0 ? 0.5 * log2(rho2) : 0.0;
    lod = level_of_detail;
  }
  return sampleTextureAt(t, uv, trilinear, lod);
}

bool hasMap(GpuMaterial m, int map) { return (m.maps[map].flags & kTexturePresent) != 0u; }

// The normal map in the tangent frame (shade_lanes.h: normalMapped): the interpolated tangent made
// orthogonal to the unit normal n, the bitangent cross(n, t) times the sign (glTF's TANGENT),
// then normalize(t x' + b y' + n z') with (x', y', z') = 2 texel - 1, x' and y' times
// normal_scale.
vec3 normalMapped(GpuMaterial m, vec3 n, vec3 tangent, float sign, UvFootprint f) {
  const float tn = dot3(n, tangent);
  precise vec3 orthogonal = tangent - n * tn;
  const vec3 t = normalizeAsCpu(orthogonal);
  precise vec3 b = vec3(n.y * t.z - n.z * t.y, n.z * t.x - n.x * t.z, n.x * t.y - n.y * t.x) * sign;
  const vec4 texel = sampleMap(m, kMapNormal, f);
  const float scale = m.pbr.z;
  precise float x = (texel.x * 2.0 - 1.0) * scale;
  precise float y = (texel.y * 2.0 - 1.0) * scale;
  precise float z = texel.z * 2.0 - 1.0;
  precise vec3 perturbed = (t * x + b * y) + n * z;
  return normalizeAsCpu(perturbed);
}

// A PBR point's linear colour (shade_lanes.h: shadePbrLanes after the normal): base is the base
// colour (factor x vertex colour x albedo texture), n the shading normal, p the world position;
// `maps` says the mesh has UVs, so that the metallic-roughness (G roughness, B metallic),
// occlusion (R) and emissive maps apply.
vec3 shadePbrMaterial(GpuMaterial m, vec3 base, vec3 n, vec3 p, bool maps, UvFootprint f) {
  float metallic = m.pbr.x, roughness = m.pbr.y, occlusion = 1.0;
  if (maps && hasMap(m, kMapMetallicRoughness)) {
    const vec4 texel = sampleMap(m, kMapMetallicRoughness, f);
    precise float r = roughness * texel.y;
    precise float mt = metallic * texel.z;
    roughness = r;
    metallic = mt;
  }
  if (maps && hasMap(m, kMapOcclusion)) {
    // glTF: 1 + strength (R - 1).
    const vec4 texel = sampleMap(m, kMapOcclusion, f);
    precise float o = 1.0 + m.pbr.w * (texel.x - 1.0);
    occlusion = o;
  }
  vec3 emissive = m.emissive.xyz;
  if (maps && hasMap(m, kMapEmissive)) {
    precise vec3 e = emissive * sampleMap(m, kMapEmissive, f).xyz;
    emissive = e;
  }
  return shadePbr(pbrLobes(base, metallic, roughness), occlusion, emissive, n, p);
}
