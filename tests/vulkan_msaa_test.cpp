// MSAA and jitter on the two Vulkan backends: coverage at the standard sample positions, the
// linear-light resolve, the pixel-centre AOVs that do not change with the sample count, the
// coverage AOV, jitter, and the device's sample-count limits.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <tessera/render/sampling.h>

#include "vulkan_fixtures.h"

using namespace tessera;
using namespace tessera::vulkan_test;

namespace {

constexpr int kSampleCounts[] = {1, 2, 4, 8};

// A white unlit rectangle on black covering window x < right and y < bottom (from beyond the
// top-left corner), in a width x height clip-space scene: two triangles sharing a diagonal.
Scene rectangleScene(float right, float bottom, int width, int height) {
  Scene scene = clipSpaceScene();
  scene.background = {0, 0, 0, 1};
  Mesh mesh;
  mesh.positions = {windowToNdc(-1, -1, 0, width, height), windowToNdc(right, -1, 0, width, height),
                    windowToNdc(right, bottom, 0, width, height),
                    windowToNdc(-1, bottom, 0, width, height)};
  mesh.indices = {0, 2, 1, 0, 3, 2};
  Object object;
  object.mesh = std::make_shared<Mesh>(mesh);
  object.shading = Shading::kUnlit;
  object.cull = CullMode::kNone;
  object.materials[0].base_color = {1, 1, 1, 1};
  scene.objects.push_back(object);
  return scene;
}

// The contract's image of rectangleScene, sample by sample: sample (sx, sy) of pixel (x, y) is
// covered when x + sx/256 < right - jitter.x and y + sy/256 < bottom - jitter.y (the right and
// bottom edges are not top-left edges: a sample exactly on one is outside). In 1/256 pixel.
struct ExpectedPixel {
  int covered = 0;
  uint32_t color = 0;
  uint8_t coverage = 0;
};
ExpectedPixel expectedRectanglePixel(int x, int y, int right256, int bottom256, int samples) {
  ExpectedPixel e;
  for (const SamplePosition& s : samplePattern(samples))
    e.covered += x * 256 + s.x < right256 && y * 256 + s.y < bottom256;
  const uint32_t grey = encodeSrgb8(static_cast<float>(e.covered) / static_cast<float>(samples));
  e.color = grey | grey << 8 | grey << 16 | 255u << 24;
  e.coverage = static_cast<uint8_t>((e.covered * 255 + samples / 2) / samples);
  return e;
}

// Renders rectangleScene(right, bottom) with `jitter` and checks every pixel's colour and
// coverage against the contract; returns how many pixels are partly covered.
template <typename B>
int expectRectangleResolves(B& backend, int samples, float right, float bottom, Jitter jitter) {
  constexpr int kW = 24, kH = 12;
  RenderOptions o = options(kW, kH);
  o.msaa = samples;
  o.coverage = true;
  o.jitter = jitter;
  const Frame frame = renderWith(backend, rectangleScene(right, bottom, kW, kH), o);
  const int right256 = static_cast<int>(std::lround((right - jitter.x) * 256));
  const int bottom256 = static_cast<int>(std::lround((bottom - jitter.y) * 256));
  int partial = 0, wrong = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const ExpectedPixel e = expectedRectanglePixel(x, y, right256, bottom256, samples);
      partial += e.covered > 0 && e.covered < samples;
      const bool ok = frame.colorAt(x, y) == e.color && frame.coverageAt(x, y) == e.coverage;
      if (!ok && ++wrong <= 5)
        ADD_FAILURE() << backend.name() << " msaa " << samples << " jitter (" << jitter.x << ", "
                      << jitter.y << ") pixel (" << x << ", " << y << "): colour " << std::hex
                      << frame.colorAt(x, y) << " coverage " << std::dec
                      << int(frame.coverageAt(x, y)) << ", expected " << std::hex << e.color
                      << " and " << std::dec << int(e.coverage) << " (" << e.covered << " of "
                      << samples << " samples)";
    }
  }
  EXPECT_EQ(wrong, 0) << backend.name() << " msaa " << samples;
  return partial;
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
