// The nonlinear projections on the CPU, held to an independent brute-force ray caster
// (projection_scenes.h) and to the formulas of ../shared/ARCHITECTURE.md ("Projections").
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <tessera/render/cpu_renderer.h>
#include <tessera/render/projection.h>
#include <tessera/scene/color.h>

#include "allocation_counter.h"  // g_count_allocations, g_allocations
#include "projection_scenes.h"

namespace tessera {
namespace {

using test::castRay;
using test::eyeScene;
using test::unlitObject;

constexpr double kPi = std::numbers::pi;

struct ModeCase {
  Projection projection;
  int width, height;
  float fov;
};

// Each mode at a size and angle that shows what is hard about it: the whole sphere where the mode
// reaches it.
const ModeCase kModes[] = {
    {Projection::kCylindrical, 240, 120, 120.0f},
    {Projection::kSpherical, 240, 120, 180.0f},
    {Projection::kStereographic, 160, 160, 300.0f},
    {Projection::kFisheye, 160, 160, 360.0f},
};

Frame renderMode(const Scene& scene, const ModeCase& m, int workers = 1, int msaa = 1,
                 SimdLevel simd = SimdLevel::kAuto) {
  CpuRenderer renderer(workers, simd);
  RenderOptions options;
  options.width = m.width;
  options.height = m.height;
  options.projection = m.projection;
  options.msaa = msaa;
  options.normals = true;
  options.coverage = msaa > 1;
  Frame frame;
  renderer.render(scene, options, frame);
  return frame;
}

// The share of pixels whose rendered triangle id is the ray caster's.
double agreement(const Scene& scene, const ModeCase& m, const Frame& frame) {
  int same = 0;
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x)
      same += castRay(scene, m.projection, x, y, m.width, m.height).id == frame.idAt(x, y);
  return static_cast<double>(same) / (m.width * m.height);
}

Scene roomScene(const ModeCase& m) {
  Scene scene = eyeScene({0.3f, -0.2f, 0.1f}, m.fov);
  scene.objects.push_back(unlitObject(test::roomMesh({0, 0, 0}, 2.0f, 6), 6));
  // Something in the room, in front of the eye and tilted.
  Object box = unlitObject(test::roomMesh({0, 0, 0}, 0.3f, 2), 6);
  box.transform.translation = {0.5f, 0.1f, -1.2f};
  box.transform.rotation = quat::fromAxisAngle(normalize(float3{1, 1, 0}), 0.6f);
  scene.objects.push_back(box);
  return scene;
}

TEST(Projection, ViewAngleRangesFollowTheContract) {
  EXPECT_EQ(checkViewAngle(Projection::kPerspective, 179.0f, 1.0f), "");
  EXPECT_NE(checkViewAngle(Projection::kPerspective, 180.0f, 1.0f), "");
  EXPECT_EQ(checkViewAngle(Projection::kSpherical, 180.0f, 2.0f), "");
  EXPECT_NE(checkViewAngle(Projection::kSpherical, 181.0f, 1.0f), "");
  EXPECT_NE(checkViewAngle(Projection::kSpherical, 180.0f, 2.5f), "");  // 450 degrees across
  EXPECT_EQ(checkViewAngle(Projection::kCylindrical, 170.0f, 2.0f), "");
  EXPECT_NE(checkViewAngle(Projection::kCylindrical, 180.0f, 1.0f), "");
  EXPECT_EQ(checkViewAngle(Projection::kFisheye, 360.0f, 1.0f), "");
  EXPECT_NE(checkViewAngle(Projection::kFisheye, 361.0f, 1.0f), "");
  EXPECT_NE(checkViewAngle(Projection::kStereographic, 360.0f, 1.0f), "");
  EXPECT_NE(checkViewAngle(Projection::kFisheye, 0.0f, 1.0f), "");
  EXPECT_EQ(checkViewAngle(Projection::kFisheye, 200.0f, 1.0f), "");
  EXPECT_NE(checkViewAngle(Projection::kFisheye, 400.0f, 1.0f).find("at most 360"),
            std::string::npos);
  EXPECT_EQ(parseProjection("fisheye"), Projection::kFisheye);
  EXPECT_EQ(parseProjection("hyperbolic"), std::nullopt);
}

TEST(Projection, RaysFollowTheFormulas) {
  double d[3];
  // The centre of every mode looks down -Z.
  for (Projection p : kProjections) {
    ASSERT_TRUE(rayDirection(p, 50, 25, 100, 50, kPi / 2, d));
    EXPECT_NEAR(d[0], 0, 1e-12);
    EXPECT_NEAR(d[1], 0, 1e-12);
    EXPECT_NEAR(d[2], -1, 1e-12);
  }
  // A 2:1 spherical image at 180 degrees: the left edge looks straight back, the quarter right.
  ASSERT_TRUE(rayDirection(Projection::kSpherical, 0, 25, 100, 50, kPi, d));
  EXPECT_NEAR(d[2], 1, 1e-12);
  ASSERT_TRUE(rayDirection(Projection::kSpherical, 75, 25, 100, 50, kPi, d));
  EXPECT_NEAR(d[0], 1, 1e-12);
  ASSERT_TRUE(rayDirection(Projection::kSpherical, 50, 0, 100, 50, kPi, d));
  EXPECT_NEAR(d[1], 1, 1e-12);  // the top row is the zenith
  // Fisheye at 360: the image's inscribed circle is straight back; beyond it, nothing.
  ASSERT_TRUE(rayDirection(Projection::kFisheye, 50, 0, 100, 100, 2 * kPi, d));
  EXPECT_NEAR(d[2], 1, 1e-12);
  EXPECT_FALSE(rayDirection(Projection::kFisheye, 0, 0, 100, 100, 2 * kPi, d));
  // Stereographic: alpha = 2 atan(r tan(s / 2)); at r = 1 that is s.
  ASSERT_TRUE(rayDirection(Projection::kStereographic, 50, 0, 100, 100, 2.0, d));
  EXPECT_NEAR(std::acos(-d[2]), 1.0, 1e-12);
  // projectDirection inverts rayDirection.
  for (Projection p : kProjections) {
    ASSERT_TRUE(rayDirection(p, 31.25, 17.5, 100, 50, 1.5, d));
    double sx, sy;
    ASSERT_TRUE(projectDirection(p, d, 100, 50, 1.5, sx, sy)) << projectionName(p);
    EXPECT_NEAR(sx, 31.25, 1e-9) << projectionName(p);
    EXPECT_NEAR(sy, 17.5, 1e-9) << projectionName(p);
  }
}

// The table's rays are rayDirection's rounded to float, bit for bit, in every mode, in every
// layer (the samples' and the centres', with a jitter): the cylindrical and spherical tables take
// each column's sine and cosine once, the others a ray at a time.
TEST(Projection, TheRayTableHoldsRayDirectionsRaysExactly) {
  const double fov = 100.0 * kPi / 180.0;
  for (Projection p : kProjections) {
    RayTable table;
    ASSERT_TRUE(table.update(p, 37, 23, 100.0f, 4, Jitter{0.125f, -0.375f}));
    const int width = table.width(), height = table.height();
    int compared = 0;
    for (int i = 0; i <= table.samples(); ++i) {
      const RayLayer& layer = i < table.samples() ? table.sample(i) : table.centre();
      for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
          double d[3] = {0, 0, 0};
          if (!rayDirection(p, x + static_cast<double>(layer.offset_x),
                            y + static_cast<double>(layer.offset_y), width, height, fov, d))
            d[0] = d[1] = d[2] = 0;
          const size_t at = static_cast<size_t>(y) * width + x;
          ASSERT_EQ(layer.x[at], static_cast<float>(d[0])) << projectionName(p) << " " << x;
          ASSERT_EQ(layer.y[at], static_cast<float>(d[1])) << projectionName(p) << " " << x;
          ASSERT_EQ(layer.z[at], static_cast<float>(d[2])) << projectionName(p) << " " << x;
          ++compared;
        }
      }
    }
    EXPECT_EQ(compared, 5 * 37 * 23) << projectionName(p);
  }
}

TEST(Projection, IdsAgreeWithABruteForceRayCasterInEveryMode) {
  for (const ModeCase& m : kModes) {
    Scene room = roomScene(m);
    EXPECT_GE(agreement(room, m, renderMode(room, m)), 0.995) << projectionName(m.projection);
    Scene seam = eyeScene({0, 0, 0}, m.fov);
    seam.objects.push_back(unlitObject(test::seamMesh(12)));
    const Frame seam_frame = renderMode(seam, m);
    EXPECT_GE(agreement(seam, m, seam_frame), 0.995) << projectionName(m.projection);
    Scene pole = eyeScene({0, 0, 0}, m.fov);
    pole.objects.push_back(unlitObject(test::poleMesh(24)));
    const Frame pole_frame = renderMode(pole, m);
    EXPECT_GE(agreement(pole, m, pole_frame), 0.995) << projectionName(m.projection);
    // The meshes are seen at all (the oracle's agreement is not all background).
    if (m.projection != Projection::kCylindrical) {
      int seen = 0;
      for (uint32_t id : pole_frame.triangle_id) seen += id != kNoTriangle;
      EXPECT_GT(seen, m.width * m.height / 20) << projectionName(m.projection);
    }
  }
}

TEST(Projection, NoBackgroundInsideAClosedRoom) {
  for (const ModeCase& m : kModes) {
    const Scene scene = roomScene(m);
    for (int msaa : {1, 4}) {
      const Frame frame = renderMode(scene, m, 2, msaa);
      const double fov = m.fov * kPi / 180.0;
      int holes = 0, rays = 0;
      for (int y = 0; y < m.height; ++y) {
        for (int x = 0; x < m.width; ++x) {
          double d[3];
          if (!rayDirection(m.projection, x + 0.5, y + 0.5, m.width, m.height, fov, d)) continue;
          ++rays;
          holes += frame.idAt(x, y) == kNoTriangle;
          // Every sample of a pixel sees the room (watertight per sample): full coverage, except
          // at the fisheye's rim, where samples leave the circle of rays.
          if (msaa > 1 && m.projection != Projection::kFisheye) {
            EXPECT_EQ(frame.coverageAt(x, y), 255)
                << projectionName(m.projection) << " " << x << "," << y;
          }
        }
      }
      EXPECT_GT(rays, m.width * m.height / 2);
      EXPECT_EQ(holes, 0) << projectionName(m.projection) << " msaa " << msaa;
    }
  }
}

TEST(Projection, DepthIsTheRayDistanceFromNearToFar) {
  const ModeCase m = kModes[1];
  const Scene scene = roomScene(m);
  const Frame frame = renderMode(scene, m);
  int checked = 0;
  for (int y = 2; y < m.height; y += 7) {
    for (int x = 3; x < m.width; x += 7) {
      const test::OracleHit hit = castRay(scene, m.projection, x, y, m.width, m.height);
      if (hit.id != frame.idAt(x, y) || hit.id == kNoTriangle) continue;
      const double expected =
          (hit.distance - scene.camera.near_z) / (scene.camera.far_z - scene.camera.near_z);
      EXPECT_NEAR(frame.depthAt(x, y), expected, 1e-5) << x << "," << y;
      ++checked;
    }
  }
  EXPECT_GT(checked, 400);
}

TEST(Projection, PanoramaOfACubeRoomShowsEachFaceInItsBand) {
  // A 2:1 panorama at 180 degrees from the room's centre: longitude 0 (the middle column) looks
  // down -Z, +90 (three quarters across) down +X, the top rows up.
  const ModeCase m{Projection::kSpherical, 360, 180, 180.0f};
  Scene scene = eyeScene({0, 0, 0}, m.fov);
  scene.objects.push_back(unlitObject(test::roomMesh({0, 0, 0}, 1.0f, 4), 6));
  const Frame frame = renderMode(scene, m);
  const uint32_t per_face = 4 * 4 * 2;
  int checked = 0;
  for (int y = 0; y < m.height; ++y) {
    for (int x = 0; x < m.width; ++x) {
      const double lon = ((x + 0.5) / m.width * 2 - 1) * kPi;
      const double lat = (0.5 - (y + 0.5) / m.height) * kPi;
      const double d[3] = {std::cos(lat) * std::sin(lon), std::sin(lat),
                           -std::cos(lat) * std::cos(lon)};
      // The face the direction meets: its largest component, away from the cube's edges.
      int axis = 0;
      for (int k = 1; k < 3; ++k)
        if (std::fabs(d[k]) > std::fabs(d[axis])) axis = k;
      bool near_edge = false;
      for (int k = 0; k < 3; ++k)
        near_edge |= k != axis && std::fabs(d[k]) > 0.97 * std::fabs(d[axis]);
      if (near_edge) continue;
      const uint32_t face = static_cast<uint32_t>(axis * 2 + (d[axis] > 0 ? 1 : 0));
      ASSERT_NE(frame.idAt(x, y), kNoTriangle);
      EXPECT_EQ((frame.idAt(x, y) - 1) / per_face, face) << x << "," << y;
      ++checked;
    }
  }
  EXPECT_GT(checked, m.width * m.height * 8 / 10);
}

TEST(Projection, AStraightLineLandsOnItsAnalyticCurve) {
  // A world-space line at height 1 and depth 2 in front of the eye, drawn in a panorama: in
  // column x its point is at longitude theta, (2 tan theta, 1, -2), latitude atan(1 / |(x, z)|).
  const ModeCase m{Projection::kSpherical, 720, 360, 180.0f};
  Scene scene = eyeScene({0, 0, 0}, m.fov);
  scene.lines.add({-60, 1, -2}, {60, 1, -2}, {1, 1, 1});
  CpuRenderer renderer(1);
  RenderOptions options;
  options.width = m.width;
  options.height = m.height;
  options.projection = m.projection;
  Frame frame;
  renderer.render(scene, options, frame);
  int columns = 0;
  for (int x = 0; x < m.width; ++x) {
    const double theta = ((x + 0.5) / m.width * 2 - 1) * kPi;
    if (std::fabs(theta) > 1.4) continue;  // the line's ends (|x| <= 60) are near 88 degrees
    const double t = 2 * std::tan(theta);
    const double lat = std::atan2(1.0, std::sqrt(t * t + 4));
    const double row = (0.5 - lat / kPi) * m.height;  // window y of the curve
    int lit = 0;
    for (int y = 0; y < m.height; ++y) {
      if ((frame.colorAt(x, y) & 0xffffff) == 0) continue;
      ++lit;
      EXPECT_LE(std::fabs(y + 0.5 - row), 1.0) << "column " << x;
    }
    EXPECT_GE(lit, 1) << "column " << x;
    ++columns;
  }
  EXPECT_GT(columns, 300);
}

TEST(Projection, ColoursComeFromTheHitsBarycentrics) {
  // One large triangle with red, green and blue corners, unlit: each pixel's colour is the
  // corners' colours weighted by the barycentrics of its ray's hit, computed here in double.
  const ModeCase m{Projection::kFisheye, 128, 128, 200.0f};
  Scene scene = eyeScene({0, 0, 0}, m.fov);
  Mesh mesh;
  mesh.positions = {{-3, -2, -1}, {3, -2, -2}, {0, 3, -4}};
  mesh.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}};
  mesh.indices = {0, 1, 2};
  Object object = unlitObject(std::move(mesh));
  object.materials[0].base_color = {1, 1, 1, 1};
  scene.objects.push_back(object);
  const Frame frame = renderMode(scene, m);
  int checked = 0;
  for (int y = 0; y < m.height; y += 3) {
    for (int x = 0; x < m.width; x += 3) {
      if (frame.idAt(x, y) != 1) continue;
      double d[3];
      ASSERT_TRUE(
          rayDirection(m.projection, x + 0.5, y + 0.5, m.width, m.height, m.fov * kPi / 180, d));
      // Barycentrics of the hit: Cramer's rule on v0 a + v1 b + v2 c = t d, a + b + c = 1.
      const auto& p = scene.objects[0].mesh->positions;
      auto tri = [&](int i, int k) { return static_cast<double>(p[static_cast<size_t>(i)][k]); };
      double w[3];
      for (int k = 0; k < 3; ++k) {
        const int i1 = (k + 1) % 3, i2 = (k + 2) % 3;
        const double n[3] = {tri(i1, 1) * tri(i2, 2) - tri(i1, 2) * tri(i2, 1),
                             tri(i1, 2) * tri(i2, 0) - tri(i1, 0) * tri(i2, 2),
                             tri(i1, 0) * tri(i2, 1) - tri(i1, 1) * tri(i2, 0)};
        w[k] = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
      }
      const double sum = w[0] + w[1] + w[2];
      for (int k = 0; k < 3; ++k) {
        const double expected = encodeSrgb8(static_cast<float>(w[k] / sum));
        const double got = (frame.colorAt(x, y) >> (8 * k)) & 0xff;
        EXPECT_NEAR(got, expected, 1.0) << x << "," << y << " channel " << k;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

TEST(Projection, ImagesAreBitIdenticalForAnyWorkerCountAndSimdLevel) {
  for (const ModeCase& m : kModes) {
    Scene scene = roomScene(m);
    scene.objects[0].shading = Shading::kPhong;
    scene.lights.push_back({normalize(float3{-0.3f, -1, -0.5f}), float3(0.8f)});
    scene.show_world_axes = true;
    for (int msaa : {1, 4}) {
      const Frame one = renderMode(scene, m, 1, msaa);
      for (int workers : {2, 3}) {
        const Frame many = renderMode(scene, m, workers, msaa);
        EXPECT_EQ(one.color, many.color) << projectionName(m.projection) << " " << workers;
        EXPECT_EQ(one.triangle_id, many.triangle_id);
        EXPECT_EQ(one.depth, many.depth);
      }
      for (SimdLevel simd : {SimdLevel::kScalar, SimdLevel::kSse2, SimdLevel::kAvx2}) {
        const Frame other = renderMode(scene, m, 2, msaa, simd);
        EXPECT_EQ(one.color, other.color) << projectionName(m.projection);
        EXPECT_EQ(one.triangle_id, other.triangle_id);
      }
    }
  }
}

TEST(Projection, AllocatesNothingPerFrameAfterWarmUp) {
  const ModeCase m = kModes[1];
  Scene scene = roomScene(m);
  scene.show_world_axes = true;
  CpuRenderer renderer(3);
  RenderOptions options;
  options.width = m.width;
  options.height = m.height;
  options.projection = m.projection;
  options.normals = true;
  Frame frame;
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      g_allocations = 0;
      g_count_allocations = true;
    }
    for (int i = 0; i < 3; ++i) {
      scene.objects[1].transform.rotation = quat::fromAxisAngle({0, 1, 0}, 0.1f * i);
      // One sample, then 8x MSAA, with and without jitter: the rays are made again for each
      // jitter, into the same buffers.
      options.msaa = i == 2 ? 8 : 1;
      options.jitter = jitterOffset(static_cast<uint32_t>(i));
      renderer.render(scene, options, frame);
    }
  }
  g_count_allocations = false;
  EXPECT_EQ(g_allocations.load(), 0u);
}

}  // namespace
}  // namespace tessera
