#include "render/ray_setup.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tessera::render {

namespace {

constexpr double kPiD = std::numbers::pi;
constexpr double kHalfPi = kPiD / 2;

struct Interval {
  double lo, hi;
};

// A box in window coordinates (not yet whole pixels).
struct WindowBox {
  double x0, y0, x1, y1;
};

struct Dir {
  double v[3];
  double dot(const Dir& o) const { return v[0] * o.v[0] + v[1] * o.v[1] + v[2] * o.v[2]; }
  Dir cross(const Dir& o) const {
    return {{v[1] * o.v[2] - v[2] * o.v[1], v[2] * o.v[0] - v[0] * o.v[2],
             v[0] * o.v[1] - v[1] * o.v[0]}};
  }
};

bool unitDirection(float3 p, Dir& d) {
  const double x = p.x, y = p.y, z = p.z;
  const double len = std::sqrt(x * x + y * y + z * z);
  if (!(len > 0.0) || !std::isfinite(len)) return false;
  d = {{x / len, y / len, z / len}};
  return true;
}

// The triangle's directions as the mode's angles about `axis` (the pole: +Y for the cylindrical
// and spherical modes, the view axis -Z for the polar ones): the range of the angle from the axis
// and of the azimuth around it. A great-circle arc shorter than half a turn changes azimuth
// monotonically unless it passes the pole, so the corners give the azimuths (unwrapped the short
// way) unless the triangle holds a pole; the angle from the axis is extreme at the corners or
// where an arc comes nearest either pole.
struct AngularExtent {
  Interval polar{0, 0};    // angle from the axis, [0, pi]
  Interval azimuth{0, 0};  // may leave [-pi, pi]; the whole turn when `full`
  bool full = false;
};

// The azimuth of d about `axis` with `ref` at azimuth 0 and ref2 = axis x ref at +pi/2.
double azimuthOf(const Dir& d, const Dir& ref, const Dir& ref2) {
  return std::atan2(d.dot(ref2), d.dot(ref));
}

bool angularExtent(const Dir u[3], const Dir& axis, const Dir& ref, const Dir& ref2,
                   AngularExtent& e) {
  // Edge planes of the directions' cone, oriented to hold the triangle.
  Dir n[3];
  for (int k = 0; k < 3; ++k) n[k] = u[(k + 1) % 3].cross(u[(k + 2) % 3]);
  const double orientation = u[0].dot(n[0]);
  if (orientation == 0.0) return false;
  auto holds = [&](const Dir& d) {
    for (int k = 0; k < 3; ++k)
      if (d.dot(n[k]) * orientation < 0.0) return false;
    return true;
  };
  const Dir back{{-axis.v[0], -axis.v[1], -axis.v[2]}};
  // The angle from the axis falls as its cosine rises: the extremes are kept as cosines and
  // turned into angles once.
  double cos_lo = 1.0;   // the cosine of the largest angle (the least cosine)
  double cos_hi = -1.0;  // the cosine of the smallest angle
  for (int k = 0; k < 3; ++k) {
    const double c = u[k].dot(axis);
    cos_lo = std::min(cos_lo, c);
    cos_hi = std::max(cos_hi, c);
  }
  // Each arc's nearest approach to either pole, when it lies within the arc.
  for (int k = 0; k < 3; ++k) {
    const Dir& a = u[(k + 1) % 3];
    const Dir& b = u[(k + 2) % 3];
    const Dir m = a.cross(b);
    const double mm = m.dot(m);
    if (!(mm > 0.0)) continue;
    for (const Dir* pole : {&axis, &back}) {
      const double t = pole->dot(m) / mm;
      Dir q{{pole->v[0] - t * m.v[0], pole->v[1] - t * m.v[1], pole->v[2] - t * m.v[2]}};
      // Whether q lies within the arc, before the square root and divisions of its unit length:
      // a positive scale keeps the signs (most arcs do not pass their nearest approach).
      if (a.cross(q).dot(m) < 0.0 || q.cross(b).dot(m) < 0.0) continue;
      const double len = std::sqrt(q.dot(q));
      if (!(len > 1e-12)) continue;  // the arc's plane is perpendicular to the pole
      for (double& c : q.v) c /= len;
      const double c = q.dot(axis);
      cos_lo = std::min(cos_lo, c);
      cos_hi = std::max(cos_hi, c);
    }
  }
  e.polar = {std::acos(std::clamp(cos_hi, -1.0, 1.0)), std::acos(std::clamp(cos_lo, -1.0, 1.0))};
  const bool holds_axis = holds(axis), holds_back = holds(back);
  if (holds_axis) e.polar.lo = 0.0;
  if (holds_back) e.polar.hi = kPiD;
  e.full = holds_axis || holds_back;
  if (e.full) return true;
  // Azimuths unwrapped the short way from the first corner; the three arcs must agree.
  double az[3];
  az[0] = azimuthOf(u[0], ref, ref2);
  // std::remainder's exact result is x itself within half a turn (the nearest multiple is 0, ties
  // going to the even one): the call only past it.
  auto wrap = [](double x) { return std::fabs(x) <= kPiD ? x : std::remainder(x, 2 * kPiD); };
  for (int k = 1; k < 3; ++k) az[k] = az[0] + wrap(azimuthOf(u[k], ref, ref2) - az[0]);
  if (std::fabs(az[2] - az[1]) >= kPiD) return false;
  e.azimuth = {std::min({az[0], az[1], az[2]}), std::max({az[0], az[1], az[2]})};
  return true;
}

// The window boxes of the extent in the cylindrical or spherical mode: one, or two across the seam.
int lonLatBoxes(const RaySetupContext& ctx, const AngularExtent& e, WindowBox out[2]) {
  const double s = ctx.fov_y_radians / 2, w = ctx.width, h = ctx.height;
  const double aspect = w / h;
  auto windowX = [&](double theta) { return (theta / s / aspect + 1.0) * w / 2.0; };
  auto windowY = [&](double polar) {
    const double phi = kHalfPi - polar;  // latitude
    const double v = ctx.projection == Projection::kSpherical
                         ? phi / s
                         : std::tan(std::clamp(phi, -1.5707, 1.5707)) / std::tan(s);
    return (1.0 - v) * h / 2.0;
  };
  const double y0 = windowY(e.polar.lo), y1 = windowY(e.polar.hi);
  const Interval lon = e.full ? Interval{-kPiD, kPiD} : e.azimuth;
  // Longitudes past one end of [-pi, pi] continue from the other.
  Interval parts[2] = {lon, {1, 0}};
  int count = 1;
  if (lon.lo < -kPiD) {
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

// The window box of the extent in the fisheye or stereographic mode: an annular sector about the
// image's centre (azimuth 0 along +u, pi/2 along +v).
WindowBox polarBox(const RaySetupContext& ctx, const AngularExtent& e) {
  const double s = ctx.fov_y_radians / 2;
  auto radius = [&](double alpha) {
    if (ctx.projection == Projection::kFisheye) return alpha / s;
    return std::min(std::tan(std::min(alpha, kPiD * 0.999999) / 2) / std::tan(s / 2), 1e6);
  };
  const double r_lo = radius(e.polar.lo), r_hi = radius(e.polar.hi);
  double u0 = -r_hi, u1 = r_hi, v0 = -r_hi, v1 = r_hi;
  if (!e.full) {
    u0 = v0 = 1e300, u1 = v1 = -1e300;
    auto take = [&](double r, double cos_psi, double sin_psi) {
      const double u = r * cos_psi, v = r * sin_psi;
      u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
    };
    // Each azimuth's cosine and sine once for both radii.
    for (double psi : {e.azimuth.lo, e.azimuth.hi}) {
      const double cos_psi = std::cos(psi), sin_psi = std::sin(psi);
      take(r_lo, cos_psi, sin_psi);
      take(r_hi, cos_psi, sin_psi);
    }
    // The sector's outer arc reaches furthest where it crosses an axis direction.
    for (int k = -8; k <= 8; ++k) {
      const double axis = k * kHalfPi;
      if (axis > e.azimuth.lo && axis < e.azimuth.hi) take(r_hi, std::cos(axis), std::sin(axis));
    }
  }
  const double w = ctx.width, h = ctx.height, aspect = w / h;
  return {(u0 / aspect + 1.0) * w / 2.0, (1.0 - v1) * h / 2.0, (u1 / aspect + 1.0) * w / 2.0,
          (1.0 - v0) * h / 2.0};
}

// The pixels some ray of which may fall in the window box: a pixel's rays lie within
// ctx.sample_reach of its centre. A hundredth of a pixel more covers the rounding of the angles.
bool toPixels(const RaySetupContext& ctx, const WindowBox& b, int16_t out[4]) {
  const double reach = ctx.sample_reach + 0.01;
  const double lo_x = std::max(std::ceil(b.x0 - 0.5 - reach), 0.0);
  const double lo_y = std::max(std::ceil(b.y0 - 0.5 - reach), 0.0);
  const double hi_x = std::min(std::floor(b.x1 - 0.5 + reach), ctx.width - 1.0);
  const double hi_y = std::min(std::floor(b.y1 - 0.5 + reach), ctx.height - 1.0);
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
  const bool polar =
      ctx.projection == Projection::kFisheye || ctx.projection == Projection::kStereographic;
  // Polar modes: axis -Z, azimuth 0 along +X and pi/2 along +Y (the image's u and v). The others:
  // axis +Y, longitude 0 straight ahead (-Z) and pi/2 along +X.
  const Dir axis = polar ? Dir{{0, 0, -1}} : Dir{{0, 1, 0}};
  const Dir ref = polar ? Dir{{1, 0, 0}} : Dir{{0, 0, -1}};
  const Dir ref2 = polar ? Dir{{0, 1, 0}} : Dir{{1, 0, 0}};
  Dir u[3];
  AngularExtent e;
  if (!unitDirection(p[0], u[0]) || !unitDirection(p[1], u[1]) || !unitDirection(p[2], u[2]) ||
      !angularExtent(u, axis, ref, ref2, e))
    return toPixels(ctx, {0, 0, ctx.width + 1.0, ctx.height + 1.0}, out.box[0]);
  WindowBox boxes[2];
  const int count = polar ? (boxes[0] = polarBox(ctx, e), 1) : lonLatBoxes(ctx, e, boxes);
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
