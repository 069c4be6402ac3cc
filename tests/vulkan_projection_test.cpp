// The nonlinear projections on the compute backend (its ray passes) against the CPU renderer:
// cylindrical, spherical, stereographic and fisheye, on scenes that surround the camera, cross
// the 360-degree seam and hold the poles; with MSAA, jitter, the 32-bit commit path and float
// division. And vulkan-raster's refusal of them.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <tessera/render/projection.h>

#include "run_process.h"
#include "temp_folder.h"
#include "vulkan_fixtures.h"

namespace tessera::vulkan_test {
namespace {

// Each mode at an image and view angle that show what is particular to it: the cylindrical and
// spherical panoramas all the way round (their seam straight behind the camera), the spherical one
// from pole to pole, the stereographic at a wide 300 degrees and the fisheye at the full 360.
struct ModeSetup {
  Projection projection;
  int width, height;
  float view_angle;
};
constexpr ModeSetup kModes[] = {
    {Projection::kCylindrical, 288, 128, 160.0f},
    {Projection::kSpherical, 256, 128, 180.0f},
    {Projection::kStereographic, 256, 192, 300.0f},
    {Projection::kFisheye, 256, 192, 360.0f},
};

RenderOptions modeOptions(const ModeSetup& m, int msaa = 1, Jitter jitter = {}) {
  RenderOptions o = options(m.width, m.height, /*normals=*/true);
  o.projection = m.projection;
  o.msaa = msaa;
  o.jitter = jitter;
  o.coverage = msaa > 1;
  return o;
}

// Flat colours per face of a cube seen from inside (faces of makeCube: 4 vertices each).
Object roomObject(float size) {
  Mesh mesh = makeCube();
  const float4 face_colors[6] = {{0.9f, 0.3f, 0.3f, 1}, {0.3f, 0.9f, 0.3f, 1},
                                 {0.3f, 0.3f, 0.9f, 1}, {0.9f, 0.9f, 0.3f, 1},
                                 {0.3f, 0.9f, 0.9f, 1}, {0.9f, 0.3f, 0.9f, 1}};
  for (size_t v = 0; v < mesh.positions.size(); ++v) mesh.colors.push_back(face_colors[v / 4 % 6]);
  Object room;
  room.mesh = std::make_shared<Mesh>(std::move(mesh));
  room.shading = Shading::kGouraud;
  room.cull = CullMode::kNone;
  room.transform.scale = float3(size);
  return room;
}

Object sphereObject(int segments, int rings, float3 at, float radius, Shading shading) {
  Object sphere;
  sphere.mesh = std::make_shared<Mesh>(makeUvSphere(segments, rings));
  sphere.shading = shading;
  sphere.materials[0].base_color = {0.2f, 0.5f, 0.9f, 1.0f};
  sphere.transform.translation = at;
  sphere.transform.scale = float3(radius);
  return sphere;
}

// The camera a little off the room's centre, looking down -Z.
Scene surroundingScene() {
  Scene scene;
  addLights(scene);
  scene.camera.position = {0.11f, 0.07f, 0.23f};
  scene.camera.target = {0.11f, 0.07f, -1.0f};
  scene.camera.near_z = 0.05f;
  scene.camera.far_z = 30.0f;
  return scene;
}

// A closed cube room around the camera, a Gouraud sphere ahead and a Phong cube beside it, and
// the world axes (the line pass through the mode's mapping).
Scene roomScene() {
  Scene scene = surroundingScene();
  scene.show_world_axes = true;
  scene.objects.push_back(roomObject(9.0f));
  scene.objects.push_back(sphereObject(32, 16, {0.6f, -0.3f, -2.5f}, 0.8f, Shading::kGouraud));
  Object cube;
  cube.mesh = std::make_shared<Mesh>(makeCube());
  cube.shading = Shading::kPhong;
  cube.materials[0].base_color = {0.9f, 0.8f, 0.2f, 1.0f};
  cube.transform.translation = {-2.0f, 0.4f, -1.0f};
  cube.transform.rotation = quat::fromAxisAngle(normalize(float3{0, 1, 1}), 0.5f);
  scene.objects.push_back(cube);
  return scene;
}

// A dense UV sphere around the eye (thousands of triangles sharing edges, two pole fans) with a
// smaller sphere inside it.
Scene sphereRoomScene() {
  Scene scene = surroundingScene();
  Object shell = sphereObject(96, 48, {0.0f, 0.0f, 0.0f}, 8.0f, Shading::kPhong);
  shell.cull = CullMode::kNone;
  shell.materials[0].base_color = {0.8f, 0.7f, 0.6f, 1.0f};
  scene.objects.push_back(shell);
  scene.objects.push_back(sphereObject(24, 12, {-1.0f, 0.5f, -3.0f}, 1.0f, Shading::kFlat));
  return scene;
}

// Objects straight behind the camera, where the cylindrical and spherical images wrap round and
// the fisheye's outer ring is: a sphere, a long thin triangle and a grid across the seam.
Scene seamScene() {
  Scene scene = surroundingScene();
  scene.camera.position = {0, 0, 0};
  scene.camera.target = {0, 0, -1};
  scene.objects.push_back(sphereObject(40, 20, {0.05f, 0.1f, 3.0f}, 1.2f, Shading::kGouraud));
  Mesh sliver;
  sliver.positions = {{-2.0f, -0.4f, 2.0f}, {2.5f, -0.35f, 2.2f}, {0.2f, -0.2f, 1.5f}};
  sliver.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}};
  sliver.indices = {0, 1, 2};
  scene.objects.push_back(whiteUnlitObject(std::move(sliver)));
  Object wall;
  wall.mesh = std::make_shared<Mesh>(makeGrid(10, 2.0f, 1.0f));
  wall.shading = Shading::kFlat;
  wall.cull = CullMode::kNone;
  wall.transform.translation = {0.0f, -1.5f, 1.0f};
  wall.transform.rotation = quat::fromAxisAngle({1, 0, 0}, 1.2f);
  scene.objects.push_back(wall);
  scene.objects.push_back(sphereObject(16, 8, {0.5f, 0.0f, -3.0f}, 0.7f, Shading::kFlat));
  return scene;
}

// Triangles around the zenith and the nadir (the spherical image's top and bottom rows, the
// fisheye's side): a ceiling grid, a triangle that holds the zenith, a floor sphere.
Scene poleScene() {
  Scene scene = surroundingScene();
  scene.camera.position = {0, 0, 0};
  scene.camera.target = {0, 0, -1};
  Object ceiling;
  ceiling.mesh = std::make_shared<Mesh>(makeGrid(6, 3.0f, 1.0f));
  ceiling.shading = Shading::kGouraud;
  ceiling.cull = CullMode::kNone;
  ceiling.materials[0].base_color = {0.7f, 0.9f, 0.6f, 1.0f};
  ceiling.transform.translation = {0.3f, 2.5f, -0.2f};
  scene.objects.push_back(ceiling);
  Mesh zenith;
  zenith.positions = {{-0.3f, 1.5f, -0.2f}, {0.35f, 1.6f, -0.25f}, {0.0f, 1.4f, 0.4f}};
  zenith.colors = {{1, 0.5f, 0, 1}, {0, 1, 0.5f, 1}, {0.5f, 0, 1, 1}};
  zenith.indices = {0, 1, 2};
  scene.objects.push_back(whiteUnlitObject(std::move(zenith)));
  scene.objects.push_back(sphereObject(32, 16, {0.1f, -2.0f, 0.05f}, 1.0f, Shading::kPhong));
  return scene;
}

struct ProjectedParity {
  Parity parity;
  size_t same_coverage = 0;  // pixels whose coverage AOV is equal (MSAA)
  float max_depth_diff = 0;  // over pixels with the same triangle
};

ProjectedParity compareProjected(const Frame& gpu, const Frame& cpu) {
  ProjectedParity p;
  p.parity = compare(gpu, cpu);
  for (size_t i = 0; i < gpu.pixelCount(); ++i) {
    if (!gpu.coverage.empty() && !cpu.coverage.empty())
      p.same_coverage += gpu.coverage[i] == cpu.coverage[i];
    if (gpu.triangle_id[i] != kNoTriangle && gpu.triangle_id[i] == cpu.triangle_id[i])
      p.max_depth_diff = std::max(p.max_depth_diff, std::abs(gpu.depth[i] - cpu.depth[i]));
  }
  return p;
}

std::string label(const char* scene, const ModeSetup& m, const RenderOptions& o) {
  std::string s = std::string(scene) + ", " + projectionName(m.projection);
  if (o.msaa > 1) s += ", " + std::to_string(o.msaa) + "x MSAA";
  if (o.jitter.x != 0.0f || o.jitter.y != 0.0f) s += ", jittered";
  return s;
}

// Renders `scene` in mode m on both backends and holds the GPU to the numbers: ids equal
// on 99.99% of the covered pixels, colours within 2/255 on 99.9%, depth within 1e-6 where the
// ids agree, the coverage AOV equal on 99.99%. Returns the GPU frame.
Frame expectModeParity(ComputeBackend& backend, const char* name, Scene scene, const ModeSetup& m,
                       const RenderOptions& o) {
  scene.camera.fov_y_degrees = m.view_angle;
  EXPECT_EQ(checkViewAngle(m.projection, m.view_angle, static_cast<float>(m.width) / m.height), "");
  const Frame cpu = renderCpu(scene, o);
  Frame gpu = renderWith(backend, scene, o);
  const std::string what = label(name, m, o);
  const ProjectedParity p = compareProjected(gpu, cpu);
  expectComputeParity(what.c_str(), p.parity);
  EXPECT_LE(p.max_depth_diff, 1e-6f) << what;
  if (o.coverage) {
    const double ratio = static_cast<double>(p.same_coverage) / p.parity.pixels;
    std::printf("[ parity   ] %s: coverage equal on %.4f%%\n", what.c_str(), 100.0 * ratio);
    EXPECT_GE(ratio, 0.9999) << what;
  }
  return gpu;
}

// Each test gets a compute backend (and is skipped only without any Vulkan device).
class VulkanProjection : public ::testing::Test {
 protected:
  void SetUp() override {
    TESSERA_SKIP_WITHOUT_VULKAN();
    gpu_ = makeCompute(vk_);
    ASSERT_TRUE(gpu_);
  }
  ComputeBackend& gpu() { return *gpu_; }
  VulkanOptions vk_;
  ComputePtr gpu_;
};

// The 32-bit commit path with float division in the ray depth.
class VulkanProjectionFallbacks : public VulkanProjection {
 protected:
  void SetUp() override {
    vk_.force_32bit_atomics = true;
    vk_.force_fp32_setup = true;
    VulkanProjection::SetUp();
  }
};

size_t emptyPixels(const Frame& frame) {
  return static_cast<size_t>(
      std::count(frame.triangle_id.begin(), frame.triangle_id.end(), kNoTriangle));
}

TEST_F(VulkanProjection, RoomAroundTheCameraMatchesCpuInEveryMode) {
  for (const ModeSetup& m : kModes) {
    const Frame frame = expectModeParity(gpu(), "room", roomScene(), m, modeOptions(m));
    // The closed room fills the panoramas (they have a ray at every pixel).
    if (m.projection == Projection::kSpherical || m.projection == Projection::kCylindrical) {
      EXPECT_EQ(emptyPixels(frame), 0u) << projectionName(m.projection);
    }
  }
}

TEST_F(VulkanProjection, DenseSphereAroundTheEyeLeavesNoCrack) {
  for (const ModeSetup& m : kModes) {
    const Frame frame =
        expectModeParity(gpu(), "sphere room", sphereRoomScene(), m, modeOptions(m));
    // Every pixel with a ray sees the shell: a crack between triangles would show the background.
    // The fisheye at 360 degrees has rays inside its image circle only (radius: half the height).
    size_t rayless = 0;
    if (m.projection == Projection::kFisheye) {
      for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
          const float u = (x + 0.5f - m.width / 2.0f) / (m.height / 2.0f);
          const float v = (y + 0.5f - m.height / 2.0f) / (m.height / 2.0f);
          rayless += u * u + v * v > 1.0f;
        }
      ASSERT_GT(rayless, 0u);
    }
    EXPECT_EQ(emptyPixels(frame), rayless) << projectionName(m.projection);
  }
}

// Narrow view angles: pixels a few arc minutes wide, so the GPU's float cone boxes have the least
// room (their margins are fixed angles plus pixels).
TEST_F(VulkanProjection, NarrowViewAnglesMatchCpu) {
  for (ModeSetup m : kModes) {
    m.view_angle = 24.0f;
    expectModeParity(gpu(), "narrow sphere room", sphereRoomScene(), m, modeOptions(m));
  }
}

TEST_F(VulkanProjection, TrianglesAcrossTheSeamMatchCpu) {
  for (const ModeSetup& m : kModes) {
    const Frame frame = expectModeParity(gpu(), "seam", seamScene(), m, modeOptions(m));
    if (m.projection != Projection::kSpherical) continue;
    // The sphere behind the camera shows at both the left and the right edge of the panorama.
    const int row = m.height / 2 - 3;
    EXPECT_NE(frame.triangle_id[static_cast<size_t>(row) * m.width], kNoTriangle);
    EXPECT_NE(frame.triangle_id[static_cast<size_t>(row) * m.width + m.width - 1], kNoTriangle);
  }
}

TEST_F(VulkanProjection, TrianglesAtThePolesMatchCpu) {
  for (const ModeSetup& m : kModes) {
    const Frame frame = expectModeParity(gpu(), "poles", poleScene(), m, modeOptions(m));
    if (m.projection != Projection::kSpherical) continue;
    // The zenith triangle holds the pole: the whole top row of the panorama.
    for (int x = 0; x < m.width; ++x) EXPECT_NE(frame.triangle_id[x], kNoTriangle) << x;
  }
}

TEST_F(VulkanProjection, TexturedSceneMatchesCpu) {
  for (const ModeSetup& m : kModes)
    expectModeParity(gpu(), "textured", texturedScene(), m, modeOptions(m));
}

TEST_F(VulkanProjection, MsaaMatchesCpu) {
  for (const ModeSetup& m : kModes) {
    expectModeParity(gpu(), "room", roomScene(), m, modeOptions(m, 4));
    expectModeParity(gpu(), "seam", seamScene(), m, modeOptions(m, 4));
  }
  expectModeParity(gpu(), "poles", poleScene(), kModes[1], modeOptions(kModes[1], 8));
  expectModeParity(gpu(), "sphere room", sphereRoomScene(), kModes[3], modeOptions(kModes[3], 2));
}

TEST_F(VulkanProjection, JitteredFramesMatchCpu) {
  for (const ModeSetup& m : kModes)
    for (uint32_t index : {1u, 5u}) {
      expectModeParity(gpu(), "room", roomScene(), m, modeOptions(m, 1, jitterOffset(index)));
      expectModeParity(gpu(), "seam", seamScene(), m, modeOptions(m, 4, jitterOffset(index)));
    }
}

TEST_F(VulkanProjectionFallbacks, ThirtyTwoBitCommitAndFloatDivisionMatchCpu) {
  for (const ModeSetup& m : kModes) {
    expectModeParity(gpu(), "room", roomScene(), m, modeOptions(m));
    expectModeParity(gpu(), "sphere room", sphereRoomScene(), m, modeOptions(m, 4));
  }
}

// The ray passes leave nothing behind: a perspective frame after panoramas is the same, bit for
// bit, as before them, and a panorama after a resize matches the CPU's.
TEST_F(VulkanProjection, SwitchingModesKeepsEachFrameExact) {
  const Scene scene = roomScene();
  const RenderOptions perspective = options();
  const Frame before = renderWith(gpu(), scene, perspective);
  for (const ModeSetup& m : kModes) expectModeParity(gpu(), "room", scene, m, modeOptions(m));
  const Frame after = renderWith(gpu(), scene, perspective);
  EXPECT_EQ(after.color, before.color);
  EXPECT_EQ(after.triangle_id, before.triangle_id);
  EXPECT_EQ(after.depth, before.depth);
  const Frame cpu = renderCpu(scene, perspective);
  EXPECT_EQ(after.triangle_id, cpu.triangle_id);
  ModeSetup wide = kModes[1];
  wide.width = 200;
  wide.height = 100;
  expectModeParity(gpu(), "room, resized", scene, wide, modeOptions(wide));
}

TEST(VulkanRasterProjection, RefusesNonlinearProjections) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(raster);
  for (const ModeSetup& m : kModes) {
    Scene scene = roomScene();
    scene.camera.fov_y_degrees = m.view_angle;
    Frame frame;
    raster->render(scene, modeOptions(m), frame);
    const Expected<void> result = raster->lastResult();
    ASSERT_FALSE(result.ok()) << projectionName(m.projection);
    EXPECT_EQ(result.error().message,
              "vulkan-raster draws the perspective projection only; use --backend cpu or vulkan");
    // The failed frame is left empty, never half drawn.
    EXPECT_EQ(emptyPixels(frame), frame.pixelCount());
  }
  // It still draws the perspective projection after refusing.
  const Frame frame = renderWith(*raster, roomScene(), options());
  EXPECT_LT(emptyPixels(frame), frame.pixelCount());
}

#ifdef TESSERA_EXE
// The CLI: vulkan-raster refuses with exit status 1, the message and no output file; the vulkan
// backend writes the CPU's id AOV byte for byte.
TEST(VulkanProjectionCli, RefusesVulkanRasterAndDrawsWithVulkan) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  const std::filesystem::path dir = test::makeTestFolder("tessera_vulkan_projection");
  test::writeFile(dir / "tri.obj",
                  "v -1 -1 -3\nv 1 -1 -3\nv 0 1 -3\nv -1 0 3\nv 1 0 3\nv 0 1.5 3\n"
                  "f 1 2 3\nf 4 6 5\n");
  const std::string model = "tri.obj --camera-position 0,0,0 --camera-focal-point 0,0,-1 ";
  const test::RunResult refused = test::runInFolder(
      dir, TESSERA_EXE,
      "render " + model + "--projection spherical --backend vulkan-raster -o refused.png");
  EXPECT_EQ(refused.exit_code, 1) << refused.err;
  EXPECT_NE(refused.err.find("vulkan-raster draws the perspective projection only; use --backend "
                             "cpu or vulkan"),
            std::string::npos)
      << refused.err;
  size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1u) << "only the model: no output, no temporary";
  for (const char* mode : {"spherical", "fisheye"}) {
    std::string ids[2];
    for (int b = 0; b < 2; ++b) {
      const std::string backend = b == 0 ? "cpu" : "vulkan";
      const test::RunResult r =
          test::runInFolder(dir, TESSERA_EXE,
                            "render " + model + "--resolution 128,64 --aov id --projection " +
                                mode + " --backend " + backend + " -o " + backend + ".png");
      EXPECT_EQ(r.exit_code, 0) << mode << ", " << backend << ": " << r.err;
      ids[b] = test::slurp(dir / (backend + ".png"));
    }
    EXPECT_FALSE(ids[0].empty()) << mode;
    EXPECT_EQ(ids[0], ids[1]) << mode;
  }
  std::filesystem::remove_all(dir);
}
#endif  // TESSERA_EXE

}  // namespace
}  // namespace tessera::vulkan_test
