// MSAA and jitter on the two Vulkan backends: coverage at the standard sample positions, the
// linear-light resolve, the pixel-centre AOVs that do not change with the sample count, the
// coverage AOV, jitter, and the device's sample-count limits.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include <tessera/render/accumulate.h>
#include <tessera/render/sampling.h>

#include "vulkan_fixtures.h"

using namespace tessera;
using namespace tessera::vulkan_test;

namespace {

constexpr int kSampleCounts[] = {1, 2, 4, 8};

// White unlit triangles on black in a clip-space scene.
Scene whiteOnBlack(Mesh mesh) {
  Scene scene = clipSpaceScene();
  scene.background = {0, 0, 0, 1};
  scene.objects.push_back(whiteUnlitObject(std::move(mesh)));
  return scene;
}

// A rectangle covering window x < right and y < bottom (from beyond the top-left corner) in a
// width x height image: two triangles sharing a diagonal.
Scene rectangleScene(float right, float bottom, int width, int height) {
  Mesh mesh;
  mesh.positions = {windowToNdc(-1, -1, 0, width, height), windowToNdc(right, -1, 0, width, height),
                    windowToNdc(right, bottom, 0, width, height),
                    windowToNdc(-1, bottom, 0, width, height)};
  mesh.indices = {0, 2, 1, 0, 3, 2};
  return whiteOnBlack(std::move(mesh));
}

// A white unlit triangle on black: a, b, c in window pixels.
Scene triangleScene(float2 a, float2 b, float2 c, int width, int height) {
  Mesh mesh;
  mesh.positions = {windowToNdc(a.x, a.y, 0, width, height),
                    windowToNdc(b.x, b.y, 0, width, height),
                    windowToNdc(c.x, c.y, 0, width, height)};
  mesh.indices = {0, 1, 2};
  return whiteOnBlack(std::move(mesh));
}

// Whether the sample point (px, py), in 1/256 pixel, is covered: the test's own statement of
// the contract for its scene.
using CoverTest = std::function<bool(int64_t px, int64_t py)>;

// Renders `scene` (white triangles on black) and checks every pixel: with n of the S samples
// covered, the colour is sRGB(n / S) (linear light, encoded once) and the coverage AOV
// (n * 255 + S / 2) / S. Returns how many pixels are partly covered.
template <typename B>
int expectResolvesTo(B& backend, const Scene& scene, int width, int height, int samples,
                     Jitter jitter, const CoverTest& covers) {
  RenderOptions o = options(width, height);
  o.msaa = samples;
  o.coverage = true;
  o.jitter = jitter;
  const Frame frame = renderWith(backend, scene, o);
  if (frame.coverage.size() != frame.pixelCount()) {
    ADD_FAILURE() << backend.name() << ": no coverage AOV";
    return 0;
  }
  int partial = 0, wrong = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      int n = 0;
      for (const SamplePosition& s : samplePattern(samples))
        n += covers(int64_t{x} * 256 + s.x, int64_t{y} * 256 + s.y);
      partial += n > 0 && n < samples;
      const uint32_t grey = encodeSrgb8(static_cast<float>(n) / static_cast<float>(samples));
      const uint32_t color = grey | grey << 8 | grey << 16 | 255u << 24;
      const int coverage = (n * 255 + samples / 2) / samples;
      if ((frame.colorAt(x, y) != color || frame.coverageAt(x, y) != coverage) && ++wrong <= 5)
        ADD_FAILURE() << backend.name() << " msaa " << samples << " jitter (" << jitter.x << ", "
                      << jitter.y << ") pixel (" << x << ", " << y << "): colour " << std::hex
                      << frame.colorAt(x, y) << " coverage " << std::dec
                      << int(frame.coverageAt(x, y)) << ", expected " << std::hex << color
                      << " and " << std::dec << coverage << " (" << n << " of " << samples
                      << " samples)";
    }
  }
  EXPECT_EQ(wrong, 0) << backend.name() << " msaa " << samples;
  return partial;
}

// rectangleScene(right, bottom): sample (px, py) is covered when px < right - jitter.x and
// py < bottom - jitter.y (the geometry moves by -jitter; the right and bottom edges are not
// top-left edges, so a sample exactly on one is outside).
template <typename B>
int expectRectangleResolves(B& backend, int samples, float right, float bottom, Jitter jitter) {
  constexpr int kW = 24, kH = 12;
  const int64_t right256 = std::lround((right - jitter.x) * 256);
  const int64_t bottom256 = std::lround((bottom - jitter.y) * 256);
  return expectResolvesTo(backend, rectangleScene(right, bottom, kW, kH), kW, kH, samples, jitter,
                          [&](int64_t px, int64_t py) { return px < right256 && py < bottom256; });
}

// A triangle whose right edge runs from a (top) to b (bottom) at a slant, its third corner far
// to the left: a sample is covered when it is strictly left of a->b (a right edge), in exact
// integer arithmetic on the 1/256 grid.
template <typename B>
int expectSlantedEdgeResolves(B& backend, int samples, Jitter jitter) {
  constexpr int kW = 24, kH = 16;
  const float2 a{9.3125f, -2.0f}, b{15.0f, 18.0f}, c{-200.0f, 8.0f};
  const int64_t ax = std::lround((a.x - jitter.x) * 256), ay = std::lround((a.y - jitter.y) * 256);
  const int64_t bx = std::lround((b.x - jitter.x) * 256), by = std::lround((b.y - jitter.y) * 256);
  return expectResolvesTo(
      backend, triangleScene(a, b, c, kW, kH), kW, kH, samples, jitter,
      [&](int64_t px, int64_t py) { return (px - ax) * (by - ay) < (bx - ax) * (py - ay); });
}

// The id, depth and normal AOVs at `samples` are those of one sample, byte for byte.
template <typename B>
void expectCentreAovsUnchanged(B& backend, const char* what, const Scene& scene, int samples) {
  RenderOptions o = options(kWidth, kHeight, /*normals=*/true);
  const Frame single = renderWith(backend, scene, o);
  o.msaa = samples;
  const Frame multi = renderWith(backend, scene, o);
  EXPECT_GT(std::count_if(single.triangle_id.begin(), single.triangle_id.end(),
                          [](uint32_t id) { return id != kNoTriangle; }),
            1000)
      << what;
  EXPECT_TRUE(multi.triangle_id == single.triangle_id) << what << ", msaa " << samples;
  EXPECT_TRUE(multi.depth == single.depth) << what << ", msaa " << samples;
  size_t normals_differ = 0;
  for (size_t i = 0; i < single.normal.size(); ++i)
    normals_differ += !(multi.normal[i] == single.normal[i]);
  EXPECT_EQ(normals_differ, 0u) << what << ", msaa " << samples;
  // The colour does change: edges are resolved from every sample.
  EXPECT_NE(multi.color, single.color) << what << ", msaa " << samples;
}

bool rasterTakes(const RasterBackend& raster, int samples) {
  const std::vector<int>& counts = raster.device().raster_sample_counts;
  return std::find(counts.begin(), counts.end(), samples) != counts.end();
}

}  // namespace

// ---- vulkan-raster ----

TEST(VulkanRasterMsaa, HalfCoveredPixelsResolveInLinearLight) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(raster);
  int tested = 0;
  for (int samples : kSampleCounts) {
    if (!rasterTakes(*raster, samples)) continue;  // VulkanRasterMsaa.UnsupportedCount...
    ++tested;
    // Edges through the pixel centres of column 10 and row 6: half of every pattern is left of
    // (above) the centre, so those pixels resolve to linear 0.5, sRGB 188, coverage 128.
    const int partial = expectRectangleResolves(*raster, samples, 10.5f, 6.5f, {});
    EXPECT_EQ(partial, samples > 1 ? 6 + 10 + 1 : 0) << samples;
  }
  EXPECT_GE(tested, 2) << "the device takes no sample count above 1";
}

TEST(VulkanRasterMsaa, JitterMovesTheSamplePattern) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(raster);
  for (int samples : kSampleCounts) {
    if (!rasterTakes(*raster, samples)) continue;
    for (Jitter j : {Jitter{0.125f, -0.25f}, Jitter{-0.3125f, 0.1875f}, jitterOffset(5)})
      expectRectangleResolves(*raster, samples, 10.5f, 6.5f, j);
  }
}

TEST(VulkanRasterMsaa, SlantedEdgeCoversTheAnalyticSamples) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(raster);
  for (int samples : kSampleCounts) {
    if (!rasterTakes(*raster, samples)) continue;
    const int partial = expectSlantedEdgeResolves(*raster, samples, {});
    if (samples > 1) {
      EXPECT_GT(partial, 3) << samples;
    }
    expectSlantedEdgeResolves(*raster, samples, jitterOffset(3));
  }
}

TEST(VulkanRasterMsaa, CentreAovsDoNotChangeWithTheSampleCount) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(raster);
  for (int samples : {2, 4, 8}) {
    if (!rasterTakes(*raster, samples)) continue;
    expectCentreAovsUnchanged(*raster, "raster: dense", denseScene(), samples);
    expectCentreAovsUnchanged(*raster, "raster: textured", texturedScene(), samples);
  }
}

TEST(VulkanRasterMsaa, UnsupportedCountIsAnError) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  auto expectRefused = [](RasterBackend& raster, int samples, const char* named) {
    RenderOptions o = options(32, 16);
    o.msaa = samples;
    Frame frame;
    raster.render(cubeScene(), o, frame);
    const Expected<void> result = raster.lastResult();
    ASSERT_FALSE(result.ok()) << samples;
    EXPECT_NE(result.error().message.find(std::to_string(samples) + "x MSAA"), std::string::npos)
        << result.error().message;
    EXPECT_NE(result.error().message.find(named), std::string::npos) << result.error().message;
    EXPECT_EQ(std::count(frame.color.begin(), frame.color.end(), 0u),
              static_cast<long>(frame.pixelCount()))
        << "a refused frame is left empty";
  };
  // The device's own limits: every count it does not list is refused.
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(raster);
  for (int samples : {2, 4, 8})
    if (!rasterTakes(*raster, samples))
      expectRefused(*raster, samples, "framebufferColorSampleCounts");
  // A device that takes at most 2 samples, and one without the standard positions.
  VulkanOptions vk;
  vk.pretend_max_samples = 2;
  RasterPtr small = makeRaster(vk);
  ASSERT_TRUE(small);
  EXPECT_FALSE(rasterTakes(*small, 4));
  expectRefused(*small, 4, "framebufferColorSampleCounts");
  expectRefused(*small, 8, "framebufferColorSampleCounts");
  vk = {};
  vk.pretend_missing_features = {"standardSampleLocations"};
  RasterPtr odd = makeRaster(vk);
  ASSERT_TRUE(odd);
  EXPECT_EQ(odd->device().raster_sample_counts, std::vector<int>{1});
  expectRefused(*odd, 4, "standardSampleLocations");
  // The same backend still renders what it takes.
  renderWith(*odd, cubeScene(), options(32, 16));
}

// ---- vulkan (compute) ----

// A grid of cells x cells quads over the whole viewport and beyond, its inner vertices moved at
// random: every sample of every pixel is covered by one of its triangles (no cracks).
Scene crackFreeGridScene(int cells, int width, int height, uint32_t seed) {
  Mesh mesh;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> wobble(-0.4f, 0.4f);
  const float step_x = (width + 4.0f) / cells, step_y = (height + 4.0f) / cells;
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      const bool inner = i > 0 && j > 0 && i < cells && j < cells;
      const float x = -2.0f + step_x * (i + (inner ? wobble(rng) : 0.0f));
      const float y = -2.0f + step_y * (j + (inner ? wobble(rng) : 0.0f));
      mesh.positions.push_back(windowToNdc(x, y, 0, width, height));
    }
  }
  const uint32_t stride = static_cast<uint32_t>(cells + 1);
  for (uint32_t j = 0; j < static_cast<uint32_t>(cells); ++j) {
    for (uint32_t i = 0; i < static_cast<uint32_t>(cells); ++i) {
      const uint32_t a = j * stride + i, b = a + 1, c = a + stride, d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, d, b, a, c, d});
    }
  }
  return whiteOnBlack(std::move(mesh));
}

TEST(VulkanComputeMsaa, HalfCoveredPixelsResolveInLinearLight) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  for (bool atomics32 : {false, true}) {
    VulkanOptions vk;
    vk.force_32bit_atomics = atomics32;
    ComputePtr gpu = makeCompute(vk);
    ASSERT_TRUE(gpu);
    for (int samples : kSampleCounts) {
      // Column 10 and row 6 are half covered (sRGB 188, coverage 128), their corner less.
      const int partial = expectRectangleResolves(*gpu, samples, 10.5f, 6.5f, {});
      EXPECT_EQ(partial, samples > 1 ? 6 + 10 + 1 : 0) << samples;
    }
  }
}

TEST(VulkanComputeMsaa, SlantedEdgeCoversTheAnalyticSamples) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  for (int samples : kSampleCounts) {
    const int partial = expectSlantedEdgeResolves(*gpu, samples, {});
    if (samples > 1) {
      EXPECT_GT(partial, 3) << samples;
    }
  }
}

TEST(VulkanComputeMsaa, JitterMovesTheSamplePattern) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  for (int samples : kSampleCounts) {
    for (Jitter j : {Jitter{0.125f, -0.25f}, Jitter{-0.3125f, 0.1875f}, jitterOffset(5)})
      expectRectangleResolves(*gpu, samples, 10.5f, 6.5f, j);
    expectSlantedEdgeResolves(*gpu, samples, jitterOffset(3));
  }
}

TEST(VulkanComputeMsaa, SharedEdgesLeaveNoSampleUncovered) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  constexpr int kW = 40, kH = 30;
  const Scene grid = crackFreeGridScene(13, kW, kH, 17);
  for (int samples : kSampleCounts) {
    expectResolvesTo(*gpu, grid, kW, kH, samples, {}, [](int64_t, int64_t) { return true; });
    expectResolvesTo(*gpu, grid, kW, kH, samples, jitterOffset(7),
                     [](int64_t, int64_t) { return true; });
  }
}

TEST(VulkanComputeMsaa, CentreAovsDoNotChangeWithTheSampleCount) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  for (bool atomics32 : {false, true}) {
    VulkanOptions vk;
    vk.force_32bit_atomics = atomics32;
    ComputePtr gpu = makeCompute(vk);
    ASSERT_TRUE(gpu);
    for (int samples : {2, 4, 8}) {
      expectCentreAovsUnchanged(*gpu, "compute: dense", denseScene(), samples);
      expectCentreAovsUnchanged(*gpu, "compute: near plane", nearPlaneScene(), samples);
      expectCentreAovsUnchanged(*gpu, "compute: textured", texturedScene(), samples);
    }
  }
}

TEST(VulkanComputeMsaa, ThirtyTwoBitCommitResolvesTheSame) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr wide = makeCompute();
  VulkanOptions vk;
  vk.force_32bit_atomics = true;
  ComputePtr narrow = makeCompute(vk);
  ASSERT_TRUE(wide && narrow);
  const Scene scene = randomTriangles(3000, 12.0f, 70, 60, 40, 9);  // deep overlaps
  for (int samples : {2, 4, 8}) {
    RenderOptions o = options();
    o.msaa = samples;
    o.coverage = true;
    const Frame a = renderWith(*wide, scene, o), b = renderWith(*narrow, scene, o);
    EXPECT_TRUE(a.color == b.color) << samples;
    EXPECT_TRUE(a.coverage == b.coverage) << samples;
    EXPECT_TRUE(a.triangle_id == b.triangle_id) << samples;
  }
}

TEST(VulkanComputeMsaa, VisibilityBeyondTheDeviceLimitIsAnError) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  // 128 x 96 pixels: 96 KiB of visibility at one sample, 864 KiB at eight (and the centre).
  VulkanOptions vk;
  vk.pretend_max_buffer_bytes = 300 * 1024;
  ComputePtr gpu = makeCompute(vk);
  ASSERT_TRUE(gpu);
  RenderOptions o = options(128, 96);
  renderWith(*gpu, cubeScene(), o);
  o.msaa = 8;
  Frame frame;
  gpu->render(cubeScene(), o, frame);
  const Expected<void> result = gpu->lastResult();
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("visibility buffer"), std::string::npos)
      << result.error().message;
  EXPECT_NE(result.error().message.find("maxStorageBufferRange"), std::string::npos)
      << result.error().message;
  // Two samples and the centre fit: 288 KiB.
  o.msaa = 2;
  renderWith(*gpu, cubeScene(), o);
}

// ---- against the CPU's MSAA ----

namespace {

// A scene with world axes and a line list: the line pass antialiases with MSAA on every backend.
Scene cubeWithLines() {
  Scene scene = cubeScene(1.1f);
  scene.show_world_axes = true;
  scene.lines.add({-1.2f, -0.6f, 0.3f}, {1.3f, 0.7f, -0.2f}, {1.0f, 0.2f, 0.8f});
  return scene;
}

struct ParityScene {
  const char* what;
  Scene scene;
};

std::vector<ParityScene> parityScenes() {
  std::vector<ParityScene> scenes;
  scenes.push_back({"cube and lines", cubeWithLines()});
  scenes.push_back({"Phong sphere", sphereScene(48, 24, Shading::kPhong)});
  scenes.push_back({"dense", denseScene()});
  scenes.push_back({"near plane", nearPlaneScene()});
  scenes.push_back({"textured", texturedScene()});
  scenes.push_back({"sub-pixel", randomTriangles(6000, 0.9f, 0, 0, 190, 7)});
  return scenes;
}

RenderOptions sampledOptions(int samples, Jitter jitter = {}) {
  RenderOptions o = options();
  o.depth = o.ids = true;
  o.msaa = samples;
  o.coverage = true;
  o.jitter = jitter;
  return o;
}

}  // namespace

TEST(VulkanComputeMsaa, MatchesCpuCoverageAndColours) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  for (const ParityScene& p : parityScenes()) {
    for (int samples : kSampleCounts) {
      const RenderOptions o = sampledOptions(samples);
      const Frame cpu = renderCpu(p.scene, o), frame = renderWith(*gpu, p.scene, o);
      const std::string what = std::string(p.what) + ", msaa " + std::to_string(samples);
      const Parity parity = compare(frame, cpu);
      report(what.c_str(), parity);
      EXPECT_LE(parity.max_channel_diff, 2) << what;
      EXPECT_TRUE(frame.coverage == cpu.coverage) << what;
      EXPECT_TRUE(frame.triangle_id == cpu.triangle_id) << what;
      EXPECT_TRUE(frame.depth == cpu.depth) << what;
    }
  }
}

TEST(VulkanComputeMsaa, ThirtyTwoBitCommitMatchesCpu) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  VulkanOptions vk;
  vk.force_32bit_atomics = true;
  ComputePtr gpu = makeCompute(vk);
  ASSERT_TRUE(gpu);
  const Scene scene = denseScene();
  for (int samples : {2, 8}) {
    const RenderOptions o = sampledOptions(samples);
    const Frame cpu = renderCpu(scene, o), frame = renderWith(*gpu, scene, o);
    expectComputeParity("32-bit commit, dense", compare(frame, cpu));
    EXPECT_TRUE(frame.coverage == cpu.coverage) << samples;
  }
}

TEST(VulkanComputeMsaa, JitteredFramesMatchCpu) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  const Scene scene = cubeWithLines();
  for (int samples : {1, 4})
    for (uint32_t i : {1u, 2u, 6u}) {
      const RenderOptions o = sampledOptions(samples, jitterOffset(i));
      const Frame cpu = renderCpu(scene, o), frame = renderWith(*gpu, scene, o);
      expectComputeParity("jittered cube", compare(frame, cpu));
      EXPECT_TRUE(frame.coverage == cpu.coverage) << samples << " samples, jitter " << i;
    }
}

TEST(VulkanComputeMsaa, AccumulationMatchesCpu) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  CpuRenderer cpu(1);
  const Scene scene = cubeScene();
  const RenderOptions o = sampledOptions(2);
  Accumulator gpu_sum, cpu_sum;
  Frame a, b;
  ASSERT_TRUE(gpu_sum.render(*gpu, scene, o, 8, a).ok());
  ASSERT_TRUE(cpu_sum.render(cpu, scene, o, 8, b).ok());
  expectComputeParity("8 jittered frames of 2x", compare(a, b));
  EXPECT_TRUE(a.coverage == b.coverage);
}

TEST(VulkanRasterMsaa, MatchesCpuWithinTheRasterTolerance) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(raster);
  int tested = 0;
  for (const ParityScene& p : parityScenes()) {
    for (int samples : kSampleCounts) {
      if (!rasterTakes(*raster, samples)) continue;
      ++tested;
      const RenderOptions o = sampledOptions(samples);
      const Frame cpu = renderCpu(p.scene, o), frame = renderWith(*raster, p.scene, o);
      const std::string what =
          std::string("raster: ") + p.what + ", msaa " + std::to_string(samples);
      const Parity parity = compare(frame, cpu);
      expectRasterParity(what.c_str(), parity);
      // An independent rasterizer: its centroids are not the contract's shading points, which
      // shows on minified textures along edges (textured at 4x: 96.9% within 2/255).
      EXPECT_GE(parity.colorRatio(), 0.95) << what;
      size_t coverage_close = 0;
      for (size_t i = 0; i < cpu.coverage.size(); ++i)
        coverage_close += std::abs(int(frame.coverage[i]) - int(cpu.coverage[i])) <= 64;
      EXPECT_GE(static_cast<double>(coverage_close) / cpu.coverage.size(), 0.999) << what;
    }
  }
  EXPECT_GE(tested, 2 * static_cast<int>(parityScenes().size()));
}

namespace {

// Two tiny green triangles, each round a pixel centre and far from every sample of the 2, 4 and
// 8 patterns (0.35 pixel or more away): one in front of a red rectangle (over pixel (5, 5)),
// one over the black background (pixel (15, 5)).
Scene centreOnlyScene(int width, int height) {
  Mesh mesh;
  auto add = [&](float x0, float y0, float x1, float y1, float x2, float y2, float z) {
    const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    for (float2 p : {float2{x0, y0}, float2{x1, y1}, float2{x2, y2}})
      mesh.positions.push_back(windowToNdc(p.x, p.y, z, width, height));
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
  };
  add(-1, -1, 11, -1, -1, 30, 0.5f);  // red, behind, over pixels (0..9, 0..9) at least
  add(11, 30, -1, 30, 11, -1, 0.5f);
  add(5.4f, 5.4f, 5.6f, 5.45f, 5.5f, 5.6f, 0.0f);  // green, in front
  add(15.4f, 5.4f, 15.6f, 5.45f, 15.5f, 5.6f, 0.0f);
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    mesh.colors.push_back(v < 6 ? float4{1, 0, 0, 1} : float4{0, 1, 0, 1});
  return whiteOnBlack(std::move(mesh));
}

// The contract: colour comes from the samples only. A triangle that covers a pixel centre and no
// sample leaves the pixel's colour and coverage to the samples; its id is the id AOV's.
template <typename B>
void expectCentreOnlyTrianglesLeaveTheColour(B& backend, int samples) {
  constexpr int kW = 20, kH = 10;
  RenderOptions o = options(kW, kH);
  o.msaa = samples;
  o.coverage = true;
  const Frame frame = renderWith(backend, centreOnlyScene(kW, kH), o);
  EXPECT_EQ(frame.colorAt(5, 5), 0xff0000ffu) << backend.name() << " " << samples;  // red
  EXPECT_EQ(frame.coverageAt(5, 5), 255) << backend.name() << " " << samples;
  EXPECT_EQ(frame.idAt(5, 5), 3u) << backend.name() << " " << samples;  // green, triangle 2
  EXPECT_EQ(frame.colorAt(15, 5), 0xff000000u) << backend.name() << " " << samples;  // black
  EXPECT_EQ(frame.coverageAt(15, 5), 0) << backend.name() << " " << samples;
  EXPECT_EQ(frame.idAt(15, 5), 4u) << backend.name() << " " << samples;
}

}  // namespace

TEST(VulkanComputeMsaa, CentreOnlyTriangleLeavesTheColour) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  for (int samples : {2, 4, 8}) expectCentreOnlyTrianglesLeaveTheColour(*gpu, samples);
}

TEST(VulkanRasterMsaa, CentreOnlyTriangleLeavesTheColour) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(raster);
  for (int samples : {2, 4, 8})
    if (rasterTakes(*raster, samples)) expectCentreOnlyTrianglesLeaveTheColour(*raster, samples);
}

namespace {

// The CPU renderer as the Vulkan fixtures see a backend (it has no validation layer).
struct CpuUnderTest {
  CpuRenderer cpu{2};
  const char* name() const { return cpu.name(); }
  void render(const Scene& scene, const RenderOptions& o, Frame& frame) {
    cpu.render(scene, o, frame);
  }
  Expected<void> lastResult() const { return cpu.lastResult(); }
  std::vector<std::string> validationErrors() const { return {}; }
};

}  // namespace

TEST(CpuMsaa, CentreOnlyTriangleLeavesTheColour) {
  // The oracle under the same rule (needs no Vulkan device).
  CpuUnderTest cpu;
  for (int samples : {2, 4, 8}) expectCentreOnlyTrianglesLeaveTheColour(cpu, samples);
}
