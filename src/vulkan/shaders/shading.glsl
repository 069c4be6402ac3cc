// Materials, lights, texture sampling and the sRGB encode, with the arithmetic of the CPU's
// src/render/shade.cpp, src/render/setup.cpp (irradiance), src/scene/texture.cpp and
// src/scene/color.cpp, in the same order of operations (precise: no fused multiply-adds), so the
// two backends' colours differ only where a GPU's division or square root rounds differently.
// Needs common.glsl.

// Lambert irradiance: ambient plus every directional light, for unit normal n.
vec3 irradiance(vec3 n) {
  precise vec3 e = frame.ambient.xyz;
  for (uint i = 0u; i < frame.light_count; ++i) {
    const vec3 d = lights[i].direction.xyz;
    precise float cos_theta = -(n.x * d.x + n.y * d.y + n.z * d.z);
    if (cos_theta > 0.0) e = e + lights[i].color.xyz * cos_theta;
  }
  return e;
}

// The material of triangle-material index m of an object (the CPU falls back to material 0).
GpuMaterial objectMaterial(GpuObject object, uint m) {
  return materials[object.material_base + (m < object.material_count ? m : 0u)];
}

// ---- textures (src/scene/texture.cpp) ----

int wrapCoord(int i, int size, bool clamp_to_edge) {
  if (clamp_to_edge) return i < 0 ? 0 : (i >= size ? size - 1 : i);
  if (i >= 0) return i % size;
  const int m = (-i) % size;  // GLSL leaves % of negative operands undefined
  return m == 0 ? 0 : size - m;
}

float decodeSrgb8(uint code) { return uintBitsToFloat(color_tables[code]); }

vec4 texelLinear(GpuMaterial m, int x, int y) {
  const uint c = texels[m.texel_offset + uint(y) * uint(m.texture_width) + uint(x)];
  const float a = float(c >> 24) / 255.0;
  if ((m.texture_flags & kTextureSrgb) != 0u)
    return vec4(decodeSrgb8(c & 255u), decodeSrgb8((c >> 8) & 255u), decodeSrgb8((c >> 16) & 255u),
                a);
  return vec4(float(c & 255u) / 255.0, float((c >> 8) & 255u) / 255.0,
              float((c >> 16) & 255u) / 255.0, a);
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

// Texture::sample: linear RGBA at uv (v = 0 is the bottom row).
vec4 sampleTexture(GpuMaterial m, vec2 uv) {
  if (m.texture_width <= 0 || m.texture_height <= 0) return vec4(1.0);
  const bool clamp_to_edge = (m.texture_flags & kTextureClamp) != 0u;
  precise float fx = sanitizeCoordinate(uv.x) * float(m.texture_width);
  precise float fy = (1.0 - sanitizeCoordinate(uv.y)) * float(m.texture_height);
  if ((m.texture_flags & kTextureNearest) != 0u) {
    const int x = wrapCoord(int(floor(fx)), m.texture_width, clamp_to_edge);
    const int y = wrapCoord(int(floor(fy)), m.texture_height, clamp_to_edge);
    return texelLinear(m, x, y);
  }
  // Bilinear between the four nearest texel centres, in linear space.
  precise float sx = fx - 0.5, sy = fy - 0.5;
  const float x0f = floor(sx), y0f = floor(sy);
  precise float tx = sx - x0f, ty = sy - y0f;
  const int x0 = int(x0f), y0 = int(y0f);
  const int xa = wrapCoord(x0, m.texture_width, clamp_to_edge);
  const int xb = wrapCoord(x0 + 1, m.texture_width, clamp_to_edge);
  const int ya = wrapCoord(y0, m.texture_height, clamp_to_edge);
  const int yb = wrapCoord(y0 + 1, m.texture_height, clamp_to_edge);
  const vec4 top = lerp4(texelLinear(m, xa, ya), texelLinear(m, xb, ya), tx);
  const vec4 bottom = lerp4(texelLinear(m, xa, yb), texelLinear(m, xb, yb), tx);
  return lerp4(top, bottom, ty);
}

// ---- output (src/scene/color.cpp) ----

// Linear [0, 1] (clamped; NaN to 0) to the 8-bit sRGB code, through the CPU's 65536-entry table.
uint encodeSrgb8(float linear) {
  const float clamped = linear > 0.0 ? min(linear, 1.0) : 0.0;
  precise float scaled = clamped * 65535.0 + 0.5;
  const uint index = uint(scaled);
  return (color_tables[256u + index / 4u] >> (8u * (index % 4u))) & 255u;
}

// packSrgba8(float4{rgb, 1}): R in the low byte, alpha 255.
uint packColor(vec3 linear) {
  return encodeSrgb8(linear.r) | (encodeSrgb8(linear.g) << 8) | (encodeSrgb8(linear.b) << 16) |
         (255u << 24);
}
