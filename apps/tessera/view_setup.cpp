#include "view_setup.h"

#include <algorithm>

namespace tessera::cli {

void fitNearFar(Camera& camera, const Bounds& bounds) {
  const float3 forward = normalize(camera.target - camera.position);
  float nearest = 1e30f, farthest = -1e30f;
  for (int i = 0; i < 8; ++i) {
    float3 corner{i & 1 ? bounds.max.x : bounds.min.x, i & 2 ? bounds.max.y : bounds.min.y,
                  i & 4 ? bounds.max.z : bounds.min.z};
    float d = dot(corner - camera.position, forward);
    nearest = std::min(nearest, d);
    farthest = std::max(farthest, d);
  }
  camera.far_z = farthest > 0.0f ? farthest * 1.01f + 1e-6f : 1.0f;
  // A camera inside the bounds still gets a near plane; 1e-4 of far keeps depth precise.
  camera.near_z = std::max(nearest * 0.99f, camera.far_z * 1e-4f);
}

Expected<Camera> makeCamera(const CameraSettings& settings, const Bounds& bounds, float aspect) {
  const float3 up = settings.upAxis();
  const float3 toward_viewer = settings.up == "+Z" ? float3{0, -1, 0} : float3{0, 0, 1};
  const float3 right{1, 0, 0};
  Camera camera = frameBounds(bounds, toward_viewer + right * 0.6f + up * 0.45f, up,
                              settings.view_angle, aspect);
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

void addViewLights(Scene& scene) {
  const Camera& c = scene.camera;
  const float3 forward = normalize(c.target - c.position);
  float3 right = normalize(cross(forward, c.up));
  if (length(right) == 0.0f) right = normalize(cross(forward, float3{1, 0, 0}));
  const float3 up = cross(right, forward);
  scene.lights.clear();
  scene.lights.push_back({normalize(forward + right * 0.5f - up * 0.8f), float3(0.75f)});
  scene.lights.push_back({normalize(forward - right * 0.7f - up * 0.1f), float3(0.2f)});
  scene.ambient = float3(0.08f);
}

}  // namespace tessera::cli
