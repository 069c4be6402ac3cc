// The camera of `tessera render`, `view` and `bench`: the default three-quarter view of
// model_scene.h, the camera given exactly by f3d's flags, or a camera of the file's scene graph.
// Library tessera_model; the flags themselves are the CLI's (apps/tessera/view_setup.h).
#pragma once

#include <string>

#include <tessera/base/expected.h>
#include <tessera/render/projection.h>
#include <tessera/scene/graph.h>
#include <tessera/scene/scene.h>

namespace tessera::model {

// f3d's camera flags. With none of position, focal point or view up, the camera frames the model;
// with any of them the model stays in its own coordinates and that camera is used exactly.
struct CameraSettings {
  float3 position, focal_point, view_up{0, 1, 0};
  bool has_position = false, has_focal_point = false, has_view_up = false;
  float view_angle = 30.0f;  // vertical, degrees
  bool has_view_angle = false;
  std::string up = "+Y";                   // the model's up axis: kUpAxes' names
  std::string projection = "perspective";  // projection.h's names
  // --camera-orthographic: the framing (or flag-given) camera is orthographic, as high as the
  // perspective one's view of the model's bounds.
  bool orthographic = false;
  // --camera-index: a camera of the file (SceneGraph::cameras) instead; -1: none.
  int camera_index = -1;
  // f3d's --camera-azimuth-angle and --camera-elevation-angle, degrees, applied after the camera
  // is placed (framed or given), as VTK's Azimuth and Elevation: the position turns about the
  // focal point, first about view up (positive: the camera moves to its right), then towards
  // view up (positive: the camera rises).
  float azimuth = 0.0f, elevation = 0.0f;

  bool explicitCamera() const { return has_position || has_focal_point || has_view_up; }
  float3 upAxis() const;
  Projection projectionMode() const {
    return parseProjection(projection).value_or(Projection::kPerspective);
  }
};

// --up's values, f3d's: a signed world axis.
inline constexpr const char* kUpAxes[] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

// Near and far as distances from the eye (the nonlinear projections' depth) around the bounds'
// sphere, wherever the model turns about its centre: a range along the view axis may cut its
// corners short.
void fitDistanceRange(Camera& camera, const Bounds& bounds);

// The view angle the settings give for an image of this aspect: the flag's, or the mode's
// default. An error naming the mode's range when it is out of it (a usage error).
Expected<float> viewAngle(const CameraSettings& settings, float aspect);

// The camera for a model with these bounds: the three-quarter view from the front, right and
// above that fits the whole model, or the camera the flags describe (near and far fitted to the
// bounds). An error for a camera that cannot look anywhere (a usage error).
// With camera_index set, the file's camera `graph` holds at that index (SceneGraph::camera);
// past the end an error naming how many there are (a failure, not a usage error: the caller
// tells them apart with cameraIndexError).
Expected<Camera> makeCamera(const CameraSettings& settings, const Bounds& bounds, float aspect,
                            const SceneGraph* graph = nullptr);

// Whether makeCamera's error is about --camera-index (exit 1) rather than a usage error.
bool cameraIndexError(const std::string& message);

}  // namespace tessera::model
