#version 460
// vulkan-raster, vertex stage: object space to zero-to-one clip space (the viewport flips Y, so
// window coordinates are the CPU's: pixel (0, 0) top-left), the normal to world space, and the
// attributes the fragment stage interpolates. One draw per object; the push constant names it.
#include "common.glsl"
#include "shading.glsl"

layout(push_constant) uniform Draw { uint object; } draw;

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_color;
layout(location = 4) in vec4 in_tangent;  // kObjectHasTangents
layout(location = 5) in vec2 in_uv1;      // TEXCOORD_1 (TEXCOORD_0 where the mesh has none)

layout(location = 0) out vec3 out_normal;
layout(location = 1) out vec2 out_uv;
// The vertex colour; for Gouraud already lit, for the front and for the back side (two-sided
// lighting flips the normal of a back face; the fragment stage picks by gl_FrontFacing). The
// material's base colour, constant over a triangle, is applied per fragment.
layout(location = 2) out vec3 out_color_front;
layout(location = 3) out vec3 out_color_back;
// The UV again, for the multisample pass's derivatives: its copy at location 1 is interpolated at
// the centroid, whose screen-space differences do not give the footprint.
layout(location = 4) out vec2 out_uv_centre;
layout(location = 5) out vec3 out_world;  // world position: point and spot lights, kPbr
// kPbr with tangents: the world tangent, and the bitangent's sign of the triangle's first vertex
// (the provoking one), as the CPU takes its corner 0's.
layout(location = 6) out vec3 out_tangent;
layout(location = 7) flat out float out_tangent_sign;
layout(location = 8) out vec2 out_uv1;         // as out_uv, for TEXCOORD_1
layout(location = 9) out vec2 out_uv1_centre;  // as out_uv_centre

void main() {
  const GpuObject object = objects[draw.object];
  const mat4 m = object.model_view_projection_zo;
  const vec3 p = in_position;
  precise float x = m[0].x * p.x + m[1].x * p.y + m[2].x * p.z + m[3].x;
  precise float y = m[0].y * p.x + m[1].y * p.y + m[2].y * p.z + m[3].y;
  precise float z = m[0].z * p.x + m[1].z * p.y + m[2].z * p.z + m[3].z;
  precise float w = m[0].w * p.x + m[1].w * p.y + m[2].w * p.z + m[3].w;
  gl_Position = vec4(x, y, z, w);

  vec3 normal = vec3(0.0);
  if ((object.flags & kObjectHasNormals) != 0u)
    normal = normalizeAsCpu(multiply3x3(object.normal_matrix, in_normal));
  out_normal = normal;
  out_uv = (object.flags & kObjectHasUv) != 0u ? in_uv : vec2(0.0);
  out_uv_centre = out_uv;
  out_uv1 = (object.flags & kObjectHasUv) != 0u ? in_uv1 : vec2(0.0);
  out_uv1_centre = out_uv1;
  const vec3 color = (object.flags & kObjectHasColor) != 0u ? in_color.xyz : vec3(1.0);
  const bool gouraud =
      object.shading == kShadingGouraud && (object.flags & kObjectHasNormals) != 0u;
  const vec3 world = worldPosition(object.model, p);
  out_world = world;
  out_tangent = vec3(0.0);
  out_tangent_sign = 1.0;
  if ((object.flags & kObjectHasTangents) != 0u) {
    // A direction: the model's upper 3x3; a mirroring model flips the bitangent.
    const mat4 model = object.model;
    precise vec3 t =
        model[0].xyz * in_tangent.x + model[1].xyz * in_tangent.y + model[2].xyz * in_tangent.z;
    out_tangent = t;
    out_tangent_sign = in_tangent.w * object.winding_sign < 0.0 ? -1.0 : 1.0;
  }
  out_color_front = gouraud ? color * irradiance(normal, world) : color;
  out_color_back = gouraud ? color * irradiance(-normal, world) : color;
}
