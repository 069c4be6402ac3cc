// alphaMode BLEND (blend.h): blended triangles are drawn after the opaque ones, back to front,
// with the over operator in linear light, behind the opaque depth; the same bits for any worker
// count, instruction set, visibility mode, and their order of submission.
#include <gtest/gtest.h>

#include <cmath>

#include <tessera/scene/color.h>

#include "render_test_scenes.h"

namespace tessera {
namespace {

constexpr int kWidth = 32, kHeight = 16;

// A quad over window columns [x0, x1) and every row, at window depth z.
Object quad(float x0, float x1, float z, float4 color, AlphaMode mode) {
  Mesh m;
  for (float2 p : {float2{x0, 0}, float2{x1, 0}, float2{x1, kHeight}, float2{x0, kHeight}})
    m.positions.push_back(test::windowToNdc(p.x, p.y, z, kWidth, kHeight));
  m.indices = {0, 1, 2, 0, 2, 3};
  Object o = test::unlitObject(std::move(m));
  o.materials[0].base_color = color;
  o.materials[0].alpha_mode = mode;
  return o;
}

const float4 kRedHalf{1, 0, 0, 0.5f}, kBlueQuarter{0, 0, 1, 0.25f};

// An opaque green quad at the back over columns [0, 24), a half-transparent red quad at depth
// 0.5 and a quarter-transparent blue one at 0.3, both full width; `red_first` submits red first.
Scene blendScene(bool red_first) {
  Scene scene = test::clipSpaceScene();
  scene.background = {0, 0, 0, 1};
  scene.objects.push_back(quad(0, 24, 0.8f, {0, 1, 0, 1}, AlphaMode::kOpaque));
  Object red = quad(0, kWidth, 0.5f, kRedHalf, AlphaMode::kBlend);
  Object blue = quad(0, kWidth, 0.3f, kBlueQuarter, AlphaMode::kBlend);
  if (red_first) {
    scene.objects.push_back(red);
    scene.objects.push_back(blue);
  } else {
    scene.objects.push_back(blue);
    scene.objects.push_back(red);
  }
  return scene;
}

Frame render(const Scene& scene, int msaa = 1, Visibility visibility = Visibility::kDepthBuffer,
             SimdLevel level = SimdLevel::kAuto, int workers = 1, bool aovs = true) {
  RenderOptions options;
  options.width = kWidth;
  options.height = kHeight;
  options.msaa = msaa;
  options.visibility = visibility;
  options.ids = aovs;
  options.depth = aovs;
  return test::renderAt(scene, options, level, workers);
}

// The over operator in linear light: blue over (red over `behind`).
float3 expected(float3 behind) {
  const float3 red = float3{1, 0, 0} * 0.5f + behind * 0.5f;
  return float3{0, 0, 1} * 0.25f + red * 0.75f;
}

void expectColor(uint32_t got, float3 want, int x, int y) {
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(static_cast<int>((got >> (8 * k)) & 0xff), encodeSrgb8(want[k]), 1)
        << "channel " << k << " at " << x << "," << y;
}

TEST(AlphaBlend, TwoQuadsGiveTheOverOperatorInLinearLightInEitherOrder) {
  for (bool red_first : {true, false}) {
    const Frame f = render(blendScene(red_first));
    for (int y = 0; y < kHeight; y += 5)
      for (int x = 0; x < kWidth; x += 3) {
        const float3 behind = x < 24 ? float3{0, 1, 0} : float3{0, 0, 0};
        expectColor(f.color[y * kWidth + x], expected(behind), x, y);
        // The AOVs stay the opaque surface's: the green quad's triangles, or nothing.
        const size_t at = static_cast<size_t>(y) * kWidth + x;
        if (x < 24) {
          EXPECT_LE(f.triangle_id[at], 2u);
          EXPECT_NEAR(f.depth[at], 0.9f, 1e-5f);  // NDC z 0.8
        } else {
          EXPECT_EQ(f.triangle_id[at], kNoTriangle);
        }
      }
  }
}

TEST(AlphaBlend, SubmissionOrderDoesNotChangeABit) {
  EXPECT_EQ(render(blendScene(true)).color, render(blendScene(false)).color);
}

TEST(AlphaBlend, AnOpaqueSurfaceInFrontHidesTheBlendedOnes) {
  Scene scene = blendScene(true);
  scene.objects.push_back(quad(8, 16, 0.1f, {1, 1, 1, 1}, AlphaMode::kOpaque));
  const Frame f = render(scene);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 8; x < 16; ++x) ASSERT_EQ(f.color[y * kWidth + x], 0xffffffffu) << x;
  expectColor(f.color[4], expected({0, 1, 0}), 4, 0);
}

TEST(AlphaBlend, SameBitsForEveryWorkerCountInstructionSetAndVisibility) {
  const Scene scene = blendScene(true);
  const Frame reference = render(scene);
  for (SimdLevel level : {SimdLevel::kScalar, SimdLevel::kSse2, SimdLevel::kAvx2})
    for (int workers : {1, 3}) {
      EXPECT_EQ(render(scene, 1, Visibility::kDepthBuffer, level, workers).color, reference.color);
      EXPECT_EQ(render(scene, 4, Visibility::kDepthBuffer, level, workers).color,
                render(scene, 4).color);
    }
  EXPECT_EQ(render(scene, 1, Visibility::kPainter).color, reference.color);
}

TEST(AlphaBlend, MsaaInteriorPixelsMatchOneSample) {
  const Scene scene = blendScene(true);
  const Frame one = render(scene), four = render(scene, 4);
  for (int y = 2; y < kHeight - 2; ++y)
    for (int x = 2; x < kWidth - 2; ++x) {
      if (x >= 22 && x <= 25) continue;  // the green quad's edge mixes
      expectColor(four.color[y * kWidth + x], expected(x < 24 ? float3{0, 1, 0} : float3{}), x, y);
      EXPECT_EQ(four.color[y * kWidth + x], one.color[y * kWidth + x]) << x << "," << y;
    }
}

TEST(AlphaBlend, TheMatteOfATransparentBackgroundIsTheBlendedAlpha) {
  Scene scene = test::clipSpaceScene();
  scene.background = {0, 0, 0, 0};
  scene.objects.push_back(quad(0, kWidth, 0.5f, kRedHalf, AlphaMode::kBlend));
  RenderOptions options;
  options.width = kWidth;
  options.height = kHeight;
  const Frame f = test::renderAt(scene, options, SimdLevel::kAuto, 1);
  // Premultiplied: half of red's linear 1, over nothing; alpha one half.
  const uint32_t c = f.color[5 * kWidth + 5];
  EXPECT_NEAR(static_cast<int>(c >> 24), 128, 1);
  EXPECT_NEAR(static_cast<int>(c & 0xff), encodeSrgb8(0.5f), 1);
  EXPECT_EQ((c >> 8) & 0xff, 0u);
}

}  // namespace
}  // namespace tessera
