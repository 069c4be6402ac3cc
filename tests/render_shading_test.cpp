// The CPU pipeline's vertex stage and shading through its public seam: every instruction set's
// transform to the same bits, ids in scene order, perspective-correct texturing and filtering,
// Lambert lighting, the shading modes, the normal AOV and the axes' lines.
#include <gtest/gtest.h>

#include <algorithm>
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

#include "render_test_scenes.h"

using namespace tessera;
using namespace tessera::test;  // NOLINT(google-build-using-namespace)

namespace {

// Vertices for the vertex kernels' hardest cases, about one in twenty of each: NaN and infinite
// coordinates, on the camera's plane (w = 0, the camera at z = 4) and just in front of it, beyond
// the guard band and near its edges, zero and NaN normals; the rest random in a cube of side 6.
Mesh awkwardVertices(size_t count) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f);
  std::uniform_int_distribution<int> pick(0, 19);
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Mesh mesh;
  for (size_t i = 0; i < count; ++i) {
    float3 p{coordinate(rng), coordinate(rng), coordinate(rng)};
    float3 n{coordinate(rng), coordinate(rng), coordinate(rng)};
    switch (pick(rng)) {
      case 0:
        p.x = nan;
        break;
      case 1:
        p.y = inf;
        break;
      case 2:
        p.z = 4.0f;
        break;  // on the camera's plane: w = 0
      case 3:
        p.z = 4.0f - 1e-7f;
        break;  // just in front of it: huge screen positions
      case 4:
        p = p * 400.0f;
        break;  // beyond the guard band
      case 7:
        p = p * (4.0f + coordinate(rng) * coordinate(rng));
        break;  // near its edges
      case 5:
        n = float3{};
        break;  // zero normal: lit is NaN
      case 6:
        n.x = nan;
        break;
      default:
        break;
    }
    mesh.positions.push_back(p);
    mesh.normals.push_back(n);
  }
  return mesh;
}

}  // namespace

TEST(Vertex, EveryInstructionSetTransformsToTheSameBits) {
  // Every instruction set's vertex kernel against the scalar one, field by field and bit for bit:
  // vertices in front of and behind the camera, beyond the guard band, on the w = 0 plane (screen
  // positions outside int32), NaN and infinite; zero and NaN normals; with and without normals
  // and lighting; ranges that start and end anywhere, so that the AVX-512 variant's sixteen-vertex
  // steps, the eight-vertex steps and the staged tail all run.
  using namespace tessera::render;
  // Enough vertices that a difference of one ulp before the snap to subpixels shows.
  const size_t kVertices = 2000;
  Mesh mesh = awkwardVertices(kVertices);
  mesh.indices = {0, 1, 2};
  Object object;
  object.transform.rotation = quat::fromAxisAngle(normalize(float3{1, 2, 3}), 0.7f);
  object.transform.scale = float3{1.5f, 0.8f, 1.1f};
  Camera camera;
  camera.position = {0, 0, 4};
  const int width = 320, height = 200;
  const float4x4 view_projection =
      camera.projection(static_cast<float>(width) / height) * camera.view();
  ObjectTransforms transforms = makeObjectTransforms(object, view_projection);
  transforms.vertex_base = 5;
  const ViewportTransform viewport{static_cast<float>(width), static_cast<float>(height),
                                   makeGuardBand(width, height)};
  const ShadeLight lights[] = {
      shadeLight(Light::directional(normalize(float3{-1, -2, -1}), float3{0.9f, 0.8f, 0.7f})),
      shadeLight(Light::directional(normalize(float3{1, 0.5f, -1}), float3{0.2f, 0.3f, 0.4f}))};
  const VertexLighting lighting{float3{0.05f, 0.06f, 0.07f}, lights};
  Mesh without_normals = mesh;
  without_normals.normals.clear();

  auto run = [&](Isa isa, const Mesh& m, bool lit, size_t first, size_t count) {
    VertexBuffer out;
    out.resize(transforms.vertex_base + kVertices);
    kernelsFor(isa).transform_vertices(m, transforms, viewport, lit ? &lighting : nullptr, first,
                                       count, out);
    return out;
  };
  auto same = [](const auto& a, const auto& b, size_t from, size_t to) {
    return std::memcmp(a.data() + from, b.data() + from, (to - from) * sizeof(a[0])) == 0;
  };
  const std::pair<size_t, size_t> ranges[] = {{0, kVertices}, {3, 1000},          {17, 16},
                                              {1, 33},        {kVertices - 9, 9}, {20, 7}};
  int compared = 0;
  for (const Mesh* m : {&mesh, &without_normals}) {
    for (bool lit : {false, true}) {
      for (auto [first, count] : ranges) {
        const VertexBuffer reference = run(Isa::kScalar, *m, lit, first, count);
        const size_t from = transforms.vertex_base + first, to = from + count;
        for (Isa isa : {Isa::kSse2, Isa::kAvx2, Isa::kAvx512}) {
          if (isa > detectIsa()) continue;
          const VertexBuffer other = run(isa, *m, lit, first, count);
          const std::string what = std::string(isaName(isa)) + " from " + std::to_string(first) +
                                   " count " + std::to_string(count) + (lit ? " lit" : "") +
                                   (m == &mesh ? "" : " without normals");
          EXPECT_TRUE(same(reference.clip_x, other.clip_x, from, to)) << what;
          EXPECT_TRUE(same(reference.clip_y, other.clip_y, from, to)) << what;
          EXPECT_TRUE(same(reference.clip_z, other.clip_z, from, to)) << what;
          EXPECT_TRUE(same(reference.clip_w, other.clip_w, from, to)) << what;
          EXPECT_TRUE(same(reference.outcode, other.outcode, from, to)) << what;
          EXPECT_TRUE(same(reference.screen, other.screen, from, to)) << what;
          EXPECT_TRUE(same(reference.normal, other.normal, from, to)) << what;
          if (lit) {
            EXPECT_TRUE(same(reference.lit, other.lit, from, to)) << what;
          }
          ++compared;
        }
      }
    }
  }
  EXPECT_GT(compared, 0) << "no vector instruction set on this CPU to compare";
  // The inputs reach the cases they are meant to.
  const VertexBuffer all = run(Isa::kScalar, mesh, true, 0, kVertices);
  std::set<uint16_t> codes(all.outcode.begin() + 5, all.outcode.end());
  EXPECT_TRUE(codes.count(static_cast<uint16_t>(kNonFinite)));
  EXPECT_TRUE(codes.count(0));
  EXPECT_GT(codes.size(), 3u);
}

TEST(Raster, IdsFollowSceneTriangleOrderAcrossObjects) {
  Scene scene = clipSpaceScene();
  Mesh left, right;
  left.positions = {{-1, -1, 0}, {-0.1f, -1, 0}, {-1, 1, 0}, {-0.1f, 1, 0}};
  left.indices = {0, 1, 2, 1, 3, 2};
  right.positions = {{0.1f, -1, 0}, {1, -1, 0}, {0.1f, 1, 0}};
  right.indices = {0, 1, 2};
  scene.objects.push_back(unlitObject(left));
  scene.objects.push_back(unlitObject(right));
  Frame f = renderScene(scene, 20, 10);
  EXPECT_EQ(f.idAt(1, 8), 1u);  // lower-left: first triangle of the first object
  EXPECT_EQ(f.idAt(7, 1), 2u);
  EXPECT_EQ(f.idAt(12, 8), 3u);  // the second object's triangle follows the first's two
}

TEST(Shading, PerspectiveCorrectUvOnARecedingCheckerboard) {
  constexpr int kW = 96, kH = 64;
  constexpr int kChecks = 16;
  auto texture = std::make_shared<Texture>();
  texture->width = texture->height = kChecks;
  for (int y = 0; y < kChecks; ++y)
    for (int x = 0; x < kChecks; ++x)
      texture->texels.push_back((x + y) % 2 ? 0xffffffffu : 0xff000000u);

  Scene scene;
  scene.camera.position = {0, 1, 0};
  scene.camera.target = {0, 0.2f, -4};
  scene.camera.fov_y_degrees = 60;
  scene.camera.near_z = 0.1f;
  scene.camera.far_z = 100;
  // Floor y = 0 from z = -0.5 to z = -30.5, x in [-15, 15]; u along x, v along -z.
  const float z_near = -0.5f, z_far = -30.5f, half_x = 15.0f;
  Mesh floor;
  floor.positions = {
      {-half_x, 0, z_near}, {half_x, 0, z_near}, {half_x, 0, z_far}, {-half_x, 0, z_far}};
  floor.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  floor.indices = {0, 1, 2, 0, 2, 3};
  Object o = unlitObject(floor, CullMode::kBack);
  o.materials[0].albedo = texture;
  o.materials[0].sampler = {TextureFilter::kNearest, TextureWrap::kClamp, TextureWrap::kClamp};
  scene.objects.push_back(o);
  Frame f = renderScene(scene, kW, kH);

  const float aspect = static_cast<float>(kW) / kH;
  const float4x4 inverse_vp = inverse(scene.camera.projection(aspect) * scene.camera.view());
  int checked = 0, wrong = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      // Unproject the pixel centre to a world ray and intersect it with the floor.
      float ndc_x = 2.0f * (x + 0.5f) / kW - 1.0f, ndc_y = 1.0f - 2.0f * (y + 0.5f) / kH;
      float4 a = inverse_vp * float4{ndc_x, ndc_y, -1, 1},
             b = inverse_vp * float4{ndc_x, ndc_y, 1, 1};
      float3 p0 = a.xyz() * (1 / a.w), p1 = b.xyz() * (1 / b.w);
      if (!(p1.y < p0.y)) continue;
      float3 hit = p0 + (p1 - p0) * (p0.y / (p0.y - p1.y));
      float u = (hit.x + half_x) / (2 * half_x), v = (z_near - hit.z) / (z_near - z_far);
      if (u <= 0 || u >= 1 || v <= 0 || v >= 1) continue;
      float tu = u * kChecks, tv = (1 - v) * kChecks;
      // Skip centres within a sliver of a check boundary, where rounding may go either way.
      float du = std::fabs(tu - std::round(tu)), dv = std::fabs(tv - std::round(tv));
      float slack = 0.02f * (1 + 20 * (v));
      if (du < slack || dv < slack) continue;
      bool white = (static_cast<int>(tu) + static_cast<int>(tv)) % 2 == 1;
      uint32_t expected = white ? 0xffffffffu : 0xff000000u;
      ++checked;
      wrong += f.colorAt(x, y) != expected;
    }
  }
  EXPECT_GT(checked, kW * kH / 4);
  EXPECT_EQ(wrong, 0) << "of " << checked;
}

TEST(Shading, TrilinearFilteringAveragesAFineCheckerInTheDistance) {
  // A fine checker on a floor running to the horizon: far away, many texels fall in one pixel.
  // Without mip levels the samples alias to black and white; with them they blend to grey.
  constexpr int kW = 120, kH = 80;
  auto texture = std::make_shared<Texture>();
  texture->width = texture->height = 256;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x)
      texture->texels.push_back((x + y) % 2 ? 0xffffffffu : 0xff000000u);
  auto render = [&](bool mipmapped) {
    auto t = std::make_shared<Texture>(*texture);
    if (mipmapped) generateMipmaps(*t);
    Scene scene;
    scene.camera.position = {0, 0.5f, 0};
    scene.camera.target = {0, 0.3f, -4};
    scene.camera.near_z = 0.1f;
    scene.camera.far_z = 200;
    Mesh floor;
    floor.positions = {{-50, 0, -1}, {50, 0, -1}, {50, 0, -150}, {-50, 0, -150}};
    floor.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    floor.indices = {0, 1, 2, 0, 2, 3};
    Object o = unlitObject(floor, CullMode::kBack);
    o.materials[0].albedo = t;
    o.materials[0].sampler = {TextureFilter::kTrilinear, TextureWrap::kRepeat,
                              TextureWrap::kRepeat};
    scene.objects.push_back(o);
    return renderScene(scene, kW, kH);
  };
  // Pixels in the distant band that are far from the checker's mean (linear 0.5 = sRGB 188).
  auto extremes = [&](const Frame& f) {
    int top = 0;  // the first row with floor in it: the far edge, near the horizon
    while (top < kH && f.idAt(kW / 2, top) == kNoTriangle) ++top;
    int count = 0, covered = 0;
    for (int y = top; y < top + 4 && y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        if (f.idAt(x, y) == kNoTriangle) continue;
        ++covered;
        const uint32_t r = f.colorAt(x, y) & 0xff;
        count += std::abs(static_cast<int>(r) - 188) > 30;
      }
    EXPECT_GT(covered, kW * 3);
    return count;
  };
  const int aliased = extremes(render(false));
  const int filtered = extremes(render(true));
  EXPECT_GT(aliased, kW);
  EXPECT_LT(filtered, kW / 10);
}

TEST(Shading, LambertWithAmbientInLinearLight) {
  Scene scene = clipSpaceScene();
  scene.ambient = float3(0.1f);
  // A light shining straight at a face that looks at the viewer (+Z in clip space = towards
  // the viewer with the identity camera), at 60 degrees: cos = 0.5.
  scene.lights.push_back({normalize(float3{0, -std::sqrt(3.0f), -1}), float3(0.8f)});
  Mesh quad;
  quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  Object o = unlitObject(quad, CullMode::kBack);
  o.shading = Shading::kFlat;
  o.materials[0].base_color = {0.5f, 0.25f, 1.0f, 1.0f};
  scene.objects.push_back(o);
  Frame f = renderScene(scene, 8, 8);
  const float e = 0.1f + 0.8f * 0.5f;
  const uint32_t expected = packSrgba8({0.5f * e, 0.25f * e, 1.0f * e, 1.0f});
  for (uint32_t c : f.color) EXPECT_EQ(c, expected);
}

// Flat faces under directional lights are lit eight at a time by setup's batch kernel
// (setupFlatCorners, SetupBatch::markFlat); with the normal AOV asked for they take the scalar
// setupShadeCorners. The colours must be the same bits on every instruction set: front faces of a
// sphere with vertex colours, the inside of a larger open one drawn from within (back faces,
// lit from the viewer's side), lights from in front, behind and the side, and an ambient term.
// The kernel also forms the face normals: the small sphere is turned and scaled unevenly, a
// mirrored copy of it (winding sign -1) stands beside it, and batches span the objects' ends.
TEST(Shading, FlatFacesLitEightAtATimeGiveTheScalarSetupsColours) {
  Scene scene;
  scene.camera.position = {0.3f, 0.2f, 0.4f};  // inside the larger sphere
  scene.camera.target = {0, 0, -0.5f};
  scene.ambient = {0.05f, 0.07f, 0.02f};
  scene.lights.push_back({normalize(float3{-1, -1, -1}), float3{1.0f, 0.9f, 0.8f}});
  scene.lights.push_back({normalize(float3{0.3f, 0.2f, 1}), float3{0.2f, 0.5f, 0.9f}});
  scene.lights.push_back({normalize(float3{1, -0.2f, 0}), float3(0.4f)});
  Mesh inner = makeUvSphere(16, 8);
  for (size_t i = 0; i < inner.positions.size(); ++i) {
    inner.positions[i] = inner.positions[i] * 0.25f + float3{0, 0, -0.5f};
    inner.colors.push_back({0.5f + 0.5f * std::sin(static_cast<float>(i)),
                            0.5f + 0.5f * std::cos(0.7f * static_cast<float>(i)), 0.8f, 1.0f});
  }
  Object front;
  front.mesh = std::make_shared<Mesh>(inner);
  front.shading = Shading::kFlat;
  front.materials[0].base_color = {0.9f, 0.6f, 0.7f, 1.0f};
  front.transform.rotation = quat::fromAxisAngle(normalize(float3{1, 2, 0.5f}), 0.7f);
  front.transform.scale = {1.3f, 0.7f, 1.0f};
  scene.objects.push_back(front);
  Object mirrored = front;
  mirrored.transform.scale = {-0.8f, 0.9f, 1.1f};
  mirrored.transform.translation = {0.25f, -0.1f, -0.1f};
  scene.objects.push_back(mirrored);
  Object around;
  around.mesh = std::make_shared<Mesh>(makeUvSphere(24, 12));
  around.shading = Shading::kFlat;
  around.cull = CullMode::kNone;
  scene.objects.push_back(around);
  const size_t inner_triangles = inner.triangleCount();
  size_t back_facing = 0, turned = 0, mirror = 0;
  for (SimdLevel level :
       {SimdLevel::kScalar, SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512}) {
    RenderOptions options;
    options.width = 96;
    options.height = 64;
    options.ids = true;
    const Frame lanes = renderAt(scene, options, level, 1);
    options.normals = true;
    const Frame scalar = renderAt(scene, options, level, 2);
    EXPECT_EQ(lanes.color, scalar.color) << int(level);
    const auto pixels_of = [&](size_t object) {
      return static_cast<size_t>(std::ranges::count_if(lanes.triangle_id, [&](uint32_t id) {
        return id != kNoTriangle && (id - 1) / inner_triangles == object;
      }));
    };
    turned = pixels_of(0);
    mirror = pixels_of(1);
    back_facing = pixels_of(2) + pixels_of(3) + pixels_of(4);  // the larger sphere's, all back
  }
  EXPECT_GT(turned, 100u);
  EXPECT_GT(mirror, 100u);
  EXPECT_GT(back_facing, 1000u) << "the larger sphere's inside was not drawn";
}

// Gouraud faces lit in the vertex stage take setup's plain path (plainGouraudCorners) with their
// texture coordinates too; with the normal AOV asked for they take the scalar setupShadeCorners.
// The colours must be the same bits: an albedo texture read through TEXCOORD_0 on one sphere and
// through TEXCOORD_1 (a different set) on another, on every instruction set.
TEST(Shading, TexturedGouraudFacesOnThePlainPathGiveTheScalarSetupsColours) {
  auto checker = std::make_shared<Texture>();
  checker->width = checker->height = 8;
  for (int i = 0; i < 64; ++i)
    checker->texels.push_back((i + i / 8) % 2 ? 0xff40c0ffu : 0xff203080u);
  Scene scene;
  scene.camera.position = {0, 0, 4};
  scene.lights.push_back({normalize(float3{-1, -1, -1}), float3{1.0f, 0.9f, 0.8f}});
  for (int set : {0, 1}) {
    Mesh sphere = makeUvSphere(16, 8);
    for (size_t i = 0; i < sphere.positions.size(); ++i) {
      sphere.positions[i] = sphere.positions[i] + float3{set ? 0.9f : -0.9f, 0, 0};
      sphere.uvs1.push_back({sphere.uvs[i].y * 3.0f, sphere.uvs[i].x * 2.0f});
    }
    Object o;
    o.mesh = std::make_shared<Mesh>(sphere);
    o.shading = Shading::kGouraud;
    o.materials[0].albedo = checker;
    o.materials[0].sampler.texcoord = set;
    scene.objects.push_back(o);
  }
  for (SimdLevel level :
       {SimdLevel::kScalar, SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512}) {
    RenderOptions options;
    options.width = 96;
    options.height = 64;
    const Frame plain = renderAt(scene, options, level, 1);
    options.normals = true;
    const Frame scalar = renderAt(scene, options, level, 2);
    EXPECT_EQ(plain.color, scalar.color) << int(level);
    EXPECT_GT(std::set<uint32_t>(plain.color.begin(), plain.color.end()).size(), 20u);
  }
}

TEST(Shading, FlatGouraudAndPhongDifferAsExpectedOnASphere) {
  auto render = [](Shading shading) {
    Scene scene;
    scene.camera.position = {0, 0, 3};
    scene.lights.push_back({normalize(float3{-1, -1, -1}), float3(1.0f)});
    Object o;
    o.mesh = std::make_shared<Mesh>(makeUvSphere(12, 6));
    o.shading = shading;
    scene.objects.push_back(o);
    return renderScene(scene, 64, 64);
  };
  Frame flat = render(Shading::kFlat), gouraud = render(Shading::kGouraud),
        phong = render(Shading::kPhong);
  // Same coverage, different colours.
  EXPECT_EQ(flat.triangle_id, gouraud.triangle_id);
  EXPECT_EQ(flat.triangle_id, phong.triangle_id);
  EXPECT_NE(flat.color, gouraud.color);
  EXPECT_NE(gouraud.color, phong.color);
  // Flat: one colour per triangle.
  std::map<uint32_t, uint32_t> colour_of;
  for (size_t i = 0; i < flat.color.size(); ++i) {
    if (flat.triangle_id[i] == kNoTriangle) continue;
    auto [it, inserted] = colour_of.emplace(flat.triangle_id[i], flat.color[i]);
    EXPECT_EQ(it->second, flat.color[i]);
  }
  EXPECT_GT(colour_of.size(), 20u);
}

// An untextured mesh's UVs are not read by the Lambert modes (setup leaves them out, and its
// triangles take the plain Gouraud path): the images are those of the mesh without UVs. An albedo
// texture, or a PBR map without one, still reads them.
TEST(Shading, UvsMatterOnlyWhereATextureReadsThem) {
  auto render = [](Shading shading, bool uvs, auto&& material) {
    Scene scene;
    scene.camera.position = {0, 0, 3};
    scene.lights.push_back({normalize(float3{-1, -1, -1}), float3(1.0f)});
    Mesh sphere = makeUvSphere(24, 12);
    if (!uvs) sphere.uvs.clear();
    Object o;
    o.mesh = std::make_shared<Mesh>(sphere);
    o.shading = shading;
    material(o.materials[0]);
    scene.objects.push_back(o);
    return renderScene(scene, 64, 64, 2, nullptr, /*normals=*/shading == Shading::kPhong);
  };
  auto checker = std::make_shared<Texture>();
  checker->width = checker->height = 8;
  for (int i = 0; i < 64; ++i)
    checker->texels.push_back((i + i / 8) % 2 ? 0xffffffffu : 0xff202020u);
  const auto plain = [](Material&) {};
  for (Shading shading : {Shading::kFlat, Shading::kGouraud, Shading::kPhong, Shading::kUnlit}) {
    const Frame with = render(shading, true, plain), without = render(shading, false, plain);
    ASSERT_TRUE(
        std::ranges::any_of(with.triangle_id, [](uint32_t id) { return id != kNoTriangle; }));
    EXPECT_EQ(with.color, without.color) << int(shading);
    EXPECT_EQ(with.triangle_id, without.triangle_id) << int(shading);
    EXPECT_TRUE(with.normal == without.normal) << int(shading);  // empty but for Phong
    const auto textured = [&](Material& m) { m.albedo = checker; };
    EXPECT_NE(render(shading, true, textured).color, render(shading, false, textured).color)
        << int(shading) << ": the albedo texture was not read";
  }
  const auto mapped = [&](Material& m) { m.metallic_roughness.texture = checker; };
  EXPECT_NE(render(Shading::kPbr, true, mapped).color, render(Shading::kPbr, false, mapped).color)
      << "the metallic-roughness map was not read";
}

TEST(Shading, NormalAovIsUnitAndFacesTheViewer) {
  Scene scene;
  scene.camera.position = {0, 0, 3};
  Object o;
  o.mesh = std::make_shared<Mesh>(makeUvSphere(24, 12));
  o.shading = Shading::kPhong;
  scene.objects.push_back(o);
  Frame f = renderScene(scene, 48, 48, 1, nullptr, true);
  int covered = 0;
  for (size_t i = 0; i < f.pixelCount(); ++i) {
    if (f.triangle_id[i] == kNoTriangle) {
      EXPECT_EQ(f.normal[i], float3{});
      continue;
    }
    ++covered;
    EXPECT_NEAR(length(f.normal[i]), 1.0f, 1e-4f);
    EXPECT_GT(f.normal[i].z, -0.05f);
  }
  EXPECT_GT(covered, 48 * 48 / 4);
  // The centre pixel looks straight at the camera.
  EXPECT_GT(f.normal[24 * 48 + 24].z, 0.99f);
}

TEST(Lines, AxesAreDepthTestedButDoNotWriteDepth) {
  constexpr int kW = 40, kH = 20;
  Scene scene = clipSpaceScene();
  // A wall at NDC z = 0 over the left half; a red line at z = 0.5 (behind it) across the image.
  Mesh wall;
  wall.positions = {{-1, -1, 0}, {0, -1, 0}, {0, 1, 0}, {-1, 1, 0}};
  wall.indices = {0, 1, 2, 0, 2, 3};
  Object o = unlitObject(wall);
  o.materials[0].base_color = {0, 0, 1, 1};
  scene.objects.push_back(o);
  scene.lines.add({-1, 0.05f, 0.5f}, {1, 0.05f, 0.5f}, {1, 0, 0});
  Frame f = renderScene(scene, kW, kH);
  const uint32_t red = 0xff0000ffu, blue = 0xffff0000u;
  int red_right = 0;
  for (int x = 0; x < kW; ++x) {
    for (int y = 0; y < kH; ++y) {
      if (x < kW / 2) {
        EXPECT_EQ(f.colorAt(x, y), blue) << x << "," << y;
      }
      if (x >= kW / 2 && f.colorAt(x, y) == red) {
        ++red_right;
        EXPECT_EQ(f.depthAt(x, y), kInf);
      }
    }
  }
  EXPECT_GE(red_right, kW / 2 - 1);
}

TEST(Lines, WorldAxesPointAlongPositiveAxes) {
  Scene scene = clipSpaceScene();
  scene.show_world_axes = true;
  scene.world_axes_length = 0.9f;
  Frame f = renderScene(scene, 21, 21);
  // X (red) runs right from the centre, Y (green) runs up.
  EXPECT_EQ(f.colorAt(17, 10), 0xff0000ffu);
  EXPECT_EQ(f.colorAt(10, 3), 0xff00ff00u);
  EXPECT_EQ(f.colorAt(3, 10), packSrgba8(scene.background));
}
