// Tests of anti-aliasing on the CPU pipeline: per-sample coverage at the standard positions, the
// resolve, the AOVs' independence of the sample count, jitter and accumulation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>

#include <tessera/render/accumulate.h>
#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/color.h>
#include <tessera/scene/primitives.h>

#include "msaa_test_scenes.h"

using namespace tessera;
using namespace tessera::test;

namespace {

constexpr int kSampleCounts[] = {2, 4, 8};

// The coverage rule, written out independently of the renderer: a point is inside when it is on
// the inner side of all three edges, or on an edge that is a top or left one (y down, the
// triangle wound clockwise on screen).
bool insideTriangle(const SubPixel v[3], int64_t px, int64_t py) {
  const int64_t area =
      (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x);
  if (area == 0) return false;
  const SubPixel* w[3] = {&v[0], area > 0 ? &v[1] : &v[2], area > 0 ? &v[2] : &v[1]};
  for (int k = 0; k < 3; ++k) {
    const SubPixel& a = *w[k];
    const SubPixel& b = *w[(k + 1) % 3];
    const int64_t e = (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
    const bool top_left = (b.y - a.y) < 0 || ((b.y - a.y) == 0 && (b.x - a.x) > 0);
    if (e < 0 || (e == 0 && !top_left)) return false;
  }
  return true;
}

// A mesh of triangles given in sub-pixels, one material per triangle.
struct SubPixelMesh {
  std::vector<SubPixel> points;
  std::vector<uint32_t> indices;
};

Mesh toMesh(const SubPixelMesh& m, int width, int height) {
  Mesh mesh;
  for (const SubPixel& p : m.points) mesh.positions.push_back(toNdc(p, 0.0f, width, height));
  mesh.indices = m.indices;
  return mesh;
}

}  // namespace

TEST(Msaa, StraightEdgeCoversTheAnalyticCountOfSamples) {
  // A slanted edge crossing a 64x64 image, at sub-pixel positions no sample lies on: every
  // pixel's coverage is the number of its samples left of the edge, counted here from the line's
  // equation.
  const int size = 64;
  const SubPixel v[3] = {{-4000, -3000}, {30 * 256 + 77, -3000}, {41 * 256 + 13, 80 * 256 + 5}};
  Mesh mesh;
  for (const SubPixel& p : v) mesh.positions.push_back(toNdc(p, 0.0f, size, size));
  mesh.indices = {0, 1, 2};
  Scene scene = clipSpaceScene();
  scene.objects.push_back(unlitMesh(mesh));
  for (int n : kSampleCounts) {
    SCOPED_TRACE(n);
    const Frame frame = render(scene, optionsFor(size, size, n));
    int partial = 0;
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        int covered = 0;
        for (const SamplePosition& s : samplePattern(n)) {
          const int64_t px = int64_t{x} * 256 + s.x, py = int64_t{y} * 256 + s.y;
          // The edge from v[1] to v[2]: no sample exactly on it (the test's premise).
          const int64_t e = (v[2].x - v[1].x) * (py - v[1].y) - (v[2].y - v[1].y) * (px - v[1].x);
          ASSERT_NE(e, 0);
          covered += insideTriangle(v, px, py);
        }
        partial += covered > 0 && covered < n;
        ASSERT_EQ(frame.coverageAt(x, y), (covered * 255 + n / 2) / n) << x << "," << y;
      }
    }
    EXPECT_GT(partial, 30);  // the edge splits the samples of a pixel in most rows
  }
}

TEST(Msaa, MeshSharingEdgesCoversEverySampleExactlyOnce) {
  // Thirty-two triangles over a grid of jittered points, each its own colour, all at one depth: a
  // sample covered twice would take the colour of whichever triangle comes first, so the image
  // in both orders must equal the resolve of each sample's one owner (found here by the rule).
  const int size = 64;
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> wobble(-300, 300);
  SubPixelMesh grid;
  const int cells = 4;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) {
      const bool border = i == 0 || j == 0 || i == cells || j == cells;
      grid.points.push_back(
          {i * 16 * 256 + (border ? 0 : wobble(rng)), j * 16 * 256 + (border ? 0 : wobble(rng))});
    }
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const uint32_t a = static_cast<uint32_t>(j * (cells + 1) + i), b = a + 1, c = a + cells + 1,
                     d = c + 1;
      grid.indices.insert(grid.indices.end(), {a, b, d, a, d, c});
    }
  const size_t triangles = grid.indices.size() / 3;
  std::vector<float3> palette;
  for (size_t t = 0; t < triangles; ++t)
    palette.push_back({static_cast<float>((t * 7) % 5) / 4.0f,
                       static_cast<float>((t * 3) % 4) / 3.0f, static_cast<float>(t % 3) / 2.0f});

  for (bool reversed : {false, true}) {
    SubPixelMesh ordered = grid;
    if (reversed)
      for (size_t t = 0; t < triangles / 2; ++t)
        for (int k = 0; k < 3; ++k)
          std::swap(ordered.indices[3 * t + k], ordered.indices[3 * (triangles - 1 - t) + k]);
    Mesh mesh = toMesh(ordered, size, size);
    Object object = unlitMesh(Mesh{});
    object.materials.clear();
    for (size_t t = 0; t < triangles; ++t) {
      const float3 c = palette[reversed ? triangles - 1 - t : t];
      Material m;
      m.base_color = {c.x, c.y, c.z, 1};
      object.materials.push_back(m);
      mesh.triangle_materials.push_back(static_cast<uint16_t>(t));
    }
    object.mesh = std::make_shared<Mesh>(std::move(mesh));
    Scene scene = clipSpaceScene();
    scene.objects.push_back(object);
    for (int n : kSampleCounts) {
      SCOPED_TRACE(testing::Message() << n << " samples, reversed " << reversed);
      const Frame frame = render(scene, optionsFor(size, size, n));
      for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
          float3 sum{0, 0, 0};
          for (const SamplePosition& s : samplePattern(n)) {
            int owners = 0;
            for (size_t t = 0; t < triangles; ++t) {
              const SubPixel v[3] = {grid.points[grid.indices[3 * t]],
                                     grid.points[grid.indices[3 * t + 1]],
                                     grid.points[grid.indices[3 * t + 2]]};
              if (insideTriangle(v, int64_t{x} * 256 + s.x, int64_t{y} * 256 + s.y)) {
                ++owners;
                sum = sum + palette[t];
              }
            }
            ASSERT_EQ(owners, 1) << "the rule itself: the grid covers the image once";
          }
          const uint32_t c = frame.colorAt(x, y);
          for (int k = 0; k < 3; ++k) {
            const int expected = encodeSrgb8(sum[k] / static_cast<float>(n));
            ASSERT_NEAR(static_cast<int>((c >> (8 * k)) & 0xff), expected, 1)
                << x << "," << y << " channel " << k;
          }
          ASSERT_EQ(frame.coverageAt(x, y), 255);
        }
      }
    }
  }
}

TEST(Msaa, HalfCoveredWhitePixelResolvesToLinearHalf) {
  // White on black, an edge through the middle of a pixel column: half the samples of every
  // pattern lie left of x + 0.5, so the column resolves to linear 0.5 = sRGB 188, not 128.
  const int size = 32;
  Mesh mesh;
  const SubPixel v[4] = {
      {-256, -256}, {10 * 256 + 128, -256}, {10 * 256 + 128, 33 * 256}, {-256, 33 * 256}};
  for (const SubPixel& p : v) mesh.positions.push_back(toNdc(p, 0.0f, size, size));
  mesh.indices = {0, 1, 2, 0, 2, 3};
  Scene scene = clipSpaceScene();
  scene.objects.push_back(unlitMesh(mesh));
  ASSERT_EQ(encodeSrgb8(0.5f), 188);
  for (int n : kSampleCounts) {
    SCOPED_TRACE(n);
    const Frame frame = render(scene, optionsFor(size, size, n));
    for (int y = 0; y < size; ++y) {
      EXPECT_EQ(frame.colorAt(9, y) & 0xffffff, 0xffffffu);
      EXPECT_EQ(frame.colorAt(10, y) & 0xffffff, 0xbcbcbcu) << y;
      EXPECT_EQ(frame.colorAt(11, y) & 0xffffff, 0u);
      EXPECT_EQ(frame.coverageAt(10, y), 128);
    }
  }
}

namespace {

// A lit, untextured scene with curved silhouettes, shared edges and overlaps: a sphere in front
// of a cube, Phong and Gouraud, through a real perspective camera.
Scene litScene(Shading sphere_shading) {
  Scene scene;
  Object cube;
  cube.mesh = std::make_shared<Mesh>(makeCube());
  cube.shading = Shading::kFlat;
  cube.transform.rotation = quat::fromAxisAngle(normalize(float3{1, 1, 0}), 0.6f);
  scene.objects.push_back(cube);
  Object sphere;
  sphere.mesh = std::make_shared<Mesh>(makeUvSphere(24, 16));
  sphere.shading = sphere_shading;
  sphere.materials[0].base_color = {0.9f, 0.4f, 0.2f, 1};
  sphere.transform.translation = {0.5f, 0.3f, 0.6f};
  sphere.transform.scale = float3(0.6f);
  scene.objects.push_back(sphere);
  scene.lights.push_back({normalize(float3{-1, -2, -1}), float3(0.9f)});
  scene.camera.position = {0.4f, 0.8f, 3.2f};
  scene.camera.target = {0, 0, 0};
  scene.background = {0.05f, 0.1f, 0.2f, 1};
  return scene;
}

}  // namespace

TEST(Msaa, AovsAreThoseOfThePixelCentreAtEverySampleCount) {
  const Scene scene = litScene(Shading::kPhong);
  RenderOptions options = optionsFor(160, 120, 1);
  options.normals = true;
  const Frame one = render(scene, options);
  int drawn = 0;
  for (uint32_t id : one.triangle_id) drawn += id != kNoTriangle;
  ASSERT_GT(drawn, 3000);
  for (int n : kSampleCounts) {
    SCOPED_TRACE(n);
    options.msaa = n;
    const Frame many = render(scene, options, 2);
    EXPECT_EQ(many.triangle_id, one.triangle_id);
    ASSERT_EQ(many.depth.size(), one.depth.size());
    EXPECT_EQ(0,
              std::memcmp(many.depth.data(), one.depth.data(), sizeof(float) * one.depth.size()));
    ASSERT_EQ(many.normal.size(), one.normal.size());
    EXPECT_EQ(
        0, std::memcmp(many.normal.data(), one.normal.data(), sizeof(float3) * one.normal.size()));
    EXPECT_NE(many.color, one.color);  // the colour is resolved from the samples
    // Pixels wholly inside one triangle keep the one-sample colour.
    int interior = 0, same = 0;
    for (int y = 1; y + 1 < one.height; ++y)
      for (int x = 1; x + 1 < one.width; ++x) {
        if (many.coverageAt(x, y) != 255) continue;
        const uint32_t id = one.idAt(x, y);
        bool uniform = true;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) uniform &= one.idAt(x + dx, y + dy) == id;
        if (!uniform) continue;
        ++interior;
        same += many.colorAt(x, y) == one.colorAt(x, y);
      }
    EXPECT_GT(interior, 800);
    EXPECT_GT(same, interior * 9 / 10);
  }
}

TEST(Msaa, ImageIsTheSameForEveryWorkerCountAndInstructionSet) {
  for (Shading shading : {Shading::kGouraud, Shading::kPhong}) {
    const Scene scene = litScene(shading);
    for (int n : kSampleCounts) {
      SCOPED_TRACE(testing::Message() << n << " samples, shading " << static_cast<int>(shading));
      RenderOptions options = optionsFor(200, 150, n);
      options.depth = options.ids = false;
      const Frame reference = render(scene, options, 1, SimdLevel::kScalar);
      for (int workers : {1, 2, 3})
        for (SimdLevel simd :
             {SimdLevel::kScalar, SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512}) {
          const Frame frame = render(scene, options, workers, simd);
          EXPECT_EQ(frame.color, reference.color)
              << workers << " workers, simd " << static_cast<int>(simd);
          EXPECT_EQ(frame.coverage, reference.coverage);
        }
    }
  }
}

TEST(Msaa, JitterMovesTheSamplesAgainstTheGeometry) {
  // An edge at x = 10.625: the centre of pixel 10 (10.5) is inside; moved by +0.25 px the sample
  // (10.75) is outside, and moved by -0.25 px pixel 11's (11.25) is still outside.
  const int size = 32;
  Mesh mesh;
  const SubPixel v[4] = {
      {-256, -256}, {10 * 256 + 160, -256}, {10 * 256 + 160, 33 * 256}, {-256, 33 * 256}};
  for (const SubPixel& p : v) mesh.positions.push_back(toNdc(p, 0.0f, size, size));
  mesh.indices = {0, 1, 2, 0, 2, 3};
  Scene scene = clipSpaceScene();
  scene.objects.push_back(unlitMesh(mesh));
  RenderOptions options = optionsFor(size, size, 1);
  EXPECT_EQ(render(scene, options).coverageAt(10, 5), 255);
  options.jitter = {0.25f, 0.0f};
  EXPECT_EQ(render(scene, options).coverageAt(10, 5), 0);
  EXPECT_EQ(render(scene, options).coverageAt(9, 5), 255);
  options.jitter = {-0.25f, 0.0f};
  EXPECT_EQ(render(scene, options).coverageAt(10, 5), 255);
  EXPECT_EQ(render(scene, options).coverageAt(11, 5), 0);
}

TEST(Msaa, JitteredAccumulationConverges) {
  // The mean difference between accumulations of N and 2N jittered frames shrinks as N grows.
  const Scene scene = litScene(Shading::kGouraud);
  RenderOptions options = optionsFor(120, 90, 1);
  options.depth = options.ids = options.coverage = false;
  CpuRenderer renderer(2);
  Accumulator accumulator;
  auto accumulate = [&](int samples) {
    Frame frame;
    EXPECT_TRUE(accumulator.render(renderer, scene, options, samples, frame).ok());
    return frame;
  };
  auto meanDifference = [](const Frame& a, const Frame& b) {
    double sum = 0;
    for (size_t i = 0; i < a.color.size(); ++i)
      for (int k = 0; k < 3; ++k)
        sum += std::abs(static_cast<int>((a.color[i] >> (8 * k)) & 0xff) -
                        static_cast<int>((b.color[i] >> (8 * k)) & 0xff));
    return sum / static_cast<double>(a.color.size());
  };
  std::vector<double> differences;
  Frame previous = accumulate(2);
  for (int n = 4; n <= 32; n *= 2) {
    Frame next = accumulate(n);
    differences.push_back(meanDifference(previous, next));
    previous = std::move(next);
  }
  EXPECT_GT(differences.front(), 0.05);  // edges did change
  for (size_t i = 1; i < differences.size(); ++i)
    EXPECT_LT(differences[i], differences[i - 1]) << i;
  // Deterministic: the same accumulation twice is the same image.
  EXPECT_EQ(accumulate(8).color, accumulate(8).color);
  // Frame 0 is the plain image: one frame of accumulation is the plain render.
  Frame plain;
  renderer.render(scene, options, plain);
  EXPECT_EQ(accumulate(1).color, plain.color);
}

TEST(Msaa, LinesAreAntialiasedWithSeveralSamples) {
  // A white line across black: with one sample each column has one white pixel; with MSAA each
  // column's two pixels nearest the line share one pixel's worth of light (in linear terms).
  const int size = 64;
  Scene scene = clipSpaceScene();
  scene.lines.add(toNdc({2 * 256, 10 * 256 + 77}, 0.0f, size, size),
                  toNdc({62 * 256, 21 * 256 + 200}, 0.0f, size, size), float3{1, 1, 1});
  for (int n : {1, 4}) {
    SCOPED_TRACE(n);
    const Frame frame = render(scene, optionsFor(size, size, n));
    int partial = 0;
    for (int x = 4; x < 60; ++x) {
      float ink = 0;
      for (int y = 0; y < size; ++y) {
        const uint8_t code = static_cast<uint8_t>(frame.colorAt(x, y));
        ink += decodeSrgb8(code);
        partial += code != 0 && code != 255;
      }
      EXPECT_NEAR(ink, 1.0f, 0.02f) << x;
    }
    if (n == 1)
      EXPECT_EQ(partial, 0);
    else
      EXPECT_GT(partial, 40);
  }
}

TEST(Msaa, ColourComesFromTheSamplesWhenTheCentreHoldsAnotherTriangle) {
  // A speck covering the centre of pixel (5, 5) and none of its four samples, in front of a quad
  // covering the whole image: with the centre AOVs asked for, the id AOV shows the speck (as with
  // one sample) but the colour is the quad's, as the samples say; alone, the speck leaves the
  // background and a coverage of 0.
  const int size = 16;
  const SubPixel speck[3] = {{5 * 256 + 108, 5 * 256 + 110},
                             {5 * 256 + 150, 5 * 256 + 120},
                             {5 * 256 + 125, 5 * 256 + 150}};
  Mesh mesh;
  for (const SubPixel& p : speck) mesh.positions.push_back(toNdc(p, -0.5f, size, size));
  mesh.indices = {0, 1, 2};
  Object red = unlitMesh(mesh);
  red.materials[0].base_color = {1, 0, 0, 1};
  Mesh quad;
  const SubPixel corners[4] = {
      {-256, -256}, {17 * 256, -256}, {17 * 256, 17 * 256}, {-256, 17 * 256}};
  for (const SubPixel& p : corners) quad.positions.push_back(toNdc(p, 0.5f, size, size));
  quad.indices = {0, 1, 2, 0, 2, 3};
  Scene scene = clipSpaceScene();
  scene.objects.push_back(red);
  RenderOptions options = optionsFor(size, size, 4);
  const Frame alone = render(scene, options);
  EXPECT_EQ(alone.idAt(5, 5), 1u);  // the centre AOV sees it
  EXPECT_EQ(alone.colorAt(5, 5) & 0xffffff, 0u);
  EXPECT_EQ(alone.coverageAt(5, 5), 0);
  scene.objects.push_back(unlitMesh(quad));
  const Frame both = render(scene, options);
  EXPECT_EQ(both.idAt(5, 5), 1u);
  EXPECT_EQ(both.colorAt(5, 5), both.colorAt(7, 7));  // the quad's white
  EXPECT_EQ(both.coverageAt(5, 5), 255);
  options.depth = options.ids = false;  // no centre layer: the same colours
  EXPECT_EQ(render(scene, options).color, both.color);
}

TEST(Msaa, MixedPixelsAreShadedAtTheCentreOrTheFirstSampleTheTriangleHolds) {
  // One triangle at a time on black, its vertex colours a ramp across it (red 0 on edge AB, 1 at
  // C; green the reverse): a pixel its edges cross resolves to the ramp at the pixel centre when
  // the centre is inside the triangle (the rule above), else at the first of its samples, in
  // pattern order, inside it, times the share of samples covered. Small triangles and long thin
  // ones (whose box takes the raster's large-triangle walk), at every sample count.
  const int size = 256;
  std::mt19937 rng(5);
  std::uniform_int_distribution<int64_t> anywhere(20 * 256, 236 * 256), near(-6 * 256, 6 * 256);
  std::uniform_int_distribution<int64_t> span(120 * 256, 200 * 256), width(2 * 256, 5 * 256);
  int decisive = 0;  // pixels where the other shading point would be 3 codes off or more
  for (int n : kSampleCounts) {
    for (int trial = 0; trial < 9; ++trial) {
      SubPixel v[3];
      v[0] = {anywhere(rng), anywhere(rng)};
      if (trial < 6) {
        v[1] = {v[0].x + near(rng), v[0].y + near(rng)};
        v[2] = {v[0].x + near(rng), v[0].y + near(rng)};
      } else {  // from a corner region across the image, C a few pixels off AB's middle
        v[0] = {v[0].x / 8, v[0].y / 8};
        v[1] = {v[0].x + span(rng), v[0].y + span(rng)};
        const int64_t d = width(rng);
        v[2] = {(v[0].x + v[1].x) / 2 + d, (v[0].y + v[1].y) / 2 - d};
      }
      const int64_t area =
          (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x);
      if (area == 0) continue;
      // The ramp: 0 on AB, 1 at C, linear.
      const auto ramp = [&](double px, double py) {
        return static_cast<double>((v[1].x - v[0].x) * 1.0 * (py - v[0].y) -
                                   (v[1].y - v[0].y) * 1.0 * (px - v[0].x)) /
               static_cast<double>(area);
      };
      Mesh mesh;
      for (const SubPixel& p : v) {
        mesh.positions.push_back(toNdc(p, 0.0f, size, size));
        const float r =
            static_cast<float>(ramp(static_cast<double>(p.x), static_cast<double>(p.y)));
        mesh.colors.push_back({r, 1.0f - r, 0.0f, 1.0f});
      }
      mesh.indices = {0, 1, 2};
      Scene scene = clipSpaceScene();
      scene.objects.push_back(unlitMesh(mesh));
      const Frame frame = render(scene, optionsFor(size, size, n));
      SCOPED_TRACE(testing::Message() << n << " samples, triangle " << trial);
      for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
          const int64_t cx = int64_t{x} * 256 + 128, cy = int64_t{y} * 256 + 128;
          int covered = 0;
          SubPixel first{};
          for (const SamplePosition& s : samplePattern(n)) {
            const SubPixel p{int64_t{x} * 256 + s.x, int64_t{y} * 256 + s.y};
            if (!insideTriangle(v, p.x, p.y)) continue;
            if (covered++ == 0) first = p;
          }
          if (covered == 0 || covered == n) continue;  // the mixed pixels
          const bool centre = insideTriangle(v, cx, cy);
          const SubPixel at = centre ? SubPixel{cx, cy} : first;
          const double share = static_cast<double>(covered) / n;
          const double f = ramp(static_cast<double>(at.x), static_cast<double>(at.y));
          const uint32_t c = frame.colorAt(x, y);
          const int red = static_cast<int>(c & 0xff), green = static_cast<int>((c >> 8) & 0xff);
          ASSERT_NEAR(red, encodeSrgb8(static_cast<float>(f * share)), 1) << x << "," << y;
          ASSERT_NEAR(green, encodeSrgb8(static_cast<float>((1.0 - f) * share)), 1)
              << x << "," << y;
          if (centre) {
            const double g = ramp(static_cast<double>(first.x), static_cast<double>(first.y));
            decisive += std::abs(encodeSrgb8(static_cast<float>(g * share)) - red) >= 3;
          }
        }
      }
    }
  }
  EXPECT_GT(decisive, 500);  // the test tells the two shading points apart (1,102 here)
}
