// Projections: the mapping from a window position to a camera-space view ray, one formula per
// mode (../shared/ARCHITECTURE.md, "Projections"). Every backend, test and document takes its rays
// from here. Perspective is drawn by the classic pipeline (edge functions on projected vertices);
// the other modes by testing each pixel's ray against the triangle (render/ray_setup.h), because
// under a nonlinear projection a straight edge is a curve.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <tessera/math/vec.h>
#include <tessera/render/sampling.h>

namespace tessera {

enum class Projection : uint8_t {
  kPerspective,
  kCylindrical,
  kSpherical,      // equirectangular: a 2:1 image at 180 degrees is a full 360 x 180 panorama
  kStereographic,  // the conformal "hyperbolic" mode
  kFisheye,        // equidistant; reaches 360 degrees
};

inline constexpr Projection kProjections[] = {Projection::kPerspective, Projection::kCylindrical,
                                              Projection::kSpherical, Projection::kStereographic,
                                              Projection::kFisheye};

const char* projectionName(Projection p);
std::optional<Projection> parseProjection(std::string_view name);
// "perspective|cylindrical|spherical|stereographic|fisheye", for usage messages.
std::string projectionChoices();

// "" when `fov_y_degrees` (the vertical view angle) is valid for the mode on an image of this
// aspect (width / height); otherwise a message naming the valid range.
std::string checkViewAngle(Projection p, float fov_y_degrees, float aspect);
// The view angle a mode takes when none is given, for an image of this aspect (width / height):
// perspective 30, cylindrical min(170, 360 / aspect) and spherical min(180, 360 / aspect) (a 2:1
// spherical image is a whole 360 x 180 panorama), stereographic and fisheye 180.
float defaultViewAngle(Projection p, float aspect);

// The unit camera-space ray (+X right, +Y up, looking down -Z) through window point (sx, sy)
// (pixel centres at +0.5) of a width x height image with vertical view angle fov_y_radians;
// computed in double precision. False where the mode has no ray there (fisheye past 180 degrees
// from the axis): such a point shows the background.
bool rayDirection(Projection p, double sx, double sy, int width, int height, double fov_y_radians,
                  double d[3]);

// The window point (sx, sy) a camera-space direction maps to (the inverse of rayDirection), for
// the line pass; false where no pixel of the mode looks that way.
bool projectDirection(Projection p, const double d[3], int width, int height, double fov_y_radians,
                      double& sx, double& sy);

// The rays of one sample of every pixel, rounded to float, as three planes (x, y, z), row-major
// from the top row: the ray of pixel (x, y) is at index y * width + x. The sample lies at
// (x + offset_x, y + offset_y): a standard sample position plus the frame's jitter. A pixel with no
// ray holds (0, 0, 0), which no triangle covers. Eight zero rays follow the last pixel.
struct RayLayer {
  float offset_x = 0.5f, offset_y = 0.5f;
  std::vector<float> x, y, z;
};

// The ray layers a frame needs: one per sample (in pattern order) and, last, the pixel centres
// (with the jitter). Rebuilt only when the mode, size, view angle, sample count or jitter change.
class RayTable {
 public:
  // Runs row(i) for every i in [0, count), in any order and on any thread (the renderer's
  // workers); empty: in order on the calling thread.
  using RowRunner = std::function<void(int count, const std::function<void(int)>& row)>;
  // True when it was rebuilt.
  bool update(Projection p, int width, int height, float fov_y_degrees, int samples, Jitter jitter,
              const RowRunner& run_rows = {});
  const RayLayer& sample(int i) const { return layers_[static_cast<size_t>(i)]; }
  const RayLayer& centre() const { return layers_[static_cast<size_t>(layer_count_ - 1)]; }
  int samples() const { return samples_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  Projection projection_ = Projection::kPerspective;
  int width_ = 0, height_ = 0, samples_ = 0;
  int layer_count_ = 0;  // the samples' and the centres': layers_ may hold more
  float fov_ = 0;
  Jitter jitter_{-1, -1};
  std::vector<RayLayer> layers_;
  // The cylindrical and spherical modes: sin and cos of each layer's columns' angle theta.
  std::vector<double> column_trig_;

  void separableRow(int layer, int y, double fov);
};

}  // namespace tessera
