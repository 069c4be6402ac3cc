#include <tessera/scene/graph.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <tessera/scene/clusters.h>
#include <tessera/scene/tangents.h>

namespace tessera {

namespace {

bool mirrors(const float4x4& m) {
  return determinant(upper3x3(m)) < 0.0f;
}

float3 transformPoint(const float4x4& m, float3 p) {
  return (m * float4{p, 1.0f}).xyz();
}

}  // namespace

Expected<void> SceneGraph::validate() const {
  const auto inRange = [](int32_t index, size_t size) {
    return index == kNoIndex || (index >= 0 && static_cast<size_t>(index) < size);
  };
  for (size_t i = 0; i < nodes.size(); ++i) {
    const GraphNode& node = nodes[i];
    const std::string what = "scene graph node " + std::to_string(i) +
                             (node.name.empty() ? "" : " ('" + node.name + "')");
    if (node.parent != kNoIndex && (node.parent < 0 || static_cast<size_t>(node.parent) >= i))
      return makeError(what + ": parent " + std::to_string(node.parent) +
                       " does not come before it (nodes are stored parents first)");
    if (!inRange(node.mesh, meshes.size()))
      return makeError(what + ": mesh " + std::to_string(node.mesh) + " of " +
                       std::to_string(meshes.size()));
    if (!inRange(node.camera, cameras.size()))
      return makeError(what + ": camera " + std::to_string(node.camera) + " of " +
                       std::to_string(cameras.size()));
  }
  for (size_t m = 0; m < meshes.size(); ++m)
    if (!meshes[m].mesh || meshes[m].materials.empty())
      return makeError("scene graph mesh " + std::to_string(m) + " has no mesh or no material");
  return {};
}

void SceneGraph::updateWorld() {
  world.resize(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    const GraphNode& node = nodes[i];
    const float4x4 local = node.local.matrix();
    world[i] = node.parent == kNoIndex ? local : world[static_cast<size_t>(node.parent)] * local;
  }
}

void SceneGraph::prepareMeshes() {
  if (world.size() != nodes.size()) updateWorld();
  // A normal map needs tangents: generated for meshes whose file gave none (OBJ; glTF's loader
  // makes its own).
  for (GraphMesh& m : meshes) {
    const Mesh& mesh = *m.mesh;
    const bool mapped = std::any_of(m.materials.begin(), m.materials.end(),
                                    [](const Material& material) { return bool(material.normal); });
    if (!mapped || !mesh.tangents.empty() || mesh.uvs.size() != mesh.vertexCount() ||
        mesh.normals.size() != mesh.vertexCount())
      continue;
    auto with_tangents = std::make_shared<Mesh>(mesh);
    // From the normal map's set (the first mapped material's: one set per mesh's tangents).
    const auto normal_mapped =
        std::find_if(m.materials.begin(), m.materials.end(),
                     [](const Material& material) { return bool(material.normal); });
    generateTangents(*with_tangents, normal_mapped->normal.sampler.texcoord);
    m.mesh = std::move(with_tangents);
    m.clusters = nullptr;
  }
  for (GraphMesh& m : meshes)
    if (!m.clusters) m.clusters = buildClusters(*m.mesh);
  for (size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].mesh == kNoIndex || !mirrors(world[i])) continue;
    GraphMesh& m = meshes[static_cast<size_t>(nodes[i].mesh)];
    if (m.mirrored) continue;
    auto mirrored = std::make_shared<const Mesh>(reversedWinding(*m.mesh));
    m.mirrored_clusters = buildClusters(*mirrored);
    m.mirrored = std::move(mirrored);
  }
}

size_t SceneGraph::instanceCount() const {
  return static_cast<size_t>(std::count_if(nodes.begin(), nodes.end(),
                                           [](const GraphNode& n) { return n.mesh != kNoIndex; }));
}

size_t SceneGraph::drawnTriangleCount() const {
  size_t count = 0;
  for (const GraphNode& node : nodes)
    if (node.mesh != kNoIndex)
      count += meshes[static_cast<size_t>(node.mesh)].mesh->triangleCount();
  return count;
}

Mesh SceneGraph::flatten() const {
  Mesh out;
  for (size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].mesh == kNoIndex) continue;
    const Mesh& mesh = *meshes[static_cast<size_t>(nodes[i].mesh)].mesh;
    const float4x4& m = world[i];
    const float3x3 normal_matrix = normalMatrix(m);
    const auto base = static_cast<uint32_t>(out.positions.size());
    for (const float3& p : mesh.positions) out.positions.push_back(transformPoint(m, p));
    const bool has_normals = mesh.normals.size() == mesh.vertexCount();
    for (size_t v = 0; has_normals && v < mesh.normals.size(); ++v)
      out.normals.push_back(safeNormalize(normal_matrix * mesh.normals[v]));
    const bool mirror = mirrors(m);
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      const uint32_t* idx = &mesh.indices[t * 3];
      out.indices.push_back(base + idx[0]);
      out.indices.push_back(base + idx[mirror ? 2 : 1]);
      out.indices.push_back(base + idx[mirror ? 1 : 2]);
      out.triangle_materials.push_back(
          mesh.triangle_materials.size() == mesh.triangleCount() ? mesh.triangle_materials[t] : 0);
    }
    // Attributes a mesh lacks are filled as the renderer reads them (white, (0, 0)).
    if (!mesh.uvs.empty() || !out.uvs.empty()) {
      out.uvs.resize(base, float2{0, 0});
      if (mesh.uvs.size() == mesh.vertexCount())
        out.uvs.insert(out.uvs.end(), mesh.uvs.begin(), mesh.uvs.end());
      out.uvs.resize(out.positions.size(), float2{0, 0});
    }
    // A mesh without set 1 gives set 0 in its place (what the renderer reads for it).
    if (!mesh.uvs1.empty() || !out.uvs1.empty()) {
      out.uvs1.resize(base, float2{0, 0});
      const std::vector<float2>& set1 = mesh.uvs1.empty() ? mesh.uvs : mesh.uvs1;
      if (set1.size() == mesh.vertexCount())
        out.uvs1.insert(out.uvs1.end(), set1.begin(), set1.end());
      out.uvs1.resize(out.positions.size(), float2{0, 0});
    }
    if (!mesh.tangents.empty() || !out.tangents.empty()) {
      // Directions: the model's upper 3x3; a mirror flips the bitangent's sign.
      out.tangents.resize(base, float4{1, 0, 0, 1});
      if (mesh.tangents.size() == mesh.vertexCount())
        for (const float4& t : mesh.tangents)
          out.tangents.push_back(
              float4(safeNormalize((m * float4(t.xyz(), 0.0f)).xyz()), mirror ? -t.w : t.w));
      out.tangents.resize(out.positions.size(), float4{1, 0, 0, 1});
    }
    if (!mesh.colors.empty() || !out.colors.empty()) {
      out.colors.resize(base, float4{1, 1, 1, 1});
      if (mesh.colors.size() == mesh.vertexCount())
        out.colors.insert(out.colors.end(), mesh.colors.begin(), mesh.colors.end());
      out.colors.resize(out.positions.size(), float4{1, 1, 1, 1});
    }
  }
  if (out.normals.size() != out.positions.size()) out.normals.clear();
  return out;
}

Bounds SceneGraph::bounds() const {
  Bounds b;
  for (size_t i = 0; i < nodes.size() && i < world.size(); ++i) {
    if (nodes[i].mesh == kNoIndex) continue;
    for (const float3& p : meshes[static_cast<size_t>(nodes[i].mesh)].mesh->positions) {
      if (!isFinite(p)) continue;
      const float3 w = transformPoint(world[i], p);
      if (isFinite(w)) b.add(w);
    }
  }
  return b;
}

Expected<Camera> SceneGraph::camera(size_t index, float aspect, const Bounds& scene_bounds) const {
  if (index >= cameras.size())
    return makeError("camera " + std::to_string(index) + " does not exist: the scene has " +
                     std::to_string(cameras.size()) + " camera" + (cameras.size() == 1 ? "" : "s"));
  const GraphCamera& c = cameras[index];
  if (!c.skipped.empty())
    return makeError("camera " + std::to_string(index) + " was skipped: it has " + c.skipped);
  for (size_t i = 0; i < nodes.size() && i < world.size(); ++i) {
    if (nodes[i].camera != static_cast<int32_t>(index)) continue;
    const float4x4& m = world[i];
    Camera camera;
    camera.position = transformPoint(m, {0, 0, 0});
    const float3 forward = normalize((m * float4{0, 0, -1, 0}).xyz());
    camera.target = camera.position + forward;
    camera.up = normalize((m * float4{0, 1, 0, 0}).xyz());
    camera.orthographic = c.orthographic;
    camera.ortho_half_height = c.ymag;
    camera.fov_y_degrees = c.yfov_radians * 180.0f / 3.14159265358979f;
    camera.near_z = c.znear;
    camera.far_z = c.zfar;
    if (!(c.zfar > c.znear)) {
      // Far left open: past the farthest corner of the scene along the view axis.
      float farthest = c.znear * 2.0f + 1e-6f;
      for (int k = 0; k < 8 && !scene_bounds.empty(); ++k) {
        const float3 corner{k & 1 ? scene_bounds.max.x : scene_bounds.min.x,
                            k & 2 ? scene_bounds.max.y : scene_bounds.min.y,
                            k & 4 ? scene_bounds.max.z : scene_bounds.min.z};
        farthest = std::max(farthest, dot(corner - camera.position, forward) * 1.01f);
      }
      camera.far_z = farthest;
    }
    (void)aspect;  // the image's aspect decides the width, as for a framing camera
    if (!(length(forward) > 0.0f) || !isFinite(camera.position))
      return makeError(std::string("camera ") + std::to_string(index) +
                       ": its node's transform does not give it a view direction");
    return camera;
  }
  return makeError("camera " + std::to_string(index) + " is held by no node of the scene");
}

void instantiate(const SceneGraph& graph, const Object& object, Scene& scene) {
  scene.objects.reserve(scene.objects.size() + graph.instanceCount());
  for (size_t i = 0; i < graph.nodes.size(); ++i) {
    const GraphNode& node = graph.nodes[i];
    if (node.mesh == kNoIndex) continue;
    const GraphMesh& m = graph.meshes[static_cast<size_t>(node.mesh)];
    Object instance = object;
    const bool mirror = mirrors(graph.world[i]) && m.mirrored;
    instance.mesh = mirror ? m.mirrored : m.mesh;
    instance.clusters = mirror ? m.mirrored_clusters : m.clusters;
    instance.materials = m.materials;
    instance.transform = Transform{};
    instance.transform.base = graph.world[i];
    scene.objects.push_back(std::move(instance));
  }
}

void updateInstances(const SceneGraph& graph, size_t first_object, Scene& scene) {
  size_t o = first_object;
  for (size_t i = 0; i < graph.nodes.size() && o < scene.objects.size(); ++i) {
    const GraphNode& node = graph.nodes[i];
    if (node.mesh == kNoIndex) continue;
    const GraphMesh& m = graph.meshes[static_cast<size_t>(node.mesh)];
    Object& instance = scene.objects[o++];
    const bool mirror = mirrors(graph.world[i]) && m.mirrored;
    instance.mesh = mirror ? m.mirrored : m.mesh;
    instance.clusters = mirror ? m.mirrored_clusters : m.clusters;
    instance.transform.base = graph.world[i];
  }
}

}  // namespace tessera
