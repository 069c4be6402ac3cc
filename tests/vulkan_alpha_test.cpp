// alphaMode MASK and BLEND on the Vulkan backends (docs/vulkan-features.md).
//
// MASK: vulkan-raster discards the fragments whose alpha is below the cutoff, as the CPU cuts them;
// the compute backend's MASK pass commits masked records where the alpha test passes, per sample
// (with 64-bit atomics; the 32-bit path still draws them opaque).
//
// BLEND: both backends draw blended triangles after the opaque ones, in the CPU's back-to-front
// order, with the over operator in linear light behind the opaque depth (blend.h); held to the CPU
// image within 2/255, in either submission order, and to the over operator itself.
#include <gtest/gtest.h>

#include <tessera/scene/color.h>
#include <tessera/scene/primitives.h>

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

// ---- BLEND ----

constexpr int kBlendWidth = 64, kBlendHeight = 32;

// A quad over window columns [x0, x1) and every row, at NDC depth z, unlit.
Object quad(float x0, float x1, float z, float4 color, AlphaMode mode) {
  Mesh m;
  for (float2 p :
       {float2{x0, 0}, float2{x1, 0}, float2{x1, kBlendHeight}, float2{x0, kBlendHeight}})
    m.positions.push_back(windowToNdc(p.x, p.y, z, kBlendWidth, kBlendHeight));
  m.indices = {0, 1, 2, 0, 2, 3};
  Object o = whiteUnlitObject(std::move(m));
  o.materials[0].base_color = color;
  o.materials[0].alpha_mode = mode;
  return o;
}

const float4 kRedHalf{1, 0, 0, 0.5f}, kBlueQuarter{0, 0, 1, 0.25f};

// An opaque green quad at the back over columns [0, 48), a half-transparent red quad at NDC depth
// 0.5 and a quarter-transparent blue one at 0.3 over columns [8, 64) and [0, 56): they overlap on
// [8, 56). `red_first` submits red first. `edge` moves the three inner edges by that much of a
// pixel (by different amounts: under MSAA, pixels the blended quads cover in part).
Scene blendScene(bool red_first, float edge = 0.0f) {
  Scene scene = clipSpaceScene();
  scene.ambient = float3(1.0f);
  scene.background = {0, 0, 0, 1};
  scene.objects.push_back(quad(0, 48 - 0.5f * edge, 0.8f, {0, 1, 0, 1}, AlphaMode::kOpaque));
  Object red = quad(8 + 0.4f * edge, kBlendWidth, 0.5f, kRedHalf, AlphaMode::kBlend);
  Object blue = quad(0, 56 - 0.6f * edge, 0.3f, kBlueQuarter, AlphaMode::kBlend);
  scene.objects.push_back(red_first ? red : blue);
  scene.objects.push_back(red_first ? blue : red);
  return scene;
}

RenderOptions blendOptions(int msaa = 1) {
  RenderOptions o = options(kBlendWidth, kBlendHeight);
  o.msaa = msaa;
  o.coverage = true;
  return o;
}

// What the over operator in linear light gives at column x of blendScene: blue over (red over
// what lies behind), each where it is.
float3 expectedAt(int x) {
  float3 c = x < 48 ? float3{0, 1, 0} : float3{0, 0, 0};
  if (x >= 8) c = float3{1, 0, 0} * 0.5f + c * 0.5f;
  if (x < 56) c = float3{0, 0, 1} * 0.25f + c * 0.75f;
  return c;
}

void expectOver(const char* what, const Frame& f, int x, int y, float3 want) {
  const uint32_t got = f.color[static_cast<size_t>(y) * f.width + x];
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(static_cast<int>((got >> (8 * k)) & 0xff), encodeSrgb8(want[k]), 1)
        << what << ": channel " << k << " at " << x << "," << y;
}

// Every pixel within 2/255 of the CPU's, the ids (the opaque surface's) equal; with `coverage`,
// the coverage AOV (the blended matte) within 1/255.
void expectMatchesCpu(const char* what, const Frame& gpu, const Frame& cpu, bool coverage = true) {
  const Parity p = compare(gpu, cpu);
  report(what, p);
  EXPECT_LE(p.max_channel_diff, 2) << what;
  EXPECT_EQ(p.same_id, p.covered) << what;
  if (!coverage) return;
  ASSERT_EQ(gpu.coverage.size(), cpu.coverage.size()) << what;
  int worst = 0;
  for (size_t i = 0; i < cpu.coverage.size(); ++i)
    worst = std::max(worst, std::abs(int{gpu.coverage[i]} - int{cpu.coverage[i]}));
  EXPECT_LE(worst, 1) << what << ": coverage";
}

// A blended, two-sided, lit sphere (its back and front triangles overlap: only the CPU's order
// gives the CPU's image) with a blended textured card in front of it, over the textured scene.
Scene blendedSphereScene() {
  Scene scene = texturedScene();
  Object sphere;
  sphere.mesh = std::make_shared<Mesh>(makeUvSphere(24, 12));
  sphere.shading = Shading::kPhong;
  sphere.cull = CullMode::kNone;
  sphere.materials[0].base_color = {0.9f, 0.4f, 0.2f, 0.45f};
  sphere.materials[0].alpha_mode = AlphaMode::kBlend;
  sphere.transform.translation = {-0.3f, -0.2f, -1.8f};
  sphere.transform.scale = float3(0.45f);
  scene.objects.push_back(sphere);
  for (Object& o : scene.objects)
    if (o.materials[0].sampler.filter == TextureFilter::kNearest) {
      o.materials[0].base_color.w = 0.6f;
      o.materials[0].alpha_mode = AlphaMode::kBlend;
    }
  return scene;
}

}  // namespace

TEST(VulkanAlpha, BothBackendsCutMaskedMaterialsAsTheCpu) {
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

  // The compute backend's MASK pass: the CPU's ids on every pixel, its colours within 2/255.
  ComputePtr compute = makeCompute();
  ASSERT_TRUE(compute);
  ASSERT_TRUE(compute->uses64BitCommits()) << "lavapipe has 64-bit atomics";
  const Parity q = compare(cpu, renderWith(*compute, maskedScene(AlphaMode::kMask), options()));
  expectComputeParity("mask, compute", q);
  EXPECT_EQ(q.same_id, q.covered);
  EXPECT_LE(q.max_channel_diff, 2);
}

TEST(VulkanAlpha, ComputeCutsEachSampleAsTheCpuWithMsaa) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  RenderOptions o = options();
  o.msaa = 4;
  o.coverage = true;
  const Frame cpu = renderCpu(maskedScene(AlphaMode::kMask), o);
  ComputePtr compute = makeCompute();
  ASSERT_TRUE(compute);
  expectMatchesCpu("mask 4x, compute", renderWith(*compute, maskedScene(AlphaMode::kMask), o), cpu);
}

TEST(VulkanAlpha, ThirtyTwoBitComputeDrawsMaskedMaterialsOpaque) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  VulkanOptions vk;
  vk.force_32bit_atomics = true;
  ComputePtr compute = makeCompute(vk);
  ASSERT_TRUE(compute);
  expectComputeParity("mask drawn opaque, 32-bit compute",
                      compare(renderCpu(maskedScene(AlphaMode::kOpaque), options()),
                              renderWith(*compute, maskedScene(AlphaMode::kMask), options())));
}

TEST(VulkanBlend, TwoQuadsGiveTheCpuImageAndTheOverOperatorInEitherOrder) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr compute = makeCompute();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(compute && raster);
  for (bool red_first : {true, false}) {
    const Scene scene = blendScene(red_first);
    const Frame cpu = renderCpu(scene, blendOptions());
    const Frame gpus[2] = {renderWith(*compute, scene, blendOptions()),
                           renderWith(*raster, scene, blendOptions())};
    const char* names[2] = {"blend, compute", "blend, raster"};
    for (int b = 0; b < 2; ++b) {
      SCOPED_TRACE(red_first ? "red first" : "blue first");
      expectMatchesCpu(names[b], gpus[b], cpu);
      for (int y = 1; y < kBlendHeight; y += 6)
        for (int x = 2; x < kBlendWidth; x += 5) expectOver(names[b], gpus[b], x, y, expectedAt(x));
      // The AOVs stay the opaque surface's: the green quad, or nothing.
      const size_t at = 5 * kBlendWidth + 20;
      EXPECT_LE(gpus[b].triangle_id[at], 2u) << names[b];
      EXPECT_NEAR(gpus[b].depth[at], 0.9f, 1e-5f) << names[b];
      EXPECT_EQ(gpus[b].triangle_id[5 * kBlendWidth + 60], kNoTriangle) << names[b];
    }
  }
}

TEST(VulkanBlend, AnOpaqueSurfaceInFrontHidesTheBlendedOnes) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  Scene scene = blendScene(true);
  scene.objects.push_back(quad(16, 32, 0.1f, {1, 1, 1, 1}, AlphaMode::kOpaque));
  const Frame cpu = renderCpu(scene, blendOptions());
  ComputePtr compute = makeCompute();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(compute && raster);
  const Frame gpus[2] = {renderWith(*compute, scene, blendOptions()),
                         renderWith(*raster, scene, blendOptions())};
  for (const Frame& f : gpus) {
    expectMatchesCpu("hidden", f, cpu);
    for (int y = 0; y < kBlendHeight; y += 3)
      for (int x = 16; x < 32; ++x)
        ASSERT_EQ(f.color[static_cast<size_t>(y) * kBlendWidth + x], 0xffffffffu) << x << "," << y;
    expectOver("beside the white quad", f, 12, 4, expectedAt(12));
  }
}

TEST(VulkanBlend, MsaaBlendsEachSampleAsTheCpu) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  const Scene scene = blendScene(false, 1.0f);
  const Frame cpu = renderCpu(scene, blendOptions(4));
  // The edges fall inside pixels: 4x differs from 1x there.
  ASSERT_GT(compare(cpu, renderCpu(scene, blendOptions())).max_channel_diff, 20);
  ComputePtr compute = makeCompute();
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(compute && raster);
  const Frame from_compute = renderWith(*compute, scene, blendOptions(4));
  const Frame from_raster = renderWith(*raster, scene, blendOptions(4));
  expectMatchesCpu("blend 4x, compute", from_compute, cpu);
  expectMatchesCpu("blend 4x, raster", from_raster, cpu);
  for (const Frame* f : {&from_compute, &from_raster})
    for (int x = 2; x < kBlendWidth; x += 5)
      if (x != 8 && x != 47 && x != 55) expectOver("4x", *f, x, 9, expectedAt(x));
}

TEST(VulkanBlend, ASortedSphereAndCardMatchTheCpu) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  const Scene scene = blendedSphereScene();
  RenderOptions o = options();
  o.coverage = true;
  const Frame cpu = renderCpu(scene, o);
  // The blended objects show: the image differs from their opaque one.
  Scene opaque = scene;
  for (Object& object : opaque.objects) object.materials[0].alpha_mode = AlphaMode::kOpaque;
  ASSERT_GT(compare(cpu, renderCpu(opaque, o)).max_channel_diff, 40);

  // Each backend draws the opaque scene first, its sphere culled as the others are: the blend
  // pass's pipelines, and the raster's for two-sided draws, are made when the next frame needs
  // them, and its image is the CPU's all the same.
  Scene first = opaque;
  for (Object& object : first.objects) object.cull = CullMode::kBack;
  ComputePtr compute = makeCompute();
  ASSERT_TRUE(compute);
  expectMatchesCpu("opaque first, compute", renderWith(*compute, first, o), renderCpu(first, o));
  const Frame from_compute = renderWith(*compute, scene, o);
  expectMatchesCpu("sphere and card, compute", from_compute, cpu);
  RasterPtr raster = makeRaster();
  ASSERT_TRUE(raster);
  expectRasterParity("opaque first, raster",
                     compare(renderWith(*raster, first, o), renderCpu(first, o)));
  const Parity p = compare(renderWith(*raster, scene, o), cpu);
  expectRasterParity("sphere and card, raster", p);
  EXPECT_GE(p.colorRatio(), 0.99) << "raster colours within 2/255";
}
