// Environment light: the equirectangular mapping, the irradiance and prefiltered specular an
// image is prepared into, the split-sum BRDF table, and reading Radiance .hdr files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include <tessera/io/image_loader.h>
#include <tessera/scene/environment.h>

#if TESSERA_HAS_OPENEXR
#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfRgbaFile.h>
#endif

#include "run_process.h"
#include "stb_image_write.h"
#include "temp_folder.h"

namespace tessera {
namespace {

// A width x height image whose texel at direction d is radiance(d).
template <typename F>
EnvironmentImage makeImage(int width, int height, F radiance) {
  EnvironmentImage image;
  image.width = width;
  image.height = height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image.texels.push_back(radiance(equirectDirection(
          {(static_cast<float>(x) + 0.5f) / width, (static_cast<float>(y) + 0.5f) / height})));
  return image;
}

void expectNear3(float3 actual, float3 expected, float tolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(Environment, EquirectangularMappingFollowsItsConvention) {
  const float2 up = equirectUv({0, 1, 0}), down = equirectUv({0, -1, 0});
  EXPECT_NEAR(up.y, 0.0f, 1e-6f);
  EXPECT_NEAR(down.y, 1.0f, 1e-6f);
  EXPECT_NEAR(equirectUv({0, 0, -1}).x, 0.0f, 1e-6f);
  EXPECT_NEAR(equirectUv({1, 0, 0}).x, 0.25f, 1e-6f);
  EXPECT_NEAR(equirectUv({0, 0, 1}).x, 0.5f, 1e-6f);
  EXPECT_NEAR(equirectUv({-1, 0, 0}).x, 0.75f, 1e-6f);
  std::mt19937 random(7);
  std::normal_distribution<float> normal;
  for (int i = 0; i < 1000; ++i) {
    const float3 d = normalize(float3{normal(random), normal(random), normal(random)});
    expectNear3(equirectDirection(equirectUv(d)), d, 1e-5f);
  }
}

// equirectUv's own arctangent (the same float operations in the scalar and the eight-lane code)
// stays within a float's step of libm's in every octant, on the axes and at the origin; a direction
// that is not finite reads no light.
TEST(Environment, SeriesArctangentMatchesLibmEverywhere) {
  std::mt19937 random(11);
  std::uniform_real_distribution<float> any(-3.0f, 3.0f);
  float worst = 0.0f;
  for (int i = 0; i < 200000; ++i) {
    const float y = any(random), x = any(random);
    worst = std::max(worst, std::fabs(atan2Series(y, x) - std::atan2(y, x)));
  }
  EXPECT_LT(worst, 3e-7f);
  for (float y : {-1.0f, 0.0f, 1.0f})
    for (float x : {-1.0f, 0.0f, 1.0f}) {
      if (x == 0.0f && y == 0.0f) continue;
      EXPECT_NEAR(atan2Series(y, x), std::atan2(y, x), 3e-7f) << y << "," << x;
    }
  EXPECT_EQ(atan2Series(0.0f, 0.0f), 0.0f);
  EXPECT_TRUE(std::isnan(atan2Series(NAN, 1.0f)));
  EnvironmentImage white;
  white.width = 4;
  white.height = 2;
  white.texels.assign(8, float3{1, 1, 1});
  EXPECT_EQ(sampleEquirect(white, {NAN, 0, 1}).x, 0.0f);
  EXPECT_EQ(sampleEquirect(white, {0, INFINITY, 0}).y, 0.0f);
  EXPECT_EQ(sampleEquirect(white, {0, 0, 1}).z, 1.0f);
}

TEST(Environment, UniformLightIsTheSameEverywhereAtEveryRoughness) {
  const Environment environment(makeImage(64, 32, [](float3) { return float3{2, 1, 0.5f}; }));
  for (float3 n :
       {float3{0, 1, 0}, float3{0, -1, 0}, float3{1, 0, 0}, normalize(float3{1, 2, 3})}) {
    expectNear3(environment.diffuse(n), {2, 1, 0.5f}, 0.01f);
    for (float roughness : {0.0f, 0.3f, 0.5f, 0.9f, 1.0f})
      expectNear3(environment.specular(n, roughness), {2, 1, 0.5f}, 0.01f);
  }
}

// Radiance 1 from the upper hemisphere: the irradiance over pi is 1 facing up, 0 facing down and
// 1/2 facing the horizon, and bands 0 to 2 of spherical harmonics hold that exactly (the clamped
// cosine has nothing in band 3 and only little past it).
TEST(Environment, DiffuseOfASkyIsOneUpHalfSidewaysAndNoneDown) {
  const Environment environment(makeImage(128, 64, [](float3 d) {
    return d.y > 0 ? float3{1, 1, 1} : float3{0, 0, 0};
  }));
  EXPECT_NEAR(environment.diffuse({0, 1, 0}).x, 1.0f, 0.02f);
  EXPECT_NEAR(environment.diffuse({0, -1, 0}).x, 0.0f, 0.02f);
  EXPECT_NEAR(environment.diffuse({1, 0, 0}).x, 0.5f, 0.02f);
  EXPECT_NEAR(environment.diffuse({0, 0, -1}).y, 0.5f, 0.02f);
}

TEST(Environment, SpecularReflectsAMirrorAndBlursWithRoughness) {
  // A bright patch around +X, black elsewhere.
  const float3 patch{1, 0, 0};
  const Environment environment(makeImage(128, 64, [&](float3 d) {
    return dot(d, patch) > 0.98f ? float3{10, 10, 10} : float3{0, 0, 0};
  }));
  EXPECT_NEAR(environment.specular(patch, 0.0f).x, 10.0f, 0.01f);  // the image itself
  EXPECT_EQ(environment.specular({-1, 0, 0}, 0.0f).x, 0.0f);
  const float3 aside = normalize(float3{1, 0.6f, 0});  // 31 degrees off the patch
  EXPECT_LT(environment.specular(aside, 0.0f).x, 1e-6f);
  EXPECT_GT(environment.specular(aside, 0.8f).x, 0.01f);  // a rough lobe reaches it
  // The peak falls as the lobe widens.
  EXPECT_GT(environment.specular(patch, 0.2f).x, environment.specular(patch, 0.6f).x);
  EXPECT_GT(environment.specular(patch, 0.6f).x, environment.specular(patch, 1.0f).x);
}

TEST(Environment, PreparationIsDeterministic) {
  auto radiance = [](float3 d) { return float3{d.x * d.x, 0.5f + 0.5f * d.y, std::abs(d.z)}; };
  const Environment a(makeImage(64, 32, radiance)), b(makeImage(64, 32, radiance));
  for (float roughness : {0.1f, 0.5f, 1.0f})
    for (float3 r : {float3{0, 1, 0}, normalize(float3{1, -1, 2})}) {
      const float3 x = a.specular(r, roughness), y = b.specular(r, roughness);
      EXPECT_EQ(x.x, y.x);
      EXPECT_EQ(x.y, y.y);
      EXPECT_EQ(x.z, y.z);
    }
}

// The white furnace test of the specular lobe: with Fresnel at 1 (F0 = 1) a lobe reflects at
// most what comes in, all of it for a mirror; single scattering loses more as roughness grows.
TEST(Environment, SplitSumBrdfNeverReflectsMoreThanComesIn) {
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) {
      const float n_dot_v = i / 20.0f, roughness = j / 20.0f;
      const float2 ab = splitSumBrdf(n_dot_v, roughness);
      EXPECT_GE(ab.x, 0.0f);
      EXPECT_GE(ab.y, 0.0f);
      EXPECT_LE(ab.x + ab.y, 1.0f + 1e-3f) << n_dot_v << " " << roughness;
    }
  for (float n_dot_v : {0.2f, 0.5f, 1.0f})
    EXPECT_NEAR(splitSumBrdf(n_dot_v, 0.0f).x + splitSumBrdf(n_dot_v, 0.0f).y, 1.0f, 0.01f);
  const float2 smooth = splitSumBrdf(1.0f, 0.2f), rough = splitSumBrdf(1.0f, 1.0f);
  EXPECT_LT(rough.x + rough.y, smooth.x + smooth.y - 0.1f);
  // Head on, Fresnel barely rises above F0: the F0-independent part is small; at grazing angles
  // of a smooth surface it is most of the reflection.
  EXPECT_LT(splitSumBrdf(1.0f, 0.1f).y, 0.01f);
  EXPECT_GT(splitSumBrdf(0.05f, 0.1f).y, 0.3f);
}

// ---- Radiance .hdr files ----

class HdrFiles : public ::testing::Test {
 protected:
  void SetUp() override { root_ = test::makeTestFolder("tessera_hdr"); }
  void TearDown() override { std::filesystem::remove_all(root_); }
  std::filesystem::path write(const std::string& name, const std::string& bytes) {
    return test::writeFile(root_ / name, bytes);
  }
  std::filesystem::path root_;
};

// A flat (not run-length encoded) RGBE image, 4 pixels wide: (r, g, b) = mantissas x 2^(e-136).
std::string hdrFile(int width, int height, const std::string& pixels) {
  return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " +
         std::to_string(width) + "\n" + pixels;
}

TEST_F(HdrFiles, DecodesRgbeToLinearRadiance) {
  std::string pixels;
  for (int i = 0; i < 8; ++i)
    pixels += std::string{'\x80', '\x40', '\x20', '\x81'};            // 1, 0.5, 0.25
  pixels.replace(4, 4, std::string{'\x80', '\x80', '\x80', '\x84'});  // 8, 8, 8
  Expected<EnvironmentImage> image =
      io::loadEnvironmentImage(write("sky.hdr", hdrFile(4, 2, pixels)));
  ASSERT_TRUE(image) << image.error().message;
  ASSERT_EQ(image->width, 4);
  ASSERT_EQ(image->height, 2);
  expectNear3(image->at(0, 0), {1.0f, 0.5f, 0.25f}, 1e-6f);
  expectNear3(image->at(1, 0), {8.0f, 8.0f, 8.0f}, 1e-6f);
  expectNear3(image->at(3, 1), {1.0f, 0.5f, 0.25f}, 1e-6f);
}

// stb_image_write writes scanlines of 8 pixels or more run-length encoded, as most .hdr files are.
TEST_F(HdrFiles, ReadsRunLengthEncodedScanlinesAndRefusesThemTruncated) {
  const int width = 64, height = 32;
  std::vector<float> rgb;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (float value : {x < 32 ? 1.0f : 4.0f, 0.25f * static_cast<float>(y % 4), 0.5f})
        rgb.push_back(value);
  const std::filesystem::path path = root_ / "rle.hdr";
  ASSERT_NE(stbi_write_hdr(path.string().c_str(), width, height, 3, rgb.data()), 0);
  Expected<EnvironmentImage> image = io::loadEnvironmentImage(path);
  ASSERT_TRUE(image) << image.error().message;
  ASSERT_EQ(image->width, width);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; x += 9)
      expectNear3(image->at(x, y), {x < 32 ? 1.0f : 4.0f, 0.25f * static_cast<float>(y % 4), 0.5f},
                  0.01f);
  std::string bytes = test::slurp(path);
  bytes.resize(bytes.size() - 10);
  Expected<EnvironmentImage> truncated = io::loadEnvironmentImage(write("cut.hdr", bytes));
  ASSERT_FALSE(truncated);
  EXPECT_NE(truncated.error().message.find("truncated"), std::string::npos)
      << truncated.error().message;
}

#if TESSERA_HAS_OPENEXR
TEST_F(HdrFiles, ReadsOpenExrImages) {
  const int width = 8, height = 4;
  Imf::Array2D<Imf::Rgba> pixels(height, width);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      pixels[y][x] = Imf::Rgba(x * 0.5f, y < 2 ? 3.0f : 0.0f, 0.25f, 1);
  const std::filesystem::path path = root_ / "sky.exr";
  {
    Imf::RgbaOutputFile file(path.string().c_str(), width, height, Imf::WRITE_RGBA);
    file.setFrameBuffer(&pixels[0][0], 1, width);
    file.writePixels(height);
  }
  Expected<EnvironmentImage> image = io::loadEnvironmentImage(path);
  ASSERT_TRUE(image) << image.error().message;
  ASSERT_EQ(image->width, width);
  ASSERT_EQ(image->height, height);
  expectNear3(image->at(3, 0), {1.5f, 3.0f, 0.25f}, 1e-3f);
  expectNear3(image->at(6, 3), {3.0f, 0.0f, 0.25f}, 1e-3f);
  // Cut short, or over the budget: refused with a message.
  std::string bytes = test::slurp(path);
  bytes.resize(bytes.size() / 2);
  Expected<EnvironmentImage> cut = io::loadEnvironmentImage(write("cut.exr", bytes));
  ASSERT_FALSE(cut);
  EXPECT_NE(cut.error().message.find("cut.exr"), std::string::npos) << cut.error().message;
  Expected<EnvironmentImage> big = io::loadEnvironmentImage(path, /*max_pixels=*/16);
  ASSERT_FALSE(big);
  EXPECT_NE(big.error().message.find("--max-texture-pixels"), std::string::npos);
}
#endif

TEST_F(HdrFiles, WhatIsNotAnHdrImageIsAClearError) {
  for (const auto& [name, bytes] :
       {std::pair<std::string, std::string>{"empty.hdr", ""},
        {"text.hdr", "hello, this is not an image\n"},
        {"png.hdr", std::string("\x89PNG\r\n\x1a\n", 8) + std::string(40, '\0')},
        {"truncated.hdr", hdrFile(4, 2, std::string(7, '\x40'))},
        // Exponent 255: 255 x 2^119 per channel, whose sums would be infinite.
        {"huge.hdr", hdrFile(4, 2, std::string(32, '\xff'))}}) {
    Expected<EnvironmentImage> image = io::loadEnvironmentImage(write(name, bytes));
    ASSERT_FALSE(image) << name;
    EXPECT_NE(image.error().message.find(name), std::string::npos) << image.error().message;
  }
  Expected<EnvironmentImage> missing = io::loadEnvironmentImage(root_ / "missing.hdr");
  EXPECT_FALSE(missing);
}

TEST_F(HdrFiles, AnImageOverTheBudgetIsRefusedBeforeDecoding) {
  std::string pixels;
  for (int i = 0; i < 8; ++i) pixels += std::string{'\x80', '\x40', '\x20', '\x81'};
  Expected<EnvironmentImage> image =
      io::loadEnvironmentImage(write("big.hdr", hdrFile(4, 2, pixels)), /*max_pixels=*/4);
  ASSERT_FALSE(image);
  EXPECT_NE(image.error().message.find("--max-texture-pixels"), std::string::npos);
}

}  // namespace
}  // namespace tessera
