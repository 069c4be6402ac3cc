// Tests of the llvmpipe reference of `tessera bench --vs llvmpipe`: it draws the pixels tessera
// draws, at one sample per pixel and multisampled. Nothing here times anything.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/color.h>

#include "bench/llvmpipe_reference.h"
#include "bench/scenes.h"
#include "bench_test_scenes.h"

using namespace tessera;
using test::colorAndIds;
using test::lookAtCube;
using test::scene;

// ---- the llvmpipe reference draws what tessera draws ----

namespace {

struct Comparison {
  double coverage_agreement = 0;  // share of pixels both cover or both leave empty
  double close_colors = 0;        // share of the pixels both cover within 2/255 per channel
  size_t tessera_covered = 0;
  // Over the pixels both cover, every channel: the mean and the largest |tessera - llvmpipe|, in
  // 8-bit sRGB codes.
  double mean_difference = 0;
  int max_difference = 0;
};

// Renders `s` with tessera and the reference at w x h and compares them pixel by pixel.
Comparison compareWithReference(bench::LlvmpipeReference& reference, const Scene& s, int w, int h) {
  CpuRenderer renderer(1);
  Frame frame;
  renderer.render(s, colorAndIds(w, h), frame);
  EXPECT_TRUE(reference.setScene(s).ok());
  EXPECT_TRUE(reference.setResolution(w, h).ok());
  reference.render(s);
  std::vector<uint32_t> gl;
  reference.readColor(gl);
  EXPECT_EQ(gl.size(), frame.pixelCount());
  const uint32_t background = packSrgba8(s.background) & 0xffffffu;
  Comparison c;
  size_t agree = 0, both = 0, close = 0;
  double difference_sum = 0;
  for (size_t i = 0; i < gl.size() && i < frame.pixelCount(); ++i) {
    const bool by_tessera = frame.triangle_id[i] != kNoTriangle;
    const bool by_gl = (gl[i] & 0xffffffu) != background;
    agree += by_tessera == by_gl;
    c.tessera_covered += by_tessera;
    if (!by_tessera || !by_gl) continue;
    ++both;
    int worst = 0;
    for (int k = 0; k < 3; ++k) {
      const int d = std::abs(static_cast<int>((frame.color[i] >> (8 * k)) & 255) -
                             static_cast<int>((gl[i] >> (8 * k)) & 255));
      worst = std::max(worst, d);
      difference_sum += d;
    }
    close += worst <= 2;
    c.max_difference = std::max(c.max_difference, worst);
  }
  c.mean_difference = both ? difference_sum / (3.0 * static_cast<double>(both)) : 0.0;
  c.coverage_agreement = static_cast<double>(agree) / static_cast<double>(gl.size());
  c.close_colors = both ? static_cast<double>(close) / static_cast<double>(both) : 0.0;
  return c;
}

class Reference : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!bench::llvmpipeReferenceBuilt()) GTEST_SKIP() << "built without OSMesa";
    Expected<std::unique_ptr<bench::LlvmpipeReference>> created =
        bench::LlvmpipeReference::create(1);
    ASSERT_TRUE(created.ok()) << created.error().message;
    reference_ = std::move(*created);
  }
  std::unique_ptr<bench::LlvmpipeReference> reference_;
};

}  // namespace

TEST_F(Reference, RendersWithLlvmpipe) {
  EXPECT_TRUE(reference_->isLlvmpipe()) << reference_->renderer();
  EXPECT_NE(reference_->version().find("Mesa"), std::string::npos) << reference_->version();
  EXPECT_EQ(reference_->threads(), 1);
}

TEST_F(Reference, CubeCoversTheSamePixelsAsTessera) {
  Expected<bench::BenchScene> s = scene("cube", Shading::kFlat);
  ASSERT_TRUE(s.ok());
  lookAtCube(s->scene);
  bench::poseForFrame(*s, 10);
  const Comparison c = compareWithReference(*reference_, s->scene, 160, 120);
  EXPECT_GT(c.tessera_covered, 160u * 120u / 10);  // the cube is in view
  EXPECT_GE(c.coverage_agreement, 0.98);
  EXPECT_GE(c.close_colors, 0.98);
}

TEST_F(Reference, ShadingModelsMatchTessera) {
  for (Shading shading : {Shading::kFlat, Shading::kGouraud, Shading::kPhong, Shading::kUnlit}) {
    for (CullMode cull : {CullMode::kBack, CullMode::kNone}) {
      Expected<bench::BenchScene> s = scene("textured", shading);
      ASSERT_TRUE(s.ok());
      lookAtCube(s->scene);
      s->scene.objects[0].cull = cull;
      s->scene.objects[0].transform.scale = float3(0.8f);
      bench::poseForFrame(*s, 5);
      const Comparison c = compareWithReference(*reference_, s->scene, 96, 72);
      EXPECT_GE(c.coverage_agreement, 0.98) << static_cast<int>(shading);
      EXPECT_GE(c.close_colors, 0.98) << static_cast<int>(shading);
    }
  }
}

// How close llvmpipe's PBR (and tone-mapped) images come to tessera's, over the pixels both
// cover, per 8-bit sRGB channel: the mean and the largest difference. The two evaluate the same
// formulas (pbr_brdf.glsl mirrors render/pbr.h, tone_curve.glsl render/tone.h; llvmpipe free to
// fuse multiply-adds) from inputs that differ in their last bits (llvmpipe interpolates the
// normal and the world position its own way and normalizes with its own rsqrt): untextured, they
// are at most 1 code apart (measured: mean 0.013 on the bunny, at most 0.002 on the sphere). The
// checker texture adds the two bilinear filters' disagreement where a pixel straddles a sharp
// checker edge (measured: mean 0.09 to 0.15, max 4), as for the Lambert modes.
constexpr double kPlainMeanTolerance = 0.05;
constexpr int kPlainMaxTolerance = 2;
constexpr double kTexturedMeanTolerance = 0.25;
constexpr int kTexturedMaxTolerance = 6;

// The textured sphere under the cube's view and lights, in PBR with the given metal and
// roughness, without its texture unless `textured`, and with a point light beside the directional
// ones when `point_light`.
Scene pbrSphere(float metallic, float roughness, CullMode cull, bool point_light, bool textured) {
  Expected<bench::BenchScene> s = scene("textured", Shading::kPbr);
  EXPECT_TRUE(s.ok());
  lookAtCube(s->scene);
  Object& sphere = s->scene.objects[0];
  sphere.cull = cull;
  sphere.transform.scale = float3(0.8f);
  sphere.materials[0].metallic = metallic;
  sphere.materials[0].roughness = roughness;
  if (!textured) sphere.materials[0].albedo = nullptr;
  if (point_light) s->scene.lights.push_back(Light::point({1.2f, 1.0f, 1.5f}, float3(1.0f), 2.0f));
  bench::poseForFrame(*s, 5);
  return s->scene;
}

TEST_F(Reference, PbrMatchesTessera) {
  struct Case {
    float metallic, roughness;
    CullMode cull;
    bool point_light;
  };
  const Case cases[] = {{0.0f, 1.0f, CullMode::kBack, false},
                        {0.0f, 0.35f, CullMode::kNone, false},
                        {1.0f, 0.3f, CullMode::kBack, false},
                        {0.5f, 0.6f, CullMode::kBack, true}};
  for (const Case& k : cases) {
    for (bool textured : {false, true}) {
      const Scene s = pbrSphere(k.metallic, k.roughness, k.cull, k.point_light, textured);
      const Comparison c = compareWithReference(*reference_, s, 160, 120);
      const std::string what =
          "metallic " + std::to_string(k.metallic) + ", roughness " + std::to_string(k.roughness) +
          (k.point_light ? ", point light" : "") + (textured ? ", textured" : "");
      EXPECT_GT(c.tessera_covered, 160u * 120u / 10) << what;
      EXPECT_GE(c.coverage_agreement, 0.98) << what;
      EXPECT_GE(c.close_colors, 0.98) << what;
      EXPECT_LE(c.mean_difference, textured ? kTexturedMeanTolerance : kPlainMeanTolerance) << what;
      EXPECT_LE(c.max_difference, textured ? kTexturedMaxTolerance : kPlainMaxTolerance) << what;
    }
  }
}

// The bench's own PBR row: the bunny, framed and lit as `tessera bench bunny --shading pbr`.
TEST_F(Reference, PbrBunnyMatchesTessera) {
  if (!std::filesystem::exists(bench::kBunnyPath))
    GTEST_SKIP() << bench::kBunnyPath << " is not installed (Debian's " << bench::kBunnyPackage
                 << ")";
  Expected<bench::BenchScene> s = scene("bunny", Shading::kPbr);
  ASSERT_TRUE(s.ok()) << s.error().message;
  s->scene.camera.position = s->bounds.center() + float3{0.0f, 0.0f, 2.2f} * s->bounds.radius();
  s->scene.camera.target = s->bounds.center();
  s->scene.camera.near_z = 0.5f * s->bounds.radius();
  s->scene.camera.far_z = 4.0f * s->bounds.radius();
  s->scene.lights = {Light::directional(normalize(float3{0.3f, -0.5f, -1.0f}), float3(1.0f))};
  s->scene.ambient = float3(0.08f);
  s->scene.objects[0].materials[0].roughness = 0.4f;
  const Comparison c = compareWithReference(*reference_, s->scene, 192, 108);
  EXPECT_GT(c.tessera_covered, 192u * 108u / 10);
  EXPECT_GE(c.coverage_agreement, 0.98);
  EXPECT_LE(c.mean_difference, kPlainMeanTolerance);
  EXPECT_LE(c.max_difference, kPlainMaxTolerance);
}

TEST_F(Reference, ToneCurvesMatchTessera) {
  for (Shading shading : {Shading::kGouraud, Shading::kPbr}) {
    for (ToneMapping curve : {ToneMapping::kNone, ToneMapping::kAces, ToneMapping::kPbrNeutral}) {
      Scene s = pbrSphere(0.0f, 0.5f, CullMode::kBack, false, false);
      s.objects[0].shading = shading;
      s.tone_mapping = curve;
      s.exposure = 1.5f;  // bright enough that every curve compresses the highlights
      const Comparison c = compareWithReference(*reference_, s, 96, 72);
      const std::string what = "shading " + std::to_string(static_cast<int>(shading)) + ", curve " +
                               std::to_string(static_cast<int>(curve));
      EXPECT_GE(c.coverage_agreement, 0.98) << what;
      EXPECT_LE(c.mean_difference, kPlainMeanTolerance) << what;
      EXPECT_LE(c.max_difference, kPlainMaxTolerance) << what;
    }
  }
}

TEST_F(Reference, PbrMapsItDoesNotDrawAreErrors) {
  Scene s = pbrSphere(0.0f, 0.5f, CullMode::kBack, false, true);
  auto map = std::make_shared<Texture>(bench::makeCheckerTexture(8, 2));
  s.objects[0].materials[0].normal.texture = map;
  Expected<void> set = reference_->setScene(s);
  ASSERT_FALSE(set.ok());
  EXPECT_NE(set.error().message.find("normal map"), std::string::npos) << set.error().message;
  s.objects[0].shading = Shading::kPhong;  // the Lambert modes read no PBR map
  EXPECT_TRUE(reference_->setScene(s).ok());
}

TEST_F(Reference, TwoReferencesKeepTheirOwnFrames) {
  Expected<std::unique_ptr<bench::LlvmpipeReference>> other = bench::LlvmpipeReference::create(1);
  ASSERT_TRUE(other.ok()) << other.error().message;
  Expected<bench::BenchScene> cube = scene("cube", Shading::kFlat);
  Expected<bench::BenchScene> fill = scene("fill", Shading::kUnlit);
  ASSERT_TRUE(cube.ok() && fill.ok());
  lookAtCube(cube->scene);
  ASSERT_TRUE(reference_->setScene(cube->scene).ok());
  ASSERT_TRUE(reference_->setResolution(32, 24).ok());
  ASSERT_TRUE((*other)->setScene(fill->scene).ok());
  ASSERT_TRUE((*other)->setResolution(16, 16).ok());
  reference_->render(cube->scene);
  (*other)->render(fill->scene);
  std::vector<uint32_t> cube_pixels, fill_pixels;
  reference_->readColor(cube_pixels);
  (*other)->readColor(fill_pixels);
  ASSERT_EQ(cube_pixels.size(), 32u * 24u);
  ASSERT_EQ(fill_pixels.size(), 16u * 16u);
  const uint32_t background = packSrgba8(cube->scene.background);
  EXPECT_EQ(cube_pixels[0], background);             // a corner of the cube's frame is background
  EXPECT_NE(cube_pixels[12 * 32 + 16], background);  // its centre is the cube
  for (uint32_t p : fill_pixels) EXPECT_NE(p, packSrgba8(fill->scene.background));
}

TEST_F(Reference, ReadBackRowsRunTopDown) {
  // A red layer over the upper half of the view only: the top rows of the read-back are red.
  Scene s;
  s.camera.position = {0, 0, 3};
  s.camera.near_z = 1;
  s.camera.far_z = 10;
  Mesh upper;
  upper.positions = {{-5, 0.1f, 0}, {5, 0.1f, 0}, {5, 5, 0}, {-5, 5, 0}};
  upper.normals.assign(4, float3{0, 0, 1});
  upper.indices = {0, 1, 2, 0, 2, 3};
  Object o;
  o.mesh = std::make_shared<Mesh>(upper);
  o.shading = Shading::kUnlit;
  o.materials[0].base_color = {1, 0, 0, 1};
  s.objects.push_back(o);
  ASSERT_TRUE(reference_->setScene(s).ok());
  ASSERT_TRUE(reference_->setResolution(8, 8).ok());
  reference_->render(s);
  std::vector<uint32_t> rgba;
  reference_->readColor(rgba);
  ASSERT_EQ(rgba.size(), 64u);
  EXPECT_EQ(rgba[0] & 0xffffffu, 0x0000ffu);   // top-left: red
  EXPECT_EQ(rgba[63] & 0xffffffu, 0x000000u);  // bottom-right: the black background
}

// ---- the llvmpipe reference, multisampled ----

namespace {

int channelDifference(uint32_t a, uint32_t b) {
  int worst = 0;
  for (int k = 0; k < 3; ++k)
    worst = std::max(worst, std::abs(static_cast<int>((a >> (8 * k)) & 255) -
                                     static_cast<int>((b >> (8 * k)) & 255)));
  return worst;
}

// Whether every pixel within `radius` of (x, y) has the colour of (x, y).
bool inFlatArea(const std::vector<uint32_t>& rgba, int w, int h, int x, int y, int radius) {
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const int nx = std::clamp(x + dx, 0, w - 1), ny = std::clamp(y + dy, 0, h - 1);
      if ((rgba[ny * w + nx] & 0xffffffu) != (rgba[y * w + x] & 0xffffffu)) return false;
    }
  return true;
}

}  // namespace

TEST_F(Reference, SampleCountsItCannotDrawExactlyAreErrors) {
  EXPECT_EQ(reference_->samples(), 1);
  ASSERT_TRUE(reference_->setSamples(4).ok());
  EXPECT_EQ(reference_->samples(), 4);
  for (int samples : {2, 8}) {
    Expected<void> set = reference_->setSamples(samples);
    if (set) {
      EXPECT_EQ(reference_->samples(), samples);
    } else {
      EXPECT_NE(set.error().message.find("cannot draw " + std::to_string(samples)),
                std::string::npos)
          << set.error().message;
      EXPECT_NE(set.error().message.find("exactly 1"), std::string::npos) << set.error().message;
      EXPECT_EQ(reference_->samples(), 4) << "a refused count leaves the count as it was";
    }
    ASSERT_TRUE(reference_->setSamples(4).ok());
  }
}

// 4x against 1x of the same flat-shaded cube: silhouette and crease pixels blend, the inside of
// each face does not change.
TEST_F(Reference, MultisamplingSmoothsEdgesAndLeavesFlatInteriorsAlone) {
  Expected<bench::BenchScene> s = scene("cube", Shading::kFlat);
  ASSERT_TRUE(s.ok());
  lookAtCube(s->scene);
  s->scene.background = {0.0f, 0.0f, 0.0f, 1.0f};
  bench::poseForFrame(*s, 10);
  const int w = 160, h = 120;
  ASSERT_TRUE(reference_->setScene(s->scene).ok());
  ASSERT_TRUE(reference_->setResolution(w, h).ok());
  std::vector<uint32_t> one, four;
  reference_->render(s->scene);
  reference_->readColor(one);
  ASSERT_TRUE(reference_->setSamples(4).ok());
  reference_->render(s->scene);
  reference_->readColor(four);
  ASSERT_EQ(one.size(), four.size());
  ASSERT_EQ(one.size(), static_cast<size_t>(w) * h);

  size_t interior = 0, interior_changed = 0, edge_changed = 0, silhouette_blends = 0;
  const uint32_t black = 0xff000000u;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      const int difference = channelDifference(one[i], four[i]);
      if (inFlatArea(one, w, h, x, y, 2)) {
        ++interior;
        // At most 1: the 1x shader encodes sRGB with pow(), the 4x framebuffer with llvmpipe's
        // own approximation, which differs by one step for a few values.
        interior_changed += difference > 1;
      } else {
        edge_changed += difference > 8;
      }
      // Background at 1x (centre outside the cube), part cube at 4x (some sample inside).
      silhouette_blends += one[i] == black && four[i] != black;
    }
  EXPECT_GT(interior, static_cast<size_t>(w) * h / 2);  // mostly flat background and faces
  EXPECT_EQ(interior_changed, 0u);
  EXPECT_GT(edge_changed, 50u) << "no edge pixel blends: the frame was not multisampled";
  EXPECT_GT(silhouette_blends, 20u) << "no background pixel takes part of the cube";
}

namespace {

// A white unlit quad over window x < `right` and y (down) < `bottom` of an 8x8 view.
Scene whiteCorner(float right, float bottom) {
  Scene s;
  s.camera.position = {0, 0, 3};
  s.camera.target = {0, 0, 0};
  s.camera.fov_y_degrees = 90.0f;  // 8x8 pixels over [-3, 3]: x = (X / 3 + 1) 4, y = (1 - Y / 3) 4
  s.camera.near_z = 1;
  s.camera.far_z = 10;
  s.background = {0, 0, 0, 1};
  const float x = 3.0f * (right / 4.0f - 1.0f), y = 3.0f * (1.0f - bottom / 4.0f);
  Mesh quad;
  quad.positions = {{-5, y, 0}, {x, y, 0}, {x, 5, 0}, {-5, 5, 0}};
  quad.normals.assign(4, float3{0, 0, 1});
  quad.indices = {0, 1, 2, 0, 2, 3};
  Object o;
  o.mesh = std::make_shared<Mesh>(quad);
  o.shading = Shading::kUnlit;
  o.materials[0].base_color = {1, 1, 1, 1};
  s.objects.push_back(o);
  return s;
}

}  // namespace

// A white quad over the left part of a pixel: at 4x two of its four samples (standard positions
// x = 0.125 and 0.375) are white, so the resolve is linear 0.5, sRGB 188, not the 128 of an
// average of sRGB values. At 1x the centre (0.5) is covered: 255.
TEST_F(Reference, MultisampleResolveAveragesInLinearLight) {
  const Scene s = whiteCorner(4.55f, 100.0f);  // pixel column 4 up to 0.55 of its width
  ASSERT_TRUE(reference_->setScene(s).ok());
  ASSERT_TRUE(reference_->setResolution(8, 8).ok());
  std::vector<uint32_t> one, four;
  reference_->render(s);
  reference_->readColor(one);
  ASSERT_TRUE(reference_->setSamples(4).ok());
  reference_->render(s);
  reference_->readColor(four);
  ASSERT_EQ(four.size(), 64u);
  for (int y = 0; y < 8; ++y) {
    EXPECT_EQ(one[y * 8 + 4] & 255, 255u) << "row " << y;
    EXPECT_EQ(four[y * 8 + 3] & 255, 255u) << "row " << y;  // wholly covered
    EXPECT_EQ(four[y * 8 + 5] & 255, 0u) << "row " << y;    // wholly uncovered
    // 188 is sRGB of linear 0.5; llvmpipe's encoder may round one step off.
    EXPECT_NEAR(static_cast<int>(four[y * 8 + 4] & 255), 188, 1) << "row " << y;
  }
}

// GL gives sample positions from a pixel's lower-left corner, y up; tessera's (sampling.h) from
// the upper-left, y down. Pixel (4, 4) with the quad over its x < 0.5, y < 0.25 part holds one
// standard sample, (0.375, 0.125); the pattern mirrored top to bottom has none there.
TEST_F(Reference, SamplesSitWhereTesserasDo) {
  const Scene s = whiteCorner(4.5f, 4.25f);
  ASSERT_TRUE(reference_->setScene(s).ok());
  ASSERT_TRUE(reference_->setResolution(8, 8).ok());
  ASSERT_TRUE(reference_->setSamples(4).ok());
  reference_->render(s);
  std::vector<uint32_t> gl;
  reference_->readColor(gl);
  ASSERT_EQ(gl.size(), 64u);
  CpuRenderer renderer(1);
  Frame frame;
  RenderOptions options = colorAndIds(8, 8);
  options.msaa = 4;
  renderer.render(s, options, frame);
  // One sample of four: linear 0.25, sRGB 137 (llvmpipe's encoder may be a step off).
  EXPECT_NEAR(static_cast<int>(gl[4 * 8 + 4] & 255), 137, 1);
  EXPECT_EQ(frame.color[4 * 8 + 4] & 255, 137u);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      EXPECT_LE(channelDifference(gl[y * 8 + x], frame.color[y * 8 + x]), 1) << x << "," << y;
}

// The same scene at 4x in both: the same samples covered, so the same colours (within 2/255)
// in every pixel, edges included. An untextured scene: where a pixel holds two triangles,
// tessera shades the one whose centre is outside at its first sample and GL at the centre, which
// on a minified texture picks other texels.
TEST_F(Reference, MultisampledFrameMatchesTessera) {
  for (Shading shading : {Shading::kFlat, Shading::kGouraud}) {
    Expected<bench::BenchScene> s = scene("cube", shading);
    ASSERT_TRUE(s.ok());
    lookAtCube(s->scene);
    bench::poseForFrame(*s, 10);
    const int w = 160, h = 120;
    ASSERT_TRUE(reference_->setScene(s->scene).ok());
    ASSERT_TRUE(reference_->setResolution(w, h).ok());
    ASSERT_TRUE(reference_->setSamples(4).ok());
    reference_->render(s->scene);
    std::vector<uint32_t> gl;
    reference_->readColor(gl);
    CpuRenderer renderer(1);
    Frame frame;
    RenderOptions options = colorAndIds(w, h);
    options.msaa = 4;
    renderer.render(s->scene, options, frame);
    ASSERT_EQ(gl.size(), frame.pixelCount());
    size_t far = 0, blended = 0;
    const uint32_t background = packSrgba8(s->scene.background);
    for (size_t i = 0; i < gl.size(); ++i) {
      far += channelDifference(gl[i], frame.color[i]) > 2;
      // A silhouette pixel: background at its centre, part cube at 4x.
      blended += frame.triangle_id[i] == kNoTriangle && frame.color[i] != background;
    }
    EXPECT_GT(blended, 20u) << "the frame has anti-aliased edges to compare";
    EXPECT_EQ(far, 0u) << static_cast<int>(shading);
  }
}
