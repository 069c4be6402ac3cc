#version 460
// Pass 3 of the nonlinear projections, setup and cull: one invocation per scene triangle. The
// transform pass ran with the view matrix in place of view-projection, so clip.xyz is the
// camera-space position, as the CPU's vertex stage gives it in these modes. Then
// render::setupRayTriangle (src/render/ray_setup.cpp): the eye-centred plane test's edge normals
// and owner bits, in float in the CPU's order (precise: no fused multiply-adds), so coverage is
// the CPU's bit for bit; and the triangle's pixel boxes from a cone around its corners. The boxes
// need only be conservative: they are computed in float with the GPU's trig functions, whose
// error Vulkan bounds loosely, so the cone and the boxes get wider margins than the CPU's.
// No clipping: rays behind the eye or past the depth range never cover; every record is fan
// piece 0 of its triangle, in slot t.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "common.glsl"
#include "records.glsl"
#include "screen.glsl"
#include "shading.glsl"
#include "setup_common.glsl"

layout(local_size_x = 64) in;

// tessera::Projection
const uint kCylindrical = 1u;
const uint kSpherical = 2u;
const uint kFisheye = 4u;

// kPi: pbr.glsl (through shading.glsl).
const float kHalfPi = 1.57079632679490;
// Added to the cone's radius: float directions and float trig (NIR's asin and atan are
// polynomial approximations good to about 1e-5).
const float kConeMargin = 2e-4;
// The CPU's 88-degree whole-image cone, a little earlier.
const float kWholeImageCone = 1.5;  // 86 degrees
// Pixels added on every side (the CPU adds two).
const float kBoxMargin = 3.0;

// The cone around the corners' directions: its unit axis and radius. False when it is too wide
// to bound (or a corner is at the eye): the caller takes the whole image.
bool boundingCone(vec3 p[3], out vec3 axis, out float radius) {
  vec3 u[3];
  for (int k = 0; k < 3; ++k) {
    const float len = length(p[k]);
    if (!(len > 0.0) || isinf(len)) return false;
    u[k] = p[k] / len;
  }
  const vec3 m = u[0] + u[1] + u[2];
  const float len = length(m);
  if (!(len > 1e-4)) return false;
  axis = m / len;
  // The angle from the axis, from the chord: accurate for small cones, where acos is not.
  float chord = 0.0;
  for (int k = 0; k < 3; ++k) chord = max(chord, length(u[k] - axis));
  radius = 2.0 * asin(min(chord * 0.5, 1.0)) + kConeMargin;
  return radius < kWholeImageCone;
}

// Half the azimuth range of a cone of `radius` whose axis is at angle asin(polar_sin) from the
// pole; pi when it holds (or nearly holds) the pole.
float azimuthHalfWidth(float radius, float polar_sin) {
  const float ratio = sin(radius) / polar_sin;
  return ratio >= 0.999 || !(ratio >= 0.0) ? kPi : asin(ratio) + kConeMargin;
}

float windowX(float theta, float s) {
  return (theta / s / (float(frame.width) / float(frame.height)) + 1.0) * float(frame.width) * 0.5;
}

// The cylindrical and spherical modes: longitude (about +Y, 0 straight ahead) and latitude of
// the cone, one window box (x0, y0, x1, y1) or two across the seam (render::lonLatBoxes).
int lonLatBoxes(vec3 axis, float radius, out vec4 boxes[2]) {
  const float s = frame.view_half_angle, h = float(frame.height);
  const float lat_c = atan(axis.y, length(axis.xz));
  vec2 lat = vec2(lat_c - radius, lat_c + radius);
  vec2 lon = vec2(-kPi, kPi);
  if (lat.y >= kHalfPi || lat.x <= -kHalfPi) {
    lat = vec2(max(lat.x, -kHalfPi), min(lat.y, kHalfPi));
  } else {
    const float half_width = azimuthHalfWidth(radius, cos(lat_c));
    const float lon_c = atan(axis.x, -axis.z);
    if (half_width < kPi) lon = vec2(lon_c - half_width, lon_c + half_width);
  }
  vec2 v = lat / s;
  if (frame.projection != kSpherical) v = tan(clamp(lat, -1.5707, 1.5707)) / tan(s);
  const float y0 = (1.0 - v.y) * h * 0.5, y1 = (1.0 - v.x) * h * 0.5;
  // Wrap the longitudes into [-pi, pi]: an interval past one end continues from the other.
  vec2 parts[2] = vec2[2](lon, vec2(1.0, 0.0));
  int count = 1;
  if (lon.y - lon.x >= 2.0 * kPi) {
    parts[0] = vec2(-kPi, kPi);
  } else if (lon.x < -kPi) {
    parts[0] = vec2(-kPi, lon.y);
    parts[1] = vec2(lon.x + 2.0 * kPi, kPi);
    count = 2;
  } else if (lon.y > kPi) {
    parts[0] = vec2(lon.x, kPi);
    parts[1] = vec2(-kPi, lon.y - 2.0 * kPi);
    count = 2;
  }
  for (int i = 0; i < count; ++i)
    boxes[i] = vec4(windowX(parts[i].x, s), y0, windowX(parts[i].y, s), y1);
  return count;
}

// The fisheye and stereographic modes: the image radius of angle alpha from the axis.
float polarRadius(float alpha) {
  const float s = frame.view_half_angle;
  if (frame.projection == kFisheye) return alpha / s;
  return min(tan(min(alpha, kPi * 0.99999) * 0.5) / tan(s * 0.5), 1e6);
}

// The fisheye and stereographic modes (polar about -Z): the window box of the cone's sector
// (render::polarBox).
vec4 polarBox(vec3 axis, float radius) {
  const float alpha_c = atan(length(axis.xy), -axis.z);
  float lo = alpha_c - radius, hi = alpha_c + radius;
  bool full = false;
  if (lo <= 0.0) {
    lo = 0.0;
    full = true;
  }
  if (hi >= kPi) {
    hi = kPi;
    full = true;
  }
  const float half_width = full ? kPi : azimuthHalfWidth(radius, sin(alpha_c));
  if (half_width >= kPi) full = true;
  const float r_lo = polarRadius(lo), r_hi = polarRadius(hi);
  vec4 uv = vec4(-r_hi, -r_hi, r_hi, r_hi);  // u0, v0, u1, v1
  if (!full) {
    const float psi_c = atan(axis.y, axis.x);
    const float a0 = psi_c - half_width, a1 = psi_c + half_width;
    uv = vec4(1e30, 1e30, -1e30, -1e30);
    const vec2 corners[4] = vec2[4](r_lo * vec2(cos(a0), sin(a0)), r_lo * vec2(cos(a1), sin(a1)),
                                    r_hi * vec2(cos(a0), sin(a0)), r_hi * vec2(cos(a1), sin(a1)));
    for (int i = 0; i < 4; ++i) uv = vec4(min(uv.xy, corners[i]), max(uv.zw, corners[i]));
    // The sector's outer arc reaches furthest where it crosses an axis direction.
    for (int k = -4; k <= 4; ++k) {
      const float direction = float(k) * kHalfPi;
      if (direction < a0 - kConeMargin || direction > a1 + kConeMargin) continue;
      const vec2 far_point = r_hi * vec2(cos(direction), sin(direction));
      uv = vec4(min(uv.xy, far_point), max(uv.zw, far_point));
    }
  }
  const float w = float(frame.width), h = float(frame.height), aspect = w / h;
  return vec4((uv.x / aspect + 1.0) * w * 0.5, (1.0 - uv.w) * h * 0.5,
              (uv.z / aspect + 1.0) * w * 0.5, (1.0 - uv.y) * h * 0.5);
}

// The pixels of a window box, widened and clipped to the image; empty (min > max) when it misses.
ivec4 toPixels(vec4 b) {
  const vec2 size = vec2(float(frame.width - 1), float(frame.height - 1));
  if (any(isnan(b))) return ivec4(0, 0, frame.width - 1, frame.height - 1);
  const vec2 lo = max(floor(b.xy - kBoxMargin), vec2(0.0));
  const vec2 hi = min(ceil(b.zw + kBoxMargin), size);
  if (!(lo.x <= hi.x && lo.y <= hi.y)) return ivec4(1, 1, 0, 0);
  return ivec4(lo, hi);
}

bool boxEmpty(ivec4 b) { return b.x > b.z || b.y > b.w; }

// Corners q in rasterizer order: the record's boxes; false when no pixel can see the triangle.
bool setBoxes(vec3 q[3], inout RayRecord r) {
  r.box[0] = r.box[1] = ivec4(1, 1, 0, 0);
  vec3 axis;
  float radius;
  if (!boundingCone(q, axis, radius)) {
    r.box[0] = ivec4(0, 0, frame.width - 1, frame.height - 1);
    return true;
  }
  vec4 boxes[2];
  int count = 1;
  if (frame.projection == kCylindrical || frame.projection == kSpherical)
    count = lonLatBoxes(axis, radius, boxes);
  else
    boxes[0] = polarBox(axis, radius);
  int kept = 0;
  for (int i = 0; i < count; ++i) {
    const ivec4 box = toPixels(boxes[i]);
    if (!boxEmpty(box)) r.box[kept++] = box;
  }
  return kept > 0;
}

// render::owns: the first non-zero component of n is positive.
bool owns(vec3 n) {
  return n.x > 0.0 || (n.x == 0.0 && (n.y > 0.0 || (n.y == 0.0 && n.z > 0.0)));
}

// render::setupRayTriangle for camera-space corners p (input order): false when culled.
bool setupRay(vec3 p[3], uint cull, out RayRecord r, out int order[3], out bool back_facing) {
  const float det = dotRay(p[0], crossRay(p[1], p[2]));
  if (!(det != 0.0) || isinf(det) || isnan(det)) return false;
  // Counter-clockwise as seen from the eye (front-facing) is a negative det; such triangles take
  // the corners in the order 0, 2, 1.
  back_facing = det > 0.0;
  if ((back_facing && cull == kCullBack) || (!back_facing && cull == kCullFront)) return false;
  order = int[3](0, back_facing ? 1 : 2, back_facing ? 2 : 1);
  const vec3 q[3] = vec3[3](p[order[0]], p[order[1]], p[order[2]]);
  r.owner = 0u;
  for (int k = 0; k < 3; ++k) {
    const vec3 n = crossRay(q[(k + 1) % 3], q[(k + 2) % 3]);
    r.n[3 * k] = n.x;
    r.n[3 * k + 1] = n.y;
    r.n[3 * k + 2] = n.z;
    if (owns(n)) r.owner |= 1u << uint(k);
  }
  r.det = dotRay(q[0], rayNormal(r, 0));
  if (!(r.det > 0.0)) return false;  // rounding made a sliver edge-on
  return setBoxes(q, r);
}

void main() {
  const uint t = flatWorkgroupIndex() * 64u + gl_LocalInvocationIndex;
  if (t >= frame.triangle_count) return;
  const GpuObject object = objects[objectOfTriangle(t)];
  const uint idx[3] = uint[3](indices[3u * t], indices[3u * t + 1u], indices[3u * t + 2u]);
  if (idx[0] >= object.vertex_count || idx[1] >= object.vertex_count ||
      idx[2] >= object.vertex_count) {
    atomicAdd(counters.culled, 1u);
    return;
  }
  vec3 p[3];
  uint codes = 0u;
  for (int k = 0; k < 3; ++k) {
    const TransformedVertex tv = transformed[object.vertex_base + idx[k]];
    p[k] = tv.clip.xyz;
    codes |= tv.outcode;
  }
  RayRecord ray;
  int order[3];
  bool back_facing;
  if ((codes & kNonFinite) != 0u || !setupRay(p, object.cull, ray, order, back_facing)) {
    atomicAdd(counters.culled, 1u);
    return;
  }
  ray.key = t << 3;
  TriangleContext ctx = triangleContext(t, object, idx);
  ctx.clipped = false;
  const ClipVertex unused[3] = ClipVertex[3](ClipVertex(vec4(0.0), vec3(0.0)),
                                             ClipVertex(vec4(0.0), vec3(0.0)),
                                             ClipVertex(vec4(0.0), vec3(0.0)));
  ShadeRecord shade;
  shade.inv_w0 = shade.p1dx = shade.p1dy = shade.p2dx = shade.p2dy = shade.sdx = shade.sdy = 0.0;
  setupShadeCorners(ctx, unused, order, back_facing, shade);
  ray_records[t] = ray;
  shade_records[t] = shade;
  visible_list[atomicAdd(counters.visible, 1u)] = t;
}
