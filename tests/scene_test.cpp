#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <tessera/base/huge_pages.h>
#include <tessera/scene/color.h>
#include <tessera/scene/primitives.h>
#include <tessera/scene/scene.h>

using namespace tessera;

namespace {

// Every triangle is counter-clockwise seen from outside: its geometric normal points away from
// the centre of a convex, origin-centred mesh.
void expectOutwardWinding(const Mesh& mesh) {
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    float3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
           c = mesh.positions[mesh.indices[3 * t + 2]];
    float3 n = cross(b - a, c - a);
    ASSERT_GT(length(n), 0.0f) << "degenerate triangle " << t;
    EXPECT_GT(dot(n, (a + b + c) * (1.0f / 3.0f)), 0.0f) << "triangle " << t;
  }
}

}  // namespace

TEST(Primitives, CubeHasOutwardFacesAndFlatNormals) {
  Mesh cube = makeCube();
  EXPECT_EQ(cube.vertexCount(), 24u);
  EXPECT_EQ(cube.triangleCount(), 12u);
  expectOutwardWinding(cube);
  for (size_t t = 0; t < cube.triangleCount(); ++t) {
    float3 a = cube.positions[cube.indices[3 * t]], b = cube.positions[cube.indices[3 * t + 1]],
           c = cube.positions[cube.indices[3 * t + 2]];
    float3 face = normalize(cross(b - a, c - a));
    for (int k = 0; k < 3; ++k) EXPECT_EQ(cube.normals[cube.indices[3 * t + k]], face);
  }
  Bounds b = cube.bounds();
  EXPECT_EQ(b.min, float3(-0.5f));
  EXPECT_EQ(b.max, float3(0.5f));
}

TEST(Primitives, SphereIsClosedWithUnitNormals) {
  Mesh sphere = makeUvSphere(16, 8);
  expectOutwardWinding(sphere);
  // 16 segments, 8 rings: 2 triangles per quad except one at each pole.
  EXPECT_EQ(sphere.triangleCount(), 16u * (2 * 8 - 2));
  for (size_t i = 0; i < sphere.vertexCount(); ++i) {
    EXPECT_NEAR(length(sphere.normals[i]), 1.0f, 1e-5f);
    EXPECT_NEAR(length(sphere.positions[i]), 1.0f, 1e-5f);
  }
}

TEST(Mesh, SmoothNormalsAreAreaWeighted) {
  // Two triangles meeting at vertex 0: a large one in the XY plane, a small one in the XZ plane.
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, -1}, {1, 0, 0}};
  mesh.indices = {0, 1, 2, 0, 3, 4};
  generateSmoothNormals(mesh);
  // Large face normal (0,0,1) with weight 100, small one (0,-1,0) with weight 1.
  float3 expected = normalize(float3{0, -1, 100});
  EXPECT_NEAR(mesh.normals[0].y, expected.y, 1e-5f);
  EXPECT_NEAR(mesh.normals[0].z, expected.z, 1e-5f);
  EXPECT_EQ(mesh.normals[2], float3(0, 0, 1));
}

TEST(Mesh, SmoothNormalsSurviveDegenerateAndNonFiniteFaces) {
  Mesh mesh;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {nan, 0, 0}};
  mesh.indices = {0, 1, 2, 0, 1, 3};
  generateSmoothNormals(mesh);
  for (const float3& n : mesh.normals) {
    EXPECT_TRUE(isFinite(n));
    EXPECT_NEAR(length(n), 1.0f, 1e-6f);
  }
}

TEST(Mesh, SmoothNormalsOfHugeAndTinyModelsAreUnitLength) {
  // In float, the cross products of a 3e38 model overflow and those of a 1e-42 one vanish.
  for (float scale : {1e10f, 1e20f, 3e38f, 1e-20f, 1e-42f}) {
    Mesh mesh = makeUvSphere(12, 6);
    for (float3& p : mesh.positions) p = p * scale;
    generateSmoothNormals(mesh);
    const Mesh unit = makeUvSphere(12, 6);
    Mesh reference = unit;
    generateSmoothNormals(reference);
    for (size_t v = 0; v < mesh.normals.size(); ++v) {
      EXPECT_NEAR(length(mesh.normals[v]), 1.0f, 1e-5f) << scale << " vertex " << v;
      // 1e-42 is a denormal: its positions keep few bits, so only the length is held to.
      if (scale >= 1e-20f) {
        EXPECT_GT(dot(mesh.normals[v], reference.normals[v]), 0.999f) << scale << " vertex " << v;
      }
    }
  }
}

TEST(Mesh, BoundsOfAHugeModelAreItsTrueBounds) {
  Mesh mesh;
  mesh.positions = {{-3e38f, 0, 0}, {3e38f, 1e-42f, 0}};
  const Bounds bounds = mesh.bounds();
  EXPECT_EQ(bounds.min.x, -3e38f);
  EXPECT_EQ(bounds.max.x, 3e38f);
  EXPECT_EQ(bounds.max.y, 1e-42f);
}

TEST(Color, SrgbRoundTripsEvery8BitCode) {
  for (int code = 0; code < 256; ++code) {
    float linear = decodeSrgb8(static_cast<uint8_t>(code));
    EXPECT_NEAR(linear, srgbToLinear(code / 255.0f), 1e-7f);
    EXPECT_EQ(encodeSrgb8(linear), code);
  }
}

TEST(Color, EncodeMatchesTheExactCurve) {
  EXPECT_EQ(encodeSrgb8(0.0f), 0);
  EXPECT_EQ(encodeSrgb8(1.0f), 255);
  EXPECT_EQ(encodeSrgb8(2.0f), 255);
  EXPECT_EQ(encodeSrgb8(-1.0f), 0);
  EXPECT_EQ(encodeSrgb8(std::numeric_limits<float>::quiet_NaN()), 0);
  // Mid grey in linear light is code 188 in sRGB, not 128.
  EXPECT_EQ(encodeSrgb8(0.5f), 188);
  int mismatches = 0;
  for (int i = 0; i <= 10000; ++i) {
    float linear = i / 10000.0f;
    float exact = linearToSrgb(linear) * 255.0f;
    int got = encodeSrgb8(linear);
    EXPECT_LE(std::fabs(got - exact), 0.56f) << linear;
    mismatches += got != static_cast<int>(std::lround(exact));
  }
  EXPECT_LT(mismatches, 50);
}

TEST(Texture, NearestAndBilinearInLinearSpace) {
  Texture t;
  t.width = 2;
  t.height = 1;
  t.texels = {0xff000000u, 0xffffffffu};  // black, white
  Sampler nearest{TextureFilter::kNearest, TextureWrap::kClamp, TextureWrap::kClamp};
  EXPECT_EQ(t.sample({0.25f, 0.5f}, nearest).x, 0.0f);
  EXPECT_EQ(t.sample({0.75f, 0.5f}, nearest).x, 1.0f);
  Sampler bilinear{TextureFilter::kBilinear, TextureWrap::kClamp, TextureWrap::kClamp};
  // Halfway between the texel centres: the average of the linear values, 0.5.
  EXPECT_NEAR(t.sample({0.5f, 0.5f}, bilinear).x, 0.5f, 1e-6f);
  // Clamp holds the edge texel; repeat wraps to the other side.
  EXPECT_EQ(t.sample({-3.0f, 0.5f}, nearest).x, 0.0f);
  EXPECT_EQ(t.sample({-0.25f, 0.5f},
                     Sampler{TextureFilter::kNearest, TextureWrap::kRepeat, TextureWrap::kRepeat})
                .x,
            1.0f);
  // Non-finite coordinates do not crash.
  float4 v = t.sample({std::numeric_limits<float>::infinity(), 0.5f}, bilinear);
  EXPECT_TRUE(std::isfinite(v.x));
}

// OpenGL 4.6, table 8.20: MIRRORED_REPEAT reads texel (n - 1) - mirror((i mod 2n) - n), with
// mirror(a) = a >= 0 ? a : -(1 + a); REPEAT i mod n; CLAMP_TO_EDGE clamps to [0, n - 1].
TEST(Texture, WrapModesReadTheTexelsOpenGlSays) {
  for (int n : {1, 3, 4, 7}) {
    for (int i = -30; i <= 30; ++i) {
      const int m = ((i % (2 * n)) + 2 * n) % (2 * n) - n;
      const int mirror = m >= 0 ? m : -(1 + m);
      EXPECT_EQ(wrapTexel(i, n, TextureWrap::kMirroredRepeat), (n - 1) - mirror) << i << " " << n;
      EXPECT_EQ(wrapTexel(i, n, TextureWrap::kRepeat), ((i % n) + n) % n) << i << " " << n;
      EXPECT_EQ(wrapTexel(i, n, TextureWrap::kClamp), std::clamp(i, 0, n - 1)) << i << " " << n;
    }
  }
  // Near the int limits (texel positions of coordinates up to 65536 on 16384 texels).
  EXPECT_EQ(wrapTexel(-(1 << 30), 3, TextureWrap::kMirroredRepeat),
            wrapTexel(-(1 << 30) + 6 * 1000, 3, TextureWrap::kMirroredRepeat));
}

// A 4x2 texture, each texel its own red code; nearest sampling with S and T wrapped separately.
TEST(Texture, SAndTWrapSeparatelyAndMirroredRepeatReflectsEachPeriod) {
  Texture t;
  t.width = 4;
  t.height = 2;
  t.srgb = false;
  for (uint32_t i = 0; i < 8; ++i) t.texels.push_back(0xff000000u | (i * 10));
  auto red = [&](float2 uv, TextureWrap s, TextureWrap w) {
    Sampler sampler;
    sampler.filter = TextureFilter::kNearest;
    sampler.wrap_s = s;
    sampler.wrap_t = w;
    return static_cast<int>(std::lround(t.sample(uv, sampler).x * 255));
  };
  // Row 0 is the top (v in (0.5, 1)); u = 1.125 is texel 4: repeat reads 0, mirror 3, clamp 3.
  EXPECT_EQ(red({1.125f, 0.75f}, TextureWrap::kRepeat, TextureWrap::kClamp), 0);
  EXPECT_EQ(red({1.125f, 0.75f}, TextureWrap::kMirroredRepeat, TextureWrap::kClamp), 30);
  EXPECT_EQ(red({1.375f, 0.75f}, TextureWrap::kMirroredRepeat, TextureWrap::kClamp), 20);
  EXPECT_EQ(red({-0.125f, 0.75f}, TextureWrap::kMirroredRepeat, TextureWrap::kClamp), 0);
  EXPECT_EQ(red({-0.375f, 0.75f}, TextureWrap::kMirroredRepeat, TextureWrap::kClamp), 10);
  EXPECT_EQ(red({2.125f, 0.75f}, TextureWrap::kMirroredRepeat, TextureWrap::kClamp), 0);
  // v = 1.25 is row -1 (above the top): T clamps to row 0, repeats to row 1, mirrors to row 0;
  // v = -0.25 (row 2): clamp row 1, repeat row 0, mirror row 1. S is the same texel throughout.
  EXPECT_EQ(red({0.375f, 1.25f}, TextureWrap::kRepeat, TextureWrap::kClamp), 10);
  EXPECT_EQ(red({0.375f, 1.25f}, TextureWrap::kClamp, TextureWrap::kRepeat), 50);
  EXPECT_EQ(red({0.375f, 1.25f}, TextureWrap::kClamp, TextureWrap::kMirroredRepeat), 10);
  EXPECT_EQ(red({0.375f, -0.25f}, TextureWrap::kRepeat, TextureWrap::kClamp), 50);
  EXPECT_EQ(red({0.375f, -0.25f}, TextureWrap::kClamp, TextureWrap::kRepeat), 10);
  EXPECT_EQ(red({0.375f, -0.25f}, TextureWrap::kClamp, TextureWrap::kMirroredRepeat), 50);
  // Bilinear at the seam of a mirrored axis blends a texel with itself: u = 1 reads texel 3 alone,
  // its 15-bit value whole (FixedFilter), within half a step of 30 / 255.
  Sampler bilinear;
  bilinear.filter = TextureFilter::kBilinear;
  bilinear.wrap_s = TextureWrap::kMirroredRepeat;
  bilinear.wrap_t = TextureWrap::kClamp;
  const int32_t code30 = texelFixedTable(false)[30];
  EXPECT_EQ(t.sample({1.0f, 0.75f}, bilinear).x,
            static_cast<float>(code30 * FixedFilter::kWeightOne) * FixedFilter::kScale);
  EXPECT_NEAR(t.sample({1.0f, 0.75f}, bilinear).x, 30.0f / 255.0f, 0.5f / FixedFilter::kTexelOne);
}

// KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv in glTF's coordinates (v down
// from the top row); tessera's v is 1 - glTF's. Each case: a glTF uv, the transform, the texel
// (column, row from the top) of a 4x4 texture it must land on.
TEST(Texture, TransformMovesAKnownUvToTheTexelTheExtensionSays) {
  Texture t;
  t.width = t.height = 4;
  t.srgb = false;
  for (uint32_t i = 0; i < 16; ++i) t.texels.push_back(0xff000000u | (i * 15));
  struct Case {
    float2 uv;
    TextureTransform transform;
    int column, row;
  };
  const float quarter_turn = 1.5707963267948966f;
  const Case cases[] = {
      {{0.1f, 0.1f}, {{0.5f, 0.0f}, 0.0f, {1, 1}}, 2, 0},  // offset u: 0.6
      {{0.1f, 0.1f}, {{0.0f, 0.5f}, 0.0f, {1, 1}}, 0, 2},  // offset v: 0.6 (down the image)
      {{0.1f, 0.2f}, {{0.1f, 0.2f}, 0.0f, {2, 3}}, 1, 3},  // scale then offset: (0.3, 0.8)
      // Rotation: (u, v) -> (cos u + sin v, -sin u + cos v) = (v, -u) at a quarter turn (the
      // direction the sample model TextureTransformTest marks green); offset (0, 1) brings it
      // back: (0.2, 0.9).
      {{0.1f, 0.2f}, {{0.0f, 1.0f}, quarter_turn, {1, 1}}, 0, 3},
      // All three: scale (2, 1) first, (0.3, 0.6) -> (0.6, 0.6); a quarter turn: (0.6, -0.6);
      // offset (0.1, 0.75): (0.7, 0.15).
      {{0.3f, 0.6f}, {{0.1f, 0.75f}, quarter_turn, {2, 1}}, 2, 0},
  };
  Sampler nearest;
  nearest.filter = TextureFilter::kNearest;
  nearest.wrap_s = nearest.wrap_t = TextureWrap::kClamp;
  for (const Case& c : cases) {
    const float2 tessera_uv{c.uv.x, 1.0f - c.uv.y};
    const float2 moved = c.transform.affine().apply(tessera_uv);
    const int code = static_cast<int>(std::lround(t.sample(moved, nearest).x * 255));
    EXPECT_EQ(code, (c.row * 4 + c.column) * 15)
        << c.uv.x << "," << c.uv.y << " -> " << moved.x << "," << 1.0f - moved.y;
  }
  EXPECT_TRUE(TextureTransform{}.identity());
  EXPECT_FALSE((TextureTransform{{0, 0}, std::nanf(""), {1, 1}}.finite()));
}

TEST(Camera, FrameBoundsSeesTheWholeModelWithNearAndFarAroundIt) {
  Bounds b;
  b.add({-100, 0, 0});
  b.add({100, 20, 30});
  Camera c = frameBounds(b, {1, 1, 1}, {0, 1, 0}, 50.0f, 2.0f);
  float4x4 vp = c.projection(2.0f) * c.view();
  for (int i = 0; i < 8; ++i) {
    float3 corner{i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z};
    float4 clip = vp * float4{corner, 1};
    float3 ndc = clip.xyz() * (1.0f / clip.w);
    EXPECT_LE(std::fabs(ndc.x), 1.0f);
    EXPECT_LE(std::fabs(ndc.y), 1.0f);
    EXPECT_GT(ndc.z, -1.0f);
    EXPECT_LT(ndc.z, 1.0f);
  }
  EXPECT_GT(c.near_z, 0.0f);
}

TEST(Texture, MipChainAveragesInLinearLight) {
  Texture t;
  t.width = 4;
  t.height = 2;
  for (int i = 0; i < 8; ++i) t.texels.push_back((i + i / 4) % 2 ? 0xffffffffu : 0xff000000u);
  generateMipmaps(t);
  ASSERT_EQ(t.levelCount(), 3);
  EXPECT_EQ(t.mips[0].width, 2);
  EXPECT_EQ(t.mips[0].height, 1);
  EXPECT_EQ(t.mips[1].width, 1);
  EXPECT_EQ(t.mips[1].height, 1);
  // Half black, half white averages to linear 0.5: sRGB code 188, not 128.
  EXPECT_EQ(t.mips[1].texels[0] & 0xff, 188u);
  EXPECT_EQ(t.mips[1].texels[0] >> 24, 255u);
  Sampler trilinear{TextureFilter::kTrilinear, TextureWrap::kRepeat, TextureWrap::kRepeat};
  // Level of detail 0 is the bilinear sample of level 0; past the last level, its average.
  EXPECT_EQ(t.sampleLod({0.3f, 0.6f}, 0.0f, trilinear), t.sample({0.3f, 0.6f}, trilinear));
  EXPECT_NEAR(t.sampleLod({0.3f, 0.6f}, 9.0f, trilinear).x, 0.5f, 0.003f);
  // Halfway between two levels blends them.
  float4 a = t.sampleLod({0.1f, 0.2f}, 1.0f, trilinear);
  float4 b = t.sampleLod({0.1f, 0.2f}, 2.0f, trilinear);
  float4 mid = t.sampleLod({0.1f, 0.2f}, 1.5f, trilinear);
  EXPECT_NEAR(mid.x, 0.5f * (a.x + b.x), 1e-6f);
  EXPECT_TRUE(std::isfinite(t.sampleLod({0.1f, 0.2f}, std::nanf(""), trilinear).x));
}

// The linear copy holds every level's texels as sampling decodes them (sRGB through the table,
// alpha and linear textures as code / 255), is made again after the texels change, and is not
// made above the size limit.
TEST(Texture, LinearTexelsAreTheDecodedTexelsOfEveryLevel) {
  Texture t;
  t.width = 3;
  t.height = 2;
  t.texels = {0x00000000u, 0xff102030u, 0x80ffffffu, 0x7f0a0b0cu, 0x01c8641eu, 0xfe010203u};
  generateMipmaps(t);
  ASSERT_EQ(t.levelCount(), 2);
  for (bool srgb : {true, false}) {
    Texture copy = t;  // a copy makes its own linear texels
    copy.srgb = srgb;
    for (int level = 0; level < copy.levelCount(); ++level) {
      const std::vector<uint32_t>& texels = level == 0 ? copy.texels : copy.mips[0].texels;
      const int16_t* linear = copy.linearTexels(level);
      ASSERT_NE(linear, nullptr);
      for (size_t i = 0; i < texels.size(); ++i)
        for (int k = 0; k < 4; ++k) {
          const uint32_t code = (texels[i] >> (8 * k)) & 0xff;
          const float decoded =
              srgb && k < 3 ? srgbDecodeTable()[code] : static_cast<float>(code) / 255.0f;
          const int want = static_cast<int>(std::lround(decoded * FixedFilter::kTexelOne));
          EXPECT_EQ(linear[4 * i + k], want) << "level " << level << " texel " << i << " " << k;
        }
    }
    EXPECT_EQ(copy.linearTexels(2), nullptr);  // no such level
  }
  // New texels and levels: the next call decodes them.
  EXPECT_EQ(t.linearTexels(0)[0], 0);
  t.texels[0] = 0xffffffffu;
  generateMipmaps(t);
  EXPECT_EQ(t.linearTexels(0)[0], FixedFilter::kTexelOne);
  Texture big;
  big.width = 1025;
  big.height = 1024;
  big.texels.assign(static_cast<size_t>(big.width) * big.height, 0xffffffffu);
  EXPECT_GT(static_cast<size_t>(big.width) * big.height, Texture::kLinearTexelLimit);
  EXPECT_EQ(big.linearTexels(0), nullptr);  // filtered from its RGBA8 texels
  Texture broken;                           // texels that do not fill the level: nothing to copy
  broken.width = 4;
  broken.height = 4;
  broken.texels.assign(3, 0u);
  EXPECT_EQ(broken.linearTexels(0), nullptr);
}

// A large level's copy lies in whole huge pages (HugePageAllocator), a small one in ordinary
// memory, and either holds the decoded texels.
TEST(Texture, LargeLinearTexelCopiesStartOnAHugePage) {
  Texture t;
  t.width = 512;
  t.height = 512;  // 2 MiB at level 0, 512 KiB at level 1
  t.texels.resize(static_cast<size_t>(t.width) * t.height);
  for (size_t i = 0; i < t.texels.size(); ++i) t.texels[i] = static_cast<uint32_t>(i * 2654435761u);
  generateMipmaps(t);
  for (int level = 0; level < t.levelCount(); ++level) {
    const std::vector<uint32_t>& texels = level == 0 ? t.texels : t.mips[level - 1].texels;
    const int16_t* linear = t.linearTexels(level);
    ASSERT_NE(linear, nullptr);
    const size_t bytes = 4 * sizeof(int16_t) * texels.size();
    if (bytes >= kHugePage / 2)
      EXPECT_EQ(reinterpret_cast<uintptr_t>(linear) % kHugePage, 0u) << "level " << level;
    const size_t last = texels.size() - 1;
    EXPECT_EQ(linear[4 * last + 3], texelFixedTable(false)[texels[last] >> 24]);
    EXPECT_EQ(linear[0], texelFixedTable(true)[texels[0] & 0xff]);
  }
}

// The allocator's two kinds of block: whole huge pages from half a huge page up, operator new
// below; a vector that grows from one kind into the other keeps its contents.
TEST(HugePages, AllocatorTakesHugePagesForLargeBlocksOnly) {
  HugePageAllocator<double> allocator;
  const size_t large = kHugePage / 2 / sizeof(double);
  double* block = allocator.allocate(large);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(block) % kHugePage, 0u);
  block[0] = 1.0;
  block[large - 1] = 2.0;
  EXPECT_EQ(block[0] + block[large - 1], 3.0);
  allocator.deallocate(block, large);
  EXPECT_EQ(HugePageAllocator<double>::mapped(large - 1), 0u);
  EXPECT_EQ(HugePageAllocator<double>::mapped(large), kHugePage);
  EXPECT_EQ(HugePageAllocator<double>::mapped(2 * large), kHugePage);
  EXPECT_EQ(HugePageAllocator<double>::mapped(2 * large + 1), 2 * kHugePage);
  std::vector<uint32_t, HugePageAllocator<uint32_t>> values;
  for (uint32_t i = 0; i < 1'000'000; ++i) values.push_back(i * 2654435761u);
  for (uint32_t i = 0; i < 1'000'000; ++i) ASSERT_EQ(values[i], i * 2654435761u) << i;
  EXPECT_EQ(reinterpret_cast<uintptr_t>(values.data()) % kHugePage, 0u);
}

// The copies' memory counts against one budget for the process: a copy that would pass it is not
// made, and a copy's bytes return to it when its texture is dropped or takes new levels.
TEST(Texture, LinearTexelCopiesKeepWithinTheBudget) {
  auto texture = [] {
    Texture t;
    t.width = 32;
    t.height = 16;
    t.texels.assign(32 * 16, 0xff336699u);
    return t;
  };
  constexpr size_t kCopy = 32 * 16 * 4 * sizeof(int16_t);  // one level's linear copy
  const size_t held = Texture::linearTexelBytes();
  const size_t budget = Texture::setLinearTexelBudget(held + 2 * kCopy + kCopy / 2);
  {
    Texture a = texture();
    Texture b = texture();
    Texture c = texture();
    ASSERT_NE(a.linearTexels(0), nullptr);
    ASSERT_NE(b.linearTexels(0), nullptr);
    EXPECT_EQ(Texture::linearTexelBytes(), held + 2 * kCopy);
    EXPECT_EQ(c.linearTexels(0), nullptr);  // half a copy's room left
    EXPECT_EQ(Texture::linearTexelBytes(), held + 2 * kCopy);
    {
      Texture moved = std::move(a);  // the copy moves with the texels
      EXPECT_EQ(Texture::linearTexelBytes(), held + 2 * kCopy);
      EXPECT_NE(moved.linearTexels(0), nullptr);
      EXPECT_EQ(Texture::linearTexelBytes(), held + 2 * kCopy);
    }
    EXPECT_EQ(Texture::linearTexelBytes(), held + kCopy);  // back with the texture that held it
    Texture d = texture();
    EXPECT_NE(d.linearTexels(0), nullptr);
    EXPECT_EQ(Texture::linearTexelBytes(), held + 2 * kCopy);
    // New levels drop b's copy; with its mips (16x8, ... 1x1) it takes more than it had.
    generateMipmaps(b);
    EXPECT_EQ(Texture::linearTexelBytes(), held + kCopy);
    ASSERT_NE(b.linearTexels(1), nullptr);
    EXPECT_GT(Texture::linearTexelBytes(), held + 2 * kCopy);
  }
  EXPECT_EQ(Texture::linearTexelBytes(), held);
  Texture::setLinearTexelBudget(budget);
}

// An instance's T * R * S is built in closed form; it must hold the bits of the three 4x4
// products it replaced, for any rotation and scale (mirrors included).
TEST(Transform, TrsHasTheBitsOfTheThreeProducts) {
  const float3 scales[] = {{1, 1, 1}, {2, 0.5f, 3}, {-1, 1, 1}, {0.001f, 1000, -7}};
  const float3 angles[] = {{0, 0, 0}, {0.3f, -1.1f, 2}, {3.1f, 0.2f, -0.7f}};
  for (const float3& scale : scales)
    for (const float3& angle : angles) {
      Transform t;
      t.translation = {1.5f, -2.25f, 1e4f};
      t.rotation = fromEuler(angle);
      t.scale = scale;
      const float4x4 products = translation(t.translation) * toMatrix4(t.rotation) * scaling(scale);
      const float4x4 closed = t.trs();
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
          EXPECT_EQ(closed(r, c) + 0.0f, products(r, c) + 0.0f)  // +0: -0 and 0 alike
              << "row " << r << ", column " << c;
      EXPECT_TRUE(t.sameTrs(t));
      Transform moved = t;
      moved.rotation.w += 1e-3f;
      EXPECT_FALSE(t.sameTrs(moved));
    }
}
