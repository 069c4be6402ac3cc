// alphaMode MASK (mask_kernel.h): a masked triangle keeps a pixel, or with MSAA a sample, only
// where its alpha reaches the cutoff; what lies behind shows through the cut, at every sample
// count, worker count and instruction set, in the z-buffer and the painter's order.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <tessera/scene/color.h>

#include "render_test_scenes.h"

namespace tessera {
namespace {

constexpr int kWidth = 32, kHeight = 8;

// A full-frame quad (two triangles) at window depth z, UVs 0..1 left to right.
Object frameQuad(float z, float4 color) {
  Mesh m;
  for (float2 p : {float2{0, 0}, float2{kWidth, 0}, float2{kWidth, kHeight}, float2{0, kHeight}}) {
    m.positions.push_back(test::windowToNdc(p.x, p.y, z, kWidth, kHeight));
    m.uvs.push_back({p.x / kWidth, 1.0f - p.y / kHeight});
  }
  m.indices = {0, 1, 2, 0, 2, 3};
  Object o = test::unlitObject(std::move(m));
  o.materials[0].base_color = color;
  return o;
}

// Texel i of 16 has alpha (i + 0.5) / 16: the alpha crosses 0.5 at u = 0.5, between pixel
// columns 15 and 16 of a 32-pixel-wide frame.
std::shared_ptr<const Texture> alphaRamp() {
  auto t = std::make_shared<Texture>();
  t->width = 16;
  t->height = 1;
  t->srgb = true;
  for (int i = 0; i < 16; ++i) {
    const uint32_t a = static_cast<uint32_t>(std::lround((i + 0.5) / 16.0 * 255.0));
    t->texels.push_back(0x00ffffffu | a << 24);
  }
  return t;
}

// A red opaque quad behind a white masked one.
Scene maskScene(float cutoff, TextureFilter filter) {
  Scene scene = test::clipSpaceScene();
  scene.objects.push_back(frameQuad(0.8f, {1, 0, 0, 1}));
  Object front = frameQuad(0.2f, {1, 1, 1, 1});
  front.materials[0].albedo = alphaRamp();
  front.materials[0].sampler.filter = filter;
  front.materials[0].alpha_mode = AlphaMode::kMask;
  front.materials[0].alpha_cutoff = cutoff;
  scene.objects.push_back(front);
  return scene;
}

Frame render(const Scene& scene, int msaa, Visibility visibility = Visibility::kDepthBuffer,
             SimdLevel level = SimdLevel::kAuto, int workers = 1) {
  RenderOptions options;
  options.width = kWidth;
  options.height = kHeight;
  options.msaa = msaa;
  options.visibility = visibility;
  options.ids = true;
  return test::renderAt(scene, options, level, workers);
}

constexpr uint32_t kRed = 0xff0000ffu, kWhite = 0xffffffffu;

TEST(AlphaMask, CutsExactlyWhereTheAlphaTextureCrossesTheCutoff) {
  for (Visibility visibility : {Visibility::kDepthBuffer, Visibility::kPainter}) {
    const Frame f = render(maskScene(0.5f, TextureFilter::kNearest), 1, visibility);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const uint32_t want = x < 16 ? kRed : kWhite;
        ASSERT_EQ(f.color[y * kWidth + x], want) << x << "," << y << " " << int(visibility);
        // The id AOV is the triangle kept: the red quad's (0, 1) or the white one's (2, 3).
        ASSERT_EQ(f.triangle_id[y * kWidth + x] >= 3, x >= 16) << x << "," << y;
      }
  }
  // Another cutoff moves the cut: 0.75 crosses between texels 11 and 12 (columns 23 and 24).
  const Frame f = render(maskScene(0.75f, TextureFilter::kNearest), 1);
  for (int x = 0; x < kWidth; ++x) EXPECT_EQ(f.color[x], x < 24 ? kRed : kWhite) << x;
  // A cutoff of 0 keeps everything; an opaque material ignores its texture's alpha.
  EXPECT_EQ(render(maskScene(0.0f, TextureFilter::kNearest), 1).color,
            std::vector<uint32_t>(kWidth * kHeight, kWhite));
  Scene opaque = maskScene(0.5f, TextureFilter::kNearest);
  opaque.objects[1].materials[0].alpha_mode = AlphaMode::kOpaque;
  EXPECT_EQ(render(opaque, 1).color, std::vector<uint32_t>(kWidth * kHeight, kWhite));
}

TEST(AlphaMask, SamplesTakeTheirOwnAlphaSoTheCutIsAntiAliased) {
  // Bilinear: the alpha is a ramp, about u; a cutoff of 0.52 crosses it inside pixel column 16,
  // which with 8 samples mixes red and white; the pixels away from it are one or the other.
  const Frame f = render(maskScene(0.52f, TextureFilter::kBilinear), 8);
  const Frame one = render(maskScene(0.52f, TextureFilter::kBilinear), 1);
  EXPECT_EQ(f.color[2 * kWidth + 2], kRed);
  EXPECT_EQ(f.color[2 * kWidth + 29], kWhite);
  int mixed = 0;
  for (int x = 0; x < kWidth; ++x) {
    const uint32_t c = f.color[2 * kWidth + x];
    mixed += c != kRed && c != kWhite;
  }
  EXPECT_GE(mixed, 1) << "no anti-aliased pixel at the cut";
  EXPECT_LE(mixed, 2);
  for (int x = 0; x < kWidth; ++x) {
    const uint32_t c = one.color[2 * kWidth + x];
    EXPECT_TRUE(c == kRed || c == kWhite) << x;
  }
  // The id AOV stays the centre's, as without MSAA.
  EXPECT_EQ(f.triangle_id, one.triangle_id);
}

TEST(AlphaMask, ImageIsBitIdenticalForEverySimdLevelAndWorkerCount) {
  const Scene scene = maskScene(0.5f, TextureFilter::kTrilinear);
  for (int msaa : {1, 4})
    for (Visibility visibility : {Visibility::kDepthBuffer, Visibility::kPainter}) {
      const Frame scalar = render(scene, msaa, visibility, SimdLevel::kScalar, 1);
      for (SimdLevel level : {SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512})
        for (int workers : {1, 2})
          EXPECT_EQ(scalar.color, render(scene, msaa, visibility, level, workers).color)
              << msaa << " " << int(level) << " " << workers;
    }
}

}  // namespace
}  // namespace tessera
