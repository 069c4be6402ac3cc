#include <tessera/model/model_scene.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include <tessera/scene/color.h>

namespace tessera::model {

Shading shadingFromName(const std::string& name) {
  if (name == "flat") return Shading::kFlat;
  if (name == "gouraud") return Shading::kGouraud;
  if (name == "unlit") return Shading::kUnlit;
  if (name == "pbr") return Shading::kPbr;
  return Shading::kPhong;
}

Shading defaultShading(const std::filesystem::path& model) {
  std::string extension = model.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".gltf" || extension == ".glb" ? Shading::kPbr : Shading::kPhong;
}

bool isDefaultMaterial(const Material& material) {
  const Material fresh;
  return !material.albedo && material.base_color.x == fresh.base_color.x &&
         material.base_color.y == fresh.base_color.y &&
         material.base_color.z == fresh.base_color.z && material.base_color.w == fresh.base_color.w;
}

bool hasDefaultMaterial(const io::Model& model) {
  auto any = [](const MaterialList& list) {
    return std::any_of(list.begin(), list.end(), isDefaultMaterial);
  };
  if (model.graph.nodes.empty())
    return std::any_of(model.materials.begin(), model.materials.end(), isDefaultMaterial);
  return std::any_of(model.graph.meshes.begin(), model.graph.meshes.end(),
                     [&](const GraphMesh& m) { return any(m.materials); });
}

namespace {

// The finite points and line end points (world space) into `b`.
void addPointBounds(Bounds& b, const PointList& points, const LineList& lines) {
  for (const float3& p : points.positions)
    if (isFinite(p)) b.add(p);
  for (const float3& p : lines.points)
    if (isFinite(p)) b.add(p);
}

// Applies `change` to each mesh's materials, once per list: meshes that shared one list share
// the changed copy.
template <class Change>
void changeMaterialLists(SceneGraph& graph, Change change) {
  std::vector<std::pair<MaterialList, MaterialList>> changed;  // before, after
  for (GraphMesh& mesh : graph.meshes) {
    auto same = std::find_if(changed.begin(), changed.end(),
                             [&](const auto& c) { return c.first.sharesWith(mesh.materials); });
    if (same != changed.end()) {
      mesh.materials = same->second;
      continue;
    }
    const MaterialList before = mesh.materials;
    for (Material& material : mesh.materials) change(material);
    changed.push_back({before, mesh.materials});
  }
}

}  // namespace

Expected<Scene> makeModelScene(io::Model model, const std::filesystem::path& path,
                               const ModelSceneSettings& settings, SceneGraph* graph_out) {
  PointList points = std::move(model.points);
  LineList lines = std::move(model.lines);
  SceneGraph graph = io::takeGraph(std::move(model));
  if (Expected<void> ok = graph.validate(); !ok)
    return makeError(path.string() + ": " + ok.error().message);
  Bounds drawn = graph.bounds();
  addPointBounds(drawn, points, lines);
  if (drawn.empty()) return makeError(path.string() + ": the model has no finite vertices");
  // --texture is every material's albedo, on a white base colour (alpha kept); --color is the
  // base colour of the loader's default materials (linear from sRGB), which multiplies the
  // texture as in f3d.
  const std::optional<float3> color = settings.default_color_srgb;
  if (settings.albedo || color) {
    const float4 linear =
        color ? float4{srgbToLinear(color->x), srgbToLinear(color->y), srgbToLinear(color->z), 1}
              : float4{};
    changeMaterialLists(graph, [&](Material& material) {
      const bool recolor = color && isDefaultMaterial(material);
      if (settings.albedo) {
        material.albedo = settings.albedo;
        material.base_color = {1.0f, 1.0f, 1.0f, material.base_color.w};
      }
      if (recolor) material.base_color = linear;
    });
  }
  graph.prepareMeshes();
  Scene scene;
  Object object;
  object.shading = settings.shading;
  object.cull = settings.cull;
  instantiate(graph, object, scene);
  scene.points = std::move(points);
  scene.lines = std::move(lines);
  const float3 bg = settings.background_srgb;
  scene.background = {srgbToLinear(bg.x), srgbToLinear(bg.y), srgbToLinear(bg.z), 1.0f};
  if (graph_out) *graph_out = std::move(graph);
  return scene;
}

Bounds modelBounds(const io::Model& model) {
  Bounds b;
  if (model.graph.nodes.empty()) {
    b = model.mesh.bounds();
  } else {
    SceneGraph graph = model.graph;
    graph.updateWorld();
    b = graph.bounds();
  }
  addPointBounds(b, model.points, model.lines);
  return b;
}

bool modelHasUvs(const io::Model& model) {
  if (model.graph.nodes.empty()) return !model.mesh.uvs.empty();
  return std::any_of(model.graph.meshes.begin(), model.graph.meshes.end(),
                     [](const GraphMesh& m) { return !m.mesh->uvs.empty(); });
}

namespace {

struct DoubleBounds {
  double lo[3] = {INFINITY, INFINITY, INFINITY};
  double hi[3] = {-INFINITY, -INFINITY, -INFINITY};

  bool empty() const { return lo[0] > hi[0]; }
  double extent() const { return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}); }
  double center(int i) const { return lo[i] * 0.5 + hi[i] * 0.5; }  // no overflow at 3e38
  double farthest() const { return std::max({-lo[0], -lo[1], -lo[2], hi[0], hi[1], hi[2]}); }
};

// `m` (a float matrix) applied in double: a 3e38 model's world positions do not overflow.
void addBounds(DoubleBounds& b, const Mesh& mesh, const float4x4* m) {
  for (const float3& p : mesh.positions) {
    if (!isFinite(p)) continue;
    double w[3] = {p.x, p.y, p.z};
    if (m) {
      for (int r = 0; r < 3; ++r)
        w[r] = double((*m)(r, 0)) * p.x + double((*m)(r, 1)) * p.y + double((*m)(r, 2)) * p.z +
               double((*m)(r, 3));
    }
    for (int i = 0; i < 3; ++i) {
      b.lo[i] = std::min(b.lo[i], w[i]);
      b.hi[i] = std::max(b.hi[i], w[i]);
    }
  }
}

void addBounds(DoubleBounds& b, const std::vector<float3>& positions) {
  for (const float3& p : positions) {
    if (!isFinite(p)) continue;
    const double w[3] = {p.x, p.y, p.z};
    for (int i = 0; i < 3; ++i) {
      b.lo[i] = std::min(b.lo[i], w[i]);
      b.hi[i] = std::max(b.hi[i], w[i]);
    }
  }
}

DoubleBounds doubleBounds(const io::Model& model) {
  DoubleBounds b;
  addBounds(b, model.points.positions);
  addBounds(b, model.lines.points);
  if (model.graph.nodes.empty()) {
    addBounds(b, model.mesh, nullptr);
    return b;
  }
  SceneGraph graph = model.graph;
  graph.updateWorld();
  for (size_t i = 0; i < graph.nodes.size(); ++i)
    if (graph.nodes[i].mesh != kNoIndex)
      addBounds(b, *graph.meshes[static_cast<size_t>(graph.nodes[i].mesh)].mesh, &graph.world[i]);
  return b;
}

// A scene graph is moved and scaled by a new root above every node: (p - center) / scale.
void refitGraph(SceneGraph& graph, const double center[3], double scale) {
  GraphNode root;
  root.name = "tessera fit";
  float4x4 fit;
  for (int i = 0; i < 3; ++i) {
    fit(i, i) = static_cast<float>(1.0 / scale);
    fit(i, 3) = static_cast<float>(-center[i] / scale);
  }
  root.local.base = fit;
  for (GraphNode& node : graph.nodes) node.parent = node.parent == kNoIndex ? 0 : node.parent + 1;
  graph.nodes.insert(graph.nodes.begin(), std::move(root));
  graph.world.clear();
  // Every node moved up by one: the animations follow their nodes.
  for (Animation& animation : graph.animations)
    for (AnimationChannel& channel : animation.channels) ++channel.node;
}

std::string shortNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

}  // namespace

std::string fitModelScale(io::Model& model, const std::filesystem::path& path,
                          bool keep_coordinates) {
  const DoubleBounds b = doubleBounds(model);
  if (b.empty()) return {};
  const double extent = b.extent(), farthest = b.farthest();
  const double kComfort = std::exp2(20.0);
  const bool comfortable = extent <= kComfort && extent >= 1 / kComfort && farthest <= kComfort;
  if (comfortable || extent == 0) return {};
  if (keep_coordinates) {
    // Camera flags are floats too: a model this far out cannot be placed in front of them.
    const double kFloatLimit = std::exp2(40.0);
    if (extent <= kFloatLimit && extent >= 1 / kFloatLimit && farthest <= kFloatLimit) return {};
    return path.string() + ": the model spans " + shortNumber(extent) + " units, up to " +
           shortNumber(farthest) +
           " from the origin: at that scale the camera flags' single-precision view cannot "
           "draw it reliably; without camera flags it is framed at any scale";
  }
  const double scale = std::exp2(std::round(std::log2(extent)));
  const double center[3] = {b.center(0), b.center(1), b.center(2)};
  auto fit = [&](float3 p) {
    return float3{static_cast<float>((double(p.x) - center[0]) / scale),
                  static_cast<float>((double(p.y) - center[1]) / scale),
                  static_cast<float>((double(p.z) - center[2]) / scale)};
  };
  // Lights move with the model; 1/d^2 keeps their irradiance when candela scale by 1/scale^2.
  for (Light& light : model.lights) {
    if (light.type == LightType::kDirectional) continue;
    light.position = fit(light.position);
    light.range = static_cast<float>(light.range / scale);
    light.intensity = static_cast<float>(light.intensity / (scale * scale));
  }
  // Points and lines are in world space already: moved and scaled themselves.
  for (float3& p : model.points.positions)
    if (isFinite(p)) p = fit(p);
  for (float3& p : model.lines.points)
    if (isFinite(p)) p = fit(p);
  if (!model.graph.nodes.empty()) {
    refitGraph(model.graph, center, scale);
    return {};
  }
  for (float3& p : model.mesh.positions)
    if (isFinite(p)) p = fit(p);
  return {};
}

float3 threeQuarterDirection(float3 up) {
  // Z up: the front is -Y (f3d's, CAD's); X or Y up: the front is +Z. Right follows from both,
  // so +Y and +Z keep +X to the right and the other four axes stay right-handed.
  const float3 toward_viewer = up.z != 0.0f ? float3{0, -1, 0} : float3{0, 0, 1};
  const float3 right = cross(up, toward_viewer);
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

}  // namespace tessera::model
