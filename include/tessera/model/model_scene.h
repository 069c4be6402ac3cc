// How a loaded model becomes a scene, shared by `tessera render`, `tessera view` and the bench
// (library tessera_model): one object per instance of the model's scene graph, the materials
// shared by the instances of a mesh, the default three-quarter view and the lights fixed to the
// view.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <tessera/base/expected.h>
#include <tessera/io/model_loader.h>
#include <tessera/scene/scene.h>

namespace tessera::model {

struct ModelSceneSettings {
  Shading shading = Shading::kPhong;
  CullMode cull = CullMode::kNone;
  float3 background_srgb{0.2f, 0.2f, 0.2f};  // sRGB, 0..1
  // When set, the albedo of every material (their base colours become white).
  std::shared_ptr<const Texture> albedo;
  // --color: when set, the base colour (sRGB, 0..1) of the materials the file did not give,
  // those the loader made (isDefaultMaterial); the file's own materials keep theirs. f3d's
  // --color likewise colours a model read without materials.
  std::optional<float3> default_color_srgb;
};

// Whether `material` is the one a loader gives faces without a material of the file: 0.8 grey,
// opaque, untextured (Material's defaults).
bool isDefaultMaterial(const Material& material);
// Whether any material the model draws with is the loader's default.
bool hasDefaultMaterial(const io::Model& model);

// "flat", "smooth" (per-pixel), "gouraud" (per-vertex), "unlit" or "pbr".
Shading shadingFromName(const std::string& name);

// The shading a model is drawn with when the user names none: kPbr for glTF (.gltf, .glb), whose
// materials are metallic-roughness ones; kPhong (smooth) for the other formats.
Shading defaultShading(const std::filesystem::path& model);

// The model's instances as the scene's objects (instantiate, graph.h), in its own coordinates:
// one object for OBJ and STL; Model::points and Model::lines become Scene::points and
// Scene::lines. The camera is left as it is and there are no lights yet
// (addViewLights). Fails when the model has no finite vertex. `graph`, when given, receives the
// model's scene graph (its cameras, and the nodes an animation moves).
Expected<Scene> makeModelScene(io::Model model, const std::filesystem::path& path,
                               const ModelSceneSettings& settings, SceneGraph* graph = nullptr);

// World bounds of what the model draws: its meshes, points and line end points.
Bounds modelBounds(const io::Model& model);
// Whether any mesh the model draws has texture coordinates.
bool modelHasUvs(const io::Model& model);

// Float frames, clips and lights a model well between about 2^-20 and 2^20 units, near the
// origin. Past that (a model 1e10 or 3e38 across, or 1e-42), with the framing camera
// (`keep_coordinates` false), the model is moved and scaled in double, by a power of two, to
// about unit size at the origin: the picture is the one its own scale would give. With camera
// flags it stays as it is (a scene graph is moved by a new root node, the meshes untouched), and
// when it is far outside float's comfort the returned warning says why it may not be drawn. Empty
// when there is nothing to say.
std::string fitModelScale(io::Model& model, const std::filesystem::path& path,
                          bool keep_coordinates);

// The direction, from the model towards the camera, of the default view: from the front, right
// and above. `up` is a signed world axis (--up).
float3 threeQuarterDirection(float3 up);

// Near and far that bracket the bounds as seen from the camera.
void fitNearFar(Camera& camera, const Bounds& bounds);

// A key light from above-left of the camera and a fill from the right, fixed to the view.
void addViewLights(Scene& scene);

}  // namespace tessera::model
