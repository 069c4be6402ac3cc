// The viewer's anti-aliasing without a window: the modes the keys switch and the temporal pass
// (reprojection, neighbourhood clamp, disocclusion, convergence at a still camera), on frames
// from a ray-cast backend whose every sample is known. Apart from viewer_test.cpp to keep each
// file to one concern.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include <tessera/math/projection.h>
#include <tessera/render/accumulate.h>
#include <tessera/scene/color.h>
#include <tessera/viewer/sampling_modes.h>
#include <tessera/viewer/temporal.h>

using namespace tessera;
using namespace tessera::viewer;

namespace {

TEST(SamplingModes, ShiftF3CyclesTheSampleCountsAndTheOverlaySaysTheMode) {
  SamplingModes modes(4, false, true);
  RenderOptions options;
  modes.prepare(options);
  EXPECT_EQ(options.msaa, 4);
  EXPECT_EQ(modes.describe(), "MSAA 4x, TAA (F10)");
  const int cycle[] = {8, 1, 2, 4};
  for (int expected : cycle) {
    modes.cycleMsaa();
    modes.prepare(options);
    EXPECT_EQ(options.msaa, expected);
  }
  EXPECT_EQ(SamplingModes(2, false, false).describe(), "MSAA 2x");
  EXPECT_EQ(SamplingModes(8, true, false).describe(), "MSAA 8x, jitter");
  EXPECT_EQ(SamplingModes(1, true, true).describe(), "MSAA 1x, jitter, TAA 0/16");
}

TEST(SamplingModes, JitterTakesEachOffsetOfTheCycleInTurnAndAsksForDepthWithTemporal) {
  SamplingModes modes(1, false, true);
  RenderOptions options;
  modes.prepare(options);
  EXPECT_EQ(options.jitter.x, 0.0f);
  EXPECT_FALSE(options.depth);  // nothing to reproject without jitter
  EXPECT_FALSE(modes.wantsAnotherFrame());
  modes.toggleJitter();
  EXPECT_TRUE(modes.wantsAnotherFrame());
  for (uint32_t i = 0; i < 2 * kJitterCycle; ++i) {
    modes.prepare(options);
    const Jitter expected = jitterOffset(i % kJitterCycle);
    EXPECT_EQ(options.jitter.x, expected.x) << i;
    EXPECT_EQ(options.jitter.y, expected.y) << i;
    EXPECT_TRUE(options.depth);
  }
  modes.toggleTemporal();
  modes.prepare(options);
  EXPECT_FALSE(options.depth);
  EXPECT_TRUE(modes.wantsAnotherFrame());  // raw jittered frames change every frame
}

// A frame of one colour, its depth in the middle of the range: what a still camera sees.
Frame flatFrame(uint32_t color) {
  Frame frame;
  frame.resize(8, 8, /*with_depth=*/true, false, false);
  std::fill(frame.color.begin(), frame.color.end(), color);
  std::fill(frame.depth.begin(), frame.depth.end(), 0.5f);
  return frame;
}

TEST(SamplingModes, TemporalReprojectionRestsInTheNonlinearProjectionsAndRestartsOnASwitch) {
  SamplingModes modes(1, /*jitter=*/true, /*temporal=*/true);
  const float4x4 view_projection = perspective(radians(50.0f), 1.0f, 0.5f, 50.0f);
  RenderOptions options;
  const uint32_t dark = 0xff202020u, light = 0xffe0e0e0u;
  // Perspective: the second frame at a still camera is blended with the first.
  for (uint32_t color : {dark, light}) {
    Frame frame = flatFrame(color);
    modes.prepare(options);
    EXPECT_TRUE(options.depth);
    modes.finish(frame, view_projection);
    if (color == light) {
      EXPECT_NE(frame.color[0], light);
    }
  }
  EXPECT_EQ(modes.describe(), "MSAA 1x, jitter, TAA 2/16");
  // Spherical: no depth asked for, every frame shown as drawn, the jitter cycling for ever.
  modes.setProjection(Projection::kSpherical);
  EXPECT_EQ(modes.describe(), "MSAA 1x, jitter, TAA: perspective only");
  for (int i = 0; i < 2 * kJitterCycle; ++i) {
    const uint32_t color = i % 2 ? dark : light;
    Frame frame = flatFrame(color);
    modes.prepare(options);
    EXPECT_FALSE(options.depth);
    modes.finish(frame, view_projection);
    EXPECT_EQ(frame.color[0], color) << i;
    EXPECT_TRUE(modes.wantsAnotherFrame());
  }
  // Back in perspective the history starts again: the first frame is shown as drawn.
  modes.setProjection(Projection::kPerspective);
  EXPECT_EQ(modes.describe(), "MSAA 1x, jitter, TAA 0/16");
  Frame frame = flatFrame(light);
  modes.prepare(options);
  modes.finish(frame, view_projection);
  EXPECT_EQ(frame.color[0], light);
  // Without jitter a nonlinear mode still says why the temporal pass is idle.
  SamplingModes plain(4, false, true);
  plain.setProjection(Projection::kFisheye);
  EXPECT_EQ(plain.describe(), "MSAA 4x, TAA: perspective only");
}

// Discs facing +Z at a given z, drawn by casting each sample's ray (no rasterizer): a backend
// whose every pixel, depth and jitter the tests know exactly.
struct Disc {
  float3 centre;
  float radius;
  float3 color;  // linear
};

class DiscBackend : public Backend {
 public:
  std::vector<Disc> discs;
  float3 background{0.02f, 0.02f, 0.05f};

  const char* name() const override { return "discs"; }
  void render(const Scene& scene, const RenderOptions& options, Frame& frame) override {
    const int w = options.width, h = options.height;
    frame.resize(w, h, /*with_depth=*/true, false, false);
    const float4x4 vp = scene.camera.projection(static_cast<float>(w) / h) * scene.camera.view();
    const float4x4 inv = inverse(vp);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float nx = 2.0f * (x + 0.5f + options.jitter.x) / w - 1.0f;
        const float ny = 1.0f - 2.0f * (y + 0.5f + options.jitter.y) / h;
        const float3 from = unproject(inv, {nx, ny, -1.0f}), to = unproject(inv, {nx, ny, 1.0f});
        float best = std::numeric_limits<float>::infinity();
        float3 color = background;
        for (const Disc& d : discs) {
          const float t = (d.centre.z - from.z) / (to.z - from.z);
          const float3 p = from + (to - from) * t;
          if (t > 0.0f && t < best && length(p - d.centre) < d.radius) best = t, color = d.color;
        }
        const size_t i = static_cast<size_t>(y) * w + x;
        frame.color[i] = packSrgba8({color, 1.0f});
        frame.depth[i] = std::numeric_limits<float>::infinity();
        if (std::isfinite(best)) {
          const float4 clip = vp * float4{from + (to - from) * best, 1.0f};
          frame.depth[i] = clip.z / clip.w * 0.5f + 0.5f;
        }
      }
  }
  static float3 unproject(const float4x4& inv, float3 ndc) {
    const float4 p = inv * float4{ndc, 1.0f};
    return p.xyz() / p.w;
  }
};

constexpr int kSize = 40;

Scene sceneFrom(float3 position, float3 target) {
  Scene scene;
  scene.camera.position = position;
  scene.camera.target = target;
  scene.camera.near_z = 0.5f;
  scene.camera.far_z = 50.0f;
  return scene;
}

float4x4 viewProjection(const Scene& scene) {
  return scene.camera.projection(1.0f) * scene.camera.view();
}

// A red disc in front of a large grey one, edges at every angle.
DiscBackend occluderScene() {
  DiscBackend backend;
  backend.discs = {{{0, 0, 0}, 3.0f, {0.3f, 0.3f, 0.3f}},
                   {{0.1f, 0.05f, 2.0f}, 0.8f, {0.9f, 0.1f, 0.05f}}};
  return backend;
}

// Renders with `jitter` and resolves the frame.
void step(DiscBackend& backend, TemporalResolver& resolver, const Scene& scene, Jitter jitter,
          Frame& frame) {
  RenderOptions options;
  options.width = options.height = kSize;
  options.jitter = jitter;
  backend.render(scene, options, frame);
  resolver.resolve(frame, viewProjection(scene), jitter);
}

int maxChannelDifference(uint32_t a, uint32_t b) {
  int most = 0;
  for (int shift = 0; shift < 24; shift += 8)
    most = std::max(most, std::abs(static_cast<int>((a >> shift) & 0xff) -
                                   static_cast<int>((b >> shift) & 0xff)));
  return most;
}

TEST(Temporal, AStillCameraConvergesToTheAccumulatorsAverageAndStays) {
  DiscBackend backend = occluderScene();
  const Scene scene = sceneFrom({0, 0, 6}, {0, 0, 0});
  RenderOptions options;
  options.width = options.height = kSize;
  Frame expected;
  Accumulator accumulator;
  ASSERT_TRUE(accumulator.render(backend, scene, options, kJitterCycle, expected).ok());
  Frame plain;
  backend.render(scene, options, plain);

  TemporalResolver resolver;
  Frame frame;
  for (uint32_t i = 0; i < kJitterCycle; ++i) {
    EXPECT_FALSE(resolver.converged()) << i;
    step(backend, resolver, scene, jitterOffset(i), frame);
  }
  EXPECT_TRUE(resolver.converged());
  int edges = 0;
  for (size_t i = 0; i < frame.pixelCount(); ++i) {
    EXPECT_LE(maxChannelDifference(frame.color[i], expected.color[i]), 1) << "pixel " << i;
    if (expected.color[i] != plain.color[i]) ++edges;
  }
  EXPECT_GT(edges, 40);  // the jitter did smooth the discs' edges
  // Further frames at the same camera leave the converged image alone.
  const std::vector<uint32_t> converged = frame.color;
  for (uint32_t i = 0; i < 5; ++i) step(backend, resolver, scene, jitterOffset(i), frame);
  EXPECT_EQ(frame.color, converged);
}

TEST(Temporal, AMovedCameraReprojectsAPixelToWhereItsPointWas) {
  DiscBackend backend = occluderScene();
  const Scene before = sceneFrom({0, 0, 6}, {0, 0, 0});
  const Scene after = sceneFrom({0.7f, 0.4f, 5.5f}, {0.2f, 0.1f, 0});
  RenderOptions options;
  options.width = options.height = kSize;
  Frame frame;
  backend.render(after, options, frame);
  const float4x4 current = viewProjection(after), previous = viewProjection(before);
  const float4x4 inverse_current = inverse(current);
  // On the red disc (z = 2) and on the grey one (z = 0): where the pixel centre's ray meets the
  // disc's plane, projected by the previous camera.
  const std::pair<int2, float> pixels[] = {{{20, 20}, 2.0f}, {{5, 30}, 0.0f}};
  for (const auto& [pixel, plane_z] : pixels) {
    const float depth = frame.depthAt(pixel.x, pixel.y);
    ASSERT_TRUE(std::isfinite(depth));
    const float nx = 2.0f * (pixel.x + 0.5f) / kSize - 1.0f;
    const float ny = 1.0f - 2.0f * (pixel.y + 0.5f) / kSize;
    const float3 from = after.camera.position;
    const float3 direction = DiscBackend::unproject(inverse_current, {nx, ny, 1.0f}) - from;
    const float3 world = from + direction * ((plane_z - from.z) / direction.z);
    const float4 clip = previous * float4{world, 1.0f};
    const Reprojected r = reprojectPixel(previous * inverse_current, inverse_current, pixel.x,
                                         pixel.y, depth, kSize, kSize);
    EXPECT_NEAR(r.x, (clip.x / clip.w + 1.0f) * 0.5f * kSize, 2e-3f);
    EXPECT_NEAR(r.y, (1.0f - clip.y / clip.w) * 0.5f * kSize, 2e-3f);
    EXPECT_NEAR(r.view_depth, -(before.camera.view() * float4{world, 1.0f}).z, 1e-3f);
    // The camera moved enough for this to matter.
    EXPECT_GT(std::fabs(r.x - (pixel.x + 0.5f)) + std::fabs(r.y - (pixel.y + 0.5f)), 1.5f);
  }
}

// The summed channel differences of two images.
long imageDifference(const Frame& a, const Frame& b) {
  long sum = 0;
  for (size_t i = 0; i < a.pixelCount(); ++i)
    for (int shift = 0; shift < 24; shift += 8)
      sum += std::abs(static_cast<int>((a.color[i] >> shift) & 0xff) -
                      static_cast<int>((b.color[i] >> shift) & 0xff));
  return sum;
}

TEST(Temporal, WhileTheCameraMovesTheImageIsNearerTheSupersampledOne) {
  // A slow pan, a new jitter offset each frame: the blended history smooths the edges that
  // each raw frame has stair-stepped.
  DiscBackend backend = occluderScene();
  TemporalResolver resolver;
  Frame frame;
  Scene scene;
  for (uint32_t i = 0; i < 24; ++i) {
    const float x = 0.004f * static_cast<float>(i);
    scene = sceneFrom({x, 0, 6}, {x, 0, 0});
    step(backend, resolver, scene, jitterOffset(i % kJitterCycle), frame);
  }
  RenderOptions options;
  options.width = options.height = kSize;
  options.jitter = jitterOffset(23 % kJitterCycle);
  Frame raw, supersampled;
  backend.render(scene, options, raw);
  options.jitter = {};
  Accumulator accumulator;
  ASSERT_TRUE(accumulator.render(backend, scene, options, kJitterCycle, supersampled).ok());
  const long blended_error = imageDifference(frame, supersampled);
  const long raw_error = imageDifference(raw, supersampled);
  EXPECT_LT(blended_error * 2, raw_error) << blended_error << " against " << raw_error;
}

TEST(Temporal, HistoryFollowsTheCameraAcrossStripes) {
  // Red dots on every other pixel centre of the middle row, on blue, seen square on at distance
  // 6; the camera then moves by exactly one pixel, so that each pixel's history is its
  // neighbour's colour where it was and the other colour where it is.
  DiscBackend backend;
  const float pixel = 2.0f * 6.0f * std::tan(radians(25.0f)) / kSize;
  const int y = kSize / 2;
  for (int column = 0; column < kSize + 2; column += 2)
    backend.discs.push_back(
        {{(column + 0.5f - kSize / 2) * pixel, (kSize / 2 - y - 0.5f) * pixel, 0},
         0.4f * pixel,
         {0.8f, 0.1f, 0.1f}});
  backend.background = {0.1f, 0.1f, 0.8f};
  // The plane behind the dots gives every pixel a depth.
  backend.discs.push_back({{0, 0, -0.01f}, 100.0f, backend.background});
  TemporalResolver resolver;
  Frame frame;
  step(backend, resolver, sceneFrom({0, 0, 6}, {0, 0, 0}), {}, frame);
  const Scene moved = sceneFrom({pixel, 0, 6}, {pixel, 0, 0});
  step(backend, resolver, moved, {}, frame);
  Frame current;
  RenderOptions options;
  options.width = options.height = kSize;
  backend.render(moved, options, current);
  int red = 0;
  for (int x = 2; x < kSize - 2; ++x) {
    EXPECT_LE(maxChannelDifference(frame.colorAt(x, y), current.colorAt(x, y)), 1) << x;
    if ((current.colorAt(x, y) & 0xff) > 200) ++red;
  }
  EXPECT_GT(red, kSize / 4);  // the dots are there, every other pixel
}

float3 yCoCg(uint32_t srgb) {
  const float3 c{decodeSrgb8(srgb & 0xff), decodeSrgb8((srgb >> 8) & 0xff),
                 decodeSrgb8((srgb >> 16) & 0xff)};
  return {0.25f * c.x + 0.5f * c.y + 0.25f * c.z, 0.5f * c.x - 0.5f * c.z,
          -0.25f * c.x + 0.5f * c.y - 0.25f * c.z};
}

TEST(Temporal, StaleHistoryIsClampedToTheColoursAroundThePixelNow) {
  // The grey disc turns blue between two frames (without a reset, as a highlight that moves
  // would). Grey lies outside the YCoCg box of blue, red and the background, so no blend of it
  // may leave the box of the colours around its pixel now.
  DiscBackend backend = occluderScene();
  TemporalResolver resolver;
  Frame frame;
  for (uint32_t i = 0; i < 4; ++i)
    step(backend, resolver, sceneFrom({0, 0, 6}, {0, 0, 0}), jitterOffset(i), frame);
  backend.discs[0].color = {0.1f, 0.1f, 0.9f};
  const Scene moved = sceneFrom({0.1f, 0, 6}, {0.1f, 0, 0});
  step(backend, resolver, moved, jitterOffset(4), frame);
  Frame current;
  RenderOptions options;
  options.width = options.height = kSize;
  options.jitter = jitterOffset(4);
  backend.render(moved, options, current);
  int mixed = 0;
  for (int y = 1; y < kSize - 1; ++y)
    for (int x = 1; x < kSize - 1; ++x) {
      float3 lo = yCoCg(current.colorAt(x, y)), hi = lo;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          lo = min(lo, yCoCg(current.colorAt(x + dx, y + dy)));
          hi = max(hi, yCoCg(current.colorAt(x + dx, y + dy)));
        }
      if (hi == lo) continue;
      ++mixed;
      const float3 c = yCoCg(frame.colorAt(x, y));
      constexpr float kEncoding = 0.01f;  // an 8-bit code, and the clamp's round trip
      for (int k = 0; k < 3; ++k) {
        EXPECT_GE(c[k], lo[k] - kEncoding) << x << "," << y << " component " << k;
        EXPECT_LE(c[k], hi[k] + kEncoding) << x << "," << y << " component " << k;
      }
    }
  EXPECT_GT(mixed, 50);
}

TEST(Temporal, ADisoccludedPixelStartsAgainFromTheCurrentFrame) {
  DiscBackend backend = occluderScene();
  const Scene before = sceneFrom({0, 0, 6}, {0, 0, 0});
  const Scene after = sceneFrom({1.0f, 0, 6}, {1.0f, 0, 0});
  TemporalResolver resolver;
  Frame frame;
  step(backend, resolver, before, jitterOffset(3), frame);
  step(backend, resolver, after, jitterOffset(4), frame);
  // The raw frames, before and after the move.
  RenderOptions options;
  options.width = options.height = kSize;
  options.jitter = jitterOffset(3);
  Frame previous, current;
  backend.render(before, options, previous);
  options.jitter = jitterOffset(4);
  backend.render(after, options, current);

  const float4x4 inverse_current = inverse(viewProjection(after));
  const float4x4 reprojection = viewProjection(before) * inverse_current;
  const uint32_t red = packSrgba8({0.9f, 0.1f, 0.05f, 1.0f});
  int disoccluded = 0;
  for (int y = 1; y < kSize - 1; ++y)
    for (int x = 1; x < kSize - 1; ++x) {
      // Grey now and red in all four history pixels around where it was (hidden by the red
      // disc), with red beside it now: the neighbourhood clamp would keep that history, so only
      // the reset gives the current colour.
      const float depth = current.depthAt(x, y);
      if (!std::isfinite(depth) || current.colorAt(x, y) == red) continue;
      const Reprojected r =
          reprojectPixel(reprojection, inverse_current, x, y, depth, kSize, kSize);
      const int x0 = static_cast<int>(std::floor(r.x - 0.5f));
      const int y0 = static_cast<int>(std::floor(r.y - 0.5f));
      if (x0 < 0 || y0 < 0 || x0 + 1 >= kSize || y0 + 1 >= kSize) continue;
      bool red_before = true, red_beside = false;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) red_before &= previous.colorAt(x0 + dx, y0 + dy) == red;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) red_beside |= current.colorAt(x + dx, y + dy) == red;
      if (!red_before || !red_beside) continue;
      ++disoccluded;
      EXPECT_EQ(frame.colorAt(x, y), current.colorAt(x, y)) << x << "," << y;
    }
  EXPECT_GT(disoccluded, 3);
}

TEST(Temporal, AResetOrANewSizeStartsFromTheCurrentFrame) {
  DiscBackend backend = occluderScene();
  const Scene scene = sceneFrom({0, 0, 6}, {0, 0, 0});
  TemporalResolver resolver;
  Frame frame;
  for (uint32_t i = 0; i < 3; ++i) step(backend, resolver, scene, jitterOffset(i), frame);
  backend.discs.pop_back();  // the red disc is gone: a new model
  resolver.reset();
  step(backend, resolver, scene, jitterOffset(3), frame);
  Frame current;
  RenderOptions options;
  options.width = options.height = kSize;
  options.jitter = jitterOffset(3);
  backend.render(scene, options, current);
  EXPECT_EQ(frame.color, current.color);
  EXPECT_EQ(resolver.stillFrames(), 1);
  // A frame of another size starts afresh by itself.
  options.width = kSize / 2;
  backend.render(scene, options, current);
  Frame small = current;
  resolver.resolve(small, viewProjection(scene), options.jitter);
  EXPECT_EQ(small.color, current.color);
}

}  // namespace
