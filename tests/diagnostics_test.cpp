// The frame diagnostics (RenderOptions::diagnostics): overdraw, occupancy, material, density,
// tile occlusion and edges, and the pipeline counters, on scenes small enough to count by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <tessera/render/cpu_renderer.h>
#include <tessera/render/diagnostics.h>
#include <tessera/scene/primitives.h>
#include <tessera/scene/scene.h>

#include "diagnostics_scenes.h"

using namespace tessera;

namespace {

using namespace tessera::diagnostics_test;

Frame render(const Scene& scene, int width, int height, int workers = 1, int msaa = 1,
             bool diagnostics = true) {
  CpuRenderer renderer(workers);
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.msaa = msaa;
  options.diagnostics = diagnostics;
  Frame frame;
  renderer.render(scene, options, frame);
  return frame;
}

}  // namespace

TEST(Diagnostics, OverdrawOfStackedFullScreenQuadsIsTheirCount) {
  constexpr int kQuads = 5;
  // 96x96: the quads' diagonals pass through pixel centres, where the top-left rule decides.
  for (const auto& [kW, kH] : {std::pair{150, 100}, std::pair{96, 96}}) {
    // Back to front and front to back: tests count whether they pass or not.
    const Scene scene = stackedQuads(kQuads, kW, kH);
    for (int msaa : {1, 4}) {
      const Frame f = render(scene, kW, kH, 2, msaa);
      ASSERT_TRUE(f.diagnostics.valid);
      ASSERT_EQ(f.diagnostics.overdraw.size(), f.pixelCount());
      for (size_t p = 0; p < f.pixelCount(); ++p)
        ASSERT_EQ(f.diagnostics.overdraw[p], static_cast<uint32_t>(kQuads)) << "pixel " << p;
      const PipelineCounters& c = f.diagnostics.counters;
      EXPECT_EQ(c.pixels_tested, f.pixelCount() * kQuads);
      // Quad 0 (z -0.5) is the nearest: every later test fails.
      EXPECT_EQ(c.pixels_passed, f.pixelCount());
      EXPECT_EQ(c.pixels_shaded, f.pixelCount());
      EXPECT_EQ(c.tiles_full, c.tiles);
      EXPECT_EQ(c.tiles_empty, 0u);
      expectCountersAddUp(c);
    }
  }
}

TEST(Diagnostics, OccupancyIsTheTrianglesBinnedIntoEachTile) {
  const Scene scene = occupancyScene();  // 3 x 2 tiles
  const Frame f = render(scene, kOccupancyWidth, kOccupancyHeight);
  const FrameDiagnostics& d = f.diagnostics;
  expectOccupancySceneCounts(d);
}

TEST(Diagnostics, TileOcclusionOfAHalfCoveredTile) {
  constexpr int kW = 128, kH = 64;
  Scene scene = clipSpaceScene();
  Mesh m;
  addRect(m, 0, 0, 64, 32, 0.0f, kW, kH);     // tile 0: the top 32 of 64 rows, window z 0.5
  addRect(m, 64, 0, 128, 64, -0.5f, kW, kH);  // tile 1: all of it, window z 0.25
  scene.objects.push_back(objectOf(m));
  const Frame f = render(scene, kW, kH);
  const FrameDiagnostics& d = f.diagnostics;
  EXPECT_NEAR(d.tile_covered[0], 0.5f, 1.0f / 64);  // within one pixel row
  EXPECT_FLOAT_EQ(d.tile_depth_min[0], 0.5f);
  EXPECT_FLOAT_EQ(d.tile_depth_max[0], 0.5f);
  EXPECT_EQ(d.tile_covered[1], 1.0f);
  EXPECT_FLOAT_EQ(d.tile_depth_min[1], 0.25f);
  EXPECT_EQ(d.counters.tiles_full, 1u);
  // Edges: tile 0's 64 columns at the coverage's bottom; tile 0's row pairs into tile 1 across
  // x = 63/64: the 32 uncovered rows against tile 1, and the 32 covered at depths 0.5 and 0.25.
  EXPECT_EQ(d.tile_edges[0], 64u + 64u);
  EXPECT_EQ(d.tile_edges[1], 0u);
}

TEST(Diagnostics, TileEdgesIgnoreSmallDepthSteps) {
  constexpr int kW = 64, kH = 64;
  Scene scene = clipSpaceScene();
  Mesh m;
  addRect(m, 0, 0, 32, 64, 0.0f, kW, kH);
  addRect(m, 32, 0, 64, 64, 0.01f, kW, kH);  // window z steps by 0.005: no edge
  scene.objects.push_back(objectOf(m));
  EXPECT_EQ(render(scene, kW, kH).diagnostics.tile_edges[0], 0u);
  Scene stepped = clipSpaceScene();
  Mesh s;
  addRect(s, 0, 0, 32, 64, 0.0f, kW, kH);
  addRect(s, 32, 0, 64, 64, 0.1f, kW, kH);  // by 0.05: one edge per row
  stepped.objects.push_back(objectOf(s));
  EXPECT_EQ(render(stepped, kW, kH).diagnostics.tile_edges[0], 64u);
}

TEST(Diagnostics, MaterialAndDensityOfTheVisibleTriangle) {
  constexpr int kW = 64, kH = 64;
  Scene scene = clipSpaceScene();
  Mesh m;
  addRect(m, 0, 0, 32, 64, 0.0f, kW, kH, 0);
  addRect(m, 32, 0, 64, 32, 0.0f, kW, kH, 2);
  Object o = objectOf(m);
  o.materials.resize(3);
  o.materials[2].density = 2.5f;
  scene.objects.push_back(o);
  const Frame f = render(scene, kW, kH);
  const FrameDiagnostics& d = f.diagnostics;
  EXPECT_EQ(d.material[10 * kW + 5], 1u);
  EXPECT_EQ(d.density[10 * kW + 5], 1.0f);  // the default
  EXPECT_EQ(d.material[10 * kW + 40], 3u);
  EXPECT_EQ(d.density[10 * kW + 40], 2.5f);
  EXPECT_EQ(d.material[50 * kW + 40], 0u);
  EXPECT_EQ(d.density[50 * kW + 40], 0.0f);
}

TEST(Diagnostics, CountersAddUpWithEveryCullReasonAndClipping) {
  constexpr int kW = 64, kH = 64;
  const Mesh m = cullReasonMesh();
  // One at a time (a group holding an index past the mesh goes triangle by triangle), and in
  // groups of eight through the cull kernel (every index valid): 7 x 8 triangles.
  Mesh single = m, grouped = m;
  single.indices.insert(single.indices.end(), {0, 1, 99});
  for (int i = 1; i < 8; ++i)
    grouped.indices.insert(grouped.indices.end(), m.indices.begin(), m.indices.end());
  for (const Mesh* mesh : {&single, &grouped}) {
    Scene scene = clipSpaceScene();
    scene.objects.push_back(objectOf(*mesh, CullMode::kBack));
    const uint64_t n = mesh == &single ? 1 : 8;
    const PipelineCounters c = render(scene, kW, kH).diagnostics.counters;
    EXPECT_EQ(c.triangles_in, mesh->triangleCount());
    EXPECT_EQ(c.culled.invalid, mesh == &single ? 1u : 0u);
    EXPECT_EQ(c.culled.non_finite, n);
    EXPECT_EQ(c.culled.frustum, n);
    EXPECT_EQ(c.culled.degenerate, n);
    EXPECT_EQ(c.culled.facing, n);
    EXPECT_EQ(c.culled.no_pixel, n);
    EXPECT_EQ(c.culled.clipped_away, 0u);
    EXPECT_EQ(c.triangles_clipped, n);
    EXPECT_EQ(c.clip_splits, n);  // the near plane cuts a corner off: a quad, two pieces
    EXPECT_EQ(c.triangles_setup, 3 * n);
    expectCountersAddUp(c);
  }
}

TEST(Diagnostics, TrianglesMissingTheFewCentresOfTheirBoxAreCulledForNoPixel) {
  // Triangles about a pixel in size (fewCentreScene): at one sample those whose box holds at most
  // two centres a side and covers none are dropped in setup (missesEveryCentre: the cull kernel's
  // groups of eight and the triangles after the last group alike), and nothing they would have
  // drawn is missing.
  constexpr int kW = 100, kH = 64;  // 33 x 21 triangles: 86 groups of eight and 5 more
  const FewCentres few = fewCentreScene(kW, kH);
  const size_t n = few.dropped.size();
  ASSERT_NE(n % 8, 0u);
  const auto dropped =
      static_cast<uint64_t>(std::count(few.dropped.begin(), few.dropped.end(), true));
  ASSERT_GT(dropped, 50u);
  ASSERT_GT(n - dropped, 300u);
  const Frame one = render(few.scene, kW, kH);
  uint64_t covered = 0;
  for (size_t i = 0; i < n; ++i) {
    const auto [cx, cy] = few.pixel[i];
    for (int y = cy - 1; y <= cy + 1; ++y)
      for (int x = cx - 1; x <= cx + 1; ++x) {
        const bool in =
            std::count(few.covered[i].begin(), few.covered[i].end(), std::pair{x, y}) > 0;
        covered += in;
        EXPECT_EQ(one.idAt(x, y), in ? static_cast<uint32_t>(i + 1) : kNoTriangle)
            << "triangle " << i << " at " << x << "," << y;
      }
  }
  const PipelineCounters& c = one.diagnostics.counters;
  EXPECT_EQ(c.triangles_setup, n - dropped);
  EXPECT_EQ(c.culled.no_pixel, dropped);
  EXPECT_EQ(c.pixels_passed, covered);
  expectCountersAddUp(c);
  // With MSAA a box reaches the samples about its centres and nothing is dropped for missing
  // them: more triangles are set up, and the centres' ids are the same.
  const Frame four = render(few.scene, kW, kH, 1, 4);
  EXPECT_GT(four.diagnostics.counters.triangles_setup, n - dropped);
  EXPECT_EQ(four.triangle_id, one.triangle_id);
}

TEST(Diagnostics, TheSameForOneAndThreeWorkers) {
  Scene scene;
  Object sphere = objectOf(makeUvSphere(48, 32));
  scene.objects.push_back(sphere);
  scene.objects.push_back(sphere);
  scene.objects[1].transform.translation = {0.6f, 0.2f, -0.5f};
  scene.camera.position = {0, 0, 3};
  scene.camera.target = {0, 0, 0};
  const Frame one = render(scene, 300, 200, 1, 4);
  const Frame three = render(scene, 300, 200, 3, 4);
  const FrameDiagnostics &a = one.diagnostics, &b = three.diagnostics;
  EXPECT_EQ(a.overdraw, b.overdraw);
  EXPECT_EQ(a.material, b.material);
  EXPECT_EQ(a.density, b.density);
  EXPECT_EQ(a.tile_triangles, b.tile_triangles);
  EXPECT_EQ(a.tile_covered, b.tile_covered);
  EXPECT_EQ(a.tile_edges, b.tile_edges);
  EXPECT_EQ(a.counters.pixels_tested, b.counters.pixels_tested);
  EXPECT_EQ(a.counters.pixels_passed, b.counters.pixels_passed);
  EXPECT_EQ(a.counters.triangles_binned, b.counters.triangles_binned);
  EXPECT_EQ(a.counters.culled.facing + a.counters.culled.no_pixel,
            b.counters.culled.facing + b.counters.culled.no_pixel);
  EXPECT_GT(a.counters.pixels_tested, a.counters.pixels_passed);  // the spheres overlap
  // The replayed coverage is the raster kernel's: a pixel showing a triangle was tested at
  // least once, a background pixel never.
  for (size_t p = 0; p < one.pixelCount(); ++p)
    ASSERT_EQ(a.overdraw[p] > 0, one.triangle_id[p] != kNoTriangle) << "pixel " << p;
  expectCountersAddUp(a.counters);
}

TEST(Diagnostics, OffByDefaultAndTheImageDoesNotChange) {
  Scene scene;
  scene.objects.push_back(objectOf(makeUvSphere(24, 16)));
  scene.camera.position = {0, 0, 3};
  scene.camera.target = {0, 0, 0};
  const Frame plain = render(scene, 130, 70, 2, 1, false);
  EXPECT_FALSE(plain.diagnostics.valid);
  EXPECT_TRUE(plain.diagnostics.overdraw.empty());
  const Frame with = render(scene, 130, 70, 2, 1, true);
  EXPECT_EQ(plain.color, with.color);
  // Shading once per visible pixel: the shaded count is the id AOV's covered count.
  uint64_t covered = 0;
  for (uint32_t id : with.triangle_id) covered += id != kNoTriangle;
  EXPECT_EQ(with.diagnostics.counters.pixels_shaded, covered);
  EXPECT_GT(covered, 0u);
}
