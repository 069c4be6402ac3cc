// The Vulkan backends' frame diagnostics (RenderOptions::diagnostics), held to the CPU's: the
// same scenes as tests/diagnostics_test.cpp, the same numbers where both measure the same thing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <tessera/render/diagnostics.h>

#include "diagnostics_scenes.h"
#include "vulkan_fixtures.h"

using namespace tessera;
using namespace tessera::vulkan_test;
using namespace tessera::diagnostics_test;

namespace {

RenderOptions diagnosticOptions(int width, int height, int msaa = 1) {
  RenderOptions o = options(width, height);
  o.msaa = msaa;
  o.diagnostics = true;
  return o;
}

// Every counter both backends count the same way. With MSAA both grow a triangle's bounding box
// by the pattern's own sample extents (sampleReach on the CPU), so the box-dependent counters are
// equal at every sample count too.
void expectSameCounters(const PipelineCounters& cpu, const PipelineCounters& gpu) {
  EXPECT_EQ(cpu.triangles_in, gpu.triangles_in);
  EXPECT_EQ(cpu.culled.invalid, gpu.culled.invalid);
  EXPECT_EQ(cpu.culled.non_finite, gpu.culled.non_finite);
  EXPECT_EQ(cpu.culled.frustum, gpu.culled.frustum);
  EXPECT_EQ(cpu.culled.degenerate, gpu.culled.degenerate);
  EXPECT_EQ(cpu.culled.facing, gpu.culled.facing);
  EXPECT_EQ(cpu.culled.no_pixel, gpu.culled.no_pixel);
  EXPECT_EQ(cpu.culled.clipped_away, gpu.culled.clipped_away);
  EXPECT_EQ(cpu.triangles_clipped, gpu.triangles_clipped);
  EXPECT_EQ(cpu.clip_splits, gpu.clip_splits);
  EXPECT_EQ(cpu.triangles_setup, gpu.triangles_setup);
  EXPECT_EQ(cpu.triangles_binned, gpu.triangles_binned);
  EXPECT_EQ(cpu.pixels_tested, gpu.pixels_tested);
  EXPECT_EQ(cpu.pixels_passed, gpu.pixels_passed);
  EXPECT_EQ(cpu.pixels_shaded, gpu.pixels_shaded);
  EXPECT_EQ(cpu.tiles, gpu.tiles);
  EXPECT_EQ(cpu.tiles_empty, gpu.tiles_empty);
  EXPECT_EQ(cpu.tiles_full, gpu.tiles_full);
}

// NaN (a tile with nothing covered) equals NaN here.
void expectSameFloats(const std::vector<float>& a, const std::vector<float>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::isnan(a[i]) && std::isnan(b[i])) continue;
    ASSERT_EQ(a[i], b[i]) << what << " " << i;
  }
}

// Frames whose ids are equal: every diagnostic is.
void expectSameDiagnostics(const Frame& cpu, const Frame& gpu) {
  ASSERT_EQ(cpu.triangle_id, gpu.triangle_id) << "the images differ: not comparable";
  const FrameDiagnostics &c = cpu.diagnostics, &g = gpu.diagnostics;
  ASSERT_TRUE(g.valid);
  EXPECT_EQ(c.has_pixel_tests, g.has_pixel_tests);
  EXPECT_EQ(c.tile_size, g.tile_size);
  EXPECT_EQ(c.tile_columns, g.tile_columns);
  EXPECT_EQ(c.tile_rows, g.tile_rows);
  EXPECT_EQ(c.overdraw, g.overdraw);
  EXPECT_EQ(c.material, g.material);
  EXPECT_EQ(c.density, g.density);
  EXPECT_EQ(c.tile_triangles, g.tile_triangles);
  expectSameFloats(c.tile_covered, g.tile_covered, "covered");
  expectSameFloats(c.tile_depth_min, g.tile_depth_min, "depth min");
  expectSameFloats(c.tile_depth_max, g.tile_depth_max, "depth max");
  EXPECT_EQ(c.tile_edges, g.tile_edges);
  expectSameCounters(c.counters, g.counters);
}

}  // namespace

TEST(VulkanDiagnostics, OverdrawOfStackedFullScreenQuadsIsTheirCount) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  // 40 quads: more tests per pixel than a pixel holds at once (diag_tests.comp's kHeld), so the
  // pass takes its walk in key order as well.
  for (int quads : {5, 40}) {
    for (const auto& [w, h] : {std::pair{150, 100}, std::pair{96, 96}}) {
      const Scene scene = stackedQuads(quads, w, h);
      for (int msaa : {1, 4}) {
        const Frame f = renderWith(*gpu, scene, diagnosticOptions(w, h, msaa));
        const FrameDiagnostics& d = f.diagnostics;
        ASSERT_TRUE(d.valid);
        ASSERT_TRUE(d.has_pixel_tests);
        ASSERT_EQ(d.overdraw.size(), f.pixelCount());
        for (size_t p = 0; p < f.pixelCount(); ++p)
          ASSERT_EQ(d.overdraw[p], static_cast<uint32_t>(quads)) << "pixel " << p;
        EXPECT_EQ(d.counters.pixels_tested, f.pixelCount() * quads);
        // Quad 0 (z -0.5) is the nearest and first: every later test fails.
        EXPECT_EQ(d.counters.pixels_passed, f.pixelCount());
        EXPECT_EQ(d.counters.tiles_full, d.counters.tiles);
        expectCountersAddUp(d.counters);
        expectSameDiagnostics(renderCpu(scene, diagnosticOptions(w, h, msaa)), f);
      }
    }
  }
}

TEST(VulkanDiagnostics, PassesCountInSubmissionOrder) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  // Far to near: every test passes; then one equal depth after the nearest: it fails (z < stored).
  constexpr int kW = 80, kH = 48;
  for (int quads : {6, 36}) {
    Scene scene = clipSpaceScene();
    Mesh m;
    for (int i = 0; i < quads; ++i)
      addRect(m, 0, 0, kW, kH, 0.9f - 0.02f * static_cast<float>(i), kW, kH);
    addRect(m, 0, 0, kW, kH, 0.9f - 0.02f * static_cast<float>(quads - 1), kW, kH);
    scene.objects.push_back(objectOf(m));
    const Frame f = renderWith(*gpu, scene, diagnosticOptions(kW, kH));
    const size_t pixels = f.pixelCount();
    EXPECT_EQ(f.diagnostics.counters.pixels_tested, pixels * (quads + 1));
    EXPECT_EQ(f.diagnostics.counters.pixels_passed, pixels * quads);
    expectSameDiagnostics(renderCpu(scene, diagnosticOptions(kW, kH)), f);
  }
}

TEST(VulkanDiagnostics, OccupancyIsTheTrianglesKnownToTouchEachTile) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  const Frame f =
      renderWith(*gpu, occupancyScene(), diagnosticOptions(kOccupancyWidth, kOccupancyHeight));
  const FrameDiagnostics& d = f.diagnostics;
  // The CPU's 64x64 grid, not the backend's own 16x16 bins.
  EXPECT_EQ(d.tile_size, 64);
  expectOccupancySceneCounts(d);
}

TEST(VulkanDiagnostics, CountersAddUpWithEveryCullReasonAndAgreeWithTheCpu) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  Mesh m = cullReasonMesh();
  m.indices.insert(m.indices.end(), {0, 1, 99});  // a vertex index past the mesh
  Scene scene = clipSpaceScene();
  scene.objects.push_back(objectOf(m, CullMode::kBack));
  const Frame f = renderWith(*gpu, scene, diagnosticOptions(64, 64));
  const PipelineCounters& c = f.diagnostics.counters;
  EXPECT_EQ(c.triangles_in, m.triangleCount());
  EXPECT_EQ(c.culled.invalid, 1u);
  EXPECT_EQ(c.culled.non_finite, 1u);
  EXPECT_EQ(c.culled.frustum, 1u);
  EXPECT_EQ(c.culled.degenerate, 1u);
  EXPECT_EQ(c.culled.facing, 1u);
  EXPECT_EQ(c.culled.no_pixel, 1u);
  EXPECT_EQ(c.triangles_clipped, 1u);
  EXPECT_EQ(c.clip_splits, 1u);
  EXPECT_EQ(c.triangles_setup, 3u);
  expectCountersAddUp(c);
  expectSameDiagnostics(renderCpu(scene, diagnosticOptions(64, 64)), f);
}

TEST(VulkanDiagnostics, TrianglesMissingTheFewCentresOfTheirBoxAreCulledAsOnTheCpu) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  constexpr int kW = 100, kH = 64;
  const FewCentres few = fewCentreScene(kW, kH);
  const auto dropped =
      static_cast<uint64_t>(std::count(few.dropped.begin(), few.dropped.end(), true));
  const Frame f = renderWith(*gpu, few.scene, diagnosticOptions(kW, kH));
  EXPECT_EQ(f.diagnostics.counters.triangles_setup, few.dropped.size() - dropped);
  EXPECT_EQ(f.diagnostics.counters.culled.no_pixel, dropped);
  expectSameDiagnostics(renderCpu(few.scene, diagnosticOptions(kW, kH)), f);
}

TEST(VulkanDiagnostics, TheCpusOnLitScenesWithEqualImages) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  Scene spheres = sphereScene(48, 32, Shading::kGouraud);
  Object second = spheres.objects[0];
  second.transform.translation = {0.5f, 0.2f, -0.6f};
  second.materials[0].density = 2.5f;
  spheres.objects.push_back(second);
  for (const Scene* scene : {&spheres}) {
    // Every sample count: each pattern has its own reach, which both backends' boxes take.
    for (int msaa : {1, 2, 4, 8}) {
      const RenderOptions o = diagnosticOptions(kWidth, kHeight, msaa);
      const Frame f = renderWith(*gpu, *scene, o);
      const FrameDiagnostics& d = f.diagnostics;
      EXPECT_GT(d.counters.pixels_tested, d.counters.pixels_passed);  // they overlap
      EXPECT_GT(d.counters.pixels_passed, d.counters.pixels_shaded);
      expectCountersAddUp(d.counters);
      SCOPED_TRACE(msaa);
      expectSameDiagnostics(renderCpu(*scene, o), f);
    }
  }
  const Frame cube = renderWith(*gpu, cubeScene(), diagnosticOptions(kWidth, kHeight));
  expectSameDiagnostics(renderCpu(cubeScene(), diagnosticOptions(kWidth, kHeight)), cube);
}

TEST(VulkanDiagnostics, BinOverflowIsCountedAndChangesNothingElse) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  VulkanOptions small;
  small.initial_bin_capacity = 16;
  ComputePtr gpu = makeCompute(small);
  ASSERT_TRUE(gpu);
  const Scene scene = sphereScene(32, 16, Shading::kFlat);
  const RenderOptions o = diagnosticOptions(kWidth, kHeight);
  const Frame f = renderWith(*gpu, scene, o);
  EXPECT_GT(f.diagnostics.counters.bin_overflow, 0u);
  Frame cpu = renderCpu(scene, o);
  cpu.diagnostics.counters.bin_overflow = f.diagnostics.counters.bin_overflow;
  expectSameDiagnostics(cpu, f);
  // The next frame fits the grown bins.
  EXPECT_EQ(renderWith(*gpu, scene, o).diagnostics.counters.bin_overflow, 0u);
}

TEST(VulkanDiagnostics, OffByDefaultAndTheImageDoesNotChange) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  const Scene scene = cubeScene();
  RenderOptions plain_options = options();
  plain_options.depth = plain_options.ids = false;
  const Frame plain = renderWith(*gpu, scene, plain_options);
  EXPECT_FALSE(plain.diagnostics.valid);
  RenderOptions with_options = plain_options;
  with_options.diagnostics = true;  // turns the depth and id AOVs on, which it reads
  const Frame with = renderWith(*gpu, scene, with_options);
  EXPECT_TRUE(with.diagnostics.valid);
  EXPECT_EQ(plain.color, with.color);
  EXPECT_EQ(with.triangle_id.size(), with.pixelCount());
  EXPECT_FALSE(renderWith(*gpu, scene, plain_options).diagnostics.valid);
}

TEST(VulkanDiagnostics, NonlinearProjectionsMeasureWhatTheCpuMeasures) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  Scene scene = cubeScene();
  scene.camera.fov_y_degrees = 120.0f;
  RenderOptions o = diagnosticOptions(kWidth, kHeight);
  o.projection = Projection::kFisheye;
  const Frame f = renderWith(*gpu, scene, o);
  const Frame cpu = renderCpu(scene, o);
  EXPECT_FALSE(f.diagnostics.has_pixel_tests);
  EXPECT_TRUE(f.diagnostics.overdraw.empty());
  EXPECT_GT(f.diagnostics.counters.pixels_shaded, 0u);
  expectCountersAddUp(f.diagnostics.counters);
  EXPECT_EQ(f.diagnostics.counters.triangles_setup, cpu.diagnostics.counters.triangles_setup);
  EXPECT_EQ(f.diagnostics.counters.culled.no_pixel, cpu.diagnostics.counters.culled.no_pixel);
  // The ray passes test the CPU's own rays: the same ids, so the same frame-derived measures.
  ASSERT_EQ(cpu.triangle_id, f.triangle_id);
  EXPECT_EQ(cpu.diagnostics.material, f.diagnostics.material);
  EXPECT_EQ(cpu.diagnostics.tile_covered, f.diagnostics.tile_covered);
  EXPECT_EQ(cpu.diagnostics.tile_edges, f.diagnostics.tile_edges);
  EXPECT_EQ(cpu.diagnostics.counters.pixels_shaded, f.diagnostics.counters.pixels_shaded);
  EXPECT_EQ(cpu.diagnostics.counters.tiles_empty, f.diagnostics.counters.tiles_empty);
}

TEST(VulkanDiagnostics, RasterBackendFillsWhatItMeasuresAndMarksTheRest) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(raster);
  const Scene scene = occupancyScene();
  const RenderOptions o = diagnosticOptions(kOccupancyWidth, kOccupancyHeight);
  const Frame f = renderWith(*raster, scene, o);
  const Frame cpu = renderCpu(scene, o);
  const FrameDiagnostics& d = f.diagnostics;
  ASSERT_TRUE(d.valid);
  EXPECT_FALSE(d.has_pixel_tests);
  EXPECT_FALSE(d.has_setup_counters);
  EXPECT_TRUE(d.overdraw.empty());
  EXPECT_TRUE(d.tile_triangles.empty());
  EXPECT_EQ(d.counters.triangles_in, cpu.diagnostics.counters.triangles_in);
  // Axis-aligned rectangles: the driver covers the same pixel centres as the CPU.
  ASSERT_EQ(cpu.triangle_id, f.triangle_id);
  EXPECT_EQ(d.material, cpu.diagnostics.material);
  EXPECT_EQ(d.density, cpu.diagnostics.density);
  EXPECT_EQ(d.tile_covered, cpu.diagnostics.tile_covered);
  EXPECT_EQ(d.tile_edges, cpu.diagnostics.tile_edges);
  EXPECT_EQ(d.counters.pixels_shaded, cpu.diagnostics.counters.pixels_shaded);
  EXPECT_EQ(d.counters.tiles_full, cpu.diagnostics.counters.tiles_full);
  EXPECT_EQ(d.counters.tiles, 6u);
}
