// The camera flags shared by `render` and `bench`, and the camera they describe: the default
// three-quarter view of model_scene.h, or the camera given exactly. Everything here but
// addCameraFlags depends on the core alone, so the micro-benchmarks build it too.
#pragma once

#include <string>

#include <tessera/base/expected.h>
#include <tessera/render/projection.h>
#include <tessera/scene/scene.h>

#include "flags.h"

namespace tessera::cli {

// f3d's camera flags. With none of position, focal point or view up, the camera frames the model;
// with any of them the model stays in its own coordinates and that camera is used exactly.
struct CameraSettings {
  float3 position, focal_point, view_up{0, 1, 0};
  bool has_position = false, has_focal_point = false, has_view_up = false;
  float view_angle = 30.0f;  // vertical, degrees
  bool has_view_angle = false;
  std::string up = "+Y";                   // the model's up axis: +Y or +Z
  std::string projection = "perspective";  // projection.h's names

  bool explicitCamera() const { return has_position || has_focal_point || has_view_up; }
  float3 upAxis() const { return up == "+Z" ? float3{0, 0, 1} : float3{0, 1, 0}; }
  Projection projectionMode() const {
    return parseProjection(projection).value_or(Projection::kPerspective);
  }
};

inline void addCameraFlags(FlagSet& flags, CameraSettings& c) {
  flags.addFloat3("camera-position", &c.position, &c.has_position, "camera position (model units)");
  flags.addFloat3("camera-focal-point", &c.focal_point, &c.has_focal_point,
                  "point the camera looks at");
  flags.addFloat3("camera-view-up", &c.view_up, &c.has_view_up, "camera up direction");
  flags.addCustom("camera-view-angle", "DEG",
                  "vertical view angle in degrees (default 30; with another --projection the "
                  "widest the mode allows: a 2:1 spherical image at 180 is a 360x180 panorama)",
                  [&c](const std::string& text) -> std::string {
                    if (!parseFloatStrict(text, c.view_angle) || !(c.view_angle > 0.0f))
                      return "needs a number of degrees above 0, got '" + text + "'";
                    c.has_view_angle = true;
                    return "";
                  });
  flags.addChoice("up", &c.up, {"+Y", "+Z"}, "the model's up axis (default +Y)");
  std::vector<std::string> modes;
  for (Projection p : kProjections) modes.push_back(projectionName(p));
  flags.addChoice("projection", &c.projection, modes,
                  "how pixels map to view rays (default perspective; docs/usage.md)");
}

// The view angle the settings give for an image of this aspect: the flag's, or the mode's
// default. An error naming the mode's range when it is out of it (a usage error).
Expected<float> viewAngle(const CameraSettings& settings, float aspect);

// The camera for a model with these bounds: the three-quarter view from the front, right and
// above that fits the whole model, or the camera the flags describe (near and far fitted to the
// bounds). An error for a camera that cannot look anywhere (a usage error).
Expected<Camera> makeCamera(const CameraSettings& settings, const Bounds& bounds, float aspect);

}  // namespace tessera::cli
