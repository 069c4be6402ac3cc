// Tests of the Vulkan backends against the CPU renderer, on Mesa's lavapipe in CI (any Vulkan
// device works). A test skips only when the machine has no Vulkan device at all, and says so.
// Their errors, device list and CLI are in vulkan_errors_test.cpp.
//
// With TESSERA_VULKAN_VALIDATION=1 every backend runs under VK_LAYER_KHRONOS_validation and every
// test fails on any validation error; Vulkan.ValidationLayersReportNoErrors turns it on by itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include <tessera/scene/color.h>

#include "vulkan_fixtures.h"

using namespace tessera;
using namespace tessera::vulkan_test;

// ---- the compute backend against the CPU ----

TEST(VulkanCompute, MatchesCpuOnCube) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  expectComputeMatchesCpu("cube", cubeScene());
}

TEST(VulkanCompute, MatchesCpuOnSpheres) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  expectComputeMatchesCpu("sphere, flat", sphereScene(24, 12, Shading::kFlat), {}, gpu.get());
  expectComputeMatchesCpu("sphere, Gouraud", sphereScene(32, 16, Shading::kGouraud), {}, gpu.get());
  expectComputeMatchesCpu("sphere, Phong", sphereScene(48, 24, Shading::kPhong), {}, gpu.get());
}

// kPbr: vulkan_pbr_test.cpp.

TEST(VulkanCompute, MatchesCpuOnDenseMesh) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  expectComputeMatchesCpu("dense sphere (200x100) and cube", denseScene());
}

TEST(VulkanCompute, MatchesCpuOnTrianglesCrossingTheNearPlane) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  expectComputeMatchesCpu("near plane", nearPlaneScene());
}

TEST(VulkanCompute, MatchesCpuOnSubPixelTriangles) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  expectComputeMatchesCpu("sub-pixel triangles",
                          randomTriangles(20000, 0.9f, 0.0f, 0.0f, 190.0f, 7));
}

TEST(VulkanCompute, MatchesCpuOnTexturedPlane) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  expectComputeMatchesCpu("textured plane", texturedScene());
}

// Mirrored repeat, S and T wrapped differently, and KHR_texture_transform's offset, rotation
// and scale (the trilinear wall's level of detail through them too).
TEST(VulkanCompute, MatchesCpuOnMirroredAndTransformedTextures) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  Scene scene = texturedScene();
  const TextureTransform moved{{0.3f, -0.2f}, 0.6f, {1.7f, 2.5f}};
  for (Object& o : scene.objects) {
    Sampler& s = o.materials[0].sampler;
    s.wrap_s = TextureWrap::kMirroredRepeat;
    s.wrap_t = s.filter == TextureFilter::kNearest ? TextureWrap::kClamp : TextureWrap::kRepeat;
    if (s.filter != TextureFilter::kBilinear) s.transform = moved;
  }
  expectComputeMatchesCpu("mirrored and transformed textures", scene);
}

TEST(VulkanCompute, NormalAovMatchesCpu) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  const Scene scene = sphereScene(32, 16, Shading::kPhong);
  const RenderOptions o = options(kWidth, kHeight, /*normals=*/true);
  const Frame cpu = renderCpu(scene, o);
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  const Frame frame = renderWith(*gpu, scene, o);
  ASSERT_EQ(frame.normal.size(), cpu.normal.size());
  size_t close = 0, drawn = 0;
  for (size_t i = 0; i < frame.pixelCount(); ++i) {
    if (cpu.triangle_id[i] == kNoTriangle) continue;
    ++drawn;
    close += length(frame.normal[i] - cpu.normal[i]) < 1e-5f;
    EXPECT_EQ(frame.depth[i], cpu.depth[i]) << "pixel " << i;
  }
  EXPECT_GT(drawn, 1000u);
  EXPECT_EQ(close, drawn);
}

TEST(VulkanCompute, EdgeCasesMatchCpu) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(gpu && raster);
  // An empty scene, an object without a mesh between two with, odd and tiny viewports, no
  // AOVs at all.
  Scene empty;
  empty.background = {0.3f, 0.1f, 0.2f, 1.0f};
  Scene gaps = cubeScene();
  gaps.objects.insert(gaps.objects.begin(), Object{});
  gaps.objects.push_back(Object{});
  gaps.objects.push_back(cubeScene(1.9f).objects[0]);
  gaps.objects.back().transform.translation = {0.4f, -0.3f, -0.5f};
  struct Case {
    const Scene* scene;
    int width, height;
  };
  for (const Case& c : {Case{&empty, 40, 30}, Case{&gaps, 1, 1}, Case{&gaps, 17, 9},
                        Case{&gaps, 300, 7}, Case{&gaps, 131, 97}}) {
    for (bool aovs : {true, false}) {
      RenderOptions o = options(c.width, c.height);
      o.depth = o.ids = aovs;
      const Frame cpu = renderCpu(*c.scene, o);
      Frame frame;
      gpu->render(*c.scene, o, frame);
      ASSERT_TRUE(gpu->lastResult().ok()) << gpu->lastResult().error().message;
      EXPECT_EQ(frame.color, cpu.color) << c.width << "x" << c.height;
      EXPECT_EQ(frame.triangle_id, cpu.triangle_id) << c.width << "x" << c.height;
      EXPECT_EQ(frame.depth, cpu.depth) << c.width << "x" << c.height;
      raster->render(*c.scene, o, frame);
      ASSERT_TRUE(raster->lastResult().ok()) << raster->lastResult().error().message;
      EXPECT_EQ(frame.triangle_id.size(), cpu.triangle_id.size());
      EXPECT_EQ(frame.depth.size(), cpu.depth.size());
    }
  }
}

// ---- the fallbacks: still the CPU's image ----

TEST(VulkanCompute, ThirtyTwoBitCommitMatchesCpu) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  VulkanOptions vk;
  vk.force_32bit_atomics = true;
  ComputePtr gpu = makeCompute(vk);
  ASSERT_TRUE(gpu);
  expectComputeMatchesCpu("32-bit commit, dense", denseScene(), vk, gpu.get());
  EXPECT_FALSE(gpu->lastStats().int64_atomics);
  expectComputeMatchesCpu("32-bit commit, one tile", randomTriangles(3000, 12.0f, 80, 80, 4, 3), vk,
                          gpu.get());
}

TEST(VulkanCompute, DeviceWithoutInt64AtomicsTakesThe32BitPath) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  VulkanOptions vk;
  vk.pretend_missing_features = {"shaderBufferInt64Atomics"};
  ComputePtr gpu = makeCompute(vk);
  ASSERT_TRUE(gpu);
  EXPECT_FALSE(gpu->device().int64_atomics);
  EXPECT_NE(gpu->device().compute_note.find("32-bit"), std::string::npos)
      << gpu->device().compute_note;
  expectComputeMatchesCpu("no int64 atomics, cube", cubeScene(), vk, gpu.get());
  EXPECT_FALSE(gpu->lastStats().int64_atomics);
}

// The viewer's Shift+F2: the same backend object switches its commit path, and the image stays.
TEST(VulkanCompute, TheCommitPathSwitchesAtRunTimeAndDrawsTheSameImage) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  if (!gpu->device().int64_atomics) GTEST_SKIP() << "the device has no 64-bit atomics";
  const Scene scene = denseScene();
  const RenderOptions o = options();
  EXPECT_TRUE(gpu->uses64BitCommits());
  const Frame atomic64 = renderWith(*gpu, scene, o);
  ASSERT_TRUE(gpu->setForce32BitAtomics(true).ok());
  EXPECT_FALSE(gpu->uses64BitCommits());
  const Frame atomic32 = renderWith(*gpu, scene, o);
  EXPECT_FALSE(gpu->lastStats().int64_atomics);
  EXPECT_EQ(atomic32.color, atomic64.color);
  EXPECT_EQ(atomic32.triangle_id, atomic64.triangle_id);
  ASSERT_TRUE(gpu->setForce32BitAtomics(false).ok());
  EXPECT_TRUE(gpu->uses64BitCommits());
  const Frame again = renderWith(*gpu, scene, o);
  EXPECT_TRUE(gpu->lastStats().int64_atomics);
  EXPECT_EQ(again.color, atomic64.color);
}

TEST(VulkanCompute, FloatSetupKeepsCoverageExact) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  VulkanOptions vk;
  vk.force_fp32_setup = true;
  ComputePtr gpu = makeCompute(vk);
  ASSERT_TRUE(gpu);
  expectComputeMatchesCpu("float setup, dense", denseScene(), vk, gpu.get());
  EXPECT_FALSE(gpu->lastStats().fp64_setup);
}

// ---- binning ----

TEST(VulkanCompute, ManyTrianglesInOneTileStillMatch) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  // 5000 triangles over one 16x16 tile (and its neighbours): the tile's list is split into
  // several raster workgroups that commit into the same pixels.
  const Scene scene = randomTriangles(5000, 14.0f, 66.0f, 66.0f, 6.0f, 11);
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  expectComputeMatchesCpu("5000 triangles in one tile", scene, {}, gpu.get());
  const vulkan::ComputeStats& stats = gpu->lastStats();
  EXPECT_GE(stats.max_tile_entries, 4000u);
  EXPECT_GT(stats.raster_workgroups, stats.tiles_occupied);
}

TEST(VulkanCompute, BinOverflowRendersAgainWithLargerBins) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  VulkanOptions vk;
  vk.initial_bin_capacity = 64;  // far too few: the first round overflows
  ComputePtr gpu = makeCompute(vk);
  ASSERT_TRUE(gpu);
  expectComputeMatchesCpu("overflowing bins", denseScene(), vk, gpu.get());
  const vulkan::ComputeStats& stats = gpu->lastStats();
  EXPECT_GE(stats.bin_overflows, 1u);
  EXPECT_GE(stats.bin_capacity, stats.bin_entries);
  // The grown buffer is kept: the next frame fits at once.
  expectComputeMatchesCpu("overflowing bins, next frame", denseScene(), vk, gpu.get());
  EXPECT_EQ(gpu->lastStats().bin_overflows, 0u);
}

TEST(VulkanCompute, ManyClippedTrianglesGrowTheClipRecords) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  // 3000 triangles with one corner behind the camera: the near plane cuts each into a quad, two
  // records, which is more extra records than the first frame's allowance.
  Scene scene;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> where(-1.5f, 1.5f), width(0.05f, 0.4f);
  Mesh mesh;
  for (uint32_t t = 0; t < 3000; ++t) {
    const float x = where(rng), y = where(rng), w = width(rng);
    mesh.positions.insert(mesh.positions.end(),
                          {{x, y, 1.0f}, {x - w, y, -4.0f + x}, {x + w, y + w, -4.0f - y}});
    mesh.indices.insert(mesh.indices.end(), {3 * t, 3 * t + 1, 3 * t + 2});
  }
  Object object;
  object.mesh = std::make_shared<Mesh>(mesh);
  object.cull = CullMode::kNone;
  scene.objects.push_back(object);
  addLights(scene);
  scene.camera.position = {0, 0, 0};
  scene.camera.target = {0, 0, -1};
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  expectComputeMatchesCpu("3000 triangles through the near plane", scene, {}, gpu.get());
  EXPECT_GT(gpu->lastStats().triangles_clipped, 2000u);
  EXPECT_GE(gpu->lastStats().bin_overflows, 1u);
}

TEST(VulkanCompute, StatsAndTimingsAreFilled) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  const Scene scene = denseScene();
  renderWith(*gpu, scene, options());
  const vulkan::ComputeStats& s = gpu->lastStats();
  EXPECT_EQ(s.triangles_in, scene.triangleCount());
  EXPECT_GT(s.triangles_culled, s.triangles_in / 3);  // the back half of the sphere, at least
  EXPECT_GT(s.triangles_binned, 0u);
  EXPECT_LE(s.triangles_binned, s.triangles_setup);
  EXPECT_GE(s.bin_entries, s.triangles_binned);
  EXPECT_EQ(s.tiles, static_cast<size_t>((kWidth / 16) * (kHeight / 16)));
  EXPECT_GT(s.tiles_occupied, 0u);
  EXPECT_LE(s.tiles_occupied, s.tiles);
  if (s.timings.valid) {
    EXPECT_GT(s.timings.total, 0.0);
    EXPECT_GE(s.timings.total + 1e-9, s.timings.setup + s.timings.raster + s.timings.shade);
  }
  std::printf(
      "[ stats    ] %zu in, %zu culled, %zu clipped, %zu set up, %zu binned, %zu entries "
      "in %zu/%zu tiles (max %zu), %zu raster workgroups\n",
      s.triangles_in, s.triangles_culled, s.triangles_clipped, s.triangles_setup,
      s.triangles_binned, s.bin_entries, s.tiles_occupied, s.tiles, s.max_tile_entries,
      s.raster_workgroups);
  std::printf(
      "[ timings  ] clear %.3f, transform %.3f, setup %.3f, bin %.3f, raster %.3f, "
      "shade %.3f, total %.3f ms (valid %d)\n",
      s.timings.clear, s.timings.transform, s.timings.setup, s.timings.bin, s.timings.raster,
      s.timings.shade, s.timings.total, s.timings.valid);
}

TEST(VulkanCompute, HeatmapShowsTileOccupancy) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  // Triangles only in the left half: the right half's tiles are empty and stay black.
  const Scene scene = randomTriangles(2000, 6.0f, 8.0f, 8.0f, 100.0f, 5);
  renderWith(*gpu, scene, options());
  const vulkan::TileOccupancy& occupancy = gpu->lastTileOccupancy();
  ASSERT_EQ(occupancy.entries.size(), static_cast<size_t>(occupancy.columns * occupancy.rows));
  const std::vector<uint32_t> image = vulkan::makeOccupancyHeatmap(occupancy, kWidth, kHeight);
  ASSERT_EQ(image.size(), static_cast<size_t>(kWidth * kHeight));
  size_t lit = 0;
  for (uint32_t pixel : image) lit += (pixel & 0xffffffu) != 0;
  EXPECT_GT(lit, 1000u);
  EXPECT_EQ(image[static_cast<size_t>(kHeight - 2) * kWidth + kWidth - 2] & 0xffffffu, 0u);
  EXPECT_NE(image[static_cast<size_t>(60) * kWidth + 60] & 0xffffffu, 0u);
}

// ---- the raster backend against the CPU ----

TEST(VulkanRaster, MatchesCpuIds) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(raster);
  expectRasterMatchesCpu("raster: cube", cubeScene(), *raster);
  expectRasterMatchesCpu("raster: sphere", sphereScene(48, 24, Shading::kPhong), *raster);
  expectRasterMatchesCpu("raster: dense", denseScene(), *raster);
  expectRasterMatchesCpu("raster: near plane", nearPlaneScene(), *raster);
  expectRasterMatchesCpu("raster: textured", texturedScene(), *raster);
  expectRasterMatchesCpu("raster: sub-pixel", randomTriangles(20000, 0.9f, 0, 0, 190, 7), *raster);
  EXPECT_EQ(raster->lastStats().draws, 1u);
}

TEST(VulkanRaster, DropsTheTrianglesTheCpuDrops) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  // An index past the end and a non-finite vertex: the CPU draws neither triangle.
  Scene scene = clipSpaceScene();
  Mesh mesh;
  mesh.positions = {{-0.8f, -0.8f, 0}, {0.8f, -0.8f, 0}, {0, 0.8f, 0}, {0, 0, 0}, {NAN, 0, 0}};
  mesh.indices = {0, 1, 2, 0, 1, 9, 0, 4, 2};
  Object object;
  object.mesh = std::make_shared<Mesh>(mesh);
  object.shading = Shading::kUnlit;
  object.cull = CullMode::kNone;
  scene.objects.push_back(object);
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(raster);
  expectRasterMatchesCpu("raster: dropped triangles", scene, *raster);
  expectComputeMatchesCpu("compute: dropped triangles", scene);
}

// ---- validation ----

TEST(Vulkan, ValidationLayersReportNoErrors) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  VulkanOptions vk;
  vk.validation = true;
  ComputePtr gpu = makeCompute(vk);
  ASSERT_TRUE(gpu);
  expectComputeMatchesCpu("validated: near plane", nearPlaneScene(), vk, gpu.get());
  expectComputeMatchesCpu("validated: textured", texturedScene(), vk, gpu.get(), true);
  vk.force_32bit_atomics = true;
  vk.initial_bin_capacity = 16;
  ComputePtr fallback = makeCompute(vk);
  ASSERT_TRUE(fallback);
  expectComputeMatchesCpu("validated: 32-bit, overflow", cubeScene(), vk, fallback.get());
  RasterPtr raster = makeRaster(vk);
  ASSERT_TRUE(raster);
  expectRasterMatchesCpu("validated: raster", texturedScene(), *raster);
  // renderWith() fails the test on any validation error; check once more after teardown-free
  // idle.
  EXPECT_TRUE(gpu->validationErrors().empty());
  EXPECT_TRUE(fallback->validationErrors().empty());
  EXPECT_TRUE(raster->validationErrors().empty());
}

namespace {

// Pixels whose colour is exactly `color`.
int countColor(const Frame& f, uint32_t color) {
  int n = 0;
  for (uint32_t c : f.color) n += c == color;
  return n;
}

}  // namespace

// Both Vulkan backends draw Scene::points and Scene::lines (at line_width) on their read-back
// frame with the CPU's passes: the same pixels as the CPU backend, with and without triangles.
TEST(VulkanPoints, BothBackendsDrawPointsAndWideLinesAsTheCpu) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr compute = makeCompute();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(compute && raster);
  constexpr uint32_t kMagenta = 0xffff00ffu, kGreen = 0xff00ff00u;
  for (bool with_cube : {true, false}) {
    Scene scene = with_cube ? cubeScene() : Scene{};
    scene.camera.position = {0, 0, 5};
    for (int i = 0; i < 7; ++i) {
      // In front of the cube (z 1.5) and behind it (z -1.5): the latter hidden where it is.
      scene.points.positions.push_back({-1.2f + 0.4f * i, 0.3f, i % 2 ? 1.5f : -1.5f});
      scene.points.colors.push_back(packSrgba8({1, 0, 1, 1}));
    }
    scene.lines.add({-2, -0.9f, 1.2f}, {2, -0.9f, 1.2f}, {0, 1, 0});
    RenderOptions o = options();
    o.points.size = 5;
    o.line_width = 3;
    const Frame cpu = renderCpu(scene, o);
    const int points = countColor(cpu, kMagenta), lines = countColor(cpu, kGreen);
    EXPECT_GT(points, with_cube ? 50 : 100);
    EXPECT_GT(lines, 100);
    for (Backend* gpu :
         {static_cast<Backend*>(compute.get()), static_cast<Backend*>(raster.get())}) {
      const Frame frame =
          gpu == compute.get() ? renderWith(*compute, scene, o) : renderWith(*raster, scene, o);
      int same = 0;
      for (size_t i = 0; i < cpu.color.size(); ++i)
        same +=
            (cpu.color[i] == kMagenta || cpu.color[i] == kGreen) && frame.color[i] == cpu.color[i];
      EXPECT_GE(same, (points + lines) * 98 / 100) << (with_cube ? "cube" : "no objects");
    }
  }
}
