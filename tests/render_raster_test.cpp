// The CPU pipeline's raster stage through its public seam, on scenes small enough to reason about
// pixel by pixel: coverage and the top-left rule, clipping, depth and Hi-Z. Culling, dropped
// triangles and the setup kernels are render_setup_test.cpp's.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <tessera/render/cpu_renderer.h>

#include "render_test_scenes.h"

using namespace tessera;
using namespace tessera::test;  // NOLINT(google-build-using-namespace)

TEST(Raster, SharedEdgeGridCoversEachPixelOnce) {
  constexpr int kW = 64, kH = 48;
  // Vertex columns and rows on pixel centres (x.5) and off them; the 7x7 cells have diagonals
  // that pass exactly through pixel centres.
  const float xs[] = {0, 7.5f, 14.5f, 20.5f, 31.5f, 40.5f, 47.5f, 55.25f, 64};
  const float ys[] = {0, 5.5f, 12.5f, 18.5f, 29.5f, 36.5f, 48};
  std::vector<float3> triangles;
  for (int r = 0; r + 1 < 7; ++r) {
    for (int c = 0; c + 1 < 9; ++c) {
      float3 p00{xs[c], ys[r], 0}, p10{xs[c + 1], ys[r], 0}, p01{xs[c], ys[r + 1], 0},
          p11{xs[c + 1], ys[r + 1], 0};
      // Alternate the diagonal, and the winding, from cell to cell.
      bool flip = (r + c) % 2 == 1;
      if (flip)
        triangles.insert(triangles.end(), {p00, p10, p11, p00, p11, p01});
      else
        triangles.insert(triangles.end(), {p00, p01, p10, p10, p01, p11});
      if (c % 3 == 0) std::swap(triangles[triangles.size() - 1], triangles[triangles.size() - 2]);
    }
  }
  std::vector<int> coverage(kW * kH, 0);
  for (size_t t = 0; t < triangles.size(); t += 3) {
    Scene scene = clipSpaceScene();
    scene.objects.push_back(
        unlitObject(windowTriangle(triangles[t], triangles[t + 1], triangles[t + 2], kW, kH)));
    Frame f = renderScene(scene, kW, kH);
    for (int i = 0; i < kW * kH; ++i) coverage[i] += f.triangle_id[i] != kNoTriangle;
  }
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) EXPECT_EQ(coverage[y * kW + x], 1) << "pixel " << x << "," << y;
}

TEST(Raster, TopLeftRuleOnEdgesThroughPixelCentres) {
  constexpr int kW = 10, kH = 10;
  // A square whose four edges pass exactly through pixel centres: the top and left edges own
  // their centres, the bottom and right ones do not.
  Scene scene = clipSpaceScene();
  Mesh quad;
  for (float3 p :
       {float3{2.5f, 2.5f, 0}, float3{6.5f, 2.5f, 0}, float3{6.5f, 6.5f, 0}, float3{2.5f, 6.5f, 0}})
    quad.positions.push_back(windowToNdc(p.x, p.y, p.z, kW, kH));
  quad.indices = {0, 2, 1, 0, 3, 2};
  scene.objects.push_back(unlitObject(quad));
  Frame f = renderScene(scene, kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      bool inside = x >= 2 && x <= 5 && y >= 2 && y <= 5;
      EXPECT_EQ(f.idAt(x, y) != kNoTriangle, inside) << x << "," << y;
    }
}

TEST(Raster, TopLeftRuleForASingleTriangle) {
  constexpr int kW = 8, kH = 8;
  // Right triangle: horizontal top edge on row 1's centres (top: owned), vertical left edge on
  // column 1's centres (left: owned), hypotenuse through centres (bottom-right: not owned).
  Scene scene = clipSpaceScene();
  scene.objects.push_back(
      unlitObject(windowTriangle({1.5f, 1.5f, 0}, {5.5f, 1.5f, 0}, {1.5f, 5.5f, 0}, kW, kH)));
  Frame f = renderScene(scene, kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      // Centre (x+0.5, y+0.5) strictly inside or on an owned edge: x >= 1, y >= 1, x + y < 6.
      bool expected = x >= 1 && y >= 1 && (x + y) < 6;
      EXPECT_EQ(f.idAt(x, y) != kNoTriangle, expected) << x << "," << y;
    }
}

TEST(Raster, SubpixelTriangleBetweenCentresCoversNothing) {
  Scene scene = clipSpaceScene();
  scene.objects.push_back(
      unlitObject(windowTriangle({3.6f, 3.6f, 0}, {3.9f, 3.6f, 0}, {3.6f, 3.9f, 0}, 8, 8)));
  PipelineStats stats;
  Frame f = renderScene(scene, 8, 8, 1, &stats);
  EXPECT_EQ(coveredCount(f), 0);
  EXPECT_EQ(stats.triangles_setup, 0u);
  EXPECT_EQ(stats.triangles_culled, 1u);
}

TEST(Raster, TriangleFarOutsideTheGuardBandIsClippedAndFillsTheScreen) {
  constexpr int kW = 40, kH = 30;
  Scene scene = clipSpaceScene();
  Mesh huge;
  huge.positions = {{-1e6f, -1e6f, 0.0f}, {1e6f, -1e6f, 0.0f}, {0.0f, 1e6f, 0.0f}};
  huge.indices = {0, 1, 2};
  scene.objects.push_back(unlitObject(huge));
  PipelineStats stats;
  Frame f = renderScene(scene, kW, kH, 1, &stats);
  EXPECT_EQ(stats.triangles_clipped, 1u);
  EXPECT_EQ(coveredCount(f), kW * kH);
  for (float z : f.depth) EXPECT_NEAR(z, 0.5f, 1e-6f);
}

TEST(Raster, TriangleCrossingTheNearPlaneMatchesTheAnalyticFloor) {
  // A floor at y = -1 running from behind the camera to z = -40; the camera at the origin looks
  // down -Z with a 90 degree field of view.
  constexpr int kW = 64, kH = 48;
  Scene scene;
  scene.ambient = float3(1.0f);
  scene.camera.position = {0, 0, 0};
  scene.camera.target = {0, 0, -1};
  scene.camera.fov_y_degrees = 90.0f;
  scene.camera.near_z = 0.5f;
  scene.camera.far_z = 100.0f;
  Mesh floor;
  floor.positions = {{-30, -1, 10}, {30, -1, 10}, {30, -1, -40}, {-30, -1, -40}};
  floor.indices = {0, 1, 2, 0, 2, 3};
  scene.objects.push_back(unlitObject(floor, CullMode::kBack));
  PipelineStats stats;
  Frame f = renderScene(scene, kW, kH, 1, &stats);
  EXPECT_EQ(stats.triangles_clipped, 2u);

  const float aspect = static_cast<float>(kW) / kH;
  const float4x4 projection = scene.camera.projection(aspect);
  int checked = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      float ndc_x = 2.0f * (x + 0.5f) / kW - 1.0f, ndc_y = 1.0f - 2.0f * (y + 0.5f) / kH;
      float3 dir{ndc_x * aspect, ndc_y, -1.0f};  // tan(45 deg) = 1
      bool hit = false;
      float t = 0;
      if (dir.y < 0) {
        t = -1.0f / dir.y;  // view distance along -Z
        float3 p = dir * t;
        // Skip pixels within a pixel's worth of the floor's far edge or sides.
        float margin = 0.6f * t * 2.0f / kH;
        if (std::fabs(p.z + 40.0f) < margin * 3 || std::fabs(std::fabs(p.x) - 30.0f) < margin * 3)
          continue;
        hit = p.z > -40.0f && std::fabs(p.x) < 30.0f;
      }
      EXPECT_EQ(f.idAt(x, y) != kNoTriangle, hit) << x << "," << y;
      if (hit) {
        float4 clip = projection * float4{dir * t, 1.0f};
        // Vertices snap to 1/256 pixel and the plane is evaluated in float: near the horizon
        // that moves depth by a few 1e-5.
        EXPECT_NEAR(f.depthAt(x, y), clip.z / clip.w * 0.5f + 0.5f, 1e-4f) << x << "," << y;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, kW * kH / 3);
}

TEST(Raster, InterpenetratingTrianglesResolveByDepth) {
  constexpr int kW = 32, kH = 16;
  Scene scene = clipSpaceScene();
  Mesh m;
  // Quad A leans from z = -0.5 (left, near) to z = 0.5 (right, far); quad B is flat at z = 0.
  m.positions = {{-1, -1, -0.5f}, {1, -1, 0.5f}, {1, 1, 0.5f}, {-1, 1, -0.5f},
                 {-1, -1, 0.0f},  {1, -1, 0.0f}, {1, 1, 0.0f}, {-1, 1, 0.0f}};
  m.indices = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
  scene.objects.push_back(unlitObject(m));
  Frame f = renderScene(scene, kW, kH);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      uint32_t id = f.idAt(x, y);
      if (x < kW / 2 - 1) {
        EXPECT_TRUE(id == 1 || id == 2) << x << "," << y << " id " << id;
      }
      if (x > kW / 2) {
        EXPECT_TRUE(id == 3 || id == 4) << x << "," << y << " id " << id;
      }
      // Depth is the nearer of the two planes.
      float z_a = 0.5f * ((x + 0.5f) / kW * 2.0f - 1.0f) * 0.5f + 0.5f;
      EXPECT_NEAR(f.depthAt(x, y), std::min(z_a, 0.5f), 1e-6f);
    }
  }
}

TEST(Raster, HiZRejectsOnlyWhatIsHidden) {
  // A screen-covering wall at z = 0 drawn first (it sets the blocks' depth bounds), then small
  // and large triangles behind it (all hidden) and in front of it (all visible), interleaved.
  constexpr int kW = 128, kH = 96;
  Scene scene = clipSpaceScene();
  Mesh m;
  auto quad = [&](float x0, float y0, float x1, float y1, float z) {
    const uint32_t base = static_cast<uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}});
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  };
  quad(-1, -1, 1, 1, 0.0f);  // ids 1, 2
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> pos(-0.95f, 0.8f);
  std::vector<std::pair<float, float>> in_front;
  for (int i = 0; i < 60; ++i) {
    const float x = pos(rng), y = pos(rng);
    const float size = i % 10 == 0 ? 0.6f : 0.08f;  // some large, most small
    const bool front = i % 3 == 0;
    quad(x, y, x + size, y + size, front ? -0.2f - 0.001f * i : 0.3f);
    if (front) in_front.emplace_back(x, y);
  }
  scene.objects.push_back(unlitObject(m, CullMode::kBack));
  Frame f = renderScene(scene, kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const uint32_t id = f.idAt(x, y);
      ASSERT_NE(id, kNoTriangle);
      // Triangle index id - 1 belongs to quad (id - 1) / 2; quad 0 is the wall, quad q >= 1 is
      // random quad q - 1, in front when (q - 1) % 3 == 0.
      const int q = static_cast<int>(id - 1) / 2;
      EXPECT_TRUE(q == 0 || (q - 1) % 3 == 0) << "hidden quad " << q << " at " << x << "," << y;
    }
  // Every quad in front owns the pixel at its lower-left corner's inside.
  for (auto [qx, qy] : in_front) {
    const int px = static_cast<int>((qx + 1.0f) * 0.5f * kW) + 1;
    const int py = static_cast<int>((1.0f - (qy + 0.02f)) * 0.5f * kH) - 1;
    const int q = static_cast<int>(f.idAt(px, py) - 1) / 2;
    EXPECT_NE(q, 0) << "a quad in front is missing at " << px << "," << py;
  }
}

TEST(Raster, HiZBoundsOfTiltedWallsHoldTheirFarthestCorner) {
  // A black screen-covering wall tilted in x and y sets each whole block's depth bound; then white
  // quads on a plane parallel to it and a little in front, so each is visible, at one sample (the
  // ids) and at four (the colour: the sample layers keep bounds of their own). A bound taken at a
  // block corner nearer than its farthest would reject the quads near the farthest corner.
  constexpr int kW = 128, kH = 96;
  for (const float tilt : {1.0f, -1.0f}) {
    const auto wall = [&](float x, float y) { return tilt * (0.3f * x - 0.2f * y); };
    auto quad = [&](Mesh& m, float x0, float y0, float x1, float y1, float in_front) {
      const uint32_t base = static_cast<uint32_t>(m.positions.size());
      m.positions.insert(m.positions.end(), {{x0, y0, wall(x0, y0) - in_front},
                                             {x1, y0, wall(x1, y0) - in_front},
                                             {x1, y1, wall(x1, y1) - in_front},
                                             {x0, y1, wall(x0, y1) - in_front}});
      m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    };
    Mesh back, front;
    quad(back, -1, -1, 1, 1, 0.0f);  // ids 1, 2
    // Quads two pixels wide every three pixels, 0.002 in front (the wall moves 0.0047 a pixel
    // across and 0.0042 down); the pixel at (px + 1, py + 1) is wholly inside each.
    std::vector<std::pair<int, int>> inside;
    for (int py = 1; py + 2 < kH; py += 3)
      for (int px = 1; px + 2 < kW; px += 3) {
        const float x0 = 2.0f * px / kW - 1.0f, y1 = 1.0f - 2.0f * py / kH;
        quad(front, x0, y1 - 4.0f / kH, x0 + 4.0f / kW, y1, 0.002f);
        inside.emplace_back(px + 1, py + 1);
      }
    Scene scene = clipSpaceScene();
    scene.objects.push_back(unlitObject(back, CullMode::kBack));
    scene.objects.back().materials[0].base_color = {0, 0, 0, 1};
    scene.objects.push_back(unlitObject(front, CullMode::kBack));
    for (const int msaa : {1, 4}) {
      RenderOptions options;
      options.width = kW;
      options.height = kH;
      options.msaa = msaa;
      const Frame f = renderAt(scene, options, SimdLevel::kAuto, 1);
      for (auto [px, py] : inside) {
        if (msaa == 1) {
          EXPECT_GT(f.idAt(px, py), 2u) << "the wall hides a quad at " << px << "," << py;
        }
        EXPECT_EQ(f.colorAt(px, py), 0xffffffffu)
            << "the wall shows through a quad at " << px << "," << py << ", " << msaa << "x";
      }
    }
  }
}
