#include "render/ray_setup.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tessera::render {

namespace {

constexpr double kPiD = std::numbers::pi;
constexpr double kHalfPi = kPiD / 2;
// Cones this wide or wider take the whole image: their extent in the mode's angles is not worth
// bounding (and at 90 degrees the cone stops being convex).
constexpr double kWholeImageCone = 88.0 * kPiD / 180.0;
// Pixels added on every side of a box: samples and jitter lie within a pixel of the centre, and a
// pixel more covers the rounding of the angles.
constexpr double kBoxMargin = 2.0;

struct Interval {
  double lo, hi;
};

// A box in window coordinates (not yet whole pixels).
struct WindowBox {
  double x0, y0, x1, y1;
};

struct Cone {
  double m[3];  // unit axis
  double radius;
};

bool boundingCone(const float3 p[3], Cone& cone) {
  double u[3][3];
  for (int k = 0; k < 3; ++k) {
    const double x = p[k].x, y = p[k].y, z = p[k].z;
    const double len = std::sqrt(x * x + y * y + z * z);
    if (!(len > 0.0) || !std::isfinite(len)) return false;
    u[k][0] = x / len, u[k][1] = y / len, u[k][2] = z / len;
  }
  double m[3] = {u[0][0] + u[1][0] + u[2][0], u[0][1] + u[1][1] + u[2][1],
                 u[0][2] + u[1][2] + u[2][2]};
  const double len = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
  if (!(len > 1e-9)) return false;
  double min_cos = 1.0;
  for (int i = 0; i < 3; ++i) cone.m[i] = m[i] / len;
  for (int k = 0; k < 3; ++k)
    min_cos = std::min(min_cos, cone.m[0] * u[k][0] + cone.m[1] * u[k][1] + cone.m[2] * u[k][2]);
  // A little more than the corners need: the directions were rounded on the way.
  cone.radius = std::acos(std::clamp(min_cos, -1.0, 1.0)) + 1e-6;
  return cone.radius < kWholeImageCone;
}

// The half-width of the azimuth range of a cone of `radius` whose axis makes angle `polar_sin`'s
// angle with the pole; pi when it holds a pole.
double azimuthHalfWidth(double radius, double polar_sin) {
  const double ratio = std::sin(radius) / polar_sin;
  return ratio >= 1.0 ? kPiD : std::asin(ratio);
}

// Longitude (about +Y, 0 straight ahead) and latitude intervals of the cone (cylindrical and
// spherical modes); the longitude interval may leave [-pi, pi] (the caller wraps it).
void lonLatExtent(const Cone& c, Interval& lon, Interval& lat) {
  const double lat_c = std::asin(std::clamp(c.m[1], -1.0, 1.0));
  const double lon_c = std::atan2(c.m[0], -c.m[2]);
  lat = {lat_c - c.radius, lat_c + c.radius};
  if (lat.hi >= kHalfPi || lat.lo <= -kHalfPi) {
    lon = {-kPiD, kPiD};
    lat = {std::max(lat.lo, -kHalfPi), std::min(lat.hi, kHalfPi)};
    return;
  }
  const double half = azimuthHalfWidth(c.radius, std::cos(lat_c));
  lon = half >= kPiD ? Interval{-kPiD, kPiD} : Interval{lon_c - half, lon_c + half};
}

// The window box of the cone in the cylindrical or spherical mode: one, or two across the seam.
int lonLatBoxes(const RaySetupContext& ctx, const Cone& c, WindowBox out[2]) {
  Interval lon, lat;
  lonLatExtent(c, lon, lat);
  const double s = ctx.fov_y_radians / 2, w = ctx.width, h = ctx.height;
  const double aspect = w / h;
  auto windowX = [&](double theta) { return (theta / s / aspect + 1.0) * w / 2.0; };
  auto windowY = [&](double phi) {
    const double v = ctx.projection == Projection::kSpherical
                         ? phi / s
                         : std::tan(std::clamp(phi, -1.5707, 1.5707)) / std::tan(s);
    return (1.0 - v) * h / 2.0;
  };
  const double y0 = windowY(lat.hi), y1 = windowY(lat.lo);
  // Wrap the longitudes into [-pi, pi]: an interval past one end continues from the other.
  Interval parts[2] = {lon, {1, 0}};
  int count = 1;
  if (lon.hi - lon.lo >= 2 * kPiD) {
    parts[0] = {-kPiD, kPiD};
  } else if (lon.lo < -kPiD) {
    parts[0] = {-kPiD, lon.hi};
    parts[1] = {lon.lo + 2 * kPiD, kPiD};
    count = 2;
  } else if (lon.hi > kPiD) {
    parts[0] = {lon.lo, kPiD};
    parts[1] = {-kPiD, lon.hi - 2 * kPiD};
    count = 2;
  }
  for (int i = 0; i < count; ++i) out[i] = {windowX(parts[i].lo), y0, windowX(parts[i].hi), y1};
  return count;
}

// The window box of the cone in the fisheye or stereographic mode (polar about -Z).
WindowBox polarBox(const RaySetupContext& ctx, const Cone& c) {
  const double alpha_c = std::acos(std::clamp(-c.m[2], -1.0, 1.0));
  const double psi_c = std::atan2(c.m[1], c.m[0]);
  double lo = alpha_c - c.radius, hi = alpha_c + c.radius;
  bool full = false;
  if (lo <= 0) lo = 0, full = true;
  if (hi >= kPiD) hi = kPiD, full = true;
  double half = full ? kPiD : azimuthHalfWidth(c.radius, std::sin(alpha_c));
  if (half >= kPiD) full = true;
  const double s = ctx.fov_y_radians / 2;
  auto radius = [&](double alpha) {
    if (ctx.projection == Projection::kFisheye) return alpha / s;
    return std::min(std::tan(std::min(alpha, kPiD * 0.999999) / 2) / std::tan(s / 2), 1e6);
  };
  const double r_lo = radius(lo), r_hi = radius(hi);
  double u0 = -r_hi, u1 = r_hi, v0 = -r_hi, v1 = r_hi;
  if (!full) {
    u0 = v0 = 1e300, u1 = v1 = -1e300;
    auto take = [&](double r, double psi) {
      const double u = r * std::cos(psi), v = r * std::sin(psi);
      u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
    };
    for (double r : {r_lo, r_hi})
      for (double psi : {psi_c - half, psi_c + half}) take(r, psi);
    // The sector's outer arc reaches furthest where it crosses an axis direction.
    for (int k = -4; k <= 4; ++k) {
      const double axis = k * kHalfPi;
      if (axis > psi_c - half && axis < psi_c + half) take(r_hi, axis);
    }
  }
  const double w = ctx.width, h = ctx.height, aspect = w / h;
  return {(u0 / aspect + 1.0) * w / 2.0, (1.0 - v1) * h / 2.0, (u1 / aspect + 1.0) * w / 2.0,
          (1.0 - v0) * h / 2.0};
}

// The pixels of a window box, widened by the margin and clipped to the image; false when empty.
bool toPixels(const RaySetupContext& ctx, const WindowBox& b, int16_t out[4]) {
  const double lo_x = std::max(std::floor(b.x0 - kBoxMargin), 0.0);
  const double lo_y = std::max(std::floor(b.y0 - kBoxMargin), 0.0);
  const double hi_x = std::min(std::ceil(b.x1 + kBoxMargin), ctx.width - 1.0);
  const double hi_y = std::min(std::ceil(b.y1 + kBoxMargin), ctx.height - 1.0);
  if (!(lo_x <= hi_x && lo_y <= hi_y)) return false;
  out[0] = static_cast<int16_t>(lo_x), out[1] = static_cast<int16_t>(lo_y);
  out[2] = static_cast<int16_t>(hi_x), out[3] = static_cast<int16_t>(hi_y);
  return true;
}

void emptyBox(int16_t box[4]) {
  box[0] = 1, box[1] = 1, box[2] = 0, box[3] = 0;
}

bool setBoxes(const RaySetupContext& ctx, const float3 p[3], RayTriangle& out) {
  emptyBox(out.box[0]);
  emptyBox(out.box[1]);
  Cone cone;
  if (!boundingCone(p, cone))
    return toPixels(ctx, {0, 0, ctx.width - 1.0, ctx.height - 1.0}, out.box[0]);
  WindowBox boxes[2];
  int count = 1;
  if (ctx.projection == Projection::kCylindrical || ctx.projection == Projection::kSpherical)
    count = lonLatBoxes(ctx, cone, boxes);
  else
    boxes[0] = polarBox(ctx, cone);
  int kept = 0;
  for (int i = 0; i < count; ++i)
    if (toPixels(ctx, boxes[i], out.box[kept])) ++kept;
  return kept > 0;
}

bool owns(float3 n) {
  return n.x > 0.0f || (n.x == 0.0f && (n.y > 0.0f || (n.y == 0.0f && n.z > 0.0f)));
}

}  // namespace

bool setupRayTriangle(const RaySetupContext& ctx, const float3 p[3], RayTriangle& out,
                      TriangleOrientation& o) {
  const float det = dotRay(p[0], crossRay(p[1], p[2]));
  if (!(det != 0.0f) || !std::isfinite(det)) return false;
  // Counter-clockwise as seen from the eye (front-facing) is a negative det; such triangles take
  // the corners in the order 0, 2, 1, as the perspective path's orient() does.
  o.back_facing = det > 0.0f;
  if ((o.back_facing && ctx.cull == CullMode::kBack) ||
      (!o.back_facing && ctx.cull == CullMode::kFront))
    return false;
  o.order[0] = 0;
  o.order[1] = o.back_facing ? 1 : 2;
  o.order[2] = o.back_facing ? 2 : 1;
  o.l1dx = o.l1dy = o.l2dx = o.l2dy = 0;
  const float3 q[3] = {p[o.order[0]], p[o.order[1]], p[o.order[2]]};
  out.owner = 0;
  for (int k = 0; k < 3; ++k) {
    const float3 n = crossRay(q[(k + 1) % 3], q[(k + 2) % 3]);
    out.n[k][0] = n.x, out.n[k][1] = n.y, out.n[k][2] = n.z;
    if (owns(n)) out.owner = static_cast<uint8_t>(out.owner | (1u << k));
  }
  out.det = dotRay(q[0], {out.n[0][0], out.n[0][1], out.n[0][2]});
  if (!(out.det > 0.0f)) return false;  // rounding made a sliver edge-on
  return setBoxes(ctx, q, out);
}

}  // namespace tessera::render
