// The display transform (render/tone.h, Scene::tone_mapping and Scene::exposure): the curves'
// defining properties, a rendered pixel against the scalar reference, and the image the same on
// every instruction set, worker count and sample count.
#include "render/tone.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <tessera/scene/color.h>
#include <tessera/scene/primitives.h>

#include "render_test_scenes.h"

namespace tessera::render {
namespace {

float3 curve(ToneMapping mapping, float3 c, float exposure = 0.0f) {
  return toneMap({mapping, std::exp2(exposure)}, c);
}

TEST(ToneMapping, NoneOnlyScalesByTheExposure) {
  const float3 c{0.1f, 0.7f, 3.0f};
  EXPECT_EQ(curve(ToneMapping::kNone, c), c);
  EXPECT_EQ(curve(ToneMapping::kNone, c, 1.0f), (float3{0.2f, 1.4f, 6.0f}));
  EXPECT_EQ(curve(ToneMapping::kNone, c, -2.0f), (float3{0.025f, 0.175f, 0.75f}));
  EXPECT_FALSE(ToneCurve{}.active());
  EXPECT_TRUE((ToneCurve{ToneMapping::kNone, 2.0f}.active()));
}

TEST(ToneMapping, PbrNeutralKeepsBaseColoursBelowTheKneeAndCompressesAbove) {
  // Below the knee (0.76 after the offset) only the offset moves a colour: 0.04 once the darkest
  // channel passes 0.08, x - x^2 / 0.16 below it.
  const float3 mid = curve(ToneMapping::kPbrNeutral, {0.5f, 0.3f, 0.2f});
  EXPECT_NEAR(mid.x, 0.46f, 1e-6f);
  EXPECT_NEAR(mid.y, 0.26f, 1e-6f);
  EXPECT_NEAR(mid.z, 0.16f, 1e-6f);
  const float3 dark = curve(ToneMapping::kPbrNeutral, {0.04f, 0.5f, 0.5f});
  EXPECT_NEAR(dark.x, 0.04f - (0.04f - 0.04f * 0.04f / 0.16f), 1e-7f);
  EXPECT_NEAR(dark.y, 0.5f - 0.03f, 1e-6f);
  EXPECT_EQ(curve(ToneMapping::kPbrNeutral, {0, 0, 0}), (float3{0, 0, 0}));
  // Above it: monotonic, below 1, approaching white for a very bright colour.
  float last = 0.0f;
  for (float v = 0.5f; v < 1000.0f; v *= 1.3f) {
    const float3 grey = curve(ToneMapping::kPbrNeutral, {v, v, v});
    EXPECT_GT(grey.y, last) << v;
    EXPECT_LE(grey.y, 1.0f) << v;
    last = grey.y;
  }
  EXPECT_GT(last, 0.999f);
  // A saturated highlight is desaturated: its darkest channel rises relative to its brightest.
  const float3 red = curve(ToneMapping::kPbrNeutral, {8.0f, 1.0f, 1.0f});
  EXPECT_LT(red.x, 1.0f);
  EXPECT_GT(red.y / red.x, 1.0f / 8.0f);
}

TEST(ToneMapping, AcesMapsBlackToBlackGreyNearGreyAndClipsAtOne) {
  EXPECT_EQ(curve(ToneMapping::kAces, {0, 0, 0}), (float3{0, 0, 0}));
  // The boosted fit at mid grey: fit(0.18 / 0.6) = 0.2131 (the input matrix's rows sum to 1, the
  // output's too, so a grey stays grey).
  const float3 grey = curve(ToneMapping::kAces, {0.18f, 0.18f, 0.18f});
  EXPECT_NEAR(grey.x, 0.2131f, 2e-4f);
  EXPECT_NEAR(grey.y, grey.x, 2e-4f);
  EXPECT_NEAR(grey.z, grey.x, 2e-4f);
  float last = 0.0f;
  for (float v = 0.01f; v < 1e4f; v *= 1.5f) {
    const float y = curve(ToneMapping::kAces, {v, v, v}).y;
    EXPECT_GE(y, last) << v;
    last = y;
  }
  EXPECT_EQ(curve(ToneMapping::kAces, {1e6f, 1e6f, 1e6f}), (float3{1, 1, 1}));
  // Negative light (none from the shading) counts as none.
  EXPECT_EQ(curve(ToneMapping::kAces, {-5, -5, -5}), (float3{0, 0, 0}));
  // Exposure acts before the curve: +1 stop at 0.09 is the curve at 0.18.
  EXPECT_EQ(curve(ToneMapping::kAces, {0.09f, 0.09f, 0.09f}, 1.0f), grey);
}

// An unlit quad of one colour over the whole frame, brighter than the display's white.
Scene brightQuad(float3 color) {
  Scene scene = test::clipSpaceScene();
  Object o = test::unlitObject(
      test::windowTriangle({-10, -10, 0.5f}, {70, -10, 0.5f}, {-10, 70, 0.5f}, 16, 16));
  o.materials[0].base_color = float4(color, 1.0f);
  scene.objects.push_back(o);
  return scene;
}

TEST(ToneMapping, ShadedPixelIsTheReferenceCurveEncoded) {
  const float3 color{2.5f, 0.6f, 0.05f};
  for (ToneMapping mapping : {ToneMapping::kNone, ToneMapping::kAces, ToneMapping::kPbrNeutral})
    for (float exposure : {0.0f, -1.5f}) {
      Scene scene = brightQuad(color);
      scene.tone_mapping = mapping;
      scene.exposure = exposure;
      const float3 want = toneMap(ToneCurve::of(scene), color);
      for (SimdLevel level : {SimdLevel::kScalar, SimdLevel::kAuto}) {
        RenderOptions options;
        options.width = options.height = 16;
        const Frame frame = test::renderAt(scene, options, level, 1);
        const uint32_t pixel = frame.color[5 * 16 + 5];
        EXPECT_EQ(pixel & 0xff, encodeSrgb8(want.x)) << int(mapping) << " " << exposure;
        EXPECT_EQ((pixel >> 8) & 0xff, encodeSrgb8(want.y)) << int(mapping) << " " << exposure;
        EXPECT_EQ((pixel >> 16) & 0xff, encodeSrgb8(want.z)) << int(mapping) << " " << exposure;
      }
    }
  // Without a curve the red channel clips; with one it does not reach 255.
  Scene scene = brightQuad(color);
  scene.tone_mapping = ToneMapping::kPbrNeutral;
  RenderOptions options;
  options.width = options.height = 16;
  EXPECT_EQ(test::renderAt(brightQuad(color), options, SimdLevel::kAuto, 1).color[0] & 0xff, 255u);
  EXPECT_LT(test::renderAt(scene, options, SimdLevel::kAuto, 1).color[0] & 0xff, 255u);
}

// A lit PBR sphere, a Gouraud cube and a Phong cube, with a light bright enough to need a curve.
Scene litScene(ToneMapping mapping) {
  Scene scene;
  scene.camera.position = {0.2f, 0.3f, 2.4f};
  scene.lights.push_back(Light::directional(normalize(float3{-0.4f, -0.6f, -1.0f}), {1, 1, 1}, 4));
  scene.lights.push_back(Light::point({1.0f, 1.0f, 1.5f}, {1.0f, 0.7f, 0.4f}, 6.0f));
  const Shading modes[] = {Shading::kPbr, Shading::kGouraud, Shading::kPhong};
  for (int i = 0; i < 3; ++i) {
    Object o;
    o.mesh = std::make_shared<Mesh>(i == 0 ? makeUvSphere(24, 12) : makeCube());
    o.shading = modes[i];
    o.materials[0].base_color = {0.9f, 0.5f - 0.1f * i, 0.2f + 0.2f * i, 1.0f};
    o.materials[0].metallic = 0.2f;
    o.materials[0].roughness = 0.4f;
    o.transform.translation = {-1.1f + 1.1f * i, 0.2f * i, -0.3f * i};
    o.transform.scale = float3(0.6f);
    scene.objects.push_back(o);
  }
  scene.tone_mapping = mapping;
  scene.exposure = 0.5f;
  return scene;
}

TEST(ToneMapping, ImageIsBitIdenticalForEverySimdLevelWorkerCountAndWithMsaa) {
  for (ToneMapping mapping : {ToneMapping::kAces, ToneMapping::kPbrNeutral}) {
    const Scene scene = litScene(mapping);
    for (int msaa : {1, 4}) {
      RenderOptions options;
      options.width = 161;
      options.height = 97;
      options.msaa = msaa;
      const Frame scalar = test::renderAt(scene, options, SimdLevel::kScalar, 1);
      EXPECT_GT(test::coveredCount(scalar), 161 * 97 / 8);
      for (SimdLevel level :
           {SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512, SimdLevel::kAuto})
        for (int workers : {1, 3})
          EXPECT_EQ(scalar.color, test::renderAt(scene, options, level, workers).color)
              << int(mapping) << ", " << int(level) << ", " << workers << ", msaa " << msaa;
      // The curve changes the picture.
      EXPECT_NE(scalar.color,
                test::renderAt(litScene(ToneMapping::kNone), options, SimdLevel::kScalar, 1).color);
    }
  }
}

}  // namespace
}  // namespace tessera::render
