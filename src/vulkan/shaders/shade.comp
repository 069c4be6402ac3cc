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
  const float x0 = raster_records[slot].x0, y0 = raster_records[slot].y0;

  // Perspective-correct barycentrics from the 1/w-weighted planes.
  precise float dx = (float(x) + 0.5) - x0;
  precise float dy = (float(y) + 0.5) - y0;
  precise float w_sum = s.inv_w0 + s.sdx * dx + s.sdy * dy;
  precise float inv_s = 1.0 / w_sum;
  precise float b1 = (s.p1dx * dx + s.p1dy * dy) * inv_s;
  precise float b2 = (s.p2dx * dx + s.p2dy * dy) * inv_s;
  precise float b0 = 1.0 - b1 - b2;

  const GpuObject object = objects[s.object];
  const uint shading = (s.material_shading >> 16) & 255u;
  const bool has_uv = (s.material_shading & (1u << 24)) != 0u;
  const GpuMaterial material = objectMaterial(object, s.material_shading & 0xffffu);

  precise vec4 albedo = material.base_color;
  albedo = albedo * (s.color[0] * b0 + s.color[1] * b1 + s.color[2] * b2);
  if ((material.texture_flags & kTexturePresent) != 0u && has_uv) {
    precise vec2 uv = s.uv[0] * b0 + s.uv[1] * b1 + s.uv[2] * b2;
    albedo = albedo * sampleTexture(material, uv);
  }

  vec3 normal;
  if (shading == kShadingFlat)
    normal = s.normal[0].xyz;
  else
    normal = normalizeAsCpu(s.normal[0].xyz * b0 + s.normal[1].xyz * b1 + s.normal[2].xyz * b2);

  precise vec3 light = vec3(1.0);
  if (shading == kShadingFlat) {
    light = irradiance(s.normal[0].xyz);
  } else if (shading == kShadingPhong) {
    light = irradiance(normal);
  } else if (shading == kShadingGouraud) {
    light = irradiance(s.normal[0].xyz) * b0 + irradiance(s.normal[1].xyz) * b1 +
            irradiance(s.normal[2].xyz) * b2;
  }
  precise vec3 color = albedo.xyz * light;

  output_words[pixel] = packColor(color);
  output_words[n + pixel] = floatBitsToUint(depthFromOrdered(visibility_words[2u * pixel + 1u]));
  output_words[2u * n + pixel] = s.triangle_id + 1u;
  if (normals) {
    output_words[3u * n + 3u * pixel] = floatBitsToUint(normal.x);
    output_words[3u * n + 3u * pixel + 1u] = floatBitsToUint(normal.y);
    output_words[3u * n + 3u * pixel + 2u] = floatBitsToUint(normal.z);
  }
}
