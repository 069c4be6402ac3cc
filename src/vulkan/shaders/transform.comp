#version 460
// Pass 2, transform: every vertex of every object to clip space (P * V * M, OpenGL clip space),
// its outcode and, inside the guard band and the depth range, 1/w and its snapped window
// position; its normal to world space. As the CPU's src/render/vertex_kernel.h: the same sums in the
// same order, so positions are bit-identical, and a vertex shared by many triangles is projected
// once.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "common.glsl"
#include "records.glsl"
#include "screen.glsl"

layout(local_size_x = 256) in;

// The object holding vertex v: the last one whose vertex_base is <= v.
uint objectOfVertex(uint v) {
  uint lo = 0u, hi = frame.object_count;
  while (lo < hi) {
    const uint mid = (lo + hi) / 2u;
    if (objects[mid].vertex_base <= v) lo = mid + 1u;
    else hi = mid;
  }
  return lo - 1u;
}

void main() {
  const uint v = flatWorkgroupIndex() * 256u + gl_LocalInvocationIndex;
  if (v >= frame.vertex_count) return;
  const GpuObject object = objects[objectOfVertex(v)];
  const vec3 p = vertexPosition(v);
  const mat4 m = object.model_view_projection;
  precise float x = m[0].x * p.x + m[1].x * p.y + m[2].x * p.z + m[3].x;
  precise float y = m[0].y * p.x + m[1].y * p.y + m[2].y * p.z + m[3].y;
  precise float z = m[0].z * p.x + m[1].z * p.y + m[2].z * p.z + m[3].z;
  precise float w = m[0].w * p.x + m[1].w * p.y + m[2].w * p.z + m[3].w;
  vec3 normal = vec3(0.0);
  if ((object.flags & kObjectHasNormals) != 0u)
    normal = normalizeAsCpu(multiply3x3(object.normal_matrix, vertexNormal(v)));
  const vec4 clip = vec4(x, y, z, w);
  const bool finite = !any(isinf(clip)) && !any(isnan(clip));
  const uint code = finite ? outcode(clip) : kNonFinite;
  ScreenVertex screen = ScreenVertex(0, 0, 0.0, 0.0);
  if ((code & kCutPlanes) == 0u) screen = projectToScreen(clip);
  transformed[v] = TransformedVertex(clip, normal, code, ivec2(screen.x, screen.y), screen.z,
                                     screen.inv_w);
}
