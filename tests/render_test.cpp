// The CPU renderer as a whole: the same bits for any worker count and instruction set, no
// allocation per frame after warm-up, buffers reused across sizes, AOVs; and the worker and page
// pools under it. (The raster and shading stages: render_raster_test.cpp, render_shading_test.cpp.)
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <new>
#include <random>
#include <set>
#include <thread>

#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/color.h>
#include <tessera/scene/primitives.h>

#include "render/chunk_layout.h"
#include "render/clip.h"
#include "render/kernels.h"
#include "render/page_pool.h"
#include "render/replication.h"
#include "render/worker_pool.h"

#include "allocation_counter.h"  // g_count_allocations, g_allocations
#include "render_test_scenes.h"

using namespace tessera;
using namespace tessera::test;  // NOLINT(google-build-using-namespace)

TEST(Renderer, ImageIsBitIdenticalForAnyWorkerCount) {
  Scene scene;
  scene.camera.position = {0, 2, 6};
  scene.camera.near_z = 0.5f;
  scene.lights.push_back({normalize(float3{-1, -2, -1}), float3(0.9f)});
  scene.show_world_axes = true;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(-1, 1);
  auto sphere = std::make_shared<Mesh>(makeUvSphere(20, 10));
  auto cube = std::make_shared<Mesh>(makeCube());
  for (int i = 0; i < 60; ++i) {
    Object o;
    o.mesh = i % 3 ? sphere : cube;
    o.shading = static_cast<Shading>(i % 4);
    o.cull = static_cast<CullMode>(i % 3);
    o.transform.translation = {unit(rng) * 4, unit(rng) * 3, unit(rng) * 6};  // some cross near
    o.transform.rotation = fromEuler({unit(rng), unit(rng), unit(rng)});
    o.transform.scale = float3(0.3f + 0.5f * std::fabs(unit(rng)));
    o.materials[0].base_color = {std::fabs(unit(rng)), std::fabs(unit(rng)), 0.5f, 1};
    o.show_axes = i % 7 == 0;
    scene.objects.push_back(o);
  }
  PipelineStats stats;
  Frame one = renderScene(scene, 333, 217, 1, &stats, true);
  EXPECT_GT(stats.triangles_clipped, 0u);
  EXPECT_GT(stats.triangles_setup, 1000u);
  for (int workers : {2, 7}) {
    Frame many = renderScene(scene, 333, 217, workers, nullptr, true);
    EXPECT_EQ(one.color, many.color) << workers << " workers";
    EXPECT_EQ(one.triangle_id, many.triangle_id) << workers << " workers";
    EXPECT_EQ(0, std::memcmp(one.depth.data(), many.depth.data(), one.depth.size() * 4));
    EXPECT_EQ(0, std::memcmp(one.normal.data(), many.normal.data(), one.normal.size() * 12));
  }
}

TEST(Renderer, ImageIsBitIdenticalForEverySimdLevel) {
  // Small triangles (a dense sphere), large ones (a floor through the near plane, screen-sized
  // quads), thin slivers and sub-pixel ones: both raster paths of every kernel variant.
  Scene scene;
  scene.camera.position = {0, 1, 4};
  scene.camera.near_z = 0.3f;
  scene.lights.push_back({normalize(float3{-1, -2, -1}), float3(0.9f)});
  Object sphere;
  sphere.mesh = std::make_shared<Mesh>(makeUvSphere(96, 48));
  sphere.shading = Shading::kPhong;
  scene.objects.push_back(sphere);
  Mesh floor;
  floor.positions = {{-40, -1, 30}, {40, -1, 30}, {40, -1, -40}, {-40, -1, -40}};
  floor.indices = {0, 1, 2, 0, 2, 3};
  Object floor_object;
  floor_object.mesh = std::make_shared<Mesh>(floor);
  scene.objects.push_back(floor_object);
  Mesh slivers;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(-1.5f, 1.5f);
  for (int i = 0; i < 400; ++i) {
    float3 a{unit(rng), unit(rng), unit(rng)};
    float3 b = a + float3{unit(rng), unit(rng), unit(rng)} * (i % 2 ? 1.0f : 0.004f);
    float3 c = a + (b - a) * 0.5f + float3{0.002f, -0.001f, 0.003f};
    uint32_t base = static_cast<uint32_t>(slivers.positions.size());
    slivers.positions.insert(slivers.positions.end(), {a, b, c});
    slivers.indices.insert(slivers.indices.end(), {base, base + 1, base + 2});
  }
  generateSmoothNormals(slivers);
  Object sliver_object;
  sliver_object.mesh = std::make_shared<Mesh>(slivers);
  sliver_object.cull = CullMode::kNone;
  sliver_object.shading = Shading::kGouraud;
  scene.objects.push_back(sliver_object);

  RenderOptions options;
  options.width = 301;
  options.height = 203;
  auto render = [&](SimdLevel level) { return renderAt(scene, options, level, 2); };
  Frame scalar = render(SimdLevel::kScalar);
  EXPECT_GT(coveredCount(scalar), 301 * 203 / 3);
  for (SimdLevel level :
       {SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512, SimdLevel::kAuto}) {
    Frame other = render(level);
    EXPECT_EQ(scalar.triangle_id, other.triangle_id) << static_cast<int>(level);
    EXPECT_EQ(scalar.color, other.color) << static_cast<int>(level);
    EXPECT_EQ(0, std::memcmp(scalar.depth.data(), other.depth.data(), scalar.depth.size() * 4));
  }
}

namespace {

// The scene rendered by every instruction set's kernels, with and without the normal AOV (which
// takes the per-triangle path where the plain one would serve), checked against the scalar kernels
// with it: the same colours and ids. Returns that reference.
Frame expectSameWithEveryKernelAndTheNormalAov(const Scene& scene, int width, int height,
                                               int msaa = 1) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.msaa = msaa;
  auto render = [&](SimdLevel level, bool normals) {
    options.normals = normals;
    return renderAt(scene, options, level, 2);
  };
  const Frame reference = render(SimdLevel::kScalar, true);
  for (SimdLevel level : {SimdLevel::kScalar, SimdLevel::kSse2, SimdLevel::kAvx2,
                          SimdLevel::kAvx512, SimdLevel::kAuto}) {
    for (bool normals : {false, true}) {
      const Frame other = render(level, normals);
      EXPECT_EQ(reference.color, other.color) << static_cast<int>(level) << " " << normals;
      EXPECT_EQ(reference.triangle_id, other.triangle_id) << static_cast<int>(level);
    }
  }
  return reference;
}

// An unlit mesh (one object) and a flat-shaded orange cube at `cube_at`, turned to show three
// faces lit differently by a light from the side, seen from `camera` on the +z side.
Scene unlitMeshBesideFlatCube(const Mesh& mesh, float3 camera, float3 cube_at) {
  Scene scene;
  scene.camera.position = camera;
  scene.lights.push_back({normalize(float3{-1, -0.5f, -2}), float3(0.8f)});
  scene.objects.push_back(unlitObject(mesh));
  Object cube;
  cube.mesh = std::make_shared<Mesh>(makeCube());
  cube.shading = Shading::kFlat;
  cube.transform.translation = cube_at;
  cube.transform.rotation = quat::fromAxisAngle(normalize(float3{1, 1, 0}), 0.6f);
  cube.materials[0].base_color = {0.9f, 0.5f, 0.2f, 1};
  scene.objects.push_back(cube);
  return scene;
}

}  // namespace

TEST(Renderer, PlainShadingIsTheSameForEverySimdLevelAndWithTheNormalAov) {
  // No texture and no Phong: eight pixels owned by several triangles are shaded lane by lane from
  // their own records. Asking for normals takes the per-triangle path instead; both, at every
  // instruction set, must give the same bits. Small triangles of three shading modes, some with
  // vertex colours, interpenetrating so that many eight-pixel runs have several owners.
  Scene scene;
  scene.camera.position = {0, 0.5f, 3};
  scene.lights.push_back({normalize(float3{-1, -2, -1}), float3(0.9f)});
  const Shading modes[] = {Shading::kGouraud, Shading::kFlat, Shading::kUnlit};
  for (int i = 0; i < 3; ++i) {
    Object o;
    Mesh mesh = makeUvSphere(80 + 10 * i, 40);
    for (size_t v = 0; i == 0 && v < mesh.positions.size(); ++v)
      mesh.colors.push_back({0.5f + 0.5f * std::sin(static_cast<float>(v)), 0.7f, 0.3f, 1});
    o.mesh = std::make_shared<Mesh>(mesh);
    o.shading = modes[i];
    o.transform.translation = {0.45f * static_cast<float>(i - 1), 0.1f * static_cast<float>(i), 0};
    o.materials[0].base_color = {0.3f + 0.3f * static_cast<float>(i), 0.8f, 0.5f, 1};
    scene.objects.push_back(o);
  }
  const Frame reference = expectSameWithEveryKernelAndTheNormalAov(scene, 257, 163);
  EXPECT_GT(coveredCount(reference), 257 * 163 / 4);
}

TEST(Renderer, SolidTrianglesShadeToTheirOwnColourAtEverySimdLevel) {
  // A triangle whose corners share a colour (an unlit quad of one colour; a flat-shaded cube, lit
  // from the side) takes its encoded colour without barycentrics on the plain path. Every covered
  // pixel of the quad is exactly that colour's sRGB, and the whole image is the same bits with the
  // normal AOV (the per-triangle path) and at every instruction set. 203 pixels wide: a row ends
  // inside an eight-pixel group, and the sixteen-lane encode meets groups of the quad beside
  // groups of the cube and of nothing.
  const float4 quad_colour{0.2f, 0.45f, 0.7f, 1};
  Mesh quad;
  quad.positions = {
      {-1.4f, -0.9f, -0.5f}, {-0.2f, -0.9f, -0.5f}, {-0.2f, 0.9f, -0.5f}, {-1.4f, 0.9f, -0.5f}};
  quad.colors.assign(4, quad_colour);
  quad.indices = {0, 1, 2, 0, 2, 3};
  const Scene scene = unlitMeshBesideFlatCube(quad, {0, 0.3f, 3}, {0.6f, 0, 0});
  const Frame reference = expectSameWithEveryKernelAndTheNormalAov(scene, 203, 150);
  const uint32_t expected = packSrgba8(quad_colour);
  int quad_pixels = 0;
  std::set<uint32_t> cube_colours;
  for (size_t i = 0; i < reference.color.size(); ++i) {
    if (reference.triangle_id[i] == 1 || reference.triangle_id[i] == 2) {
      ++quad_pixels;
      ASSERT_EQ(reference.color[i], expected) << "pixel " << i;
    } else if (reference.triangle_id[i] > 2) {
      cube_colours.insert(reference.color[i]);
    }
  }
  EXPECT_GT(quad_pixels, 203 * 150 / 8);
  EXPECT_GE(cube_colours.size(), 2u) << "the cube shows faces lit differently";
}

TEST(Renderer, RowsOfOneSolidTriangleTakeItsColourWithAndWithoutMsaa) {
  // One triangle of one colour, larger than the view, behind a flat-shaded cube on the right: the
  // rows of the left tiles hold that triangle alone and take its colour at once (solidRowRgba),
  // the rows the cube cuts (and, with MSAA, those holding a mixed pixel) take the groups' paths,
  // and the narrow last tile (203 pixels: 11 columns) never the row's. The image is the same bits
  // with the normal AOV (the per-triangle path) and at every instruction set, at 1 and 4 samples,
  // and the large triangle's pixels away from the cube are its colour's sRGB.
  const float4 colour{0.65f, 0.3f, 0.15f, 1};
  Mesh wall;
  wall.positions = {{-30, -30, -1}, {30, -30, -1}, {0, 30, -1}};
  wall.colors.assign(3, colour);
  wall.indices = {0, 1, 2};
  const Scene scene = unlitMeshBesideFlatCube(wall, {0, 0, 3}, {0.9f, 0.1f, 0});
  const uint32_t expected = packSrgba8(colour);
  for (int msaa : {1, 4}) {
    const Frame reference = expectSameWithEveryKernelAndTheNormalAov(scene, 203, 150, msaa);
    int wall_pixels = 0, cube_pixels = 0;
    for (int y = 0; y < 150; ++y)
      for (int x = 0; x < 203; ++x) {
        const size_t i = static_cast<size_t>(y) * 203 + static_cast<size_t>(x);
        if (reference.triangle_id[i] != 1) {
          cube_pixels += reference.triangle_id[i] > 1;
          continue;
        }
        ++wall_pixels;
        if (x < 64) {
          ASSERT_EQ(reference.color[i], expected) << msaa << "x, pixel " << x << "," << y;
        }
      }
    EXPECT_GT(wall_pixels, 203 * 150 / 2) << msaa << "x";
    EXPECT_GT(cube_pixels, 203 * 150 / 20) << msaa << "x";
  }
}

TEST(Renderer, EncodesEveryColourTheSameAtEverySimdLevel) {
  // The sRGB encode (eight or, with AVX-512, sixteen lanes at a time) against the scalar
  // variant: an unlit quad filling the view, red rising from below 0 up the image, green and
  // blue across it (blue past 1), slowly enough that together the channels take every 8-bit
  // code, the linear segment near black and the clamps included. 257 pixels wide: the last tile's
  // rows end inside a sixteen-pixel step.
  Scene scene;
  scene.camera.position = {0, 0, 1};
  scene.camera.fov_y_degrees = 90.0f;
  Mesh quad;
  quad.positions = {{-0.6f, -1.05f, 0}, {0.6f, -1.05f, 0}, {0.6f, 1.05f, 0}, {-0.6f, 1.05f, 0}};
  quad.colors = {{-0.012f, 0.03f, 1.35f, 1},
                 {-0.012f, 0.42f, 0.28f, 1},
                 {0.09f, 0.42f, 0.28f, 1},
                 {0.09f, 0.03f, 1.35f, 1}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  scene.objects.push_back(unlitObject(quad));
  RenderOptions options;
  options.width = 257;
  options.height = 509;
  const Frame reference = renderAt(scene, options, SimdLevel::kScalar, 1);
  std::set<uint32_t> codes;
  for (uint32_t c : reference.color)
    for (int shift : {0, 8, 16}) codes.insert((c >> shift) & 0xff);
  EXPECT_EQ(codes.size(), 256u) << "the channels together take every code";
  for (SimdLevel level : {SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512, SimdLevel::kAuto})
    EXPECT_EQ(reference.color, renderAt(scene, options, level, 1).color) << static_cast<int>(level);
}

TEST(Renderer, AllocatesNothingPerFrameAfterWarmUp) {
  Scene scene;
  scene.camera.position = {0, 0.5f, 2.5f};
  scene.camera.near_z = 1.8f;  // some triangles cross the near plane
  scene.lights.push_back({normalize(float3{-1, -2, -1}), float3(0.9f)});
  scene.show_world_axes = true;
  Object sphere;
  sphere.mesh = std::make_shared<Mesh>(makeUvSphere(64, 32));
  sphere.shading = Shading::kPhong;
  sphere.show_axes = true;
  scene.objects.push_back(sphere);
  CpuRenderer renderer(3);
  RenderOptions options;
  options.width = 320;
  options.height = 200;
  options.normals = true;
  Frame frame;
  // Warm up on the same frames: buffers grow to the largest frame seen, then stay.
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      g_allocations = 0;
      g_count_allocations = true;
    }
    for (int i = 0; i < 3; ++i) {
      scene.objects[0].transform.rotation = quat::fromAxisAngle({0, 1, 0}, 0.1f * i);
      // With one sample and with MSAA (its sample layers, made once per worker), with and
      // without jitter.
      options.msaa = i == 2 ? 8 : 1;
      options.jitter = jitterOffset(static_cast<uint32_t>(i));
      renderer.render(scene, options, frame);
    }
  }
  g_count_allocations = false;
  EXPECT_GT(renderer.lastStats().triangles_clipped, 0u);
  EXPECT_EQ(g_allocations.load(), 0u);
}

// An animation with two workers, frame after frame, against one worker: the same bytes in every
// frame, while the two-worker renderer alternates and probes its two ways to run the vertex
// stage (render/replication.h) and its workers take their blocks of chunks and tiles.
TEST(Renderer, AnAnimationIsTheSameForOneAndTwoWorkers) {
  Scene scene;
  scene.camera.position = {0, 0.4f, 3};
  scene.lights.push_back({normalize(float3{-1, -1, -1}), float3(0.9f)});
  Object o;
  o.mesh = std::make_shared<Mesh>(makeUvSphere(96, 48));  // 9,216 triangles: three chunks
  o.shading = Shading::kGouraud;
  scene.objects.push_back(o);
  CpuRenderer one(1), two(2);
  RenderOptions options;
  options.width = 160;
  options.height = 120;
  Frame a, b;
  for (int frame = 0; frame < 24; ++frame) {
    scene.objects[0].transform.rotation = quat::fromAxisAngle({0, 1, 0}, 0.1f * frame);
    one.render(scene, options, a);
    two.render(scene, options, b);
    ASSERT_EQ(a.color, b.color) << "frame " << frame;
  }
  EXPECT_GT(coveredCount(a), 160 * 120 / 8);
}

TEST(Renderer, ReusesItsBuffersAcrossFramesAndSizes) {
  Scene scene;
  Object o;
  o.mesh = std::make_shared<Mesh>(makeCube());
  scene.objects.push_back(o);
  CpuRenderer renderer(2);
  RenderOptions options;
  Frame frame;
  options.width = 50, options.height = 40;
  renderer.render(scene, options, frame);
  Frame first = frame;
  options.width = 130, options.height = 70;
  renderer.render(scene, options, frame);
  EXPECT_EQ(frame.color.size(), 130u * 70u);
  options.width = 50, options.height = 40;
  renderer.render(scene, options, frame);
  EXPECT_EQ(frame.color, first.color);
  EXPECT_EQ(frame.triangle_id, first.triangle_id);
  // The same size, the cube turned and moved into one corner: nothing of the last frame's bins
  // is left over (setup empties only the tiles it filled).
  options.width = 160, options.height = 120;
  renderer.render(scene, options, frame);
  scene.objects[0].transform.rotation = quat::fromAxisAngle({0, 1, 0}, 0.7f);
  scene.objects[0].transform.translation = {1.2f, 0.9f, 0};
  renderer.render(scene, options, frame);
  CpuRenderer fresh(2);
  Frame expected;
  fresh.render(scene, options, expected);
  EXPECT_EQ(frame.color, expected.color);
  // While it learns, the renderer alternates between its two ways to run the vertex stage (once,
  // or once per worker: render/replication.h): the next two frames take one each.
  for (int i = 0; i < 2; ++i) {
    renderer.render(scene, options, frame);
    EXPECT_EQ(frame.color, expected.color) << i;
  }
}

TEST(Renderer, CameraInsideAClosedModelSeesItsInsideFaces) {
  Scene scene;
  scene.camera.position = {0.1f, 0.05f, 0.2f};
  scene.camera.target = {0, 0, -1};
  scene.camera.near_z = 0.01f;
  Object o;
  o.mesh = std::make_shared<Mesh>(makeCube());
  o.cull = CullMode::kNone;
  o.transform.scale = float3(2.0f);
  scene.objects.push_back(o);
  PipelineStats stats;
  Frame f = renderScene(scene, 64, 48, 2, &stats);
  EXPECT_EQ(coveredCount(f), 64 * 48);
  // With back faces culled the inside is invisible.
  scene.objects[0].cull = CullMode::kBack;
  EXPECT_EQ(coveredCount(renderScene(scene, 64, 48)), 0);
}

TEST(Renderer, EmptySceneIsAllBackground) {
  Scene scene;
  scene.background = {0.2f, 0.4f, 0.6f, 1.0f};
  Frame f = renderScene(scene, 7, 5);
  for (uint32_t c : f.color) EXPECT_EQ(c, packSrgba8(scene.background));
  for (float z : f.depth) EXPECT_EQ(z, kInf);
}

TEST(Renderer, AovsAreFilledOnlyWhenAskedAndDoNotChangeTheColour) {
  Scene scene;
  Object o;
  o.mesh = std::make_shared<Mesh>(makeUvSphere(16, 8));
  o.shading = Shading::kPhong;
  scene.objects.push_back(o);
  CpuRenderer renderer(2);
  RenderOptions options;
  options.width = 70;
  options.height = 50;
  Frame all, colour_only;
  options.normals = true;
  renderer.render(scene, options, all);
  options.depth = options.ids = options.normals = false;
  renderer.render(scene, options, colour_only);
  EXPECT_EQ(all.color, colour_only.color);
  EXPECT_EQ(all.depth.size(), 70u * 50u);
  EXPECT_EQ(all.normal.size(), 70u * 50u);
  EXPECT_TRUE(colour_only.depth.empty());
  EXPECT_TRUE(colour_only.triangle_id.empty());
  EXPECT_TRUE(colour_only.normal.empty());
  // Lines need depth: a scene with axes keeps a depth buffer.
  scene.show_world_axes = true;
  renderer.render(scene, options, colour_only);
  EXPECT_EQ(colour_only.depth.size(), 70u * 50u);
  EXPECT_TRUE(colour_only.triangle_id.empty());
}

// The vertex stage's two ways: alternated while both are timed, then the one with the lower
// median, the other every kProbeEvery-th frame; one slow frame does not flip it, a lasting change
// does, and a different scene starts over.
TEST(ReplicationChoice, KeepsTheFasterWayAndProbesTheOther) {
  using render::ReplicationChoice;
  ReplicationChoice choice;
  auto frame = [&](double replicated_ms, double shared_ms) {
    const bool way = choice.next(1000, 2000);
    choice.record(way, way ? replicated_ms : shared_ms);
    return way;
  };
  for (uint32_t f = 0; f < 2 * ReplicationChoice::kSamples; ++f)
    EXPECT_EQ(frame(2.0, 3.0), f % 2 == 0) << f;  // alternating while it learns
  EXPECT_TRUE(choice.preferred);
  // Replicated is faster: every frame replicated but one in kProbeEvery.
  int shared = 0;
  for (int f = 0; f < 64; ++f) shared += !frame(2.0, 3.0);
  EXPECT_EQ(shared, 64 / static_cast<int>(ReplicationChoice::kProbeEvery));
  // One very slow replicated frame changes nothing.
  choice.record(true, 50.0);
  EXPECT_TRUE(choice.preferred);
  // The host changes: sharing becomes the faster; after enough frames of each it is preferred.
  for (int f = 0; f < 200 && choice.preferred; ++f) frame(3.0, 2.0);
  EXPECT_FALSE(choice.preferred);
  int replicated = 0;
  for (int f = 0; f < 64; ++f) replicated += frame(3.0, 2.0);
  EXPECT_EQ(replicated, 64 / static_cast<int>(ReplicationChoice::kProbeEvery));
  // Another scene: learning again from the start.
  EXPECT_TRUE(choice.next(1001, 2000));
  EXPECT_EQ(choice.count[0] + choice.count[1], 0u);
  EXPECT_FALSE(choice.next(1001, 2000));
  // Replicating 1% faster is within the margin: the single transform is kept.
  ReplicationChoice close;
  for (int f = 0; f < 40; ++f) {
    const bool way = close.next(1000, 2000);
    close.record(way, way ? 1.98 : 2.0);
  }
  EXPECT_FALSE(close.preferred);
}

// Texture::linearTexels is made by whichever thread first samples a texture: several at once
// (the workers of one frame) get one copy, made once, with the decoded values. Run under
// ThreadSanitizer too (scripts/sanitize.sh).
TEST(TextureCopy, ThreadsThatMeetATextureTogetherShareOneDecodedCopy) {
  Texture texture;
  texture.width = 64;
  texture.height = 32;
  for (int i = 0; i < texture.width * texture.height; ++i)
    texture.texels.push_back(0x80000000u | static_cast<uint32_t>(i * 2654435761u >> 8));
  generateMipmaps(texture);
  const int16_t* seen[4] = {};
  std::atomic<int> waiting{4};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      waiting.fetch_sub(1);
      while (waiting.load() > 0) {
      }
      seen[t] = texture.linearTexels(t % 2);  // levels 0 and 1
    });
  for (std::thread& thread : threads) thread.join();
  ASSERT_NE(seen[0], nullptr);
  ASSERT_NE(seen[1], nullptr);
  for (int t = 2; t < 4; ++t) EXPECT_EQ(seen[t], seen[t % 2]);
  for (int i = 0; i < texture.width * texture.height; ++i)
    ASSERT_EQ(seen[0][4 * i], texelFixedTable(true)[texture.texels[static_cast<size_t>(i)] & 0xff]);
  EXPECT_EQ(seen[1][3], texelFixedTable(false)[128]);  // alpha: linear
}

// Every index of every job runs exactly once, on a worker the pool has, whether the workers are
// spinning (jobs back to back) or asleep (a pause before the job) when it starts, and a job's
// results are all there when parallelFor returns. A worker may arrive late, during a later job.
TEST(WorkerPool, EveryIndexRunsOnceAndIsDoneOnReturn) {
  render::WorkerPool pool(3);
  ASSERT_EQ(pool.size(), 3);
  std::mt19937 rng(7);
  std::vector<std::atomic<int>> runs(600);
  for (int job = 0; job < 400; ++job) {
    const size_t count = 1 + rng() % runs.size();
    if (job % 25 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    for (size_t i = 0; i < count; ++i) runs[i].store(0);
    std::atomic<int> bad_worker{0};
    pool.parallelFor(count, [&](size_t i, int worker) {
      if (worker < 0 || worker >= pool.size()) bad_worker.fetch_add(1);
      // The other workers finish their indices a little later than the caller would.
      if (worker != 0) std::this_thread::sleep_for(std::chrono::microseconds(20));
      runs[i].fetch_add(1);
    });
    ASSERT_EQ(bad_worker.load(), 0);
    for (size_t i = 0; i < count; ++i)
      ASSERT_EQ(runs[i].load(), 1) << "job " << job << " index " << i;
  }
}

TEST(PagePool, BlocksAreLineAlignedDisjointAndReusedBySize) {
  // Blocks of many sizes, filled with their own byte: none may overlap another or move off a
  // 64-byte boundary, and a freed block serves the next request of its size class.
  std::vector<std::pair<unsigned char*, size_t>> blocks;
  std::mt19937 random(7);
  for (int i = 0; i < 300; ++i) {
    const size_t bytes = size_t{1} << (random() % 19) | random() % 97;  // 1 B to ~256 KiB
    auto* block = static_cast<unsigned char*>(render::poolAllocate(bytes));
    ASSERT_EQ(reinterpret_cast<uintptr_t>(block) % 64, 0u) << bytes;
    std::memset(block, i & 0xff, bytes);
    blocks.push_back({block, bytes});
  }
  for (size_t i = 0; i < blocks.size(); ++i)
    for (size_t b = 0; b < blocks[i].second; ++b)
      ASSERT_EQ(blocks[i].first[b], static_cast<unsigned char>(i & 0xff)) << i << " " << b;
  // 100 bytes and 128 bytes share the 128-byte class; 129 does not.
  void* freed = render::poolAllocate(100);
  render::poolFree(freed, 100);
  void* again = render::poolAllocate(128);
  EXPECT_EQ(again, freed);
  void* other = render::poolAllocate(129);
  EXPECT_NE(other, freed);
  render::poolFree(again, 128);
  render::poolFree(other, 129);
  for (auto [block, bytes] : blocks) render::poolFree(block, bytes);
}

TEST(PagePool, LargeBlocksAndVectorsHoldTheirContents) {
  // Over 1 MiB a block is a mapping of its own, on a 2 MiB boundary.
  const size_t large = (size_t{3} << 20) + 5;
  auto* block = static_cast<unsigned char*>(render::poolAllocate(large));
  EXPECT_EQ(reinterpret_cast<uintptr_t>(block) % (size_t{2} << 20), 0u);
  block[0] = 1;
  block[large - 1] = 2;
  EXPECT_EQ(block[0] + block[large - 1], 3);
  render::poolFree(block, large);
  // A vector growing through every size class keeps what it holds.
  render::PoolVector<uint32_t> values;
  for (uint32_t i = 0; i < 1'000'000; ++i) values.push_back(i * 2654435761u);
  for (uint32_t i = 0; i < 1'000'000; ++i) ASSERT_EQ(values[i], i * 2654435761u) << i;
  EXPECT_EQ(reinterpret_cast<uintptr_t>(values.data()) % 64, 0u);
}
