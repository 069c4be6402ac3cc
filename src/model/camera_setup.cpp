#include <tessera/model/camera_setup.h>

#include <algorithm>

#include <tessera/model/model_scene.h>

namespace tessera::model {

float3 CameraSettings::upAxis() const {
  const float sign = !up.empty() && up[0] == '-' ? -1.0f : 1.0f;
  const char axis = up.empty() ? 'Y' : up.back();
  if (axis == 'X' || axis == 'x') return {sign, 0, 0};
  if (axis == 'Z' || axis == 'z') return {0, 0, sign};
  return {0, sign, 0};
}

Expected<float> viewAngle(const CameraSettings& settings, float aspect) {
  const Projection mode = settings.projectionMode();
  const float angle =
      settings.has_view_angle ? settings.view_angle : defaultViewAngle(mode, aspect);
  if (std::string range = checkViewAngle(mode, angle, aspect); !range.empty())
    return makeError("--camera-view-angle: " + range);
  return angle;
}

namespace {

// Near and far as distances from the camera (the nonlinear projections' depth): the nearest
// point of the bounds (0 inside them) and the farthest corner.
void fitNearFarDistance(Camera& camera, const Bounds& bounds) {
  const float3 p = camera.position;
  const float3 nearest{std::clamp(p.x, bounds.min.x, bounds.max.x),
                       std::clamp(p.y, bounds.min.y, bounds.max.y),
                       std::clamp(p.z, bounds.min.z, bounds.max.z)};
  float farthest = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const float3 corner{i & 1 ? bounds.max.x : bounds.min.x, i & 2 ? bounds.max.y : bounds.min.y,
                        i & 4 ? bounds.max.z : bounds.min.z};
    farthest = std::max(farthest, length(corner - p));
  }
  camera.far_z = farthest > 0.0f ? farthest * 1.01f + 1e-6f : 1.0f;
  camera.near_z = std::max(length(nearest - p) * 0.99f, camera.far_z * 1e-4f);
}

}  // namespace

void fitDistanceRange(Camera& camera, const Bounds& bounds) {
  const float distance = length(bounds.center() - camera.position);
  const float radius = bounds.radius() * 1.01f;
  camera.far_z = distance + radius + 1e-6f;
  camera.near_z = std::max(distance - radius, camera.far_z * 1e-4f);
}

bool cameraIndexError(const std::string& message) {
  return message.starts_with("--camera-index");
}

namespace {

// The orthographic form of a framing camera: as high as its view angle shows the bounds'
// centre plane, looking the same way; near and far bracket the bounds.
void makeOrthographic(Camera& camera, const Bounds& bounds) {
  const float distance = length(bounds.center() - camera.position);
  camera.orthographic = true;
  camera.ortho_half_height =
      std::max(distance * std::tan(radians(camera.fov_y_degrees) * 0.5f), 1e-6f);
  fitNearFar(camera, bounds);
  camera.near_z = std::max(0.0f, camera.near_z);
}

// f3d's (VTK's) Azimuth then Elevation: the position turns about the focal point, first by a
// right-handed turn about the view up, then about the camera's left axis (-right), which raises
// the camera towards view up for a positive angle. The view up is kept, as VTK keeps it.
void turnCamera(Camera& camera, float azimuth_degrees, float elevation_degrees) {
  if (azimuth_degrees == 0.0f && elevation_degrees == 0.0f) return;
  const float3 up = normalize(camera.up);
  float3 offset = camera.position - camera.target;
  offset = rotate(quat::fromAxisAngle(up, radians(azimuth_degrees)), offset);
  const float3 right = cross(-offset, up);  // forward x up
  if (length(right) > 0.0f)
    offset = rotate(quat::fromAxisAngle(-normalize(right), radians(elevation_degrees)), offset);
  camera.position = camera.target + offset;
}

}  // namespace

Expected<Camera> makeCamera(const CameraSettings& settings, const Bounds& bounds, float aspect,
                            const SceneGraph* graph) {
  if (settings.camera_index >= 0) {
    const size_t count = graph ? graph->cameras.size() : 0;
    if (static_cast<size_t>(settings.camera_index) >= count)
      return makeError("--camera-index " + std::to_string(settings.camera_index) +
                       ": the model has " + std::to_string(count) + " camera" +
                       (count == 1 ? "" : "s") +
                       (count ? " (0 to " + std::to_string(count - 1) + ")" : ""));
    Expected<Camera> camera =
        graph->camera(static_cast<size_t>(settings.camera_index), aspect, bounds);
    if (!camera) return makeError("--camera-index: " + camera.error().message);
    return camera;
  }
  const float3 up = settings.upAxis();
  Expected<float> angle = viewAngle(settings, aspect);
  if (!angle) return makeError(angle.error().message);
  const bool perspective = settings.projectionMode() == Projection::kPerspective;
  // The nonlinear modes frame the model as a 90-degree view would: a panorama or fisheye of the
  // model seen from outside, the model in the middle.
  Camera camera = frameBounds(bounds, threeQuarterDirection(up), up,
                              perspective ? *angle : std::min(*angle, 90.0f), aspect);
  camera.fov_y_degrees = *angle;
  if (!settings.explicitCamera()) {
    // About the bounds' centre: the framing's near and far (its sphere's) still hold.
    turnCamera(camera, settings.azimuth, settings.elevation);
    if (settings.orthographic) makeOrthographic(camera, bounds);
    return camera;
  }
  if (settings.has_position) camera.position = settings.position;
  if (settings.has_focal_point) camera.target = settings.focal_point;
  camera.up = settings.has_view_up ? settings.view_up : up;
  if (length(camera.target - camera.position) == 0.0f)
    return makeError("the camera position and focal point are the same point");
  if (length(camera.up) == 0.0f) return makeError("--camera-view-up must not be zero");
  turnCamera(camera, settings.azimuth, settings.elevation);
  if (perspective)
    fitNearFar(camera, bounds);
  else
    fitNearFarDistance(camera, bounds);
  if (settings.orthographic) makeOrthographic(camera, bounds);
  return camera;
}

}  // namespace tessera::model
