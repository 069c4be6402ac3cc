// The camera flags shared by `render` and `bench`, and the camera they describe: the default
// three-quarter view of model_scene.h, or the camera given exactly. Everything here but
// addCameraFlags depends on the core alone, so the micro-benchmarks build it too.
#pragma once

#include <cmath>
#include <iterator>
#include <string>

#include <tessera/base/expected.h>
#include <tessera/model/camera_setup.h>
#include <tessera/render/projection.h>
#include <tessera/scene/scene.h>

#include "flags.h"

namespace tessera::cli {

using namespace tessera::model;  // CameraSettings and the rest of camera_setup.h

inline void addCameraFlags(FlagSet& flags, CameraSettings& c) {
  flags.addFloat3("camera-position", &c.position, &c.has_position, "camera position (model units)");
  flags.addFloat3("camera-focal-point", &c.focal_point, &c.has_focal_point,
                  "point the camera looks at");
  flags.addFloat3("camera-view-up", &c.view_up, &c.has_view_up, "camera up direction");
  flags.addCustom("camera-view-angle", "DEG",
                  "vertical view angle in degrees (default 30; spherical and cylindrical: the "
                  "whole panorama, fisheye and stereographic: 180)",
                  [&c](const std::string& text) -> std::string {
                    if (!parseFloatStrict(text, c.view_angle) || !(c.view_angle > 0.0f))
                      return "needs a number of degrees above 0, got '" + text + "'";
                    c.has_view_angle = true;
                    return "";
                  });
  flags.addSwitch("camera-orthographic", &c.orthographic,
                  "orthographic projection for the framing (or flag-given) camera");
  flags.addInt("camera-index", &c.camera_index,
               "draw from the file's camera N (glTF cameras, from 0)", 0, 1 << 30);
  flags.addChoice("up", &c.up, {std::begin(kUpAxes), std::end(kUpAxes)},
                  "the model's up axis, a signed world axis (default +Y)");
  auto degrees = [](float* out) {
    return [out](const std::string& text) -> std::string {
      if (!parseFloatStrict(text, *out) || std::fabs(*out) > 360.0f)
        return "needs a number of degrees from -360 to 360, got '" + text + "'";
      return "";
    };
  };
  flags.addCustom("camera-azimuth-angle", "DEG",
                  "after placing the camera, turn it about the focal point around view up "
                  "(positive: to the camera's right; f3d's)",
                  degrees(&c.azimuth));
  flags.addCustom("camera-elevation-angle", "DEG",
                  "then turn it towards view up (positive: upwards; f3d's)", degrees(&c.elevation));
  std::vector<std::string> modes;
  for (Projection p : kProjections) modes.push_back(projectionName(p));
  flags.addChoice("projection", &c.projection, modes,
                  "how pixels map to view rays (default perspective; docs/rendering.md)");
}

}  // namespace tessera::cli
