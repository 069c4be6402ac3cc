// Shared by the Vulkan test files: backends that fail the test on any validation error, the
// comparison with the CPU renderer, and the scenes the tests draw.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>

#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/color.h>
#include <tessera/scene/primitives.h>
#include <tessera/vulkan/vulkan_backend.h>

#include "diagnostics_scenes.h"

namespace tessera::vulkan_test {

using tessera::vulkan::ComputeBackend;
using tessera::vulkan::RasterBackend;
using tessera::vulkan::VulkanOptions;

constexpr int kWidth = 256;
constexpr int kHeight = 192;

// Skips the test when there is no Vulkan device at all; otherwise does nothing (a device that
// exists but cannot run a backend is a failure, not a skip).
#define TESSERA_SKIP_WITHOUT_VULKAN()                                                          \
  do {                                                                                         \
    const std::string tessera_no_device = noVulkanDeviceReason();                              \
    if (!tessera_no_device.empty()) GTEST_SKIP() << "no Vulkan device: " << tessera_no_device; \
  } while (false)

inline std::string noVulkanDeviceReason() {
  static const std::string reason = [] {
    Expected<std::vector<vulkan::DeviceInfo>> devices = vulkan::listDevices();
    if (!devices) return devices.error().message;
    if (devices->empty()) return std::string("the loader lists no device");
    return std::string();
  }();
  return reason;
}

// Deletes a backend after failing the test on any validation error it recorded (none are
// recorded unless validation is on), so every test that makes one is checked.
struct ValidationCheck {
  template <typename B>
  void operator()(B* backend) const {
    const std::vector<std::string> errors = backend->validationErrors();
    EXPECT_TRUE(errors.empty()) << errors.size() << " validation errors, the first: "
                                << (errors.empty() ? "" : errors.front());
    delete backend;
  }
};
using ComputePtr = std::unique_ptr<ComputeBackend, ValidationCheck>;
using RasterPtr = std::unique_ptr<RasterBackend, ValidationCheck>;

inline ComputePtr makeCompute(VulkanOptions options = {}) {
  Expected<std::unique_ptr<ComputeBackend>> backend = ComputeBackend::create(options);
  EXPECT_TRUE(backend.ok()) << (backend ? "" : backend.error().message);
  return ComputePtr(backend ? backend->release() : nullptr);
}

inline RasterPtr makeRaster(VulkanOptions options = {}) {
  Expected<std::unique_ptr<RasterBackend>> backend = RasterBackend::create(options);
  EXPECT_TRUE(backend.ok()) << (backend ? "" : backend.error().message);
  return RasterPtr(backend ? backend->release() : nullptr);
}

inline RenderOptions options(int width = kWidth, int height = kHeight, bool normals = false) {
  RenderOptions o;
  o.width = width;
  o.height = height;
  o.normals = normals;
  return o;
}

inline Frame renderCpu(const Scene& scene, const RenderOptions& o, PipelineStats* stats = nullptr) {
  CpuRenderer cpu(1);
  Frame frame;
  cpu.render(scene, o, frame);
  if (stats) *stats = cpu.lastStats();
  return frame;
}

template <typename B>
inline Frame renderWith(B& backend, const Scene& scene, const RenderOptions& o) {
  Frame frame;
  backend.render(scene, o, frame);
  Expected<void> result = backend.lastResult();
  EXPECT_TRUE(result.ok()) << (result ? "" : result.error().message);
  const std::vector<std::string> errors = backend.validationErrors();
  EXPECT_TRUE(errors.empty()) << errors.size() << " validation errors, the first: "
                              << (errors.empty() ? "" : errors.front());
  return frame;
}

struct Parity {
  size_t pixels = 0;
  size_t covered = 0;      // pixels where either frame has a triangle
  size_t same_id = 0;      // of those, pixels with the same id
  size_t close_color = 0;  // pixels whose channels are all within 2/255
  int max_channel_diff = 0;
  double idRatio() const { return covered ? static_cast<double>(same_id) / covered : 1.0; }
  double colorRatio() const { return pixels ? static_cast<double>(close_color) / pixels : 1.0; }
};

inline Parity compare(const Frame& a, const Frame& b) {
  Parity p;
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  p.pixels = a.pixelCount();
  for (size_t i = 0; i < p.pixels; ++i) {
    if (!a.triangle_id.empty() && !b.triangle_id.empty() &&
        (a.triangle_id[i] != kNoTriangle || b.triangle_id[i] != kNoTriangle)) {
      ++p.covered;
      p.same_id += a.triangle_id[i] == b.triangle_id[i];
    }
    int worst = 0;
    for (int c = 0; c < 32; c += 8) {
      const int da = static_cast<int>((a.color[i] >> c) & 255u);
      const int db = static_cast<int>((b.color[i] >> c) & 255u);
      worst = std::max(worst, std::abs(da - db));
    }
    p.max_channel_diff = std::max(p.max_channel_diff, worst);
    p.close_color += worst <= 2;
  }
  return p;
}

inline void report(const char* what, const Parity& p) {
  std::printf(
      "[ parity   ] %s: %zu covered pixels, ids %.4f%% equal, colours within 2/255 on "
      "%.4f%%, max channel difference %d\n",
      what, p.covered, 100.0 * p.idRatio(), 100.0 * p.colorRatio(), p.max_channel_diff);
}

// The held-to numbers of the issue.
inline void expectComputeParity(const char* what, const Parity& p) {
  report(what, p);
  EXPECT_GT(p.covered, 0u) << what << ": nothing drawn";
  EXPECT_GE(p.idRatio(), 0.9999) << what;
  EXPECT_GE(p.colorRatio(), 0.999) << what;
}

inline void expectRasterParity(const char* what, const Parity& p) {
  report(what, p);
  EXPECT_GT(p.covered, 0u) << what << ": nothing drawn";
  EXPECT_GE(p.idRatio(), 0.999) << what;
}

// ---- scenes ----

inline void addLights(Scene& scene) {
  scene.lights.push_back({normalize(float3{-0.6f, -1.0f, -0.8f}), float3(0.85f)});
  scene.lights.push_back({normalize(float3{0.8f, 0.3f, -0.4f}), float3(0.2f)});
  scene.ambient = float3(0.12f);
  scene.background = {srgbToLinear(0.12f), srgbToLinear(0.13f), srgbToLinear(0.16f), 1.0f};
}

inline Scene cubeScene(float angle = 0.7f) {
  Scene scene;
  Object cube;
  cube.mesh = std::make_shared<Mesh>(makeCube());
  cube.shading = Shading::kFlat;
  cube.materials[0].base_color = {srgbToLinear(0.95f), srgbToLinear(0.55f), srgbToLinear(0.15f),
                                  1.0f};
  cube.transform.rotation =
      quat::fromAxisAngle({0, 1, 0}, angle) * quat::fromAxisAngle({1, 0, 0}, 0.35f);
  scene.objects.push_back(cube);
  addLights(scene);
  scene.camera.position = {0.0f, 1.1f, 2.4f};
  scene.camera.near_z = 0.1f;
  scene.camera.far_z = 20.0f;
  return scene;
}

inline Scene sphereScene(int segments, int rings, Shading shading) {
  Scene scene;
  Object sphere;
  sphere.mesh = std::make_shared<Mesh>(makeUvSphere(segments, rings));
  sphere.shading = shading;
  sphere.materials[0].base_color = {0.2f, 0.5f, 0.9f, 1.0f};
  sphere.transform.rotation = quat::fromAxisAngle(normalize(float3{1, 1, 0}), 0.4f);
  scene.objects.push_back(sphere);
  addLights(scene);
  scene.camera.position = {0.3f, 0.4f, 3.0f};
  return scene;
}

// A dense sphere with a cube pushed into it: the two meshes interpenetrate, so the depth test
// decides along the intersection curve.
inline Scene denseScene() {
  Scene scene = sphereScene(200, 100, Shading::kGouraud);
  Object cube;
  cube.mesh = std::make_shared<Mesh>(makeCube());
  cube.shading = Shading::kPhong;
  cube.materials[0].base_color = {0.9f, 0.8f, 0.2f, 1.0f};
  cube.transform.translation = {0.55f, 0.35f, 0.4f};
  cube.transform.rotation = quat::fromAxisAngle(normalize(float3{0, 1, 1}), 0.5f);
  cube.transform.scale = float3(0.9f);
  scene.objects.push_back(cube);
  return scene;
}

// A grid of quads in the plane y = 0, x and z in [-half, half], with UVs over [0, uv_scale].
inline Mesh makeGrid(int cells, float half, float uv_scale) {
  Mesh mesh;
  for (int j = 0; j <= cells; ++j) {
    for (int i = 0; i <= cells; ++i) {
      const float u = static_cast<float>(i) / cells, v = static_cast<float>(j) / cells;
      mesh.positions.push_back({-half + 2 * half * u, 0.0f, half - 2 * half * v});
      mesh.normals.push_back({0, 1, 0});
      mesh.uvs.push_back({u * uv_scale, v * uv_scale});
    }
  }
  const uint32_t stride = static_cast<uint32_t>(cells + 1);
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      const uint32_t a = j * stride + i, b = a + 1, c = a + stride, d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});  // counter-clockwise from +y
    }
  }
  return mesh;
}

// A floor that runs from behind the camera to far in front of it, and a wall of large
// triangles whose corners are behind the camera: both are cut by the near plane.
inline Scene nearPlaneScene() {
  Scene scene;
  Object floor;
  floor.mesh = std::make_shared<Mesh>(makeGrid(12, 30.0f, 1.0f));
  floor.shading = Shading::kPhong;
  floor.cull = CullMode::kNone;
  floor.materials[0].base_color = {0.7f, 0.7f, 0.7f, 1.0f};
  floor.transform.translation = {0.0f, -0.6f, 0.0f};
  scene.objects.push_back(floor);
  Object wall;
  Mesh wall_mesh;
  wall_mesh.positions = {{-3, -1, 1.5f}, {3, -0.5f, -8}, {0.5f, 3, -2}, {-2, 2, 2}, {2, 2.5f, -6}};
  wall_mesh.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 0, 1}, {0, 1, 1, 1}};
  wall_mesh.indices = {0, 1, 2, 3, 2, 4};
  wall.mesh = std::make_shared<Mesh>(wall_mesh);
  wall.shading = Shading::kUnlit;
  wall.cull = CullMode::kNone;
  wall.materials[0].base_color = {1, 1, 1, 1};
  scene.objects.push_back(wall);
  addLights(scene);
  scene.camera.position = {0.0f, 0.0f, 0.0f};
  scene.camera.target = {0.2f, -0.1f, -1.0f};
  scene.camera.near_z = 0.1f;
  scene.camera.far_z = 60.0f;
  return scene;
}

// A scene whose camera maps object coordinates straight to clip space.
using diagnostics_test::clipSpaceScene;

inline float3 windowToNdc(float x, float y, float z, int width, int height) {
  return {2.0f * x / width - 1.0f, 1.0f - 2.0f * y / height, z};
}

// `count` random triangles, each inside a `size`-pixel box placed in [x0, x0 + span) x
// [y0, y0 + span) (window pixels), at random depths, both windings.

// White, unlit, both faces drawn.
inline Object whiteUnlitObject(Mesh mesh) {
  Object object;
  object.mesh = std::make_shared<Mesh>(std::move(mesh));
  object.shading = Shading::kUnlit;
  object.cull = CullMode::kNone;
  object.materials[0].base_color = {1, 1, 1, 1};
  return object;
}

inline Scene randomTriangles(int count, float size, float x0, float y0, float span, uint32_t seed) {
  Scene scene = clipSpaceScene();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> where(0.0f, span), offset(0.0f, size), depth(-0.9f, 0.9f),
      shade(0.2f, 1.0f);
  Mesh mesh;
  for (int t = 0; t < count; ++t) {
    const float cx = x0 + where(rng), cy = y0 + where(rng), z = depth(rng);
    for (int k = 0; k < 3; ++k) {
      mesh.positions.push_back(
          windowToNdc(cx + offset(rng), cy + offset(rng), z + 0.01f * k, kWidth, kHeight));
      mesh.colors.push_back({shade(rng), shade(rng), shade(rng), 1.0f});
      mesh.indices.push_back(static_cast<uint32_t>(mesh.indices.size()));
    }
  }
  scene.objects.push_back(whiteUnlitObject(std::move(mesh)));
  return scene;
}

inline std::shared_ptr<Texture> checkerTexture(int size, bool srgb) {
  auto texture = std::make_shared<Texture>();
  texture->width = size;
  texture->height = size;
  texture->srgb = srgb;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const bool dark = ((x / 4) + (y / 4)) % 2 == 0;
      const uint32_t r = dark ? 40u : 230u, g = static_cast<uint32_t>(x * 255 / size),
                     b = static_cast<uint32_t>(y * 255 / size);
      texture->texels.push_back(r | (g << 8) | (b << 16) | (255u << 24));
    }
  }
  return texture;
}

// A checkered floor seen at a grazing angle (bilinear, repeat, sRGB texels), a tilted quad
// (nearest, clamp, linear texels) with UVs beyond [0, 1], and a far wall with mip levels
// (trilinear).
inline Scene texturedScene() {
  Scene scene;
  Object floor;
  floor.mesh = std::make_shared<Mesh>(makeGrid(4, 4.0f, 3.0f));
  floor.shading = Shading::kFlat;
  floor.materials[0].base_color = {1, 1, 1, 1};
  floor.materials[0].albedo = checkerTexture(64, true);
  floor.materials[0].sampler.filter = TextureFilter::kBilinear;
  floor.transform.translation = {0, -0.8f, -2.0f};
  scene.objects.push_back(floor);
  Object card;
  card.mesh = std::make_shared<Mesh>(makeGrid(1, 0.6f, 1.6f));
  card.shading = Shading::kUnlit;
  card.cull = CullMode::kNone;
  card.materials[0].base_color = {1, 0.9f, 0.8f, 1};
  card.materials[0].albedo = checkerTexture(16, false);
  // A third texture with mip levels, sampled trilinearly (the default sampler).
  Object far_wall;
  far_wall.mesh = std::make_shared<Mesh>(makeGrid(2, 6.0f, 12.0f));
  far_wall.shading = Shading::kGouraud;
  std::shared_ptr<Texture> mipmapped = checkerTexture(128, true);
  generateMipmaps(*mipmapped);
  far_wall.materials[0].albedo = mipmapped;
  far_wall.transform.translation = {0.0f, 0.0f, -9.0f};
  far_wall.transform.rotation = quat::fromAxisAngle({1, 0, 0}, 1.3f);
  scene.objects.push_back(far_wall);
  card.materials[0].sampler = {TextureFilter::kNearest, TextureWrap::kClamp, TextureWrap::kClamp};
  card.transform.translation = {0.4f, 0.1f, -1.5f};
  card.transform.rotation = quat::fromAxisAngle({1, 0, 0}, 1.2f);
  scene.objects.push_back(card);
  addLights(scene);
  scene.camera.position = {0.0f, 0.3f, 1.5f};
  scene.camera.target = {0.0f, -0.5f, -2.0f};
  return scene;
}

inline void expectComputeMatchesCpu(const char* what, const Scene& scene, VulkanOptions vk = {},
                                    ComputeBackend* reuse = nullptr, bool normals = false) {
  const RenderOptions o = options(kWidth, kHeight, normals);
  PipelineStats cpu_stats;
  const Frame cpu = renderCpu(scene, o, &cpu_stats);
  ComputePtr owned;
  if (!reuse) {
    owned = makeCompute(vk);
    ASSERT_TRUE(owned);
    reuse = owned.get();
  }
  const Frame gpu = renderWith(*reuse, scene, o);
  expectComputeParity(what, compare(gpu, cpu));
  // The counters agree with the CPU's too: same culling, same clipping, same records.
  const vulkan::ComputeStats& stats = reuse->lastStats();
  EXPECT_EQ(stats.triangles_in, cpu_stats.triangles_in) << what;
  EXPECT_EQ(stats.triangles_culled, cpu_stats.triangles_culled) << what;
  EXPECT_EQ(stats.triangles_clipped, cpu_stats.triangles_clipped) << what;
  EXPECT_EQ(stats.triangles_setup, cpu_stats.triangles_setup) << what;
}

inline void expectRasterMatchesCpu(const char* what, const Scene& scene, RasterBackend& raster) {
  const RenderOptions o = options();
  const Frame cpu = renderCpu(scene, o);
  const Frame gpu = renderWith(raster, scene, o);
  expectRasterParity(what, compare(gpu, cpu));
}

}  // namespace tessera::vulkan_test
