// Materials, lights, texture sampling and the sRGB encode, with the arithmetic of the CPU's
// src/render/shade.cpp, src/render/setup.cpp (irradiance), src/scene/texture.cpp and
// src/scene/color.cpp, in the same order of operations (precise: no fused multiply-adds), so the
// two backends' colours differ only where a GPU's division or square root rounds differently.
// Needs common.glsl.

// What a point or spot light gives a surface at p with unit normal n, per unit radiance
// (src/render/lights.h: localFactor, the same operations in the same order).
float localFactor(Light light, vec3 n, vec3 p) {
  precise vec3 l = light.position.xyz - p;
  precise float d2 = (l.x * l.x + l.y * l.y) + l.z * l.z;
  precise float inv_d = 1.0 / sqrt(d2);
  precise vec3 u = l * inv_d;
  precise float cos_theta = (n.x * u.x + n.y * u.y) + n.z * u.z;
  precise float window = clamp(1.0 - d2 * d2 * light.color.w, 0.0, 1.0);
  const vec3 d = light.direction.xyz;
  precise float cd = -((d.x * u.x + d.y * u.y) + d.z * u.z);
  precise float t = clamp(cd * light.position.w + light.spot.x, 0.0, 1.0);
  precise float f = cos_theta * ((window * (t * t)) / d2);
  return f;
}

// A light's Lambert factor for unit normal n at world point p (at or below 0: unlit).
float lambertFactor(Light light, vec3 n, vec3 p) {
  const vec3 d = light.direction.xyz;
  precise float f = light.direction.w == 0.0 ? -(n.x * d.x + n.y * d.y + n.z * d.z)
                                             : localFactor(light, n, p);
  return f;
}

// Lambert irradiance: ambient plus every light, for unit normal n at world point p
// (src/render/lights.h: irradiance).
vec3 irradiance(vec3 n, vec3 p) {
  precise vec3 e = frame.ambient.xyz;
  for (uint i = 0u; i < frame.light_count; ++i) {
    const Light light = lights[i];
    precise float f = lambertFactor(light, n, p);
    if (f > 0.0) e = e + light.color.xyz * f;
  }
  return e;
}

// Shadow maps: irradianceShadowed() for Phong pixels, shadowVisibility() for kPbr's lights.
#include "shadow.glsl"

// An object-space point in world space (the CPU's float4x4 * float4 with w = 1).
vec3 worldPosition(mat4 model, vec3 p) {
  precise vec3 w = model[0].xyz * p.x + model[1].xyz * p.y + model[2].xyz * p.z + model[3].xyz;
  return w;
}

// The material buffer index of triangle-material index m of an object (the CPU falls back to
// material 0).
uint objectMaterialIndex(GpuObject object, uint m) {
  return object.material_base + (m < object.material_count ? m : 0u);
}
GpuMaterial objectMaterial(GpuObject object, uint m) {
  return materials[objectMaterialIndex(object, m)];
}

// ---- textures (src/scene/texture.cpp) ----

// One mip level in the texel buffer (see the texture header in gpu_types.h).
struct TextureLevel {
  uint offset;
  int width, height;
};

// The albedo slot of a material as a TextureRef.
TextureRef albedoTexture(GpuMaterial m) {
  return TextureRef(m.texel_offset, m.texture_width, m.texture_height, m.texture_flags);
}

int textureLevelCount(TextureRef t) { return int(texels[t.texel_offset]); }
TextureLevel textureLevel(TextureRef t, int level) {
  const uint h = t.texel_offset + 1u + 3u * uint(level);
  return TextureLevel(texels[h], int(texels[h + 1u]), int(texels[h + 2u]));
}

// tessera::wrapTexel. wrap: 0 repeat, 1 clamp to edge, 2 mirrored repeat.
const int kWrapRepeat = 0;
const int kWrapClamp = 1;
const int kWrapMirror = 2;
int wrapCoord(int i, int size, int wrap) {
  if (wrap == kWrapClamp) return i < 0 ? 0 : (i >= size ? size - 1 : i);
  const int period = wrap == kWrapMirror ? 2 * size : size;
  // i mod period, never % of a negative operand (GLSL leaves that undefined).
  const int m = i >= 0 ? i % period : period - 1 - ((-1 - i) % period);
  return m < size ? m : period - 1 - m;
}

// The wrap modes along s and t of a sampler's kTexture* flags.
ivec2 textureWraps(uint f) {
  const int s = (f & kTextureClampS) != 0u
                    ? kWrapClamp
                    : ((f & kTextureMirrorS) != 0u ? kWrapMirror : kWrapRepeat);
  const int t = (f & kTextureClampT) != 0u
                    ? kWrapClamp
                    : ((f & kTextureMirrorT) != 0u ? kWrapMirror : kWrapRepeat);
  return ivec2(s, t);
}

// UvAffine::apply with rows a and b.
vec2 applyAffine(vec3 a, vec3 b, vec2 uv) {
  precise vec2 r = vec2((a.x * uv.x + a.y * uv.y) + a.z, (b.x * uv.x + b.y * uv.y) + b.z);
  return r;
}

// The sampler's transform (UvAffine::apply), where the material has one.
vec2 transformUv(GpuMaterial m, vec2 uv) {
  if ((m.texture_flags & kTextureTransformed) == 0u) return uv;
  return applyAffine(m.uv_transform[0].xyz, m.uv_transform[1].xyz, uv);
}

// PBR map `map`'s own transform, where it has one.
vec2 transformMapUv(GpuMaterial m, int map, vec2 uv) {
  if ((m.maps[map].flags & kTextureTransformed) == 0u) return uv;
  return applyAffine(m.map_transform[2 * map].xyz, m.map_transform[2 * map + 1].xyz, uv);
}

float decodeSrgb8(uint code) { return uintBitsToFloat(color_tables[code]); }

vec4 texelLinear(TextureLevel level, bool srgb, int x, int y) {
  const uint c = texels[level.offset + uint(y) * uint(level.width) + uint(x)];
  const float a = float(c >> 24) / 255.0;
  if (srgb)
    return vec4(decodeSrgb8(c & 255u), decodeSrgb8((c >> 8) & 255u), decodeSrgb8((c >> 16) & 255u),
                a);
  return vec4(float(c & 255u) / 255.0, float((c >> 8) & 255u) / 255.0,
              float((c >> 16) & 255u) / 255.0, a);
}

// The bilinear filter's fixed point (tessera::FixedFilter, texture.h): its scale after the
// encode's 18 constants (makeColorTables checks the place), then texelFixedTable's values.
const uint kFixedScale = 274u;
const uint kFixedUnorm = kFixedScale + 1u;
const uint kFixedSrgb = kFixedUnorm + 256u;
ivec4 texelFixed(TextureLevel level, bool srgb, int x, int y) {
  const uint c = texels[level.offset + uint(y) * uint(level.width) + uint(x)];
  const uint colour = srgb ? kFixedSrgb : kFixedUnorm;
  return ivec4(int(color_tables[colour + (c & 255u)]),
               int(color_tables[colour + ((c >> 8) & 255u)]),
               int(color_tables[colour + ((c >> 16) & 255u)]),
               int(color_tables[kFixedUnorm + (c >> 24)]));
}

// std::fmod(v, 65536) for finite v (exact: 65536 is a power of two), 0 otherwise.
float sanitizeCoordinate(float v) {
  if (isinf(v) || isnan(v)) return 0.0;
  if (abs(v) < 65536.0) return v;
  precise float wrapped = v - 65536.0 * trunc(v / 65536.0);
  return wrapped;
}

vec4 lerp4(vec4 a, vec4 b, float t) {
  precise vec4 r = a + (b - a) * t;
  return r;
}

// sampleLevel: nearest or bilinear in one level.
vec4 sampleLevel(TextureLevel level, bool srgb, vec2 uv, bool nearest, ivec2 wrap) {
  // Texel space: x right, y down from the top row (v = 1 is the top edge).
  precise float fx = sanitizeCoordinate(uv.x) * float(level.width);
  precise float fy = (1.0 - sanitizeCoordinate(uv.y)) * float(level.height);
  if (nearest) {
    const int x = wrapCoord(int(floor(fx)), level.width, wrap.x);
    const int y = wrapCoord(int(floor(fy)), level.height, wrap.y);
    return texelLinear(level, srgb, x, y);
  }
  // Bilinear between the four nearest texel centres, in linear space.
  precise float sx = fx - 0.5, sy = fy - 0.5;
  const float x0f = floor(sx), y0f = floor(sy);
  precise float tx = sx - x0f, ty = sy - y0f;
  const int x0 = int(x0f), y0 = int(y0f);
  const int xa = wrapCoord(x0, level.width, wrap.x);
  const int xb = wrapCoord(x0 + 1, level.width, wrap.x);
  const int ya = wrapCoord(y0, level.height, wrap.y);
  const int yb = wrapCoord(y0 + 1, level.height, wrap.y);
  // FixedFilter: across a row in integers with 14-bit weights, down in float, then scaled.
  precise float weight = tx * 16384.0;
  const int w1 = int(weight), w0 = 16384 - w1;
  const ivec4 upper_sum =
      texelFixed(level, srgb, xa, ya) * w0 + texelFixed(level, srgb, xb, ya) * w1;
  const ivec4 lower_sum =
      texelFixed(level, srgb, xa, yb) * w0 + texelFixed(level, srgb, xb, yb) * w1;
  precise vec4 upper = vec4(upper_sum), lower = vec4(lower_sum);
  precise vec4 r = (upper + (lower - upper) * ty) * uintBitsToFloat(color_tables[kFixedScale]);
  return r;
}

// Texture::sample (level 0, nearest or bilinear) or, with `trilinear`, Texture::sampleLod
// (bilinear in the two levels around lod, blended); uv after the sampler's transform. The levels
// are taken in a loop so that the shader holds one copy of sampleLevel a call: lavapipe inlines
// every call, and its compile time grows with the shader
// (docs/perf-notes/per-pixel-lighting-projections-vulkan.md).
vec4 sampleTextureAt(TextureRef t, vec2 uv, bool trilinear, float lod) {
  if (t.width <= 0 || t.height <= 0) return vec4(1.0);
  const bool srgb = (t.flags & kTextureSrgb) != 0u;
  const ivec2 wrap = textureWraps(t.flags);
  bool nearest = (t.flags & kTextureNearest) != 0u;
  int lower = 0, levels = 1;
  float blend = 0.0;
  if (trilinear) {
    const int last = textureLevelCount(t) - 1;
    if (!(lod > 0.0)) lod = 0.0;  // also catches NaN
    if (lod > float(last)) lod = float(last);
    lower = int(lod);
    precise float fraction = lod - float(lower);
    blend = fraction;
    nearest = false;
    if (!(blend == 0.0 || lower >= last)) levels = 2;
  }
  vec4 color = vec4(0.0);
  for (int i = 0; i < levels; ++i) {
    const vec4 level = sampleLevel(textureLevel(t, lower + i), srgb, uv, nearest, wrap);
    color = i == 0 ? level : lerp4(color, level, blend);
  }
  return color;
}

// ---- output (src/scene/color.cpp) ----

// tessera::encodeSrgb8 (tessera/scene/color.h, SrgbEncode): linear [0, 1] (clamped; NaN to 0) to
// the 8-bit sRGB code. Above the linear segment, c = m * 2^e: scale[e + 9] * poly(m - 1) - offset.
// The constants come from the CPU (makeColorTables), after the decode table: scale[10], poly[5],
// the end of the linear segment, its factor, the offset.
const uint kEncodeScale = 256u;
const uint kEncodePoly = kEncodeScale + 10u;
const uint kEncodeLinearEnd = kEncodePoly + 5u;
float encodeConstant(uint i) { return uintBitsToFloat(color_tables[i]); }
uint encodeSrgb8(float linear) {
  const float c = linear > 0.0 ? (linear < 1.0 ? linear : 1.0) : 0.0;
  precise float code;
  if (c <= encodeConstant(kEncodeLinearEnd)) {
    code = c * encodeConstant(kEncodeLinearEnd + 1u);
  } else {
    const uint bits = floatBitsToUint(c);
    const int e = int(bits >> 23) - 127;
    precise float x = uintBitsToFloat((bits & 0x7fffffu) | 0x3f800000u) - 1.0;
    precise float p = encodeConstant(kEncodePoly + 4u) * x + encodeConstant(kEncodePoly + 3u);
    p = p * x + encodeConstant(kEncodePoly + 2u);
    p = p * x + encodeConstant(kEncodePoly + 1u);
    p = p * x + encodeConstant(kEncodePoly);
    code = encodeConstant(kEncodeScale + uint(e + 9)) * p - encodeConstant(kEncodeLinearEnd + 2u);
    code = code < 255.0 ? code : 255.0;
  }
  precise float rounded = code + 0.5;
  return uint(int(rounded));
}

// packSrgba8(float4{rgb, 1}): R in the low byte, alpha 255.
uint packColor(vec3 linear) {
  return encodeSrgb8(linear.r) | (encodeSrgb8(linear.g) << 8) | (encodeSrgb8(linear.b) << 16) |
         (255u << 24);
}

// The display transform (tone_curve.glsl) with the frame's exposure and curve.
#include "tone_curve.glsl"

vec3 toneMap(vec3 color) {
  return toneCurve(color, frame.ambient.w, (frame.flags >> kFrameToneShift) & 3u);
}

// The metallic-roughness BRDF (kPbr), shared by both backends.
#include "pbr.glsl"
