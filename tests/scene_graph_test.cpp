// The scene graph: world transforms in one pass, instancing (one mesh, many transforms), and
// instances rendering exactly as the same triangles flattened by hand.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <vector>

#include <tessera/render/cpu_renderer.h>
#include <tessera/render/frame.h>
#include <tessera/scene/clusters.h>
#include <tessera/scene/graph.h>
#include <tessera/scene/primitives.h>

namespace tessera {
namespace {

// A camera whose matrices have exact, dyadic entries (90 degrees, near 1, far 9, eye at z = 4):
// with dyadic vertices and transforms every clip coordinate is exact, whichever way the
// products are grouped, so the instanced and hand-flattened scenes must match bit for bit.
Camera exactCamera() {
  Camera camera;
  float4x4 view;
  view(2, 3) = -4.0f;
  float4x4 projection;
  projection(2, 2) = -1.25f;
  projection(2, 3) = -2.25f;
  projection(3, 2) = -1.0f;
  projection(3, 3) = 0.0f;
  camera.view_override = view;
  camera.projection_override = projection;
  return camera;
}

// x -> y, y -> -x: a quarter turn about Z with exact entries.
float4x4 quarterTurnZ() {
  float4x4 m;
  m(0, 0) = 0, m(0, 1) = -1, m(1, 0) = 1, m(1, 1) = 0;
  return m;
}

struct ThreeLevels {
  SceneGraph graph;
  std::shared_ptr<const Mesh> cube = std::make_shared<const Mesh>(makeCube());
};

// root (mesh): scale (2, 1, 1), translate (0.25, 0, 0)
//   child (mesh): a quarter turn about Z (a matrix), translate (0, 0.5, 0)
//     grandchild (mesh): scale (-1, 0.5, 1) (mirrors), translate (1.25, 0, -0.5)
// The child stands above the root and the grandchild above the child (world y in [1.25, 2.25]),
// so that every instance shows.
ThreeLevels threeLevels() {
  ThreeLevels t;
  GraphMesh mesh;
  mesh.mesh = t.cube;
  mesh.materials = {Material{}};
  t.graph.meshes.push_back(mesh);
  GraphNode root, child, grandchild;
  root.mesh = child.mesh = grandchild.mesh = 0;
  root.local.translation = {0.25f, 0, 0};
  root.local.scale = {2, 1, 1};
  child.parent = 0;
  child.local.base = quarterTurnZ();
  child.local.translation = {0, 0.5f, 0};
  grandchild.parent = 1;
  grandchild.local.scale = {-1, 0.5f, 1};
  grandchild.local.translation = {1.25f, 0, -0.5f};
  t.graph.nodes = {root, child, grandchild};
  return t;
}

// The same three instances written out by hand: world positions, mirrored winding reversed.
Mesh flattenedByHand(const Mesh& cube) {
  auto rootOf = [](float3 p) { return float3{2 * p.x + 0.25f, p.y, p.z}; };
  auto childOf = [&](float3 p) { return rootOf(float3{-p.y, p.x + 0.5f, p.z}); };
  auto grandchildOf = [&](float3 p) {
    return childOf(float3{-p.x + 1.25f, 0.5f * p.y, p.z - 0.5f});
  };
  Mesh out;
  auto add = [&](auto place, bool mirrored) {
    const auto base = static_cast<uint32_t>(out.positions.size());
    for (const float3& p : cube.positions) out.positions.push_back(place(p));
    for (size_t t = 0; t < cube.triangleCount(); ++t) {
      const uint32_t* idx = &cube.indices[t * 3];
      out.indices.insert(out.indices.end(), {base + idx[0], base + idx[mirrored ? 2 : 1],
                                             base + idx[mirrored ? 1 : 2]});
    }
  };
  add(rootOf, false);
  add(childOf, false);
  add(grandchildOf, true);
  return out;
}

Frame render(const Scene& scene) {
  CpuRenderer renderer(2);
  RenderOptions options;
  options.width = 96;
  options.height = 96;
  Frame frame;
  renderer.render(scene, options, frame);
  return frame;
}

TEST(SceneGraph, WorldTransformsComposeParentsFirst) {
  ThreeLevels t = threeLevels();
  ASSERT_TRUE(t.graph.validate());
  t.graph.updateWorld();
  // The grandchild's origin: (1.25, 0, -0.5) -> child (0, 1.75, -0.5) -> root (0.25, 1.75, -0.5).
  const float4 origin = t.graph.world[2] * float4{0, 0, 0, 1};
  EXPECT_EQ(origin.x, 0.25f);
  EXPECT_EQ(origin.y, 1.75f);
  EXPECT_EQ(origin.z, -0.5f);
  EXPECT_LT(determinant(upper3x3(t.graph.world[2])), 0.0f);
}

TEST(SceneGraph, ThreeLevelHierarchyRendersLikeTheTrianglesFlattenedByHand) {
  ThreeLevels t = threeLevels();
  t.graph.updateWorld();
  t.graph.prepareMeshes();
  for (CullMode cull : {CullMode::kBack, CullMode::kNone}) {
    Object style;
    style.shading = Shading::kUnlit;
    style.cull = cull;
    Scene instanced;
    instanced.camera = exactCamera();
    instantiate(t.graph, style, instanced);
    ASSERT_EQ(instanced.objects.size(), 3u);
    Scene flat = instanced;
    flat.objects.clear();
    Object one = style;
    one.mesh = std::make_shared<const Mesh>(flattenedByHand(*t.cube));
    flat.objects.push_back(one);
    const Frame a = render(instanced), b = render(flat);
    EXPECT_EQ(a.triangle_id, b.triangle_id);
    EXPECT_EQ(a.color, b.color);
    // Every instance shows: ids from all three (12 triangles each).
    bool seen[3] = {false, false, false};
    for (uint32_t id : a.triangle_id)
      if (id != kNoTriangle && id <= 36) seen[(id - 1) / 12] = true;
    EXPECT_TRUE(seen[0] && seen[1] && seen[2]);
  }
  // The graph's own flattening is the same triangles in the same order.
  const Mesh flattened = t.graph.flatten();
  const Mesh by_hand = flattenedByHand(*t.cube);
  EXPECT_EQ(flattened.indices, by_hand.indices);
  ASSERT_EQ(flattened.positions.size(), by_hand.positions.size());
  for (size_t v = 0; v < by_hand.positions.size(); ++v)
    EXPECT_TRUE(flattened.positions[v] == by_hand.positions[v]) << "vertex " << v;
}

// Bytes a vector holds on the heap.
template <typename T>
size_t heapBytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

size_t meshBytes(const Mesh& m) {
  return heapBytes(m.positions) + heapBytes(m.normals) + heapBytes(m.uvs) + heapBytes(m.colors) +
         heapBytes(m.indices) + heapBytes(m.triangle_materials);
}

TEST(SceneGraph, TenThousandInstancesCostOneMeshPlusTheirTransforms) {
  SceneGraph graph;
  GraphMesh mesh;
  mesh.mesh = std::make_shared<const Mesh>(makeUvSphere(25, 21));  // 1,000 triangles
  ASSERT_EQ(mesh.mesh->triangleCount(), 1000u);
  mesh.materials = {Material{}, Material{}, Material{}};
  graph.meshes.push_back(mesh);
  constexpr size_t kInstances = 10000;
  graph.nodes.resize(kInstances);
  for (size_t i = 0; i < kInstances; ++i) {
    graph.nodes[i].mesh = 0;
    graph.nodes[i].local.translation = {float(i % 100), float(i / 100), 0};
  }
  graph.updateWorld();
  graph.prepareMeshes();
  Scene scene;
  instantiate(graph, Object{}, scene);
  ASSERT_EQ(scene.objects.size(), kInstances);
  // One mesh, one material list and one set of clusters, shared by every instance.
  for (const Object& o : scene.objects) {
    ASSERT_EQ(o.mesh.get(), mesh.mesh.get());
    ASSERT_TRUE(o.materials.sharesWith(graph.meshes[0].materials));
    ASSERT_EQ(o.clusters.get(), graph.meshes[0].clusters.get());
  }
  EXPECT_EQ(scene.triangleCount(), kInstances * 1000);
  // What the instances hold of their own: the objects, the nodes and their world matrices.
  const size_t per_instance = sizeof(Object) + sizeof(GraphNode) + sizeof(float4x4);
  const size_t shared =
      meshBytes(*mesh.mesh) + graph.meshes[0].clusters->clusters.capacity() * sizeof(MeshCluster);
  const size_t total =
      heapBytes(scene.objects) + heapBytes(graph.nodes) + heapBytes(graph.world) + shared;
  // Flattened, the same scene holds 10,000 meshes: compare with the memory of one mesh plus a
  // transform's worth per instance.
  EXPECT_LE(total, meshBytes(*mesh.mesh) * 2 + kInstances * per_instance);
  EXPECT_LT(total * 20, meshBytes(*mesh.mesh) * kInstances);
  EXPECT_LE(per_instance, 512u);
}

TEST(SceneGraph, ValidateNamesAParentThatDoesNotComeFirst) {
  SceneGraph graph;
  graph.nodes.resize(2);
  graph.nodes[0].parent = 1;
  graph.nodes[0].name = "loop";
  Expected<void> ok = graph.validate();
  ASSERT_FALSE(ok);
  EXPECT_NE(ok.error().message.find("node 0 ('loop')"), std::string::npos) << ok.error().message;
  graph.nodes[0].parent = 0;  // its own parent
  EXPECT_FALSE(graph.validate());
}

TEST(SceneGraph, DeepHierarchyTakesOnePassWithoutRecursion) {
  SceneGraph graph;
  constexpr size_t kDepth = 1000000;
  graph.nodes.resize(kDepth);
  for (size_t i = 1; i < kDepth; ++i) {
    graph.nodes[i].parent = static_cast<int32_t>(i - 1);
    graph.nodes[i].local.translation = {0, 0, 1.0f / 1024};
  }
  ASSERT_TRUE(graph.validate());
  graph.updateWorld();
  EXPECT_FLOAT_EQ((graph.world.back() * float4{0, 0, 0, 1}).z, float(kDepth - 1) / 1024);
}

TEST(SceneGraph, CameraSeesFromItsNodeAndCountsInItsError) {
  SceneGraph graph;
  GraphCamera camera;
  camera.yfov_radians = 0.5f;
  camera.znear = 0.25f;
  camera.zfar = 50.0f;
  graph.cameras.push_back(camera);
  GraphNode holder;
  holder.camera = 0;
  holder.local.translation = {1, 2, 3};
  holder.local.base = quarterTurnZ();  // looks down -Z still; up is now -X
  graph.nodes.push_back(holder);
  graph.updateWorld();
  Expected<Camera> c = graph.camera(0, 1.5f, Bounds{});
  ASSERT_TRUE(c);
  EXPECT_TRUE(c->position == (float3{1, 2, 3}));
  EXPECT_TRUE(c->target == (float3{1, 2, 2}));
  EXPECT_TRUE(c->up == (float3{-1, 0, 0}));
  EXPECT_FLOAT_EQ(c->fov_y_degrees, 0.5f * 180.0f / 3.14159265358979f);
  EXPECT_EQ(c->near_z, 0.25f);
  EXPECT_EQ(c->far_z, 50.0f);
  Expected<Camera> missing = graph.camera(3, 1.0f, Bounds{});
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("the scene has 1 camera"), std::string::npos);
}

TEST(SceneGraph, OrthographicCameraProjectsParallel) {
  Camera camera;
  camera.orthographic = true;
  camera.ortho_half_height = 2.0f;
  camera.near_z = 1.0f;
  camera.far_z = 3.0f;
  const float4x4 p = camera.projection(2.0f);
  // (4, 2) at the near plane is the top-right corner; w stays 1; far maps to z = 1.
  const float4 corner = p * float4{4, 2, -1, 1};
  EXPECT_FLOAT_EQ(corner.x, 1.0f);
  EXPECT_FLOAT_EQ(corner.y, 1.0f);
  EXPECT_FLOAT_EQ(corner.z, -1.0f);
  EXPECT_FLOAT_EQ(corner.w, 1.0f);
  EXPECT_FLOAT_EQ((p * float4{0, 0, -3, 1}).z, 1.0f);
}

}  // namespace
}  // namespace tessera
