#version 460
// vulkan-raster, fragment stage: the CPU's materials and lights (shading.glsl) on the
// hardware-interpolated attributes; writes the packed sRGB colour, the triangle id
// (gl_PrimitiveID + the object's first triangle + 1) and the world normal.
//
// TESSERA_MSAA = 1: the multisample pass's variant. It writes the linear colour with alpha 1 (the
// resolve averages it with the background's alpha 0 into covered samples / samples), and takes
// its attributes at the centroid: at the pixel centre when the triangle covers it, else inside
// the triangle, as the CPU's resolve shades a triangle at its first covered sample.
//
// TESSERA_BLEND = 1 (with TESSERA_MSAA = 1): the transparent pass's variant (alphaMode BLEND,
// raster_blend.h). Its draws read the appended copies of the blended triangles, from
// draw.first_triangle on, and it writes the linear colour with the material's alpha (base colour
// times texture, as MASK reads it; clamped to [0, 1], NaN 0), which the pipeline's blend state
// puts over what the pass holds: C A + D (1 - A), and A + a (1 - A) in alpha (the coverage).
#ifndef TESSERA_BLEND
#define TESSERA_BLEND 0
#endif
#include "common.glsl"
#include "shading.glsl"

#if TESSERA_MSAA
#define TESSERA_INTERPOLATION centroid
#else
#define TESSERA_INTERPOLATION
#endif

#if TESSERA_BLEND
layout(push_constant) uniform Draw { uint object; uint first_triangle; } draw;
#else
layout(push_constant) uniform Draw { uint object; } draw;
#endif

layout(location = 0) TESSERA_INTERPOLATION in vec3 in_normal;
layout(location = 1) TESSERA_INTERPOLATION in vec2 in_uv;
layout(location = 2) TESSERA_INTERPOLATION in vec3 in_color_front;
layout(location = 3) TESSERA_INTERPOLATION in vec3 in_color_back;
layout(location = 5) TESSERA_INTERPOLATION in vec3 in_world;
layout(location = 6) TESSERA_INTERPOLATION in vec3 in_tangent;
layout(location = 7) flat in float in_tangent_sign;
layout(location = 8) TESSERA_INTERPOLATION in vec2 in_uv1;  // TEXCOORD_1
#if TESSERA_MSAA
// The UV at the pixel centre: its differences across the quad give the level of detail.
layout(location = 4) in vec2 in_uv_centre;
layout(location = 9) in vec2 in_uv1_centre;
#else
#define in_uv_centre in_uv
#define in_uv1_centre in_uv1
#endif

#if TESSERA_MSAA
layout(location = 0) out vec4 out_linear;
#else
layout(location = 0) out uint out_color;
layout(location = 1) out uint out_id;
layout(location = 2) out vec4 out_normal;
#endif

// The triangle's UV at window point q (pixels, y down), perspective-correct, from its vertices'
// zero-to-one clip positions: the barycentrics b with sum_i b_i (clip_i.xy - ndc(q) clip_i.w) = 0
// (homogeneous rasterization, Olano and Greer 1997), normalized to sum 1.
vec2 uvAtWindow(GpuObject object, vec3 p[3], vec2 uv[3], vec2 q) {
  const vec2 ndc =
      vec2(q.x / float(frame.width) * 2.0 - 1.0, 1.0 - q.y / float(frame.height) * 2.0);
  const mat4 m = object.model_view_projection_zo;
  vec2 r[3];
  for (int k = 0; k < 3; ++k) {
    const vec4 clip = m * vec4(p[k], 1.0);
    r[k] = clip.xy - ndc * clip.w;
  }
  const vec3 b = vec3(r[1].x * r[2].y - r[1].y * r[2].x, r[2].x * r[0].y - r[2].y * r[0].x,
                      r[0].x * r[1].y - r[0].y * r[1].x);
  return (uv[0] * b.x + uv[1] * b.y + uv[2] * b.z) / (b.x + b.y + b.z);
}

// kPbr's trilinear maps (and albedo) step the UV to the next pixel centres right and down, as
// the CPU takes them, rather than by the quad's differences (a backward one on odd pixels: up to
// 29/255 from the CPU near a sphere's poles in VulkanPbr.MapsAndTangentsMatchCpu...).
// The same for both sets: uv_d[0], uv_d[1] are set 0's steps right and down, uv_d[2], uv_d[3] set
// 1's.
void uvStepsToNextPixels(GpuObject object, uvec3 corner, inout vec2 uv_d[4]) {
  vec3 p[3];
  vec2 uv[3], uv1[3];
  for (int k = 0; k < 3; ++k) {
    p[k] = vertexPosition(object.vertex_base + corner[k]);
    uv[k] = vertexUv(object.vertex_base + corner[k]);
    uv1[k] = vertexUv1(object.vertex_base + corner[k]);
  }
  const vec2 centre = uvAtWindow(object, p, uv, gl_FragCoord.xy);
  uv_d[0] = uvAtWindow(object, p, uv, gl_FragCoord.xy + vec2(1.0, 0.0)) - centre;
  uv_d[1] = uvAtWindow(object, p, uv, gl_FragCoord.xy + vec2(0.0, 1.0)) - centre;
  const vec2 centre1 = uvAtWindow(object, p, uv1, gl_FragCoord.xy);
  uv_d[2] = uvAtWindow(object, p, uv1, gl_FragCoord.xy + vec2(1.0, 0.0)) - centre1;
  uv_d[3] = uvAtWindow(object, p, uv1, gl_FragCoord.xy + vec2(0.0, 1.0)) - centre1;
}

// A kPbr fragment's linear colour from its base colour; `normal` (the interpolated one, facing
// the viewer) becomes the shading normal. f: the maps' UVs and their level of detail's.
vec3 shadePbrFragment(GpuObject object, GpuMaterial material, vec3 base, float flip, UvFootprint f,
                      inout vec3 normal) {
  // Drawn back faces flip the whole tangent frame, as the CPU's setup does.
  if ((object.flags & kObjectHasTangents) != 0u && hasMap(material, kMapNormal))
    normal = normalMapped(material, normal, in_tangent * flip, in_tangent_sign * flip, f);
  return shadePbrMaterial(material, base, normal, in_world, (object.flags & kObjectHasUv) != 0u,
                          f);
}

void main() {
  // Derivatives first, in uniform control flow: set 0's right and down, then set 1's.
  vec2 uv_d[4] = vec2[4](dFdx(in_uv_centre), dFdy(in_uv_centre), dFdx(in_uv1_centre),
                         dFdy(in_uv1_centre));
  const GpuObject object = objects[draw.object];
#if TESSERA_BLEND
  const uint t = draw.first_triangle + uint(gl_PrimitiveID);
#else
  const uint t = object.triangle_base + uint(gl_PrimitiveID);
#endif
  const float flip = gl_FrontFacing ? 1.0 : -1.0;

  // The face normal from the object-space positions, as the CPU's setup computes it.
  const uint i0 = indices[3u * t], i1 = indices[3u * t + 1u], i2 = indices[3u * t + 2u];
  const vec3 p0 = vertexPosition(object.vertex_base + i0);
  const vec3 p1 = vertexPosition(object.vertex_base + i1);
  const vec3 p2 = vertexPosition(object.vertex_base + i2);
  if (object.shading == kShadingPbr && (object.flags & kObjectHasUv) != 0u)
    uvStepsToNextPixels(object, uvec3(i0, i1, i2), uv_d);
  precise vec3 e1 = p1 - p0;
  precise vec3 e2 = p2 - p0;
  precise vec3 edge_cross = vec3(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z,
                                 e1.x * e2.y - e1.y * e2.x);
  precise vec3 winding_normal = multiply3x3(object.normal_matrix, edge_cross) * object.winding_sign;
  const vec3 face_normal = normalizeAsCpu(winding_normal) * flip;
  // The vertex normals face the viewer where the face does, unless a mirroring model's mesh (not
  // turned inside out) has them on the other side of the face than its winding (the CPU's
  // setupShadeCorners: normal_flip).
  float normal_flip = flip;
  if (object.winding_sign < 0.0 && (object.flags & kObjectHasNormals) != 0u) {
    vec3 sum = vec3(0.0);
    for (int k = 0; k < 3; ++k) {
      const uint i = k == 0 ? i0 : (k == 1 ? i1 : i2);
      sum += normalizeAsCpu(multiply3x3(object.normal_matrix,
                                        vertexNormal(object.vertex_base + i)));
    }
    if (dot(sum, winding_normal) < 0.0) normal_flip = -flip;
  }

  // Without vertex normals the CPU lights every pixel with the face normal (kPbr: through the
  // BRDF still, the face normal its shading normal).
  uint shading = object.shading;
  if (shading != kShadingUnlit && shading != kShadingPbr &&
      (object.flags & kObjectHasNormals) == 0u)
    shading = kShadingFlat;

  const uint m = (object.flags & kObjectHasTriangleMaterials) != 0u ? triangle_materials[t] : 0u;
  const GpuMaterial material = objectMaterial(object, m);
  vec3 color = material.base_color.xyz * (normal_flip > 0.0 ? in_color_front : in_color_back);
  float alpha = material.base_color.w;
  if ((material.texture_flags & kTexturePresent) != 0u && (object.flags & kObjectHasUv) != 0u) {
    // The sampler's set and transform, and its linear part on the UV derivatives.
    const bool set1 = (material.texture_flags & kTextureSet1) != 0u;
    const vec2 in_uv_a = set1 ? in_uv1 : in_uv;
    const vec2 uv_dx = set1 ? uv_d[2] : uv_d[0], uv_dy = set1 ? uv_d[3] : uv_d[1];
    const vec2 uv = transformUv(material, in_uv_a);
    const bool trilinear = (material.texture_flags & kTextureTrilinear) != 0u;
    float lod = 0.0;
    if (trilinear) {
      // The level of detail from the UV footprint of the pixel, as the CPU's sampleAlbedo.
      const vec2 size = vec2(float(material.texture_width), float(material.texture_height));
      const vec2 dx = (transformUv(material, in_uv_a + uv_dx) - uv) * size;
      const vec2 dy = (transformUv(material, in_uv_a + uv_dy) - uv) * size;
      const float rho2 = max(dot(dx, dx), dot(dy, dy));
      lod = rho2 > 0.0 ? 0.5 * log2(rho2) : 0.0;
    }
    // One call (sampleTextureAt, shading.glsl): lavapipe inlines every call.
    const vec4 texel = sampleTextureAt(albedoTexture(material), uv, trilinear, lod);
    color *= texel.xyz;
    alpha *= texel.w;
  }
  // alphaMode MASK (the CPU's mask_kernel.h): kept where alpha reaches the cutoff.
  if ((material.texture_flags & kMaterialMask) != 0u && !(alpha >= material.uv_transform[0].w))
    discard;

  vec3 normal = face_normal;
  if (shading != kShadingFlat) {
    normal = normalizeAsCpu(in_normal) * normal_flip;
    if (dot(normal, normal) == 0.0) normal = face_normal;
  }
  // Flat faces are lit at their centroid, as the CPU does.
  precise vec3 centre = (worldPosition(object.model, p0) + worldPosition(object.model, p1) +
                         worldPosition(object.model, p2)) * (1.0 / 3.0);
  if (shading == kShadingFlat) color *= irradiance(normal, centre);
  if (shading == kShadingPhong) color *= irradianceShadowed(normal, in_world);
  if (shading == kShadingPbr)
    color = shadePbrFragment(object, material, color, normal_flip,
                             UvFootprint(in_uv, in_uv + uv_d[0], in_uv + uv_d[1], in_uv1,
                                         in_uv1 + uv_d[2], in_uv1 + uv_d[3]),
                             normal);
  color = toneMap(color);

#if TESSERA_BLEND
  out_linear = vec4(color, alpha > 0.0 ? (alpha < 1.0 ? alpha : 1.0) : 0.0);
#elif TESSERA_MSAA
  out_linear = vec4(color, 1.0);
#else
  out_color = packColor(color);
  out_id = t + 1u;
  out_normal = vec4(normal, 0.0);
#endif
}
