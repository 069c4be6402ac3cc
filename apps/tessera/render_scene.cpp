#include "render_scene.h"

#include <iostream>
#include <memory>
#include <utility>
#include <vector>

#include <tessera/io/image_loader.h>
#include <tessera/model/model_scene.h>

#include "animation_frames.h"
#include "commands.h"
#include "view_setup.h"

namespace tessera::cli {

using namespace tessera::model;

namespace {

// The --light lights, scale fit and warnings applied to a loaded model, and the scene settings its
// flags give (--color, --texture). An exit status other than kExitOk when something fails
// (printed).
int prepareModel(const RenderSettings& s, const std::filesystem::path& model_path, io::Model& model,
                 ModelSceneSettings& scene_settings) {
  // The file's lights, then the --light ones: in the model's coordinates, fitted with it.
  model.lights.insert(model.lights.end(), s.lights.lights.begin(), s.lights.lights.end());
  if (std::string warning = fitModelScale(model, model_path, s.camera.explicitCamera());
      !warning.empty())
    model.warnings.push_back(warning);
  for (const std::string& warning : model.warnings)
    std::cerr << "tessera render: warning: " << warning << "\n";
  scene_settings.default_color_srgb = s.color;
  if (s.color && !hasDefaultMaterial(model))
    std::cerr << "tessera render: warning: --color has no effect: every face of "
              << model_path.string() << " has a material of the file\n";
  if (!s.texture.empty()) {
    Expected<Texture> texture = io::loadTexture(s.texture, /*srgb=*/true, s.budget.texturePixels());
    if (!texture) {
      printError("render", texture.error().message);
      return kExitFailure;
    }
    if (!modelHasUvs(model))
      std::cerr << "tessera render: warning: " << model_path.string()
                << " has no texture coordinates: --texture has no effect\n";
    scene_settings.albedo = std::make_shared<const Texture>(std::move(*texture));
  }
  return kExitOk;
}

// The scene's camera (framing `bounds`), lights, surface, environment and axes. An exit status
// other than kExitOk when something fails (printed, or usage_error's).
int finishScene(const RenderSettings& s, const std::filesystem::path& model_path,
                const Bounds& bounds, const SceneGraph& graph, const std::vector<Light>& lights,
                Scene& scene, const std::function<int(const std::string&)>& usage_error) {
  const float aspect = static_cast<float>(s.width) / static_cast<float>(s.height);
  Expected<Camera> camera = makeCamera(s.camera, bounds, aspect, &graph);
  if (!camera && cameraIndexError(camera.error().message)) {
    printError("render", model_path.string() + ": " + camera.error().message);
    return kExitFailure;
  }
  if (!camera) return usage_error(camera.error().message);
  scene.camera = *camera;
  addViewLights(scene);
  applyLights(scene, lights, s.lights);
  applySurface(s.surface, bounds, s.camera.upAxis(), scene);
  if (Expected<void> lit =
          applyEnvironment(s.surface, s.budget.texturePixels(), s.camera.upAxis(), scene);
      !lit) {
    printError("render", lit.error().message);
    return kExitFailure;
  }
  if (s.axes) {
    scene.show_world_axes = true;
    scene.world_axes_length = std::max(bounds.radius(), 1e-6f);
  }
  return kExitOk;
}

}  // namespace

int loadScene(const RenderSettings& s, const std::filesystem::path& model_path, Scene& scene,
              Bounds& bounds, SceneGraph& graph,
              const std::function<int(const std::string&)>& usage_error) {
  Expected<io::Model> model = io::loadModel(model_path, s.budget);
  if (!model) {
    printError("render", model.error().message);
    return kExitFailure;
  }
  if (s.info) {
    printModelInfo(model_path.string(), *model, std::cout);
    return kExitOk;
  }
  ModelSceneSettings scene_settings;
  if (int status = prepareModel(s, model_path, *model, scene_settings); status != kExitOk)
    return status;
  bounds = modelBounds(*model);
  if (bounds.empty()) {
    printError("render", model_path.string() + ": the model has no finite vertices");
    return kExitFailure;
  }

  scene_settings.shading =
      s.shading.empty() ? defaultShading(model_path) : shadingFromName(s.shading);
  // Without the flag a glTF model's materials decide (doubleSided); other formats draw back faces.
  const bool cull_back =
      s.backface.empty() ? model->cull_back_faces.value_or(false) : s.backface == "hidden";
  scene_settings.cull = cull_back ? CullMode::kBack : CullMode::kNone;
  scene_settings.background_srgb = s.background;
  const std::vector<Light> lights = model->lights;
  Expected<Scene> made = makeModelScene(std::move(*model), model_path, scene_settings, &graph);
  if (!made) {
    printError("render", made.error().message);
    return kExitFailure;
  }
  scene = std::move(*made);
  if (s.animation_index >= 0 && static_cast<size_t>(s.animation_index) >= graph.animations.size()) {
    printError("render", animationIndexError(model_path.string(), graph.animations.size(),
                                             s.animation_index));
    return kExitFailure;
  }
  // An animated model is framed, and its near and far planes set, for every pose of the clip.
  if (s.animation_index >= 0) {
    const Bounds moving =
        clipBounds(graph.animations[static_cast<size_t>(s.animation_index)], graph);
    if (!moving.empty()) {
      bounds.add(moving.min);
      bounds.add(moving.max);
    }
  }
  return finishScene(s, model_path, bounds, graph, lights, scene, usage_error);
}

}  // namespace tessera::cli
