// Frustum and cluster culling before the vertex stage never changes the image: randomized
// cameras over a field of instances, every image (colour and triangle ids) compared byte for byte
// with culling off, and the counters showing that culling did happen.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include <tessera/render/cpu_renderer.h>
#include <tessera/render/frame.h>
#include <tessera/scene/clusters.h>
#include <tessera/scene/graph.h>
#include <tessera/scene/primitives.h>

namespace tessera {
namespace {

// 60 instances of a 17,664-triangle sphere scattered in a 20-unit box, some scaled
// non-uniformly, some mirrored, half culling back faces. 384 segments: a cluster (256 triangles
// in the sphere's ring order) spans a third of a ring, so its normals fit a cone (a cluster of a
// coarser sphere wraps the whole ring and has none).
Scene instanceField(std::mt19937& rng) {
  SceneGraph graph;
  GraphMesh sphere;
  sphere.mesh = std::make_shared<const Mesh>(makeUvSphere(384, 24));
  sphere.materials = {Material{}};
  graph.meshes.push_back(sphere);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int i = 0; i < 60; ++i) {
    GraphNode node;
    node.mesh = 0;
    node.local.translation = {unit(rng) * 10, unit(rng) * 10, unit(rng) * 10};
    node.local.rotation =
        quat::fromAxisAngle(normalize(float3{unit(rng), 1, unit(rng)}), unit(rng) * 3);
    node.local.scale = {1 + 0.5f * unit(rng), 1, i % 7 == 0 ? -1.0f : 1.0f};
    graph.nodes.push_back(node);
  }
  graph.updateWorld();
  graph.prepareMeshes();
  Scene scene;
  Object style;
  style.shading = Shading::kPhong;
  instantiate(graph, style, scene);
  for (size_t i = 0; i < scene.objects.size(); ++i)
    scene.objects[i].cull = i % 2 ? CullMode::kBack : (i % 4 ? CullMode::kNone : CullMode::kFront);
  scene.lights.push_back({normalize(float3{-1, -2, -1}), float3(0.8f)});
  return scene;
}

struct Totals {
  size_t instances = 0, clusters = 0, facing = 0;
};

void expectSameWithAndWithoutCulling(const Scene& scene, RenderOptions options, Totals& totals,
                                     const std::string& what) {
  CpuRenderer renderer(2);
  Frame culled, full;
  options.frustum_cull = true;
  renderer.render(scene, options, culled);
  const PipelineStats stats = renderer.lastStats();
  options.frustum_cull = false;
  renderer.render(scene, options, full);
  EXPECT_EQ(renderer.lastStats().instances_culled, 0u);
  ASSERT_EQ(culled.color.size(), full.color.size());
  EXPECT_TRUE(culled.color == full.color) << what;
  EXPECT_TRUE(culled.triangle_id == full.triangle_id) << what;
  EXPECT_TRUE(culled.depth == full.depth) << what;
  totals.instances += stats.instances_culled;
  totals.clusters += stats.clusters_culled;
  totals.facing += stats.clusters_facing;
}

TEST(Culling, RandomCamerasGiveTheSameImageWithCullingOff) {
  std::mt19937 rng(18);
  const Scene field = instanceField(rng);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  Totals totals;
  for (int i = 0; i < 24; ++i) {
    Scene scene = field;
    Camera& c = scene.camera;
    c.position = {unit(rng) * 14, unit(rng) * 14, unit(rng) * 14};
    c.target = {unit(rng) * 4, unit(rng) * 4, unit(rng) * 4};
    c.fov_y_degrees = 30 + 40 * std::fabs(unit(rng));
    c.near_z = 0.05f + std::fabs(unit(rng));
    c.far_z = 10 + 20 * std::fabs(unit(rng));
    c.orthographic = i % 5 == 4;
    c.ortho_half_height = 4 + 3 * unit(rng);
    RenderOptions options;
    options.width = 160;
    options.height = 120;
    options.msaa = i % 3 == 2 ? 4 : 1;
    options.jitter = {0.25f * unit(rng), 0.25f * unit(rng)};
    expectSameWithAndWithoutCulling(scene, options, totals, "camera " + std::to_string(i));
  }
  // The test is only worth something if culling took place at every level.
  EXPECT_GT(totals.instances, 0u);
  EXPECT_GT(totals.clusters, 0u);
  EXPECT_GT(totals.facing, 0u);
}

TEST(Culling, ClusterConeHoldsEveryFaceNormal) {
  const Mesh sphere = makeUvSphere(40, 29);
  const std::shared_ptr<const MeshClusters> clusters = buildClusters(sphere);
  ASSERT_TRUE(clusters->describes(sphere));
  size_t covered = 0;
  for (const MeshCluster& c : clusters->clusters) {
    for (uint32_t t = c.first_triangle; t < c.first_triangle + c.triangle_count; ++t) {
      const float3 a = sphere.positions[sphere.indices[t * 3]],
                   b = sphere.positions[sphere.indices[t * 3 + 1]],
                   d = sphere.positions[sphere.indices[t * 3 + 2]];
      const float3 n = normalize(cross(b - a, d - a));
      if (c.cone_cos > 0) {
        EXPECT_GE(dot(n, c.cone_axis), c.cone_cos - 1e-5f);
      }
      for (float3 p : {a, b, d}) {
        EXPECT_TRUE(p.x >= c.bounds.min.x && p.y >= c.bounds.min.y && p.z >= c.bounds.min.z);
        EXPECT_TRUE(p.x <= c.bounds.max.x && p.y <= c.bounds.max.y && p.z <= c.bounds.max.z);
      }
      ++covered;
    }
  }
  EXPECT_EQ(covered, sphere.triangleCount());
}

// 256 triangles (one cluster) in z = 0 facing -z, seen from z = +5: a back-facing cluster. With
// well-shaped triangles it is rejected whole; with one sliver among them (an altitude of 1e-6,
// which snapping to the 1/256-pixel grid could turn) it is drawn, and culling still leaves the
// image as it was.
Scene backFacingGrid(bool with_sliver) {
  Mesh mesh;
  for (int y = 0; y <= 8; ++y)
    for (int x = 0; x <= 16; ++x)
      mesh.positions.push_back({-1.0f + x / 8.0f, -1.0f + y / 4.0f, 0.0f});
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 16; ++x) {
      const uint32_t a = y * 17 + x, b = a + 1, c = a + 17, d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});  // clockwise from +z
    }
  if (with_sliver) {
    mesh.positions.push_back({1.0f, -1.0f + 1e-6f, 0.0f});
    const uint32_t sliver = static_cast<uint32_t>(mesh.positions.size() - 1);
    mesh.indices[0] = 0, mesh.indices[1] = sliver, mesh.indices[2] = 16;
  }
  Scene scene;
  Object object;
  object.mesh = std::make_shared<const Mesh>(std::move(mesh));
  object.clusters = buildClusters(*object.mesh);
  object.cull = CullMode::kBack;
  object.shading = Shading::kUnlit;
  scene.objects.push_back(object);
  scene.camera.position = {0.1f, 0.2f, 5};
  scene.camera.target = {0, 0, 0};
  return scene;
}

TEST(Culling, BackFacingClusterIsRejectedOnlyWhenSnappingCannotTurnATriangle) {
  for (bool with_sliver : {false, true}) {
    const Scene scene = backFacingGrid(with_sliver);
    ASSERT_EQ(scene.objects[0].clusters->clusters.size(), 1u);
    RenderOptions options;
    options.width = 200;
    options.height = 150;
    Totals totals;
    expectSameWithAndWithoutCulling(scene, options, totals, with_sliver ? "sliver" : "fat");
    EXPECT_EQ(totals.facing, with_sliver ? 0u : 1u) << (with_sliver ? "sliver" : "fat");
  }
}

TEST(Culling, AnObjectBehindTheCameraIsSkippedWhole) {
  std::mt19937 rng(3);
  Scene scene = instanceField(rng);
  scene.camera.position = {0, 0, 40};
  scene.camera.target = {0, 0, 60};  // looking away from every instance
  CpuRenderer renderer(1);
  RenderOptions options;
  Frame frame;
  renderer.render(scene, options, frame);
  EXPECT_EQ(renderer.lastStats().instances_culled, scene.objects.size());
  EXPECT_EQ(renderer.lastStats().triangles_setup, 0u);
  EXPECT_EQ(renderer.lastStats().triangles_skipped, scene.triangleCount());
}

// Culling keeps each object's triangle and vertex bases from the frame before and mends only
// those that changed: a renderer that drew other scenes first gives the image and ids a fresh one
// gives, whether the next scene's meshes, their order or the object count changed.
TEST(Culling, ARendererThatDrewOtherScenesDrawsTheNextAsAFreshOne) {
  std::mt19937 rng(7);
  Scene field = instanceField(rng);
  field.camera.position = {0, 3, 18};  // some instances in view, some behind or beside it
  field.camera.target = {0, 0, 0};
  field.camera.far_z = 100;
  Scene mixed = field;  // the same objects, every third's mesh a cube: other bases after it
  const auto cube = std::make_shared<const Mesh>(makeCube());
  for (size_t i = 0; i < mixed.objects.size(); i += 3) {
    mixed.objects[i].mesh = cube;
    mixed.objects[i].clusters = nullptr;
  }
  Scene fewer = mixed;
  fewer.objects.resize(fewer.objects.size() / 2);
  RenderOptions options;
  options.width = 160;
  options.height = 120;
  options.ids = true;
  options.depth = true;
  CpuRenderer reused(2);
  Frame frame;
  int drawn = 0;
  for (const Scene* scene : {&field, &mixed, &fewer, &mixed, &field}) {
    reused.render(*scene, options, frame);
    CpuRenderer fresh(2);
    Frame expected;
    fresh.render(*scene, options, expected);
    EXPECT_TRUE(frame.color == expected.color) << "scene " << drawn;
    EXPECT_TRUE(frame.triangle_id == expected.triangle_id) << "scene " << drawn;
    EXPECT_TRUE(frame.depth == expected.depth) << "scene " << drawn;
    ++drawn;
  }
  // Worth something only if the scenes differ where the bases do.
  Frame a, b;
  CpuRenderer(1).render(field, options, a);
  CpuRenderer(1).render(mixed, options, b);
  EXPECT_FALSE(a.triangle_id == b.triangle_id);
}

// An object culled whole has no triangle to draw, but its axes may still cross the view: the
// line pass then reads its matrices, which must be this frame's (culling skips them for objects
// outside the frustum when no line is drawn).
TEST(Culling, TheAxesOfAnObjectCulledWholeAreDrawnWhereItIsNow) {
  SceneGraph graph;
  GraphMesh sphere;
  sphere.mesh = std::make_shared<const Mesh>(makeUvSphere(32, 16));
  sphere.materials = {Material{}};
  graph.meshes.push_back(sphere);
  GraphNode node;
  node.mesh = 0;
  graph.nodes.push_back(node);
  graph.updateWorld();
  graph.prepareMeshes();
  Scene scene;
  instantiate(graph, Object{}, scene);
  ASSERT_EQ(scene.objects.size(), 1u);
  scene.objects[0].show_axes = true;
  scene.objects[0].axes_length = 16;
  scene.camera.position = {0, 1, 10};
  scene.camera.target = {0, 0, 0};
  RenderOptions options;
  options.width = 160;
  options.height = 120;
  CpuRenderer reused(2);
  Frame frame;
  reused.render(scene, options, frame);  // in view: its matrices are written
  // Far to the right, turned so that its X axis runs back across the view.
  Transform& t = scene.objects[0].transform;
  t.translation = {9, 0, 0};
  t.rotation = quat::fromAxisAngle({0, 1, 0}, 3.14159265f);
  reused.render(scene, options, frame);
  EXPECT_EQ(reused.lastStats().instances_culled, 1u);
  Frame expected;
  options.frustum_cull = false;
  CpuRenderer(1).render(scene, options, expected);
  EXPECT_TRUE(frame.color == expected.color);
  // Worth something only if the axes show.
  Frame bare;
  scene.objects[0].show_axes = false;
  CpuRenderer(1).render(scene, options, bare);
  EXPECT_FALSE(bare.color == expected.color);
}

}  // namespace
}  // namespace tessera
