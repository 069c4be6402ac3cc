#include "view_setup.h"

#include "model_scene.h"

namespace tessera::cli {

Expected<Camera> makeCamera(const CameraSettings& settings, const Bounds& bounds, float aspect) {
  const float3 up = settings.upAxis();
  Camera camera = frameBounds(bounds, threeQuarterDirection(up), up, settings.view_angle, aspect);
  if (!settings.explicitCamera()) return camera;
  if (settings.has_position) camera.position = settings.position;
  if (settings.has_focal_point) camera.target = settings.focal_point;
  camera.up = settings.has_view_up ? settings.view_up : up;
  if (length(camera.target - camera.position) == 0.0f)
    return makeError("the camera position and focal point are the same point");
  if (length(camera.up) == 0.0f) return makeError("--camera-view-up must not be zero");
  fitNearFar(camera, bounds);
  return camera;
}

}  // namespace tessera::cli
