// Texture sampling in the shading: the eight-lane path (render/texture_lanes.h) against the one
// sampleTexture (render/shade.cpp) lane by lane, and textured scenes through every kernel variant
// and worker count, bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/primitives.h>

#include "render/shade.h"
#include "render/texture_lanes.h"

#include "render_test_scenes.h"

using namespace tessera;
using tessera::test::coveredCount;
using tessera::test::renderAt;
using tessera::test::unlitObject;

namespace {

Sampler makeSampler(TextureFilter filter, TextureWrap s, TextureWrap t) {
  Sampler sampler;
  sampler.filter = filter;
  sampler.wrap_s = s;
  sampler.wrap_t = t;
  return sampler;
}

// A texture of width x height texels of pseudo-random colours, with its mip chain.
std::shared_ptr<Texture> noiseTexture(int width, int height, bool srgb, uint32_t seed) {
  auto t = std::make_shared<Texture>();
  t->width = width;
  t->height = height;
  t->srgb = srgb;
  std::mt19937 rng(seed);
  for (int i = 0; i < width * height; ++i) t->texels.push_back(static_cast<uint32_t>(rng()));
  generateMipmaps(*t);
  return t;
}

bool sameBits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace

// Eight lanes at a time, every wrap mode on each axis, bilinear and trilinear, with and without
// a transform, power-of-two and other sizes, coordinates over several periods and footprints
// over every level: the same bits as sampleTexture, lane by lane.
// A scene for the textured-object tests: the camera at `eye` looking down -z, one sun.
Scene texturedScene(float3 eye) {
  Scene scene;
  scene.camera.position = eye;
  scene.camera.near_z = 0.2f;
  scene.camera.far_z = 100;
  scene.lights.push_back({normalize(float3{-1, -2, -1}), float3(0.9f)});
  return scene;
}

// An unlit floor (y = -1) whose coordinates run over many periods of `texture`, repeated across
// and mirrored down.
Object texturedFloor(std::shared_ptr<Texture> texture, TextureFilter filter) {
  Mesh floor;
  floor.positions = {{-30, -1, 20}, {30, -1, 20}, {30, -1, -60}, {-30, -1, -60}};
  floor.uvs = {{-20, -20}, {25, -20}, {25, 40}, {-20, 40}};
  floor.indices = {0, 1, 2, 0, 2, 3};
  Object object = unlitObject(floor, CullMode::kNone);
  object.materials[0].albedo = std::move(texture);
  object.materials[0].sampler =
      makeSampler(filter, TextureWrap::kRepeat, TextureWrap::kMirroredRepeat);
  return object;
}

TEST(TextureLanes, EightLanesHaveTheBitsOfSampleTexture) {
  using namespace tessera::render;
  // The last is above Texture::kLinearTexelLimit: it is filtered from its RGBA8 texels, the
  // others from their linear copies (Texture::linearTexels).
  const std::shared_ptr<Texture> textures[] = {
      noiseTexture(16, 8, true, 1), noiseTexture(13, 7, false, 2), noiseTexture(1, 5, true, 3),
      noiseTexture(1100, 1000, true, 4)};
  for (const auto& texture : textures)
    EXPECT_EQ(texture->linearTexels(0) == nullptr, texture->width == 1100);
  const TextureWrap wraps[] = {TextureWrap::kRepeat, TextureWrap::kClamp,
                               TextureWrap::kMirroredRepeat};
  const TextureTransform transforms[] = {TextureTransform{},
                                         TextureTransform{{0.25f, -1.5f}, 0.7f, {3.0f, 0.5f}}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coordinate(-3.0f, 4.0f), unit(-1.0f, 1.0f),
      exponent(-5.0f, 1.0f);
  int compared = 0, taken = 0;
  for (const auto& texture : textures)
    for (TextureFilter filter : {TextureFilter::kBilinear, TextureFilter::kTrilinear})
      for (TextureWrap s : wraps)
        for (TextureWrap t : wraps)
          for (const TextureTransform& transform : transforms) {
            Sampler sampler = makeSampler(filter, s, t);
            sampler.transform = transform;
            for (int round = 0; round < 16; ++round) {
              alignas(32) float u[8], v[8], ur[8], vr[8], ud[8], vd[8];
              alignas(32) int32_t mask[8];
              for (int l = 0; l < 8; ++l) {
                u[l] = coordinate(rng);
                v[l] = coordinate(rng);
                const float step = std::exp2(exponent(rng));
                ur[l] = u[l] + step * unit(rng);
                vr[l] = v[l] + step * unit(rng);
                ud[l] = u[l] + step * unit(rng);
                vd[l] = v[l] + step * unit(rng);
                mask[l] = round % 4 == 3 && l % 3 == 0 ? 0 : -1;
              }
              const Uv8 uv{load<F32x8>(u), load<F32x8>(v)};
              const Uv8 right{load<F32x8>(ur), load<F32x8>(vr)};
              const Uv8 down{load<F32x8>(ud), load<F32x8>(vd)};
              F32x8 out[4];
              ASSERT_TRUE(texture8Applies(*texture, sampler));
              if (!sampleTexture8(*texture, sampler, load<I32x8>(mask), uv, right, down, 4, out))
                continue;
              ++taken;
              for (int l = 0; l < 8; ++l) {
                if (!mask[l]) continue;
                const float4 want =
                    sampleTexture(*texture, sampler, {u[l], v[l]}, {ur[l], vr[l]}, {ud[l], vd[l]});
                for (int k = 0; k < 4; ++k)
                  EXPECT_TRUE(sameBits(lane(out[k], l), want[k]))
                      << "lane " << l << " channel " << k << ": " << lane(out[k], l) << " vs "
                      << want[k] << " texture " << texture->width << "x" << texture->height;
                ++compared;
              }
            }
          }
  EXPECT_EQ(taken, 4 * 2 * 9 * 2 * 16);  // every coordinate here is below 65536
  EXPECT_GT(compared, 1000);
}

// The same scene of textured objects (trilinear with mip levels, mirrored and clamped axes,
// transforms, coordinates over many periods of a texture whose size is not a power of two, lit
// per pixel and unlit) through every kernel variant and worker count, with and without MSAA.
TEST(TextureLanes, TexturedSceneIsBitIdenticalForEverySimdLevelAndWorkerCount) {
  Scene scene = texturedScene({0, 1.2f, 3.5f});
  Object sphere;
  sphere.mesh = std::make_shared<Mesh>(makeUvSphere(48, 24));
  sphere.shading = Shading::kPhong;
  sphere.materials[0].albedo = noiseTexture(64, 32, true, 11);
  sphere.materials[0].sampler =
      makeSampler(TextureFilter::kTrilinear, TextureWrap::kMirroredRepeat, TextureWrap::kRepeat);
  sphere.materials[0].sampler.transform = {{0.1f, 0.3f}, 0.4f, {3.0f, 2.0f}};
  scene.objects.push_back(sphere);
  const Object floor_object =
      texturedFloor(noiseTexture(24, 20, true, 12), TextureFilter::kTrilinear);
  scene.objects.push_back(floor_object);
  Mesh card = *floor_object.mesh;
  card.positions = {{-2, -0.5f, -1}, {-0.5f, -0.5f, -1}, {-0.5f, 1, -1}, {-2, 1, -1}};
  card.uvs = {{-0.5f, -0.5f}, {1.5f, -0.5f}, {1.5f, 1.5f}, {-0.5f, 1.5f}};
  Object card_object = unlitObject(card, CullMode::kNone);
  card_object.materials[0].albedo = noiseTexture(32, 32, false, 13);
  card_object.materials[0].sampler =
      makeSampler(TextureFilter::kBilinear, TextureWrap::kClamp, TextureWrap::kMirroredRepeat);
  scene.objects.push_back(card_object);
  // Bilinear in one level, untransformed, repeated on a power of two and clamped: the groups the
  // AVX-512 kernels filter two at a time (render/texture_lanes16.h), the clamped card's edges and
  // the sphere's seam among them.
  Object plain_sphere;
  plain_sphere.mesh = std::make_shared<Mesh>(makeUvSphere(32, 16));
  plain_sphere.shading = Shading::kGouraud;
  plain_sphere.transform.translation = {1.4f, 0.2f, 0.5f};
  plain_sphere.transform.scale = float3(0.6f);
  plain_sphere.materials[0].albedo = noiseTexture(64, 32, true, 14);
  plain_sphere.materials[0].sampler =
      makeSampler(TextureFilter::kBilinear, TextureWrap::kRepeat, TextureWrap::kRepeat);
  scene.objects.push_back(plain_sphere);
  card.positions = {
      {0.2f, -0.9f, -0.5f}, {1.6f, -0.9f, -0.5f}, {1.6f, 0.1f, -0.5f}, {0.2f, 0.1f, -0.5f}};
  Object clamped_card = unlitObject(card, CullMode::kNone);
  clamped_card.materials[0].albedo = noiseTexture(16, 8, false, 15);
  clamped_card.materials[0].sampler =
      makeSampler(TextureFilter::kBilinear, TextureWrap::kClamp, TextureWrap::kClamp);
  scene.objects.push_back(clamped_card);

  for (int msaa : {1, 4}) {
    RenderOptions options;
    options.width = 251;
    options.height = 167;
    options.msaa = msaa;
    const Frame reference = renderAt(scene, options, SimdLevel::kScalar, 1);
    EXPECT_GT(test::coveredCount(reference), options.width * options.height / 2);
    for (SimdLevel level :
         {SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512, SimdLevel::kAuto}) {
      for (int workers : {1, 3}) {
        const Frame other = renderAt(scene, options, level, workers);
        EXPECT_EQ(reference.color, other.color)
            << "level " << static_cast<int>(level) << ", " << workers << " workers, msaa " << msaa;
      }
    }
  }
}

// Eight pixels of textured triangles without per-pixel lighting are filtered with the rest of
// their row, one filter for the eight however many triangles they hold (prepareTexturedGroup); with
// the normal AOV on they are shaded triangle by triangle. Both give the same bits: Gouraud and flat
// spheres of small triangles (trilinear, a transform, UV set 1 on one; trilinear without a
// transform on another), an unlit floor (bilinear),
// a card whose coordinates are beyond the eight-lane filter's reach (the row's deferred filter
// hands it back to the triangle-by-triangle shading), tone mapping on and off, at 1 and 4 samples.
TEST(TextureLanes, TrianglesTexturedAlikeShareOneFilterWithTheSameBits) {
  Scene scene = texturedScene({0, 1.0f, 4.0f});
  Object gouraud;
  gouraud.mesh = std::make_shared<Mesh>(makeUvSphere(96, 48));
  gouraud.shading = Shading::kGouraud;
  gouraud.transform.translation = {-0.9f, 0, 0};
  gouraud.materials[0].albedo = noiseTexture(64, 32, true, 21);
  gouraud.materials[0].sampler =
      makeSampler(TextureFilter::kTrilinear, TextureWrap::kMirroredRepeat, TextureWrap::kRepeat);
  gouraud.materials[0].sampler.transform = {{0.1f, 0.3f}, 0.4f, {3.0f, 2.0f}};
  scene.objects.push_back(gouraud);
  Object flat = gouraud;
  Mesh second_set = makeUvSphere(64, 32);
  for (const float2& uv : second_set.uvs) second_set.uvs1.push_back({uv.y * 3.0f, uv.x * 2.0f});
  flat.mesh = std::make_shared<Mesh>(second_set);
  flat.shading = Shading::kFlat;
  flat.transform.translation = {0.9f, 0, 0};
  flat.materials[0].albedo = noiseTexture(40, 24, true, 22);
  flat.materials[0].sampler.texcoord = 1;
  scene.objects.push_back(flat);
  scene.objects.push_back(texturedFloor(noiseTexture(24, 20, false, 23), TextureFilter::kBilinear));
  Mesh card = *scene.objects.back().mesh;
  card.positions = {{-2, -0.5f, -1}, {-0.5f, -0.5f, -1}, {-0.5f, 1, -1}, {-2, 1, -1}};
  card.uvs = {{70000, 70000}, {70003, 70000}, {70003, 70002}, {70000, 70002}};
  Object far_card = unlitObject(card);
  far_card.materials[0].albedo = noiseTexture(16, 16, true, 24);
  far_card.materials[0].sampler =
      makeSampler(TextureFilter::kBilinear, TextureWrap::kRepeat, TextureWrap::kRepeat);
  scene.objects.push_back(far_card);
  // Bilinear, one level, untransformed, repeated on a power of two: the AVX-512 kernels filter
  // two of its groups at a time (render/texture_lanes16.h).
  Object plain = gouraud;
  plain.mesh = std::make_shared<Mesh>(makeUvSphere(80, 40));
  plain.transform.translation = {0, -0.6f, 0.8f};
  plain.transform.scale = float3(0.5f);
  plain.materials[0].albedo = noiseTexture(32, 16, true, 25);
  plain.materials[0].sampler =
      makeSampler(TextureFilter::kBilinear, TextureWrap::kRepeat, TextureWrap::kRepeat);
  scene.objects.push_back(plain);
  // Trilinear without a transform: the row's reads planned level by level (planRowQuads).
  Object mipped = plain;
  mipped.transform.translation = {0.2f, 0.7f, 0.6f};
  mipped.materials[0].albedo = noiseTexture(64, 64, true, 26);
  mipped.materials[0].sampler =
      makeSampler(TextureFilter::kTrilinear, TextureWrap::kRepeat, TextureWrap::kMirroredRepeat);
  scene.objects.push_back(mipped);

  // The spheres' triangles are a few pixels across: most groups of eight hold several.
  RenderOptions options;
  options.width = 233;
  options.height = 151;
  test::expectMixedShadingMatchesPerTriangle(scene, options);
}

// A tile whose chunks hold triangles of one textured material alone takes its rows' runs without
// looking at each run's record for the material (TriangleChunk::textured_alike). One sphere alone
// (the shortcut taken) and two spheres of one mesh but two materials, each thousands of triangles
// so that chunks hold one, the other or both (not taken where they meet, or the one sphere's
// pixels would be filtered from the other's texture): every level and worker count gives the
// scalar kernels' bits, whose shading has no runs.
TEST(TextureLanes, TilesOfOneTexturedMaterialGiveTheBitsOfTheScalarKernels) {
  const auto sphere = [](float3 at, uint32_t seed) {
    Object o;
    o.mesh = std::make_shared<Mesh>(makeUvSphere(96, 48));
    o.shading = Shading::kGouraud;
    o.transform.translation = at;
    o.materials[0].albedo = noiseTexture(64, 32, true, seed);
    o.materials[0].sampler =
        makeSampler(TextureFilter::kBilinear, TextureWrap::kRepeat, TextureWrap::kRepeat);
    return o;
  };
  RenderOptions options;
  options.width = 240;
  options.height = 160;
  for (int objects : {1, 2}) {
    Scene scene = texturedScene({0, 0.5f, 3.5f});
    scene.objects.push_back(sphere({objects == 1 ? 0.0f : -0.45f, 0, 0}, 31));
    if (objects == 2) scene.objects.push_back(sphere({0.45f, 0, 0.3f}, 32));
    const Frame reference = renderAt(scene, options, SimdLevel::kScalar, 1);
    EXPECT_GT(coveredCount(reference), options.width * options.height / 8);
    for (SimdLevel level : {SimdLevel::kAvx2, SimdLevel::kAvx512})
      for (int workers : {1, 2, 3})
        EXPECT_EQ(reference.color, renderAt(scene, options, level, workers).color)
            << objects << " objects, level " << static_cast<int>(level) << ", " << workers
            << " workers";
  }
}

// A frame whose every triangle is Phong without an albedo texture evaluates the lights of a group
// of several triangles without looking at each lane's record first (TriangleChunk::lit_alike); a
// textured Phong sphere beside an untextured one keeps the frame from that, and both still give
// the bits of the triangle-by-triangle shading (were the textured one's groups lit as untextured,
// they would lose their texture), as does the untextured sphere alone.
// An untextured Phong sphere of small triangles at `at`, `scale` across.
Object phongSphere(float3 at, float scale) {
  Object sphere;
  sphere.mesh = std::make_shared<Mesh>(makeUvSphere(96, 48));
  sphere.shading = Shading::kPhong;
  sphere.transform.translation = at;
  sphere.transform.scale = float3(scale);
  return sphere;
}

TEST(TextureLanes, PhongTrianglesLitAlikeBesideTexturedOnesGiveTheSameBits) {
  Scene scene = texturedScene({0, 1.0f, 4.0f});
  const Object plain = phongSphere({-0.9f, 0, 0}, 1.0f);
  scene.objects.push_back(plain);
  Object textured = plain;
  textured.transform.translation = {0.9f, 0, 0};
  textured.materials[0].albedo = noiseTexture(64, 32, true, 26);
  scene.objects.push_back(textured);
  Object floor = texturedFloor(noiseTexture(24, 20, false, 27), TextureFilter::kBilinear);
  floor.shading = Shading::kPhong;
  scene.objects.push_back(floor);
  RenderOptions options;
  options.width = 233;
  options.height = 151;
  test::expectMixedShadingMatchesPerTriangle(scene, options);
  scene.objects = {phongSphere({0, 1, 0}, 2.5f)};
  test::expectMixedShadingMatchesPerTriangle(scene, options);
}

// With MSAA, the later samples' fragments of a frame whose every record is lit alike take the one
// evaluation of their lights without the per-lane check too (fragment_queue.h's shadeFragments,
// with or without the normal AOV: the test above cannot tell). A Phong sphere's pixels, mixed ones
// included, get the same bits as in the same frame with a textured Phong card in a corner, which
// turns that off.
TEST(TextureLanes, PhongFragmentsLitAlikeGiveTheBitsOfTheCheckedOnes) {
  Scene scene = texturedScene({0, 1.0f, 4.0f});
  const Object sphere = phongSphere({0.5f, 1.0f, 0}, 1.4f);
  scene.objects.push_back(sphere);
  RenderOptions options;
  options.width = 233;
  options.height = 151;
  options.msaa = 4;
  options.ids = true;
  const Frame alone = renderAt(scene, options, SimdLevel::kAuto, 2);
  Mesh quad;
  quad.positions = {{-2.4f, 0, 0}, {-1.8f, 0, 0}, {-1.8f, 0.5f, 0}, {-2.4f, 0.5f, 0}};
  quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  Object card = unlitObject(quad, CullMode::kNone);
  card.shading = Shading::kPhong;
  card.materials[0].albedo = noiseTexture(16, 16, true, 28);
  scene.objects.push_back(card);
  const Frame with_card = renderAt(scene, options, SimdLevel::kAuto, 2);
  const uint32_t sphere_triangles = static_cast<uint32_t>(sphere.mesh->triangleCount());
  size_t compared = 0, differing = 0, card_pixels = 0;
  for (size_t i = 0; i < alone.color.size(); ++i) {
    card_pixels +=
        with_card.triangle_id[i] != kNoTriangle && with_card.triangle_id[i] >= sphere_triangles;
    if (alone.triangle_id[i] == kNoTriangle || with_card.triangle_id[i] != alone.triangle_id[i])
      continue;
    ++compared;
    if (alone.color[i] != with_card.color[i] && differing++ == 0)
      ADD_FAILURE() << "pixel " << i << ": " << std::hex << alone.color[i] << " alone, "
                    << with_card.color[i] << " beside the card";
  }
  EXPECT_EQ(differing, 0u);
  EXPECT_GT(compared, 233u * 151u / 8);
  EXPECT_GT(card_pixels, 20u);
}

// A texture whose linear copy would pass the process's budget (Texture::kLinearTexelBudget) is
// sampled from its RGBA8 texels: no copy, and the same image, bilinear and trilinear.
TEST(TextureCopy, ATextureBeyondTheBudgetIsSampledFromItsTexelsToTheSameImage) {
  Texture checker;
  checker.width = 48;
  checker.height = 40;
  for (int y = 0; y < checker.height; ++y)
    for (int x = 0; x < checker.width; ++x)
      checker.texels.push_back((x / 4 + y / 4) % 2 ? 0xff2060e0u
                                                   : 0xff000000u | static_cast<uint32_t>(x * 5));
  generateMipmaps(checker);
  Scene scene;
  scene.camera.position = {0, 0, 2.6f};
  scene.lights.push_back({normalize(float3{-1, -2, -1}), float3(0.9f)});
  Object sphere;
  sphere.mesh = std::make_shared<Mesh>(makeUvSphere(40, 20));
  scene.objects.push_back(sphere);
  RenderOptions options;
  options.width = 160;
  options.height = 120;
  for (TextureFilter filter : {TextureFilter::kBilinear, TextureFilter::kTrilinear}) {
    auto render = [&](const std::shared_ptr<const Texture>& texture) {
      Material material;
      material.albedo = texture;
      material.sampler.filter = filter;
      scene.objects[0].materials = {material};
      return renderAt(scene, options, SimdLevel::kAuto, 2);
    };
    auto with_copy = std::make_shared<const Texture>(checker);
    const Frame reference = render(with_copy);
    ASSERT_NE(with_copy->linearTexels(0), nullptr);
    EXPECT_GT(coveredCount(reference), 160 * 120 / 4);
    // No room left: a new texture of the same texels makes no copy and renders the same image.
    const size_t budget = Texture::setLinearTexelBudget(Texture::linearTexelBytes());
    auto without_copy = std::make_shared<const Texture>(checker);
    const Frame other = render(without_copy);
    Texture::setLinearTexelBudget(budget);
    EXPECT_EQ(without_copy->linearTexels(0), nullptr);
    EXPECT_EQ(reference.color, other.color) << static_cast<int>(filter);
  }
}
