// The camera flags shared by `render` and `bench`, and the camera they describe: the default
// three-quarter view of model_scene.h, or the camera given exactly. Everything here but
// addCameraFlags depends on the core alone, so the micro-benchmarks build it too.
#pragma once

#include <string>

#include <tessera/base/expected.h>
#include <tessera/scene/scene.h>

#include "flags.h"

namespace tessera::cli {

// f3d's camera flags. With none of position, focal point or view up, the camera frames the model;
// with any of them the model stays in its own coordinates and that camera is used exactly.
struct CameraSettings {
  float3 position, focal_point, view_up{0, 1, 0};
  bool has_position = false, has_focal_point = false, has_view_up = false;
  float view_angle = 30.0f;  // vertical, degrees
  std::string up = "+Y";     // the model's up axis: +Y or +Z

  bool explicitCamera() const { return has_position || has_focal_point || has_view_up; }
  float3 upAxis() const { return up == "+Z" ? float3{0, 0, 1} : float3{0, 1, 0}; }
};

inline void addCameraFlags(FlagSet& flags, CameraSettings& c) {
  flags.addFloat3("camera-position", &c.position, &c.has_position, "camera position (model units)");
  flags.addFloat3("camera-focal-point", &c.focal_point, &c.has_focal_point,
                  "point the camera looks at");
  flags.addFloat3("camera-view-up", &c.view_up, &c.has_view_up, "camera up direction");
  flags.addFloat("camera-view-angle", &c.view_angle, "vertical field of view in degrees (30)", 1.0f,
                 170.0f);
  flags.addChoice("up", &c.up, {"+Y", "+Z"}, "the model's up axis (default +Y)");
}

// The camera for a model with these bounds: the three-quarter view from the front, right and
// above that fits the whole model, or the camera the flags describe (near and far fitted to the
// bounds). An error for a camera that cannot look anywhere (a usage error).
Expected<Camera> makeCamera(const CameraSettings& settings, const Bounds& bounds, float aspect);

}  // namespace tessera::cli
