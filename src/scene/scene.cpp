#include <tessera/scene/scene.h>

#include <algorithm>
#include <cmath>

namespace tessera {

size_t Scene::triangleCount() const {
  size_t count = 0;
  for (const Object& object : objects)
    if (object.mesh) count += object.mesh->triangleCount();
  return count;
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const Object& object : objects) {
    if (!object.mesh) continue;
    float4x4 m = object.transform.matrix();
    for (const float3& p : object.mesh->positions) {
      if (!isFinite(p)) continue;
      float3 w = (m * float4{p, 1.0f}).xyz();
      if (isFinite(w)) b.add(w);
    }
  }
  // Points and lines are in world space: a point cloud or a wireframe is framed like a mesh.
  for (const float3& p : points.positions)
    if (isFinite(p)) b.add(p);
  for (const float3& p : lines.points)
    if (isFinite(p)) b.add(p);
  return b;
}

Camera frameBounds(const Bounds& bounds, float3 direction, float3 up, float fov_y_degrees,
                   float aspect) {
  Camera camera;
  camera.up = up;
  camera.fov_y_degrees = fov_y_degrees;
  float3 center = bounds.empty() ? float3{} : bounds.center();
  float radius = bounds.empty() ? 1.0f : std::max(bounds.radius(), 1e-6f);
  // Fit the bounding sphere in the narrower of the two fields of view.
  float half_v = radians(fov_y_degrees) * 0.5f;
  float half_h = std::atan(std::tan(half_v) * aspect);
  float half = std::min(half_v, half_h);
  float distance = radius / std::sin(half) * 1.05f;
  float3 dir = normalize(direction);
  if (length(dir) == 0.0f) dir = {0, 0, 1};
  camera.target = center;
  camera.position = center + dir * distance;
  // Near and far bracket the sphere; near is kept a sane fraction of far for depth precision.
  camera.far_z = distance + radius * 1.01f;
  camera.near_z = std::max(distance - radius * 1.01f, camera.far_z * 1e-4f);
  return camera;
}

}  // namespace tessera
