// Shadow maps (RenderOptions::shadows) on the two Vulkan backends, held to the CPU renderer: both
// read the maps the CPU's own ShadowMaps::build drew (shaders/shadow.glsl ports the lookup), so
// a pixel drawn from the same triangle gets the same filtered visibility.
#include <gtest/gtest.h>

#include "vulkan_fixtures.h"

using namespace tessera;
using namespace tessera::vulkan_test;

namespace {

// A box standing on a floor under a directional light that travels +x and down (its shadow
// falls on the floor beyond the box, in view), and a dim fill light from the other side.
Scene boxOnFloor(Shading shading) {
  Scene scene;
  Object floor;
  floor.mesh = std::make_shared<Mesh>(makeGrid(8, 3.0f, 1.0f));
  floor.shading = shading;
  floor.materials[0].base_color = {0.8f, 0.8f, 0.75f, 1.0f};
  floor.materials[0].roughness = 0.7f;
  scene.objects.push_back(floor);
  Object box;
  box.mesh = std::make_shared<Mesh>(makeCube());
  box.shading = shading;
  box.materials[0].base_color = {0.85f, 0.4f, 0.2f, 1.0f};
  box.materials[0].roughness = 0.5f;
  box.transform.translation = {-0.4f, 0.5f, 0.0f};
  box.transform.scale = float3(0.5f);
  box.transform.rotation = quat::fromAxisAngle({0, 1, 0}, 0.4f);
  scene.objects.push_back(box);
  scene.lights = {Light::directional(normalize(float3{1.0f, -1.3f, -0.4f}), float3(1.0f), 1.2f),
                  Light::directional(normalize(float3{-0.5f, -1.0f, 0.6f}), float3(0.15f))};
  scene.ambient = float3(0.08f);
  scene.camera.position = {0.6f, 3.2f, 4.2f};
  scene.camera.target = {0.3f, 0.0f, 0.0f};
  scene.camera.near_z = 0.1f;
  scene.camera.far_z = 30.0f;
  return scene;
}

// The same box lit by a spot light above and behind it (a perspective map) and a weak sun.
Scene boxUnderSpot(Shading shading) {
  Scene scene = boxOnFloor(shading);
  scene.lights = {Light::spot({-2.2f, 2.6f, -1.0f}, normalize(float3{1.0f, -1.2f, 0.5f}),
                              {1.0f, 0.9f, 0.8f}, 9.0f, 0.35f, 0.7f),
                  Light::directional(normalize(float3{0.2f, -1.0f, -0.3f}), float3(0.1f))};
  return scene;
}

RenderOptions shadowOptions(bool shadows, int map_size = 2048) {
  RenderOptions o = options();
  o.shadows.enabled = shadows;
  o.shadows.map_size = map_size;
  return o;
}

int green(uint32_t rgba) {
  return static_cast<int>((rgba >> 8) & 255u);
}

// Pixels where `on` is much darker than `off` (by more than 40/255 in green): the shadow.
size_t darkenedPixels(const Frame& on, const Frame& off) {
  size_t n = 0;
  for (size_t i = 0; i < on.pixelCount(); ++i) n += green(on.color[i]) + 40 < green(off.color[i]);
  return n;
}

struct Held {
  size_t max_pixels_over;  // pixels allowed beyond 2/255
  int max_diff;            // the largest channel difference allowed anywhere
};

// `backend` draws `scene` with shadows as the CPU does: colours within 2/255 on all but
// `held.max_pixels_over` pixels, none beyond `held.max_diff`; and the shadow is there: at least
// `min_shadow` pixels much darker than the same backend's frame without shadows, as on the CPU.
template <typename B>
void expectShadowsMatchCpu(const char* what, B& backend, const Scene& scene, Held held,
                           size_t min_shadow, const RenderOptions& o = shadowOptions(true, 2048)) {
  RenderOptions off = o;
  off.shadows.enabled = false;
  const Frame cpu = renderCpu(scene, o);
  const Frame gpu = renderWith(backend, scene, o);
  const Parity p = compare(gpu, cpu);
  report(what, p);
  EXPECT_GE(p.idRatio(), 0.999) << what;
  EXPECT_LE(p.pixels - p.close_color, held.max_pixels_over) << what;
  EXPECT_LE(p.max_channel_diff, held.max_diff) << what;
  // The shadow exists on both: without the lookup the GPU frame would be the unshadowed one.
  const Frame cpu_off = renderCpu(scene, off);
  const Frame gpu_off = renderWith(backend, scene, off);
  const size_t cpu_shadow = darkenedPixels(cpu, cpu_off), gpu_shadow = darkenedPixels(gpu, gpu_off);
  std::printf("[ shadow   ] %s: %zu pixels darkened on the cpu, %zu on the gpu\n", what, cpu_shadow,
              gpu_shadow);
  EXPECT_GE(cpu_shadow, min_shadow) << what;
  EXPECT_GE(gpu_shadow, min_shadow) << what;
  // And after a frame with shadows, one without is the CPU's unshadowed frame (the reused buffer
  // then names no light).
  const Parity p_off = compare(gpu_off, cpu_off);
  EXPECT_LE(p_off.pixels - p_off.close_color, held.max_pixels_over) << what << ", shadows off";
}

// The compute backend draws every pixel from the CPU's triangle with the CPU's float operations:
// the shadow lookups see the same taps.
constexpr Held kComputeHeld{0, 2};
// vulkan-raster interpolates the world position and normal with the hardware's (here llvmpipe's)
// barycentrics, which differ from the CPU's in the last bits: a tap whose depth is within those
// bits of the receiver's may flip (1/9 of the light at most, only where the receiver meets the
// caster), and silhouette pixels may take another triangle, as without shadows.
constexpr Held kRasterHeld{40, 40};

}  // namespace

TEST(VulkanShadows, ComputeMatchesCpuUnderADirectionalLight) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr compute = makeCompute();
  ASSERT_TRUE(compute);
  expectShadowsMatchCpu("sun, smooth, compute", *compute, boxOnFloor(Shading::kPhong), kComputeHeld,
                        300);
  expectShadowsMatchCpu("sun, pbr, compute", *compute, boxOnFloor(Shading::kPbr), kComputeHeld,
                        300);
}

TEST(VulkanShadows, RasterMatchesCpuUnderADirectionalLight) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(raster);
  expectShadowsMatchCpu("sun, smooth, raster", *raster, boxOnFloor(Shading::kPhong), kRasterHeld,
                        300);
  expectShadowsMatchCpu("sun, pbr, raster", *raster, boxOnFloor(Shading::kPbr), kRasterHeld, 300);
}

TEST(VulkanShadows, BothBackendsMatchCpuUnderASpotLight) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr compute = makeCompute();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(compute && raster);
  for (Shading shading : {Shading::kPhong, Shading::kPbr}) {
    const Scene scene = boxUnderSpot(shading);
    const bool pbr = shading == Shading::kPbr;
    expectShadowsMatchCpu(pbr ? "spot, pbr, compute" : "spot, smooth, compute", *compute, scene,
                          kComputeHeld, 800, shadowOptions(true, 1024));
    expectShadowsMatchCpu(pbr ? "spot, pbr, raster" : "spot, smooth, raster", *raster, scene,
                          kRasterHeld, 800, shadowOptions(true, 1024));
  }
}

TEST(VulkanShadows, ComputeMatchesCpuInASphericalProjection) {
  // The nonlinear projections' cascades are spheres around the eye, chosen by distance: the
  // compute backend's ray passes take the CPU ray renderer's maps.
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr compute = makeCompute();
  ASSERT_TRUE(compute);
  RenderOptions o = shadowOptions(true, 1024);
  o.width = 160;
  o.height = 80;
  o.projection = Projection::kSpherical;
  expectShadowsMatchCpu("sun, smooth, spherical, compute", *compute, boxOnFloor(Shading::kPhong),
                        kComputeHeld, 50, o);
}

TEST(VulkanShadows, ComputeMatchesCpuWithMsaa) {
  // With 4x MSAA the compute backend shades at the CPU's points (the centre, else the first
  // covered sample), so the lookups still see the CPU's taps.
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr compute = makeCompute();
  ASSERT_TRUE(compute);
  RenderOptions o = shadowOptions(true, 1024);
  o.msaa = 4;
  expectShadowsMatchCpu("sun, pbr, 4x MSAA, compute", *compute, boxOnFloor(Shading::kPbr),
                        kComputeHeld, 300, o);
}

TEST(VulkanShadows, MapsLargerThanAStorageBufferAreAClearError) {
  // Two suns' six 2048x2048 cascades are 96 MiB: on a device allowing 32 MiB per storage buffer
  // both backends refuse the frame, saying what to change; 1024x1024 maps (24 MiB) then draw.
  TESSERA_SKIP_WITHOUT_VULKAN();
  VulkanOptions vk;
  vk.pretend_max_buffer_bytes = 32u << 20;
  ComputePtr compute = makeCompute(vk);
  RasterPtr raster = makeRaster(vk);
  ASSERT_TRUE(compute && raster);
  const Scene scene = boxOnFloor(Shading::kPhong);
  for (Backend* backend :
       {static_cast<Backend*>(compute.get()), static_cast<Backend*>(raster.get())}) {
    Frame frame;
    backend->render(scene, shadowOptions(true, 2048), frame);
    Expected<void> result = backend->lastResult();
    ASSERT_FALSE(result.ok());
    EXPECT_NE(result.error().message.find("the shadow maps (6 of 2048x2048 texels"),
              std::string::npos)
        << result.error().message;
    EXPECT_NE(result.error().message.find("more than the 32 MiB"), std::string::npos)
        << result.error().message;
    backend->render(scene, shadowOptions(true, 1024), frame);
    EXPECT_TRUE(backend->lastResult().ok());
    const Parity p = compare(frame, renderCpu(scene, shadowOptions(true, 1024)));
    EXPECT_GE(p.colorRatio(), 0.999);
  }
}
