// Point and spot lights on the two Vulkan backends, held to the CPU renderer: the compute backend
// within its parity tolerance, vulkan-raster within an independent implementation's.
#include <gtest/gtest.h>

#include "vulkan_fixtures.h"

using namespace tessera;
using namespace tessera::vulkan_test;

namespace {

// Spheres and a floor in every shading mode, lit by a point light with a range, a spot light and
// a dim sun.
Scene pointAndSpotScene() {
  Scene scene;
  const Shading shadings[] = {Shading::kFlat, Shading::kGouraud, Shading::kPhong};
  for (int i = 0; i < 3; ++i) {
    Object sphere;
    sphere.mesh = std::make_shared<Mesh>(makeUvSphere(48, 24));
    sphere.shading = shadings[i];
    sphere.materials[0].base_color = {0.9f, 0.7f - 0.2f * static_cast<float>(i), 0.4f, 1.0f};
    sphere.transform.translation = {-1.3f + 1.3f * static_cast<float>(i), 0.0f, 0.0f};
    sphere.transform.scale = float3(0.55f);
    scene.objects.push_back(sphere);
  }
  Object floor;
  floor.mesh = std::make_shared<Mesh>(makeCube());
  floor.shading = Shading::kPhong;
  floor.transform.translation = {0, -0.75f, 0};
  floor.transform.scale = {2.5f, 0.1f, 1.5f};
  scene.objects.push_back(floor);
  scene.lights = {Light::point({-1.0f, 1.2f, 1.2f}, {1.0f, 0.8f, 0.6f}, 2.0f, 4.0f),
                  Light::spot({1.2f, 1.5f, 0.8f}, normalize(float3{-0.5f, -1.0f, -0.4f}),
                              {0.5f, 0.7f, 1.0f}, 5.0f, 0.25f, 0.5f),
                  Light::directional(normalize(float3{0.3f, -1.0f, -0.5f}), float3(0.1f))};
  scene.ambient = float3(0.04f);
  scene.camera.position = {0.0f, 1.2f, 4.0f};
  scene.camera.target = {0.0f, -0.2f, 0.0f};
  return scene;
}

}  // namespace

TEST(VulkanLights, ComputeMatchesCpuWithPointAndSpotLights) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr compute = makeCompute();
  ASSERT_TRUE(compute);
  const Scene scene = pointAndSpotScene();
  const Frame cpu = renderCpu(scene, options());
  const Frame gpu = renderWith(*compute, scene, options());
  expectComputeParity("point + spot, compute", compare(cpu, gpu));
  // The lights do something: without them the image differs.
  Scene dark = scene;
  dark.lights.clear();
  EXPECT_NE(renderCpu(dark, options()).color, cpu.color);
}

TEST(VulkanLights, RasterMatchesCpuWithPointAndSpotLights) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(raster);
  const Scene scene = pointAndSpotScene();
  const Frame cpu = renderCpu(scene, options());
  const Frame gpu = renderWith(*raster, scene, options());
  const Parity p = compare(cpu, gpu);
  expectRasterParity("point + spot, raster", p);
  EXPECT_GE(p.colorRatio(), 0.99) << "colours within 2/255";
}

TEST(VulkanLights, ClippedTrianglesAreLitAtTheirOwnCorners) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr compute = makeCompute();
  ASSERT_TRUE(compute);
  // The near plane cuts the floor and the nearest spheres: clipped pieces take their corners'
  // world positions from the clipper (CPU) and from the corner weights (GPU).
  Scene scene = pointAndSpotScene();
  scene.camera.near_z = 3.9f;
  PipelineStats stats;
  const Frame cpu = renderCpu(scene, options(), &stats);
  EXPECT_GT(stats.triangles_clipped, 0u);
  expectComputeParity("point + spot, clipped, compute",
                      compare(cpu, renderWith(*compute, scene, options())));
}

// The display transform (--tone-mapping, --exposure) in the shaders, as the CPU applies it: per
// shaded fragment, before the resolve and the sRGB encode.
TEST(VulkanLights, ToneMappingAndExposureMatchTheCpu) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr compute = makeCompute();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(compute && raster);
  for (ToneMapping mapping : {ToneMapping::kAces, ToneMapping::kPbrNeutral}) {
    Scene scene = pointAndSpotScene();
    scene.tone_mapping = mapping;
    scene.exposure = 1.5f;
    const Frame cpu = renderCpu(scene, options());
    const std::string name = mapping == ToneMapping::kAces ? "aces" : "pbr-neutral";
    expectComputeParity((name + ", compute").c_str(),
                        compare(cpu, renderWith(*compute, scene, options())));
    const Parity p = compare(cpu, renderWith(*raster, scene, options()));
    expectRasterParity((name + ", raster").c_str(), p);
    EXPECT_GE(p.colorRatio(), 0.99) << name << ": colours within 2/255";
    Scene plain = scene;
    plain.tone_mapping = ToneMapping::kNone;
    plain.exposure = 0.0f;
    EXPECT_NE(renderCpu(plain, options()).color, cpu.color) << name;
  }
}
