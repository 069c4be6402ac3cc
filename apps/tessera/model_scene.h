// How a loaded model becomes a scene, shared by `tessera render` and `tessera view`: one object
// with the model's materials, the default three-quarter view and the lights fixed to the view.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include <tessera/base/expected.h>
#include <tessera/io/model_loader.h>
#include <tessera/scene/scene.h>

namespace tessera::cli {

struct ModelSceneSettings {
  Shading shading = Shading::kPhong;
  CullMode cull = CullMode::kNone;
  float3 background_srgb{0.2f, 0.2f, 0.2f};  // sRGB, 0..1
  // When set, the albedo of every material (their base colours become white).
  std::shared_ptr<const Texture> albedo;
};

// "flat", "smooth" (per-pixel), "gouraud" (per-vertex) or "unlit".
Shading shadingFromName(const std::string& name);

// The model as the scene's one object, in its own coordinates. The camera is left as it is
// and there are no lights yet (addViewLights). Fails when the model has no finite vertex.
Expected<Scene> makeModelScene(io::Model model, const std::filesystem::path& path,
                               const ModelSceneSettings& settings);

// The direction, from the model towards the camera, of the default view: from the front, right
// and above. `up` is +Y or +Z.
float3 threeQuarterDirection(float3 up);

// Near and far that bracket the bounds as seen from the camera.
void fitNearFar(Camera& camera, const Bounds& bounds);

// A key light from above-left of the camera and a fill from the right, fixed to the view.
void addViewLights(Scene& scene);

}  // namespace tessera::cli
