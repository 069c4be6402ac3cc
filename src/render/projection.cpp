#include <tessera/render/projection.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace tessera {

namespace {

constexpr double kPiD = std::numbers::pi;

struct ImagePoint {
  double u, v;  // u in [-aspect, aspect], v in [-1, 1]
};

ImagePoint toImage(double sx, double sy, int width, int height) {
  const double aspect = static_cast<double>(width) / height;
  return {(2.0 * sx / width - 1.0) * aspect, 1.0 - 2.0 * sy / height};
}

void normalizeInto(double x, double y, double z, double d[3]) {
  const double len = std::sqrt(x * x + y * y + z * z);
  d[0] = x / len;
  d[1] = y / len;
  d[2] = z / len;
}

// The fisheye and stereographic modes: angle alpha from the axis, around it as (u, v) points.
bool polarRay(double alpha, ImagePoint p, double d[3]) {
  if (alpha > kPiD) return false;
  const double r = std::sqrt(p.u * p.u + p.v * p.v);
  if (r == 0.0) {
    d[0] = 0, d[1] = 0, d[2] = -1;
    return true;
  }
  const double s = std::sin(alpha);
  d[0] = s * p.u / r;
  d[1] = s * p.v / r;
  d[2] = -std::cos(alpha);
  return true;
}

std::string rangeMessage(Projection p, float angle, const char* range) {
  char text[320];
  std::snprintf(text, sizeof text, "view angle %g is out of range for %s: %s", angle,
                projectionName(p), range);
  return text;
}

}  // namespace

const char* projectionName(Projection p) {
  switch (p) {
    case Projection::kPerspective:
      return "perspective";
    case Projection::kCylindrical:
      return "cylindrical";
    case Projection::kSpherical:
      return "spherical";
    case Projection::kStereographic:
      return "stereographic";
    case Projection::kFisheye:
      return "fisheye";
  }
  return "perspective";
}

std::optional<Projection> parseProjection(std::string_view name) {
  for (Projection p : kProjections)
    if (name == projectionName(p)) return p;
  return std::nullopt;
}

std::string projectionChoices() {
  std::string out;
  for (Projection p : kProjections) {
    if (!out.empty()) out += '|';
    out += projectionName(p);
  }
  return out;
}

std::string checkViewAngle(Projection p, float angle, float aspect) {
  const bool positive = angle > 0.0f && std::isfinite(angle);
  const bool fits_360 = angle * aspect <= 360.0f;
  char range[160];
  switch (p) {
    case Projection::kPerspective:
      if (positive && angle < 180.0f) return "";
      return rangeMessage(p, angle, "more than 0 and below 180 degrees");
    case Projection::kCylindrical:
      if (positive && angle < 180.0f && fits_360) return "";
      std::snprintf(range, sizeof range,
                    "more than 0 and below 180 degrees, and at most 360 / aspect = %g here",
                    360.0 / aspect);
      return rangeMessage(p, angle, range);
    case Projection::kSpherical:
      if (positive && angle <= 180.0f && fits_360) return "";
      std::snprintf(range, sizeof range,
                    "more than 0 and at most 180 degrees, and at most 360 / aspect = %g here",
                    360.0 / aspect);
      return rangeMessage(p, angle, range);
    case Projection::kStereographic:
      if (positive && angle < 360.0f) return "";
      return rangeMessage(p, angle, "more than 0 and below 360 degrees");
    case Projection::kFisheye:
      if (positive && angle <= 360.0f) return "";
      return rangeMessage(p, angle, "more than 0 and at most 360 degrees");
  }
  return "";
}

float defaultViewAngle(Projection p, float aspect) {
  switch (p) {
    case Projection::kPerspective:
      return 30.0f;
    case Projection::kCylindrical:
      return std::min(170.0f, 360.0f / aspect);
    case Projection::kSpherical:
      return std::min(180.0f, 360.0f / aspect);
    case Projection::kStereographic:
    case Projection::kFisheye:
      return 180.0f;
  }
  return 30.0f;
}

bool rayDirection(Projection p, double sx, double sy, int width, int height, double fov,
                  double d[3]) {
  const ImagePoint q = toImage(sx, sy, width, height);
  const double s = fov / 2.0;
  switch (p) {
    case Projection::kPerspective:
      normalizeInto(q.u * std::tan(s), q.v * std::tan(s), -1.0, d);
      return true;
    case Projection::kCylindrical: {
      const double theta = q.u * s;
      normalizeInto(std::sin(theta), q.v * std::tan(s), -std::cos(theta), d);
      return true;
    }
    case Projection::kSpherical: {
      const double theta = q.u * s, phi = q.v * s;
      normalizeInto(std::cos(phi) * std::sin(theta), std::sin(phi),
                    -std::cos(phi) * std::cos(theta), d);
      return true;
    }
    case Projection::kFisheye:
      return polarRay(std::sqrt(q.u * q.u + q.v * q.v) * s, q, d);
    case Projection::kStereographic:
      return polarRay(2.0 * std::atan(std::sqrt(q.u * q.u + q.v * q.v) * std::tan(s / 2.0)), q, d);
  }
  return false;
}

bool projectDirection(Projection p, const double din[3], int width, int height, double fov,
                      double& sx, double& sy) {
  double d[3];
  normalizeInto(din[0], din[1], din[2], d);
  if (!std::isfinite(d[0]) || !std::isfinite(d[1]) || !std::isfinite(d[2])) return false;
  const double s = fov / 2.0;
  double u = 0, v = 0;
  switch (p) {
    case Projection::kPerspective:
      if (d[2] >= 0.0) return false;
      u = d[0] / -d[2] / std::tan(s);
      v = d[1] / -d[2] / std::tan(s);
      break;
    case Projection::kCylindrical: {
      const double h = std::sqrt(d[0] * d[0] + d[2] * d[2]);
      if (h == 0.0) return false;
      u = std::atan2(d[0], -d[2]) / s;
      v = d[1] / h / std::tan(s);
      break;
    }
    case Projection::kSpherical:
      u = std::atan2(d[0], -d[2]) / s;
      v = std::asin(std::clamp(d[1], -1.0, 1.0)) / s;
      break;
    case Projection::kFisheye:
    case Projection::kStereographic: {
      const double alpha = std::acos(std::clamp(-d[2], -1.0, 1.0));
      const double rho = std::sqrt(d[0] * d[0] + d[1] * d[1]);
      if (rho == 0.0 && alpha > 1.0) return false;  // straight behind: every direction at once
      const double r =
          p == Projection::kFisheye ? alpha / s : std::tan(alpha / 2.0) / std::tan(s / 2.0);
      if (!std::isfinite(r)) return false;
      u = rho > 0.0 ? r * d[0] / rho : 0.0;
      v = rho > 0.0 ? r * d[1] / rho : 0.0;
      break;
    }
  }
  const double aspect = static_cast<double>(width) / height;
  sx = (u / aspect + 1.0) * width / 2.0;
  sy = (1.0 - v) * height / 2.0;
  return std::isfinite(sx) && std::isfinite(sy);
}

// Whether mode p's ray at (x, y) is formed from an angle of the column alone and values of the
// row alone (RayTable::separableRow).
namespace {
bool separable(Projection p) {
  return p == Projection::kCylindrical || p == Projection::kSpherical;
}
}  // namespace

void RayTable::separableRow(int i, int y, double fov) {
  RayLayer& layer = layers_[static_cast<size_t>(i)];
  const double s = fov / 2.0;
  const double v = toImage(0.0, y + static_cast<double>(layer.offset_y), width_, height_).v;
  const double* trig = &column_trig_[static_cast<size_t>(i) * width_ * 2];
  const size_t row = static_cast<size_t>(y) * width_;
  // rayDirection's expressions with the column's sin(theta), cos(theta) and the row's values:
  // spherical, cos(phi) and sin(phi); cylindrical, 1 and the height v tan(s).
  const bool spherical = projection_ == Projection::kSpherical;
  const double row_scale = spherical ? std::cos(v * s) : 1.0;
  const double row_y = spherical ? std::sin(v * s) : v * std::tan(s);
  for (int x = 0; x < width_; ++x) {
    const double sin_theta = trig[2 * x], cos_theta = trig[2 * x + 1];
    double d[3];
    if (spherical)
      normalizeInto(row_scale * sin_theta, row_y, -row_scale * cos_theta, d);
    else
      normalizeInto(sin_theta, row_y, -cos_theta, d);
    layer.x[row + x] = static_cast<float>(d[0]);
    layer.y[row + x] = static_cast<float>(d[1]);
    layer.z[row + x] = static_cast<float>(d[2]);
  }
}

bool RayTable::update(Projection p, int width, int height, float fov_y_degrees, int samples,
                      Jitter jitter, const RowRunner& run_rows) {
  if (p == projection_ && width == width_ && height == height_ && fov_y_degrees == fov_ &&
      samples == samples_ && jitter.x == jitter_.x && jitter.y == jitter_.y)
    return false;
  projection_ = p, width_ = width, height_ = height, fov_ = fov_y_degrees;
  samples_ = samples, jitter_ = jitter;
  const std::span<const SamplePosition> pattern = samplePattern(samples);
  // The layers only grow, so that going back to a sample count seen before allocates nothing.
  layer_count_ = static_cast<int>(pattern.size()) + 1;
  if (layers_.size() < static_cast<size_t>(layer_count_))
    layers_.resize(static_cast<size_t>(layer_count_));
  const size_t count = static_cast<size_t>(width) * static_cast<size_t>(height);
  for (int i = 0; i < layer_count_; ++i) {
    RayLayer& layer = layers_[static_cast<size_t>(i)];
    const bool centre = i == layer_count_ - 1;
    // Sample positions are in 1/256 pixel from the pixel's corner (sampling.h).
    layer.offset_x = (centre ? 0.5f : static_cast<float>(pattern[i].x) / 256.0f) + jitter.x;
    layer.offset_y = (centre ? 0.5f : static_cast<float>(pattern[i].y) / 256.0f) + jitter.y;
    // Eight zero rays past the end: the kernels read eight pixels at a time.
    layer.x.assign(count + 8, 0.0f);
    layer.y.assign(count + 8, 0.0f);
    layer.z.assign(count + 8, 0.0f);
  }
  const double fov = static_cast<double>(fov_y_degrees) * kPiD / 180.0;
  // The cylindrical and spherical rays' angle about the vertical depends on the column alone:
  // its sine and cosine are taken once a column of each layer, not once a ray (a jittered frame
  // rebuilds every layer). The same calls and arithmetic as rayDirection, so the same rays.
  if (separable(p)) {
    column_trig_.resize(static_cast<size_t>(layer_count_) * static_cast<size_t>(width) * 2);
    for (int i = 0; i < layer_count_; ++i) {
      const double offset = static_cast<double>(layers_[static_cast<size_t>(i)].offset_x);
      for (int x = 0; x < width; ++x) {
        const double theta = toImage(x + offset, 0.0, width, height).u * (fov / 2.0);
        double* at = &column_trig_[(static_cast<size_t>(i) * width + x) * 2];
        at[0] = std::sin(theta);
        at[1] = std::cos(theta);
      }
    }
  }
  // Two pointers captured: the std::function made of it keeps them inline (no allocation).
  auto row = [this, &fov](int y) {
    for (int i = 0; i < layer_count_; ++i) {
      RayLayer& layer = layers_[static_cast<size_t>(i)];
      if (separable(projection_)) {
        separableRow(i, y, fov);
        continue;
      }
      for (int x = 0; x < width_; ++x) {
        double d[3] = {0, 0, 0};
        if (!rayDirection(projection_, x + static_cast<double>(layer.offset_x),
                          y + static_cast<double>(layer.offset_y), width_, height_, fov, d))
          d[0] = d[1] = d[2] = 0;
        const size_t at = static_cast<size_t>(y) * width_ + x;
        layer.x[at] = static_cast<float>(d[0]);
        layer.y[at] = static_cast<float>(d[1]);
        layer.z[at] = static_cast<float>(d[2]);
      }
    }
  };
  if (run_rows)
    run_rows(height, row);
  else
    for (int y = 0; y < height; ++y) row(y);
  return true;
}

}  // namespace tessera
