// alphaMode MASK on the Vulkan backends (docs/vulkan.md): vulkan-raster discards the fragments
// whose alpha is below the cutoff, as the CPU cuts them; the compute backend does not cut yet and
// draws masked materials opaque, which this test holds it to until it does.
#include <gtest/gtest.h>

#include "vulkan_fixtures.h"

using namespace tessera;
using namespace tessera::vulkan_test;

namespace {

// The textured scene with its tilted card masked: a checker whose light squares are opaque and
// dark squares have alpha 0 (nearest, clamp), so the floor shows through every other square.
Scene maskedScene(AlphaMode mode) {
  Scene scene = texturedScene();
  auto texture = checkerTexture(16, false);
  for (uint32_t& texel : texture->texels)
    if ((texel & 255u) < 128u) texel &= 0x00ffffffu;
  for (Object& o : scene.objects)
    if (o.materials[0].sampler.filter == TextureFilter::kNearest) {
      o.materials[0].albedo = texture;
      o.materials[0].alpha_mode = mode;
    }
  return scene;
}

}  // namespace

TEST(VulkanAlpha, RasterCutsMaskedMaterialsAsTheCpuAndComputeDrawsThemOpaque) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  const Frame cpu = renderCpu(maskedScene(AlphaMode::kMask), options());
  const Frame cpu_opaque = renderCpu(maskedScene(AlphaMode::kOpaque), options());
  // The cut shows: the floor's ids where the card's dark squares are.
  const Parity cut = compare(cpu, cpu_opaque);
  ASSERT_LT(cut.idRatio(), 0.95) << "the mask cut nothing";

  RasterPtr raster = makeRaster();
  ASSERT_TRUE(raster);
  const Parity p = compare(cpu, renderWith(*raster, maskedScene(AlphaMode::kMask), options()));
  expectRasterParity("mask, raster", p);
  EXPECT_GE(p.colorRatio(), 0.99) << "colours within 2/255";

  ComputePtr compute = makeCompute();
  ASSERT_TRUE(compute);
  expectComputeParity(
      "mask drawn opaque, compute",
      compare(cpu_opaque, renderWith(*compute, maskedScene(AlphaMode::kMask), options())));
}
