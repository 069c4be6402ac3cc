#include "model_scene.h"

#include <algorithm>

#include <tessera/scene/color.h>

namespace tessera::cli {

Shading shadingFromName(const std::string& name) {
  if (name == "flat") return Shading::kFlat;
  if (name == "gouraud") return Shading::kGouraud;
  if (name == "unlit") return Shading::kUnlit;
  return Shading::kPhong;
}

Expected<Scene> makeModelScene(io::Model model, const std::filesystem::path& path,
                               const ModelSceneSettings& settings) {
  if (model.mesh.bounds().empty())
    return makeError(path.string() + ": the model has no finite vertices");
  Scene scene;
  Object object;
  object.mesh = std::make_shared<Mesh>(std::move(model.mesh));
  object.materials = std::move(model.materials);
  if (object.materials.empty()) object.materials.push_back(Material{});
  // The texture is the albedo: a white base colour lets it show as it is (alpha is kept).
  if (settings.albedo) {
    for (Material& material : object.materials) {
      material.albedo = settings.albedo;
      material.base_color = {1.0f, 1.0f, 1.0f, material.base_color.w};
    }
  }
  object.shading = settings.shading;
  object.cull = settings.cull;
  scene.objects.push_back(std::move(object));
  const float3 bg = settings.background_srgb;
  scene.background = {srgbToLinear(bg.x), srgbToLinear(bg.y), srgbToLinear(bg.z), 1.0f};
  return scene;
}

float3 threeQuarterDirection(float3 up) {
  const float3 toward_viewer = up.z != 0.0f ? float3{0, -1, 0} : float3{0, 0, 1};
  const float3 right{1, 0, 0};
  return toward_viewer + right * 0.6f + up * 0.45f;
}

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
