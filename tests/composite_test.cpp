// Tests of compositing over the background (composite.h): a transparent background's alpha and
// premultiplied colour at every sample count, --opacity's mix in linear light, straight alpha for
// PNG, lines and accumulation over a transparent background, and the ground grid (ground_grid.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include <tessera/model/ground_grid.h>
#include <tessera/render/accumulate.h>
#include <tessera/render/composite.h>
#include <tessera/scene/color.h>

#include "environment_test_scenes.h"
#include "msaa_test_scenes.h"

using namespace tessera;
using namespace tessera::test;

namespace {

constexpr int kSize = 32;

// White, unlit, covering columns 0..9 whole and half of column 10 (its edge at x = 10.5).
Scene halfColumnScene(float4 background) {
  Mesh mesh;
  const SubPixel v[4] = {
      {-256, -256}, {10 * 256 + 128, -256}, {10 * 256 + 128, 33 * 256}, {-256, 33 * 256}};
  for (const SubPixel& p : v) mesh.positions.push_back(toNdc(p, 0.0f, kSize, kSize));
  mesh.indices = {0, 1, 2, 0, 2, 3};
  Scene scene = clipSpaceScene();
  scene.objects.push_back(unlitMesh(mesh));
  scene.background = background;
  return scene;
}

uint32_t alphaOf(uint32_t rgba) {
  return rgba >> 24;
}

}  // namespace

TEST(Composite, TransparentBackgroundGivesCoverageAsAlpha) {
  const Scene scene = halfColumnScene({0, 0, 0, 0});
  for (int n : {1, 2, 4, 8}) {
    SCOPED_TRACE(n);
    RenderOptions options = optionsFor(kSize, kSize, n);
    options.coverage = false;  // asked for by the composite itself
    const Frame frame = render(scene, options);
    for (int y = 0; y < kSize; ++y) {
      EXPECT_EQ(frame.colorAt(9, y), 0xffffffffu);
      EXPECT_EQ(frame.colorAt(11, y), 0u);  // the background: transparent black
      if (n == 1) {
        EXPECT_EQ(frame.colorAt(10, y), 0u);  // the centre (10.5) is on a right edge: outside
      } else {
        // Half the samples: alpha 128, the colour white premultiplied by a half (linear).
        EXPECT_EQ(alphaOf(frame.colorAt(10, y)), 128u) << y;
        EXPECT_EQ(frame.colorAt(10, y) & 0xffffff, 0xbcbcbcu) << y;
      }
    }
  }
}

TEST(Composite, StraightAlphaUndoesThePremultiply) {
  const Scene scene = halfColumnScene({0, 0, 0, 0});
  Frame frame = render(scene, optionsFor(kSize, kSize, 4));
  std::vector<uint32_t> pixels = frame.color;
  straightAlpha(pixels);
  EXPECT_EQ(pixels[10], 0x80ffffffu);  // white at half alpha
  EXPECT_EQ(pixels[9], 0xffffffffu);
  EXPECT_EQ(pixels[11], 0u);
  // A premultiplied linear quarter at alpha 128 is a straight linear half.
  std::vector<uint32_t> one = {encodeSrgb8(0.25f) | 128u << 24};
  straightAlpha(one);
  EXPECT_NEAR(decodeSrgb8(static_cast<uint8_t>(one[0])), 0.25f * 255.0f / 128.0f, 0.01f);
}

TEST(Composite, OpaqueBackgroundAndFullOpacityChangeNothing) {
  const Scene scene = halfColumnScene({0.2f, 0.3f, 0.4f, 1});
  EXPECT_FALSE(needsComposite(scene, optionsFor(kSize, kSize, 4)));
  const Frame plain = render(scene, optionsFor(kSize, kSize, 4));
  Frame again = plain;
  compositeOverBackground(scene.background, 1.0f, again);
  EXPECT_EQ(again.color, plain.color);
}

TEST(Composite, OpacityMixesTheSurfaceWithTheBackgroundInLinearLight) {
  // White at opacity 0.5 over black: linear 0.5 (sRGB 188) where covered, a quarter at the half
  // covered column; the background stays and the alpha stays opaque.
  const Scene scene = halfColumnScene({0, 0, 0, 1});
  for (int n : {1, 4}) {
    SCOPED_TRACE(n);
    RenderOptions options = optionsFor(kSize, kSize, n);
    options.opacity = 0.5f;
    const Frame frame = render(scene, options);
    EXPECT_EQ(frame.colorAt(5, 5), 0xffbcbcbcu);
    EXPECT_EQ(frame.colorAt(11, 5), 0xff000000u);
    if (n == 4) {
      EXPECT_EQ(frame.colorAt(10, 5), 0xff000000u | 0x010101u * encodeSrgb8(0.25f));
    }
  }
  // Opacity 0: the background only.
  RenderOptions none = optionsFor(kSize, kSize, 4);
  none.opacity = 0.0f;
  const Frame frame = render(scene, none);
  for (uint32_t c : frame.color) EXPECT_EQ(c, 0xff000000u);
}

TEST(Composite, OpacityOverATransparentBackgroundScalesAlpha) {
  const Scene scene = halfColumnScene({0, 0, 0, 0});
  RenderOptions options = optionsFor(kSize, kSize, 4);
  options.opacity = 0.5f;
  const Frame frame = render(scene, options);
  EXPECT_EQ(alphaOf(frame.colorAt(5, 5)), 128u);
  EXPECT_EQ(alphaOf(frame.colorAt(10, 5)), 64u);
  std::vector<uint32_t> pixels = frame.color;
  straightAlpha(pixels);
  EXPECT_EQ(pixels[5 * kSize + 5] & 0xffffff, 0xffffffu);  // still white, half seen
}

TEST(Composite, LinesOverATransparentBackgroundAreSeen) {
  // A white anti-aliased line over nothing: its pixels' alphas carry its ink.
  Scene scene = clipSpaceScene();
  scene.background = {0, 0, 0, 0};
  scene.lines.add(toNdc({2 * 256, 10 * 256 + 77}, 0.0f, 64, 64),
                  toNdc({62 * 256, 21 * 256 + 200}, 0.0f, 64, 64), float3{1, 1, 1});
  const Frame frame = render(scene, optionsFor(64, 64, 4));
  for (int x = 4; x < 60; ++x) {
    float alpha = 0;
    for (int y = 0; y < 64; ++y) alpha += static_cast<float>(alphaOf(frame.colorAt(x, y))) / 255;
    EXPECT_NEAR(alpha, 1.0f, 0.02f) << x;
  }
}

TEST(Composite, AccumulationAveragesAlpha) {
  // Jittered frames of the half-covered column: alpha and premultiplied colour both average, so
  // the straight colour stays white.
  const Scene scene = halfColumnScene({0, 0, 0, 0});
  CpuRenderer renderer(1);
  Accumulator accumulator;
  Frame frame;
  ASSERT_TRUE(accumulator.render(renderer, scene, optionsFor(kSize, kSize, 1), 16, frame));
  const uint32_t edge = frame.colorAt(10, 5);
  EXPECT_GT(alphaOf(edge), 40u);
  EXPECT_LT(alphaOf(edge), 215u);
  std::vector<uint32_t> pixels = {edge};
  straightAlpha(pixels);
  EXPECT_GE(pixels[0] & 0xff, 250u);
  EXPECT_EQ(frame.colorAt(5, 5), 0xffffffffu);
  EXPECT_EQ(frame.colorAt(20, 5), 0u);
}

TEST(GroundGrid, UnitIsAPowerOfTenOrHalfOne) {
  auto unitFor = [](float radius) {
    Bounds b;
    b.add({-radius, 0, 0});
    b.add({radius, 0, 0});
    return model::gridUnit(b);
  };
  EXPECT_FLOAT_EQ(unitFor(1.0f), 0.5f);
  EXPECT_FLOAT_EQ(unitFor(9.0f), 0.5f);
  EXPECT_FLOAT_EQ(unitFor(20.0f), 5.0f);
  EXPECT_NEAR(unitFor(0.02f), 0.005f, 1e-7f);
}

TEST(GroundGrid, LiesUnderTheModelAcrossTheUpAxis) {
  Bounds b;
  b.add({-1, 2, -1});
  b.add({1, 4, 1});  // radius sqrt(3): unit 0.5, half 1.5 * 1.73 = 2.6 -> 3
  LineList y_up;
  model::appendGroundGrid(b, {0, 1, 0}, y_up);
  ASSERT_EQ(y_up.points.size(), 2u * 2u * 13u);  // 13 lines each way over 12 cells
  for (const float3& p : y_up.points) {
    EXPECT_NEAR(p.y, 2.0f, 1e-3f);
    EXPECT_LT(p.y, 2.0f);  // a hair below the lowest point
    EXPECT_LE(std::fabs(p.x), 3.0f + 1e-5f);
    EXPECT_LE(std::fabs(p.z), 3.0f + 1e-5f);
  }
  // Every line runs along x or along z, a whole number of units from the origin.
  for (size_t i = 0; i < y_up.points.size(); i += 2) {
    const float3 a = y_up.points[i], c = y_up.points[i + 1];
    const bool along_x = a.z == c.z;
    EXPECT_TRUE(along_x || a.x == c.x);
    const float offset = along_x ? a.z : a.x;
    EXPECT_NEAR(offset / 0.5f, std::round(offset / 0.5f), 1e-4f);
  }
  // Down -Z: the plane z = max (the model's lowest point along -Z).
  LineList z_down;
  model::appendGroundGrid(b, {0, 0, -1}, z_down);
  for (const float3& p : z_down.points) EXPECT_NEAR(p.z, 1.0f, 1e-3f);
  LineList none;
  model::appendGroundGrid(Bounds{}, {0, 1, 0}, none);
  EXPECT_TRUE(none.points.empty());
}

// ---- The environment behind the model (--hdri-background) ----

using test::skyEnvironment;

TEST(Composite, EnvironmentBackgroundShowsTheSkyAboveAndTheGroundBelow) {
  Scene scene;
  scene.camera.position = {0, 0, 0};
  scene.camera.target = {0, 0, -1};
  scene.camera.fov_y_degrees = 90.0f;
  scene.environment = skyEnvironment({1, 1, 1}, {0, 0, 0});
  scene.environment_background = true;
  // The same picture with +Z up: the camera looks along -Y and the environment is turned so.
  Scene z_up = scene;
  z_up.camera.target = {0, -1, 0};
  z_up.camera.up = {0, 0, 1};
  z_up.world_to_environment.col[0] = {1, 0, 0};
  z_up.world_to_environment.col[1] = {0, 0, -1};
  z_up.world_to_environment.col[2] = {0, 1, 0};
  for (const Scene* s : {&scene, &z_up}) {
    const Frame frame = render(*s, optionsFor(kSize, kSize, 1));
    for (int x = 0; x < kSize; x += 5) {
      for (int y = 0; y <= 10; ++y) EXPECT_EQ(frame.colorAt(x, y), 0xffffffffu) << x << " " << y;
      for (int y = 21; y < kSize; ++y) EXPECT_EQ(frame.colorAt(x, y), 0xff000000u) << x << " " << y;
    }
  }
  // Without environment_background the environment lights but is not seen.
  scene.environment_background = false;
  const Frame plain = render(scene, optionsFor(kSize, kSize, 1));
  EXPECT_EQ(plain.colorAt(0, 0), 0xff000000u);
}

// A pixel half covered by white over an environment of linear 0.5: 0.5 + 0.5 x 0.5 = 0.75
// (code 225), the uncovered ones 0.5 (188); the plain background (black) is gone.
TEST(Composite, EnvironmentFillsTheShareOfAPixelTheModelLeaves) {
  Scene scene = halfColumnScene({0, 0, 0, 1});
  scene.environment = skyEnvironment({0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f});
  scene.environment_background = true;
  const Frame frame = render(scene, optionsFor(kSize, kSize, 4));
  for (int y = 0; y < kSize; y += 3) {
    EXPECT_EQ(frame.colorAt(9, y), 0xffffffffu);
    EXPECT_EQ(frame.colorAt(10, y), 0xffe1e1e1u) << y;
    EXPECT_EQ(frame.colorAt(11, y), 0xffbcbcbcu) << y;
  }
}
