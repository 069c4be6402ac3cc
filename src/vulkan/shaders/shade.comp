#version 460
// Pass 6, shade and resolve: one invocation per pixel. The visibility buffer's triangle key
// gives the setup record; the pixel is shaded once from it (perspective-correct barycentrics,
// material, texture, lights: src/render/shade.cpp) and written out with the CPU's sRGB encode,
// together with the AOVs of Frame: window depth (+inf where empty), triangle id (scene index + 1,
// 0 where empty) and, when asked, the world normal.
//
// Output words (n pixels): colour [0, n), depth [n, 2n), id [2n, 3n), normal [3n, 6n).
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
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

vec2 uvAt(ShadeRecord s, vec3 b) {
  precise vec2 uv = s.uv[0] * b.x + s.uv[1] * b.y + s.uv[2] * b.z;
  return uv;
}

// render::sampleAlbedo: trilinear filtering takes its level of detail from the UVs at the next
// pixel centres right and down.
vec3 sampleAlbedo(ShadeRecord s, vec2 origin, vec3 b, vec2 centre) {
  const GpuMaterial m = materials[s.material];
  const vec2 uv = uvAt(s, b);
  if ((m.texture_flags & kTextureTrilinear) == 0u) return sampleTexture(m, uv).xyz;
  const vec2 size = vec2(float(m.texture_width), float(m.texture_height));
  precise vec2 du = uvAt(s, barycentricsAt(s, origin, centre + vec2(1.0, 0.0))) - uv;
  precise vec2 dv = uvAt(s, barycentricsAt(s, origin, centre + vec2(0.0, 1.0))) - uv;
  precise vec2 dx = du * size, dy = dv * size;
  precise float rho2 = max(dx.x * dx.x + dx.y * dx.y, dy.x * dy.x + dy.y * dy.y);
  const float lod = rho2 > 0.0 ? 0.5 * log2(rho2) : 0.0;
  return sampleTextureTrilinear(m, uv, lod).xyz;
}

void main() {
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= frame.width || y >= frame.height) return;
  const uint n = uint(frame.width) * uint(frame.height);
  const uint pixel = uint(y) * uint(frame.width) + uint(x);
  const bool normals = (frame.flags & kFrameNormals) != 0u;
  const uint key = visibility_words[2u * pixel];
  if (key == kEmptyWord) {
    output_words[pixel] = frame.background;
    output_words[n + pixel] = 0x7f800000u;  // +inf
    output_words[2u * n + pixel] = 0u;
    if (normals) {
      output_words[3u * n + 3u * pixel] = 0u;
      output_words[3u * n + 3u * pixel + 1u] = 0u;
      output_words[3u * n + 3u * pixel + 2u] = 0u;
    }
    return;
  }
  const uint t = key >> 3, piece = key & 7u;
  const uint slot = piece == 0u ? t : frame.triangle_count + extra_base[t] + piece - 1u;
  const ShadeRecord s = shade_records[slot];
  const vec2 origin = vec2(raster_records[slot].x0, raster_records[slot].y0);
  const vec2 centre = vec2(float(x) + 0.5, float(y) + 0.5);
  const vec3 b = barycentricsAt(s, origin, centre);

  const uint shading = s.shading & 255u;
  precise vec3 color = s.color[0].xyz * b.x + s.color[1].xyz * b.y + s.color[2].xyz * b.z;
  if ((s.shading & kShadeHasUv) != 0u) color = color * sampleAlbedo(s, origin, b, centre);
  vec3 normal = s.normal[0].xyz;
  if (shading == kShadingPhong || (normals && shading != kShadingFlat)) {
    normal = normalizeAsCpu(s.normal[0].xyz * b.x + s.normal[1].xyz * b.y +
                            s.normal[2].xyz * b.z);
    if (shading == kShadingPhong) color = color * irradiance(normal);
  }

  output_words[pixel] = packColor(color);
  output_words[n + pixel] = floatBitsToUint(depthFromOrdered(visibility_words[2u * pixel + 1u]));
  output_words[2u * n + pixel] = s.triangle_id + 1u;
  if (normals) {
    output_words[3u * n + 3u * pixel] = floatBitsToUint(normal.x);
    output_words[3u * n + 3u * pixel + 1u] = floatBitsToUint(normal.y);
    output_words[3u * n + 3u * pixel + 2u] = floatBitsToUint(normal.z);
  }
}
