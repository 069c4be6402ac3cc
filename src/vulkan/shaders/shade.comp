#version 460
// Pass 6, shade and resolve: one invocation per pixel. A visibility layer's triangle key gives
// the setup record; a triangle is shaded from it (perspective-correct barycentrics, material,
// texture, lights: src/render/shade.cpp) and written out with the CPU's sRGB encode, together
// with the AOVs of Frame: window depth (+inf where empty), triangle id (scene index + 1, 0 where
// empty), when asked the world normal, and the coverage (covered samples / samples, 0..255).
//
// The colour resolve of render/sampling.h's contract: when every sample holds the same triangle
// it is shaded at the pixel centre, exactly as with one sample; otherwise each distinct triangle
// of the samples is shaded once, at the centre when the centre passes its three edge tests, else
// at the first sample (in pattern order) it holds, and weighted by the samples it holds; samples
// that hold none take the background; the sum is divided by the sample count in linear light and
// encoded once. The id, depth and normal AOVs are the pixel centre's layer (layer 0).
//
// TESSERA_RAY = 1 (the nonlinear projections): the barycentrics of a point are those of its ray's
// hit (rayBarycentrics), "the centre passes the edge tests" is the centre ray's plane test, and
// the trilinear level of detail takes the centre rays of the next pixels right and down (left and
// up at the image's edge), as the CPU's ray path.
//
// Output words (n pixels): colour [0, n), depth [n, 2n), id [2n, 3n), then normal (3 words a
// pixel) from 3n when asked, then coverage (one word a pixel) when asked.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#ifndef TESSERA_BLEND_PASS
#define TESSERA_BLEND_PASS 0
#endif
#ifndef TESSERA_MASK_PASS
#define TESSERA_MASK_PASS 0
#endif
#if TESSERA_MASK_PASS
#extension GL_EXT_shader_atomic_int64 : require
#endif
#include "common.glsl"
#include "records.glsl"
#include "shading.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, set = 0, binding = 17) readonly buffer VisibilityBuffer {
  uint visibility_words[];
};

// Perspective-correct barycentrics (b0, b1, b2) at window point p, from the 1/w-weighted planes
// (render::barycentricsAt).
vec3 barycentricsAt(ShadeRecord s, vec2 origin, vec2 p) {
  precise float dx = p.x - origin.x;
  precise float dy = p.y - origin.y;
  precise float inv_s = 1.0 / (s.inv_w0 + s.sdx * dx + s.sdy * dy);
  precise float b1 = (s.p1dx * dx + s.p1dy * dy) * inv_s;
  precise float b2 = (s.p2dx * dx + s.p2dy * dy) * inv_s;
  precise float b0 = 1.0 - b1 - b2;
  return vec3(b0, b1, b2);
}

// A shading point of pixel (x, y): its centre (kCentre) or the point of visibility layer `layer`.
const uint kCentre = 0xffffu;

#if TESSERA_RAY
// The ray of a pixel's point.
vec3 pointRay(ivec2 pixel, uint layer) {
  const uint ray_layer = layer == kCentre ? 0u : rayLayerOf(layer);
  return rayAt(ray_layer, uint(pixel.y) * uint(frame.width) + uint(pixel.x));
}

// The barycentrics of record `slot` at a pixel's point.
vec3 pointBarycentrics(uint slot, ShadeRecord s, ivec2 pixel, uint layer) {
  return rayBarycentrics(ray_records[slot], pointRay(pixel, layer));
}

// The barycentrics the trilinear level of detail takes for the next pixel right (step (1, 0)) or
// down: at its centre ray, or at the pixel left or up's where there is no next pixel.
vec3 neighbourBarycentrics(uint slot, ShadeRecord s, ivec2 pixel, uint layer, ivec2 step) {
  ivec2 next = pixel + step;
  if (next.x >= frame.width) next.x = max(pixel.x - 1, 0);
  if (next.y >= frame.height) next.y = max(pixel.y - 1, 0);
  return pointBarycentrics(slot, s, next, kCentre);
}
#else
// The barycentrics of record `slot` at a pixel's point (in window coordinates).
vec3 pointBarycentrics(uint slot, ShadeRecord s, ivec2 pixel, uint layer) {
  const vec2 offset = layer == kCentre
                          ? vec2(0.5)
                          : vec2(float(frame.layer_x[layer]), float(frame.layer_y[layer])) *
                                (1.0 / 256.0);
  const vec2 origin = vec2(raster_records[slot].x0, raster_records[slot].y0);
  return barycentricsAt(s, origin, vec2(pixel) + offset);
}

// The barycentrics the trilinear level of detail takes for the next pixel right (step (1, 0)) or
// down: at the same point of that pixel.
vec3 neighbourBarycentrics(uint slot, ShadeRecord s, ivec2 pixel, uint layer, ivec2 step) {
  return pointBarycentrics(slot, s, pixel + step, layer);
}
#endif

vec2 uvAt(ShadeRecord s, vec3 b) {
  precise vec2 uv = s.uv[0] * b.x + s.uv[1] * b.y + s.uv[2] * b.z;
  return uv;
}
vec2 uv1At(ShadeRecord s, vec3 b) {
  precise vec2 uv = s.uv1[0] * b.x + s.uv1[1] * b.y + s.uv1[2] * b.z;
  return uv;
}
// In the set of a texture with flags `flags` (kTextureSet1: TEXCOORD_1).
vec2 uvAt(ShadeRecord s, vec3 b, uint flags) {
  return (flags & kTextureSet1) != 0u ? uv1At(s, b) : uvAt(s, b);
}

// render::sampleAlbedo: trilinear filtering takes its level of detail from the UVs at the next
// pixels right and down.
// With alpha: the transparent pass (blend_pass.glsl) reads it as MASK does.
vec4 sampleAlbedoRgba(uint slot, ShadeRecord s, vec3 b, ivec2 pixel, uint layer) {
  const GpuMaterial m = materials[s.material];
  const uint flags = m.texture_flags;
  const vec2 uv = transformUv(m, uvAt(s, b, flags));
  const bool trilinear = (m.texture_flags & kTextureTrilinear) != 0u;
  float lod = 0.0;
  if (trilinear) {
    const vec2 size = vec2(float(m.texture_width), float(m.texture_height));
    precise vec2 du =
        transformUv(m, uvAt(s, neighbourBarycentrics(slot, s, pixel, layer, ivec2(1, 0)), flags)) -
        uv;
    precise vec2 dv =
        transformUv(m, uvAt(s, neighbourBarycentrics(slot, s, pixel, layer, ivec2(0, 1)), flags)) -
        uv;
    precise vec2 dx = du * size, dy = dv * size;
    precise float rho2 = max(dx.x * dx.x + dx.y * dx.y, dy.x * dy.x + dy.y * dy.y);
    lod = rho2 > 0.0 ? 0.5 * log2(rho2) : 0.0;
  }
  return sampleTextureAt(albedoTexture(m), uv, trilinear, lod);
}
vec3 sampleAlbedo(uint slot, ShadeRecord s, vec3 b, ivec2 pixel, uint layer) {
  return sampleAlbedoRgba(slot, s, b, pixel, layer).xyz;
}

const uint kMaxSamples = 8u;

uint layerKey(uint pixel, uint layer) {
  return visibility_words[2u * (pixel * frame.layers + layer)];
}
uint layerDepth(uint pixel, uint layer) {
  return visibility_words[2u * (pixel * frame.layers + layer) + 1u];
}

// The setup record of a triangle key (scene triangle << 3 | fan piece).
uint recordSlot(uint key) {
  const uint t = key >> 3, piece = key & 7u;
  return piece == 0u ? t : frame.triangle_count + extra_base[t] + piece - 1u;
}

// The shading normal (also the normal AOV): flat shading keeps the face normal.
vec3 normalAt(ShadeRecord s, vec3 b) {
  if ((s.shading & 255u) == kShadingFlat) return s.normal[0].xyz;
  return normalizeAsCpu(s.normal[0].xyz * b.x + s.normal[1].xyz * b.y + s.normal[2].xyz * b.z);
}

// The world position at barycentrics b (from the corners' spare floats).
vec3 worldAt(ShadeRecord s, vec3 b) {
  const vec3 w0 = vec3(s.normal[0].w, s.color[0].w, s.world_z[0]);
  const vec3 w1 = vec3(s.normal[1].w, s.color[1].w, s.world_z[1]);
  const vec3 w2 = vec3(s.normal[2].w, s.color[2].w, s.world_z[2]);
  precise vec3 p = w0 * b.x + w1 * b.y + w2 * b.z;
  return p;
}

// kPbr: the UVs of a point and of the same point of the next pixels right and down (the maps'
// trilinear level of detail, as sampleAlbedo's).
UvFootprint footprintAt(uint slot, ShadeRecord s, vec3 b, ivec2 pixel, uint layer) {
  UvFootprint f;
  const vec3 right = neighbourBarycentrics(slot, s, pixel, layer, ivec2(1, 0));
  const vec3 down = neighbourBarycentrics(slot, s, pixel, layer, ivec2(0, 1));
  f.uv = uvAt(s, b);
  f.right = uvAt(s, right);
  f.down = uvAt(s, down);
  f.uv1 = uv1At(s, b);
  f.right1 = uv1At(s, right);
  f.down1 = uv1At(s, down);
  return f;
}

// kPbr's shading normal: the interpolated one, perturbed by the material's normal map when the
// mesh has tangents (shade_lanes.h: shadePbrLanes).
vec3 pbrNormalAt(ShadeRecord s, vec3 b, UvFootprint f) {
  const vec3 n = normalAt(s, b);
  const GpuMaterial m = materials[s.material];
  if ((s.shading & kShadePbrTangents) == 0u || !hasMap(m, kMapNormal)) return n;
  precise vec3 tangent = s.tangent[0].xyz * b.x + s.tangent[1].xyz * b.y + s.tangent[2].xyz * b.z;
  return normalMapped(m, n, tangent, s.tangent[0].w < 0.0 ? -1.0 : 1.0, f);
}

// The linear colour of record `slot` at a point of pixel (x, y).
vec3 shadeAt(uint slot, ivec2 pixel, uint layer) {
  const ShadeRecord s = shade_records[slot];
  const vec3 b = pointBarycentrics(slot, s, pixel, layer);
  precise vec3 color = s.color[0].xyz * b.x + s.color[1].xyz * b.y + s.color[2].xyz * b.z;
  if ((s.shading & kShadeHasUv) != 0u) color = color * sampleAlbedo(slot, s, b, pixel, layer);
  if ((s.shading & 255u) == kShadingPbr) {
    const bool maps = (s.shading & kShadePbrUv) != 0u;
    const UvFootprint f = maps ? footprintAt(slot, s, b, pixel, layer)
                               : UvFootprint(vec2(0.0), vec2(0.0), vec2(0.0), vec2(0.0), vec2(0.0),
                                             vec2(0.0));
    color = shadePbrMaterial(materials[s.material], color, pbrNormalAt(s, b, f), worldAt(s, b),
                             maps, f);
  } else if ((s.shading & 255u) == kShadingPhong) {
    color = color * irradianceShadowed(normalAt(s, b), worldAt(s, b));
  }
  return toneMap(color);
}

#if TESSERA_RAY
// Whether the centre ray of pixel (x, y) passes the record's plane test (no depth range).
bool coversCentre(uint slot, int x, int y) {
  return rayCovers(ray_records[slot], pointRay(ivec2(x, y), kCentre));
}
#else
// Whether the pixel centre (x, y) passes the record's three edge tests.
bool coversCentre(uint slot, int x, int y) {
  const int64_t px = int64_t(x) * kSubpixelOne + kSubpixelHalf;
  const int64_t py = int64_t(y) * kSubpixelOne + kSubpixelHalf;
  for (int k = 0; k < 3; ++k)
    if (int64_t(raster_records[slot].a[k]) * px + int64_t(raster_records[slot].b[k]) * py +
            raster_records[slot].c[k] < 0l)
      return false;
  return true;
}
#endif

// The resolved sRGB colour of pixel (x, y); `covered` receives the samples holding a triangle.
uint resolveColor(uint pixel, int x, int y, out uint covered) {
  const uint samples = frame.samples, first = frame.first_sample_layer;
  uint keys[kMaxSamples], counts[kMaxSamples], first_sample[kMaxSamples];
  uint distinct = 0u;
  covered = 0u;
  for (uint i = 0u; i < samples; ++i) {
    const uint key = layerKey(pixel, first + i);
    if (key == kEmptyWord) continue;
    ++covered;
    uint d = 0u;
    while (d < distinct && keys[d] != key) ++d;
    if (d == distinct) {
      keys[d] = key;
      counts[d] = 0u;
      first_sample[d] = i;
      ++distinct;
    }
    ++counts[d];
  }
  const ivec2 pixel_xy = ivec2(x, y);
  if (covered == 0u) return frame.background;
  // One triangle on every sample: its colour at the centre, which the sum below gives unchanged
  // (times the sample count and then its inverse, both powers of two). One call of shadeAt in the
  // shader: lavapipe inlines every call, and its compile time follows the shader's size.
  const bool whole = distinct == 1u && covered == samples;
  precise vec3 sum = frame.background_linear.xyz * float(samples - covered);
  for (uint d = 0u; d < distinct; ++d) {
    const uint slot = recordSlot(keys[d]);
    const uint layer = whole || coversCentre(slot, x, y) ? kCentre : first + first_sample[d];
    sum = sum + shadeAt(slot, pixel_xy, layer) * float(counts[d]);
  }
  // Times 1 / samples, exactly (a power of two), rather than a division a GPU may round loosely.
  precise vec3 average = sum * uintBitsToFloat(uint(127 - findMSB(samples)) << 23);
  return packColor(average);
}

// Whether record r covers pixel (x, y)'s visibility layer `layer` (the exact edge test at the
// layer's sample point, as raster.comp), and its depth there: the BLEND and MASK passes' per-sample
// test.
bool layerCovered(RasterRecord r, int x, int y, uint layer) {
  const int64_t px = int64_t(x) * kSubpixelOne + frame.layer_x[layer];
  const int64_t py = int64_t(y) * kSubpixelOne + frame.layer_y[layer];
  for (int k = 0; k < 3; ++k)
    if (int64_t(r.a[k]) * px + int64_t(r.b[k]) * py + r.c[k] < 0l) return false;
  return true;
}
float layerRecordDepth(RasterRecord r, int x, int y, uint layer) {
  const float shift_x = float(frame.layer_x[layer] - kSubpixelHalf) * (1.0 / 256.0);
  const float shift_y = float(frame.layer_y[layer] - kSubpixelHalf) * (1.0 / 256.0);
  precise float x0 = r.x0 - shift_x;
  precise float y0 = r.y0 - shift_y;
  precise float z_row = r.z0 + r.dzdy * ((float(y) + 0.5) - y0);
  precise float z = z_row + r.dzdx * ((float(x) + 0.5) - x0);
  return z;
}

#if TESSERA_BLEND_PASS
// The transparent pass's main(), on this file's shading (alphaMode BLEND).
#include "blend_pass.glsl"
#elif TESSERA_MASK_PASS
// The MASK pass's main(), on this file's texture sampling (alphaMode MASK).
#include "mask_pass.glsl"
#else
void main() {
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= frame.width || y >= frame.height) return;
  const uint n = uint(frame.width) * uint(frame.height);
  const uint pixel = uint(y) * uint(frame.width) + uint(x);
  const bool normals = (frame.flags & kFrameNormals) != 0u;
  uint covered;
  output_words[pixel] = resolveColor(pixel, x, y, covered);
  if ((frame.flags & kFrameCoverage) != 0u)
    output_words[(normals ? 6u : 3u) * n + pixel] =
        (covered * 255u + frame.samples / 2u) / frame.samples;

  // The AOVs: the pixel centre is layer 0 (a sample itself when there is one sample).
  const bool has_centre = frame.samples == 1u || frame.first_sample_layer == 1u;
  const uint key = has_centre ? layerKey(pixel, 0u) : kEmptyWord;
  vec3 normal = vec3(0.0);
  if (key == kEmptyWord) {
    output_words[n + pixel] = 0x7f800000u;  // +inf
    output_words[2u * n + pixel] = 0u;
  } else {
    const uint slot = recordSlot(key);
    const ShadeRecord s = shade_records[slot];
    output_words[n + pixel] = floatBitsToUint(depthFromOrdered(layerDepth(pixel, 0u)));
    output_words[2u * n + pixel] = s.triangle_id + 1u;
    if (normals) {
      const vec3 b = pointBarycentrics(slot, s, ivec2(x, y), kCentre);
      normal = (s.shading & 255u) == kShadingPbr && (s.shading & kShadePbrUv) != 0u
                   ? pbrNormalAt(s, b, footprintAt(slot, s, b, ivec2(x, y), kCentre))
                   : normalAt(s, b);
    }
  }
  if (normals) {
    output_words[3u * n + 3u * pixel] = floatBitsToUint(normal.x);
    output_words[3u * n + 3u * pixel + 1u] = floatBitsToUint(normal.y);
    output_words[3u * n + 3u * pixel + 2u] = floatBitsToUint(normal.z);
  }
}
#endif
