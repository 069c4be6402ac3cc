// The point pass (render/point_pass.h) and line widths through the CPU renderer's public seam:
// disc coverage, depth against triangles and other points, colours, sprites, determinism over
// worker counts, and scenes without objects.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/color.h>

#include "render_test_scenes.h"

using namespace tessera;
using namespace tessera::test;  // NOLINT(google-build-using-namespace)

namespace {

constexpr int kW = 32, kH = 32;
constexpr uint32_t kWhite = 0xffffffffu, kBlack = 0xff000000u;

// A linear colour as PointList keeps it.
uint32_t packed(float3 linear) {
  return packSrgba8(float4{linear, 1.0f});
}

RenderOptions pointOptions(float size, int width = kW, int height = kH) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.points.size = size;
  return options;
}

Frame render(const Scene& scene, const RenderOptions& options, int workers = 1) {
  CpuRenderer renderer(workers);
  Frame frame;
  renderer.render(scene, options, frame);
  return frame;
}

// A clip-space scene (identity camera) with points at window positions (x, y) and NDC depth z.
void addPoint(Scene& scene, float x, float y, float z) {
  scene.points.positions.push_back(windowToNdc(x, y, z, kW, kH));
}

int countColor(const Frame& f, uint32_t color) {
  int n = 0;
  for (uint32_t c : f.color) n += c == color;
  return n;
}

}  // namespace

TEST(Points, DiscCoversThePixelCentresWithinHalfItsSize) {
  // Sizes and the pixels whose centres are within size / 2 of a pixel centre: 1 -> 1, 3 -> the
  // 3x3 block (corners at sqrt 2 < 1.5), 4 -> 13 (distance 2 included), 5 -> 21 (5x5 less the
  // corners at sqrt 8 > 2.5).
  const std::pair<float, int> cases[] = {{1.0f, 1}, {3.0f, 9}, {4.0f, 13}, {5.0f, 21}};
  for (auto [size, expected] : cases) {
    Scene scene = clipSpaceScene();
    addPoint(scene, 10.5f, 12.5f, 0.0f);
    const Frame f = render(scene, pointOptions(size));
    EXPECT_EQ(countColor(f, kWhite), expected) << "size " << size;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const float dx = x + 0.5f - 10.5f, dy = y + 0.5f - 12.5f;
        const bool inside = dx * dx + dy * dy <= 0.25f * size * size;
        EXPECT_EQ(f.colorAt(x, y), inside ? kWhite : kBlack) << x << "," << y << " size " << size;
        if (inside) {
          EXPECT_FLOAT_EQ(f.depthAt(x, y), 0.5f);
        }
      }
  }
}

TEST(Points, APointSmallerThanAPixelStillCoversTheOneHoldingIt) {
  Scene scene = clipSpaceScene();
  addPoint(scene, 7.9f, 3.1f, 0.0f);  // 0.4 and 0.6 from the centre of pixel (7, 3)
  const Frame f = render(scene, pointOptions(0.5f));
  EXPECT_EQ(countColor(f, kWhite), 1);
  EXPECT_EQ(f.colorAt(7, 3), kWhite);
}

TEST(Points, HiddenBehindATriangleAndShownInFront) {
  for (float z : {-0.5f, 0.5f}) {
    Scene scene = clipSpaceScene();
    Object tri = unlitObject(
        windowTriangle({0, 0, 0.0f}, {kW * 2.0f, 0, 0.0f}, {0, kH * 2.0f, 0.0f}, kW, kH));
    tri.materials[0].base_color = {1, 0, 0, 1};
    scene.objects.push_back(tri);
    addPoint(scene, 8.5f, 8.5f, z);
    RenderOptions options = pointOptions(3.0f);
    const Frame f = render(scene, options);
    const bool in_front = z < 0.0f;
    EXPECT_EQ(f.colorAt(8, 8), in_front ? kWhite : 0xff0000ffu) << "z " << z;
    EXPECT_EQ(f.idAt(8, 8), in_front ? kNoTriangle : 1u) << "z " << z;
    EXPECT_FLOAT_EQ(f.depthAt(8, 8), in_front ? 0.25f : 0.5f);
    EXPECT_EQ(f.colorAt(20, 8), 0xff0000ffu);  // the triangle elsewhere
  }
}

TEST(Points, TheNearerOfTwoWinsInEitherOrderAndTiesGoToTheLowerIndex) {
  // Green, nearer, at x 10.5; blue, farther, at x 11.5: submitted in both orders.
  for (bool near_first : {true, false}) {
    Scene scene = clipSpaceScene();
    for (int i = 0; i < 2; ++i) {
      const bool near = (i == 0) == near_first;
      addPoint(scene, near ? 10.5f : 11.5f, 10.5f, near ? -0.2f : 0.3f);
      scene.points.colors.push_back(packed(near ? float3{0, 1, 0} : float3{0, 0, 1}));
    }
    const Frame f = render(scene, pointOptions(5.0f));
    EXPECT_EQ(f.colorAt(10, 10), 0xff00ff00u) << near_first;
    EXPECT_EQ(f.colorAt(11, 10), 0xff00ff00u) << near_first;  // the blue one's centre
    EXPECT_EQ(f.colorAt(13, 10), 0xffff0000u) << near_first;  // the blue one's own edge
  }
  // At one depth: the lower index, which ever position it has.
  for (int first : {0, 1}) {
    Scene scene = clipSpaceScene();
    const float xs[2] = {first == 0 ? 10.5f : 11.5f, first == 0 ? 11.5f : 10.5f};
    for (int i = 0; i < 2; ++i) {
      addPoint(scene, xs[i], 10.5f, 0.0f);
      scene.points.colors.push_back(packed(i == 0 ? float3{1, 0, 0} : float3{0, 0, 1}));
    }
    const Frame f = render(scene, pointOptions(5.0f));
    EXPECT_EQ(f.colorAt(10, 10), 0xff0000ffu) << first;
    EXPECT_EQ(f.colorAt(11, 10), 0xff0000ffu) << first;
  }
}

TEST(Points, OwnColoursOrTheDefaultColour) {
  Scene scene = clipSpaceScene();
  addPoint(scene, 5.5f, 5.5f, 0.0f);
  addPoint(scene, 20.5f, 20.5f, 0.0f);
  RenderOptions options = pointOptions(3.0f);
  options.points.color = {0, 0, 1};
  Frame f = render(scene, options);
  EXPECT_EQ(f.colorAt(5, 5), 0xffff0000u);
  EXPECT_EQ(f.colorAt(20, 20), 0xffff0000u);
  scene.points.colors = {packed({1, 0, 0}), packed({0, 1, 0})};
  f = render(scene, options);
  EXPECT_EQ(f.colorAt(5, 5), 0xff0000ffu);
  EXPECT_EQ(f.colorAt(20, 20), 0xff00ff00u);
}

TEST(Points, ClippedAtNearAndFarButDrawnPartlyOffTheImage) {
  Scene scene = clipSpaceScene();
  addPoint(scene, 5.5f, 5.5f, -1.5f);   // nearer than near
  addPoint(scene, 15.5f, 5.5f, 1.5f);   // past far
  addPoint(scene, -0.5f, 20.5f, 0.0f);  // centre left of the image; its right edge on it
  const Frame f = render(scene, pointOptions(5.0f));
  EXPECT_EQ(f.colorAt(5, 5), kBlack);
  EXPECT_EQ(f.colorAt(15, 5), kBlack);
  EXPECT_EQ(f.colorAt(0, 20), kWhite);
  EXPECT_EQ(f.colorAt(1, 20), kWhite);
  EXPECT_EQ(f.colorAt(2, 20), kBlack);
}

TEST(Points, HideTheLinesBehindThem) {
  Scene scene = clipSpaceScene();
  addPoint(scene, 10.5f, 10.5f, -0.5f);
  scene.lines.add(windowToNdc(0, 10.5f, 0.0f, kW, kH), windowToNdc(kW, 10.5f, 0.0f, kW, kH),
                  {1, 0, 0});
  const Frame f = render(scene, pointOptions(3.0f));
  EXPECT_EQ(f.colorAt(10, 10), kWhite);       // the point, nearer
  EXPECT_EQ(f.colorAt(20, 10), 0xff0000ffu);  // the line elsewhere
}

TEST(Points, SameImageForAnyWorkerCount) {
  constexpr int kSize = 256;
  Scene scene = clipSpaceScene();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < 50000; ++i) {
    // Many at one depth, so the ties decide pixels too.
    const float z = i % 3 == 0 ? 0.25f : unit(rng) * 2.0f - 1.0f;
    scene.points.positions.push_back(
        windowToNdc(unit(rng) * kSize, unit(rng) * kSize, z, kSize, kSize));
    scene.points.colors.push_back(packed({unit(rng), unit(rng), unit(rng)}));
  }
  for (int msaa : {1, 4}) {
    for (bool sprites : {false, true}) {
      RenderOptions options = pointOptions(4.0f, kSize, kSize);
      options.msaa = msaa;
      options.points.sprites = sprites;
      options.normals = true;
      const Frame one = render(scene, options, 1);
      EXPECT_GT(countColor(one, kBlack), 0);
      for (int workers : {2, 4}) {
        const Frame many = render(scene, options, workers);
        EXPECT_EQ(one.color, many.color) << workers << " workers, msaa " << msaa;
        EXPECT_EQ(one.depth, many.depth) << workers << " workers, msaa " << msaa;
      }
    }
  }
}

TEST(Points, SpritesAreLitTowardsTheLightAndWriteSphereNormalsAndDepth) {
  constexpr int kSize = 64;
  Scene scene;
  scene.camera.position = {0, 0, 5};
  scene.camera.target = {0, 0, 0};
  scene.camera.fov_y_degrees = 40;
  scene.camera.near_z = 1;
  scene.camera.far_z = 10;
  scene.ambient = {0.05f, 0.05f, 0.05f};
  scene.lights.push_back(Light::directional({-1, 0, 0}, {1, 1, 1}, 1.0f));  // from +X
  scene.points.positions = {{0, 0, 0}};
  RenderOptions options = pointOptions(41.0f, kSize, kSize);
  options.normals = true;
  const Frame flat = render(scene, options);
  options.points.sprites = true;
  const Frame sprite = render(scene, options);
  const int c = kSize / 2;
  auto red = [](uint32_t color) { return color & 0xffu; };
  // Lit from +X: brightest on the right, the ambient alone on the left half.
  EXPECT_GT(red(sprite.colorAt(c + 15, c)), red(sprite.colorAt(c, c)) + 40);
  EXPECT_GE(red(sprite.colorAt(c, c)), red(sprite.colorAt(c - 15, c)));
  EXPECT_GT(red(sprite.colorAt(c + 15, c)), red(sprite.colorAt(c - 15, c)) + 100);
  EXPECT_EQ(red(flat.colorAt(c - 15, c)), 255u);  // flat discs are unlit
  // Normals: towards the eye at the centre, tilted right on the right and up at the top.
  const float3 centre = sprite.normal[c * kSize + c];
  EXPECT_GT(centre.z, 0.99f);
  EXPECT_GT(sprite.normal[c * kSize + c + 15].x, 0.5f);
  EXPECT_GT(sprite.normal[(c - 15) * kSize + c].y, 0.5f);
  EXPECT_GT(flat.normal[c * kSize + c + 15].z, 0.99f);
  // The sphere's surface is nearer than the disc, most at its centre.
  EXPECT_LT(sprite.depthAt(c, c), flat.depthAt(c, c));
  EXPECT_LT(sprite.depthAt(c, c), sprite.depthAt(c + 15, c));
}

TEST(Points, AntialiasedEdgesBlendWithMsaa) {
  Scene scene = clipSpaceScene();
  addPoint(scene, 16.0f, 16.0f, 0.0f);
  RenderOptions options = pointOptions(6.0f);
  const Frame sharp = render(scene, options);
  options.msaa = 4;
  const Frame smooth = render(scene, options);
  int partial = 0;
  for (uint32_t color : smooth.color) partial += color != kWhite && color != kBlack;
  EXPECT_GT(partial, 8);
  for (uint32_t color : sharp.color) EXPECT_TRUE(color == kWhite || color == kBlack);
  EXPECT_EQ(smooth.colorAt(16, 16), kWhite);
}

TEST(Points, SceneWithOnlyPointsOrLinesRenders) {
  Scene scene = clipSpaceScene();
  addPoint(scene, 3.5f, 3.5f, 0.0f);
  RenderOptions options = pointOptions(1.0f);
  for (int msaa : {1, 4}) {
    options.msaa = msaa;
    const Frame f = render(scene, options, 2);
    EXPECT_EQ(f.colorAt(3, 3), kWhite);
    EXPECT_EQ(countColor(f, kBlack), kW * kH - 1);
  }
  Scene lines = clipSpaceScene();
  lines.lines.add(windowToNdc(0, 3.5f, 0, kW, kH), windowToNdc(kW, 3.5f, 0, kW, kH), {1, 1, 1});
  EXPECT_EQ(countColor(render(lines, options, 2), kBlack) < kW * kH, true);
  const Frame empty = render(clipSpaceScene(), options, 2);
  EXPECT_EQ(countColor(empty, kBlack), kW * kH);
}

TEST(Lines, WidthThreeCoversThreePixelsAcross) {
  Scene scene = clipSpaceScene();
  scene.lines.add(windowToNdc(2, 10.5f, 0, kW, kH), windowToNdc(28, 10.5f, 0, kW, kH), {1, 1, 1});
  for (float width : {1.0f, 3.0f}) {
    RenderOptions options = pointOptions(1.0f);
    options.line_width = width;
    const Frame f = render(scene, options);
    int across = 0;
    for (int y = 0; y < kH; ++y) across += f.colorAt(15, y) == kWhite;
    EXPECT_EQ(across, static_cast<int>(width));
    EXPECT_EQ(f.colorAt(15, 10), kWhite);
    if (width == 3.0f) {
      EXPECT_EQ(f.colorAt(15, 9), kWhite);
      EXPECT_EQ(f.colorAt(15, 11), kWhite);
    }
  }
}

TEST(Points, NonlinearProjectionsMapTheCentreThroughTheModeWithDistanceAsDepth) {
  Scene scene;
  scene.camera.position = {0, 0, 0};
  scene.camera.target = {0, 0, -1};
  scene.camera.fov_y_degrees = 90;
  scene.camera.near_z = 1;
  scene.camera.far_z = 11;
  scene.points.positions = {{0, 0, -6}};  // straight ahead, 6 away: depth (6 - 1) / 10
  RenderOptions options = pointOptions(3.0f, 64, 32);
  options.projection = Projection::kSpherical;
  const Frame f = render(scene, options, 2);
  // The centre maps to window (32, 16), a pixel corner: the four pixels around it.
  EXPECT_EQ(countColor(f, kWhite), 4);
  for (int y : {15, 16})
    for (int x : {31, 32}) {
      EXPECT_EQ(f.colorAt(x, y), kWhite) << x << "," << y;
      EXPECT_NEAR(f.depthAt(x, y), 0.5f, 1e-6f);
    }
}
