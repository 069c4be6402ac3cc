#include "scenes.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <system_error>

#include <tessera/io/model_loader.h>
#include <tessera/scene/clusters.h>
#include <tessera/scene/color.h>
#include <tessera/scene/graph.h>
#include <tessera/scene/primitives.h>

namespace tessera::bench {

namespace {

// UV sphere sizes: makeUvSphere gives 2 * segments * (rings - 1) triangles (no pole slivers).
constexpr int kDenseSegments = 1000, kDenseRings = 501;
constexpr int kTexturedSegments = 128, kTexturedRings = 64;
static_assert(2 * kDenseSegments * (kDenseRings - 1) == kDenseTriangles);
static_assert(2 * kTexturedSegments * (kTexturedRings - 1) == kTexturedTriangles);

float4 srgbColor(float r, float g, float b) {
  return {srgbToLinear(r), srgbToLinear(g), srgbToLinear(b), 1.0f};
}

BenchScene singleObjectScene(std::string name, Mesh mesh, Material material, Shading shading) {
  BenchScene b;
  b.name = std::move(name);
  Object object;
  object.mesh = std::make_shared<Mesh>(std::move(mesh));
  object.clusters = buildClusters(*object.mesh);  // as a model the CLI loads has them
  object.materials = {std::move(material)};
  object.shading = shading;
  object.cull = CullMode::kBack;
  b.scene.objects.push_back(std::move(object));
  b.scene.background = srgbColor(0.2f, 0.2f, 0.2f);
  b.bounds = b.scene.bounds();
  b.pivot = b.bounds.center();
  return b;
}

// Ten square layers facing a camera at the origin that looks down -Z, listed farthest first, so
// every layer passes the depth test wherever it is drawn: each pixel is covered ten times. The
// squares reach 2.5 times the half-height of the view at their depth: they cover any view up to
// an aspect of 2.2 at any angle of the spin about the view axis.
BenchScene makeFillScene(Shading shading) {
  BenchScene b;
  b.name = "fill";
  b.fixed_view = true;
  Camera& camera = b.scene.camera;
  camera.position = {0, 0, 0};
  camera.target = {0, 0, -1};
  camera.up = {0, 1, 0};
  camera.fov_y_degrees = 50.0f;
  camera.near_z = 1.0f;
  camera.far_z = 20.0f;
  const float half_tan = std::tan(radians(camera.fov_y_degrees) * 0.5f);
  for (size_t layer = 0; layer < kFillLayers; ++layer) {
    const float depth = 2.0f + static_cast<float>(kFillLayers - 1 - layer);
    const float h = depth * half_tan * 2.5f;
    Mesh quad;
    quad.positions = {{-h, -h, -depth}, {h, -h, -depth}, {h, h, -depth}, {-h, h, -depth}};
    quad.normals.assign(4, float3{0, 0, 1});
    quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    quad.indices = {0, 1, 2, 0, 2, 3};  // counter-clockwise seen from the camera
    Object object;
    object.mesh = std::make_shared<Mesh>(std::move(quad));
    // A hue per layer, so a picture shows which layer won.
    const float t = static_cast<float>(layer) / static_cast<float>(kFillLayers - 1);
    object.materials[0].base_color = srgbColor(0.3f + 0.6f * t, 0.8f - 0.5f * t, 0.9f - 0.6f * t);
    object.shading = shading;
    object.cull = CullMode::kBack;
    b.scene.objects.push_back(std::move(object));
  }
  b.scene.lights.push_back({normalize(float3{0.3f, -0.4f, -1.0f}), float3(0.8f)});
  b.scene.ambient = float3(0.18f);
  b.scene.background = srgbColor(0.2f, 0.2f, 0.2f);
  b.bounds = b.scene.bounds();
  b.spin_axis = {0, 0, 1};  // about the view axis: the layers keep covering the screen
  b.pivot = {0, 0, 0};
  return b;
}

Expected<BenchScene> makeBunnyScene(Shading shading) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(kBunnyPath, error))
    return makeError(std::string("the bunny scene needs ") + kBunnyPath + " from Debian's " +
                     kBunnyPackage + " package (apt-get install " + kBunnyPackage + ")");
  Expected<BenchScene> scene = loadModelScene(kBunnyPath, shading);
  if (!scene) return scene;
  scene->name = "bunny";
  return scene;
}

}  // namespace

Texture makeCheckerTexture(int size, int cells) {
  Texture texture;
  texture.width = texture.height = size;
  texture.srgb = true;
  texture.texels.resize(static_cast<size_t>(size) * size);
  const uint32_t light = 0xffe8e0d8u, dark = 0xff503828u;  // ABGR: R in the low byte
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const bool odd = ((x * cells / size) + (y * cells / size)) % 2 != 0;
      texture.texels[static_cast<size_t>(y) * size + x] = odd ? dark : light;
    }
  return texture;
}

std::vector<std::string> builtinSceneNames() {
  return {"cube", "bunny", "dense", "fill", "textured", "instances"};
}

BenchScene makeInstancesScene(Shading shading, bool flattened) {
  // 10,000 instances of a 1,000-triangle sphere on a 100 x 100 grid, 3 units apart; the camera
  // looks at a corner of it from close by: 98 or 99 of them (1%) are in view, in every frame.
  SceneGraph graph;
  GraphMesh sphere;
  sphere.mesh = std::make_shared<const Mesh>(makeUvSphere(25, 21));
  Material material;
  material.base_color = srgbColor(0.8f, 0.6f, 0.3f);
  sphere.materials = {material};
  graph.meshes.push_back(sphere);
  for (int i = 0; i < 10000; ++i) {
    GraphNode node;
    node.mesh = 0;
    node.local.translation = {3.0f * static_cast<float>(i % 100), 0.0f,
                              -3.0f * static_cast<float>(i / 100)};
    graph.nodes.push_back(node);
  }
  graph.updateWorld();
  graph.prepareMeshes();
  BenchScene b;
  b.name = flattened ? "instances-flat" : "instances";
  Object style;
  style.shading = shading;
  style.cull = CullMode::kBack;
  if (flattened) {
    style.mesh = std::make_shared<const Mesh>(graph.flatten());
    style.materials = sphere.materials;
    b.scene.objects.push_back(style);
  } else {
    instantiate(graph, style, b.scene);
  }
  b.scene.background = srgbColor(0.2f, 0.2f, 0.2f);
  b.scene.camera.position = {-4, 6, 6};
  b.scene.camera.target = {12, -2, -12};
  b.scene.camera.fov_y_degrees = 28.5f;
  b.scene.camera.near_z = 0.5f;
  b.scene.camera.far_z = 40;
  b.scene.lights.push_back({normalize(float3{1, -2, -1}), float3(0.8f)});
  b.bounds = graph.bounds();
  b.fixed_view = true;
  b.spins = false;
  return b;
}

std::vector<std::string> extraSceneNames() {
  return {"instances-flat", "points"};
}

BenchScene makePointCloudScene() {
  constexpr int kColumns = 4000, kRows = 2500;
  static_assert(size_t{kColumns} * kRows == kCloudPoints);
  BenchScene b;
  b.name = "points";
  PointList& points = b.scene.points;
  points.positions.resize(kCloudPoints);
  points.colors.resize(kCloudPoints);
  // A 32-bit integer hash (Wellons' lowbias32) to [0, 1): the jitter and the roughness.
  auto hash = [](uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return static_cast<float>(x >> 8) * (1.0f / 16777216.0f);
  };
  for (int r = 0; r < kRows; ++r) {
    for (int c = 0; c < kColumns; ++c) {
      const uint32_t i = static_cast<uint32_t>(r) * kColumns + static_cast<uint32_t>(c);
      const float x = (static_cast<float>(c) + hash(2 * i)) / kColumns * 4.0f - 2.0f;
      const float z = (static_cast<float>(r) + hash(2 * i + 1)) / kRows * 2.5f - 1.25f;
      const float h = 0.18f * std::sin(2.5f * x) * std::cos(3.0f * z) +
                      0.06f * std::sin(9.0f * x + 5.0f * z) + 0.01f * hash(i ^ 0x9e3779b9u);
      points.positions[i] = {x, h, z};
      const float t = std::clamp((h + 0.25f) / 0.5f, 0.0f, 1.0f);  // low: blue-green, high: sand
      points.colors[i] = packSrgba8(
          {0.05f + 0.75f * t * t, 0.25f + 0.45f * t, 0.35f * (1.0f - t) + 0.2f * t, 1.0f});
    }
  }
  for (const float3& p : points.positions) b.bounds.add(p);
  b.scene.background = srgbColor(0.2f, 0.2f, 0.2f);
  b.scene.camera.position = {0.0f, 1.3f, 2.2f};
  b.scene.camera.target = {0.0f, -0.3f, -0.3f};
  b.scene.camera.fov_y_degrees = 45.0f;
  b.scene.camera.near_z = 0.5f;
  b.scene.camera.far_z = 8.0f;
  b.scene.lights.push_back(Light::directional(normalize(float3{-1, -1.5f, -0.5f}), float3(1.0f)));
  b.fixed_view = true;
  return b;
}

bool isBuiltinScene(const std::string& name) {
  const std::vector<std::string> names = builtinSceneNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

Expected<BenchScene> makeBuiltinScene(const std::string& name, Shading shading) {
  if (name == "cube") {
    Material material;
    material.base_color = srgbColor(0.95f, 0.55f, 0.15f);
    return singleObjectScene(name, makeCube(), material, shading);
  }
  if (name == "bunny") return makeBunnyScene(shading);
  if (name == "dense")
    return singleObjectScene(name, makeUvSphere(kDenseSegments, kDenseRings), Material{}, shading);
  if (name == "fill") return makeFillScene(shading);
  if (name == "instances") return makeInstancesScene(shading, /*flattened=*/false);
  // Not in the list (10 million triangles a frame): for the comparison in docs/perf.md.
  if (name == "instances-flat") return makeInstancesScene(shading, /*flattened=*/true);
  if (name == "points") return makePointCloudScene();
  if (name == "textured") {
    Material material;
    material.base_color = {1, 1, 1, 1};
    material.albedo = std::make_shared<Texture>(makeCheckerTexture(512, 16));
    // Bilinear without mip levels on both sides (tessera and llvmpipe's GL_LINEAR): the row of
    // issue 21's matrix. (Trilinear: the sampler of glTF and OBJ textures, measured in
    // docs/perf.md on a model file.)
    material.sampler.filter = TextureFilter::kBilinear;
    return singleObjectScene(name, makeUvSphere(kTexturedSegments, kTexturedRings), material,
                             shading);
  }
  std::string known;
  for (const std::string& n : builtinSceneNames()) known += (known.empty() ? "" : ", ") + n;
  return makeError("unknown scene '" + name + "' (built-in scenes: " + known + ")");
}

Expected<BenchScene> loadModelScene(const std::filesystem::path& path, Shading shading,
                                    const io::LoadBudget& budget) {
  Expected<io::Model> model = io::loadModel(path, budget);
  if (!model) return model.error();
  // A glTF scene graph is drawn flattened: one object that the bench turns.
  Mesh mesh = model->graph.nodes.empty() ? std::move(model->mesh) : io::flattenedMesh(*model);
  if (mesh.bounds().empty()) return makeError(path.string() + ": the model has no finite vertices");
  std::vector<Material> materials = model->graph.meshes.empty()
                                        ? model->materials
                                        : model->graph.meshes.front().materials.vector();
  BenchScene b = singleObjectScene(path.stem().string(), std::move(mesh), Material{}, shading);
  if (!materials.empty()) b.scene.objects[0].materials = materials;
  b.warnings = model->warnings;
  return b;
}

void poseForFrame(BenchScene& bench_scene, int frame) {
  if (!bench_scene.spins) return;
  const quat turn =
      quat::fromAxisAngle(bench_scene.spin_axis, radians(kTurnDegreesPerFrame * frame));
  for (Object& object : bench_scene.scene.objects) {
    object.transform.rotation = turn;
    object.transform.translation = bench_scene.pivot - rotate(turn, bench_scene.pivot);
  }
}

}  // namespace tessera::bench
