// The painter's algorithm (RenderOptions::visibility) and polygon edges (RenderOptions::edges):
// against the z-buffer where they must agree and where they must not, across workers and SIMD
// levels, and the edges pixel by pixel on quads placed on pixel centres. Then the CLI's flags.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>
#include <random>
#include <set>
#include <utility>

#include <tessera/io/model_loader.h>
#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/color.h>
#include <tessera/scene/primitives.h>

#include "decode.h"
#include "render/line_pass.h"
#include "run_process.h"
#include "temp_folder.h"

using namespace tessera;
namespace fs = std::filesystem;

#include "allocation_counter.h"  // g_count_allocations, g_allocations

namespace {

constexpr int kCubes = 5;

Object unlitObject(Mesh mesh, float3 color = float3(1.0f), CullMode cull = CullMode::kNone) {
  Object o;
  o.mesh = std::make_shared<Mesh>(std::move(mesh));
  o.materials[0].base_color = {color, 1};
  o.shading = Shading::kUnlit;
  o.cull = cull;
  return o;
}

// A scene whose camera maps object coordinates straight to clip space (w = 1).
Scene clipSpaceScene() {
  Scene scene;
  scene.camera.view_override = float4x4::identity();
  scene.camera.projection_override = float4x4::identity();
  return scene;
}

Frame renderFrame(const Scene& scene, RenderOptions options, int workers = 1,
                  SimdLevel simd = SimdLevel::kAuto) {
  CpuRenderer renderer(workers, simd);
  Frame frame;
  renderer.render(scene, options, frame);
  return frame;
}

RenderOptions sized(int width, int height, Visibility visibility = Visibility::kDepthBuffer) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.visibility = visibility;
  return options;
}

void expectSameFrames(const Frame& a, const Frame& b, const std::string& what) {
  EXPECT_EQ(a.color, b.color) << what;
  EXPECT_EQ(a.triangle_id, b.triangle_id) << what;
  ASSERT_EQ(a.depth.size(), b.depth.size()) << what;
  EXPECT_EQ(0, std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float))) << what;
}

// The cube demo's look, several times over: cubes one behind another along the view ray, each
// a little to the side of the one before, so that each hides part of the next; their depth
// ranges are apart.
Scene separatedCubes() {
  Scene scene;
  scene.camera.position = {0.0f, 1.1f, 2.4f};
  scene.camera.near_z = 0.1f;
  scene.camera.far_z = 40.0f;
  scene.lights.push_back({normalize(float3{-1, -2, -1}), float3(0.9f)});
  auto cube = std::make_shared<Mesh>(makeCube());
  for (int i = 0; i < kCubes; ++i) {
    const float k = static_cast<float>(i);
    Object o;
    o.mesh = cube;
    o.shading = Shading::kFlat;
    o.cull = CullMode::kBack;
    o.transform.translation = scene.camera.position * (-1.2f * k) + float3{0.9f * k, 0, 0};
    o.transform.rotation = fromEuler({0.3f * k, 0.5f, 0.2f});
    o.materials[0].base_color = {0.2f * k, 0.6f, 1.0f - 0.15f * k, 1};
    scene.objects.push_back(o);
  }
  return scene;
}

// Spheres and cubes scattered through the near plane: small, large and clipped triangles.
Scene scatteredScene() {
  Scene scene;
  scene.camera.position = {0, 2, 6};
  scene.camera.near_z = 0.5f;
  scene.lights.push_back({normalize(float3{-1, -2, -1}), float3(0.9f)});
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(-1, 1);
  auto sphere = std::make_shared<Mesh>(makeUvSphere(20, 10));
  auto cube = std::make_shared<Mesh>(makeCube());
  for (int i = 0; i < 40; ++i) {
    Object o;
    o.mesh = i % 3 ? sphere : cube;
    o.shading = static_cast<Shading>(i % 4);
    o.cull = static_cast<CullMode>(i % 3);
    o.transform.translation = {unit(rng) * 4, unit(rng) * 3, unit(rng) * 6};
    o.transform.rotation = fromEuler({unit(rng), unit(rng), unit(rng)});
    o.transform.scale = float3(0.3f + 0.5f * std::fabs(unit(rng)));
    o.materials[0].base_color = {std::fabs(unit(rng)), std::fabs(unit(rng)), 0.5f, 1};
    scene.objects.push_back(o);
  }
  return scene;
}

}  // namespace

TEST(Painter, EqualsTheDepthBufferOnSeparatedObjects) {
  const Scene scene = separatedCubes();
  for (int msaa : {1, 4}) {
    RenderOptions z = sized(160, 120), painter = sized(160, 120, Visibility::kPainter);
    z.msaa = painter.msaa = msaa;
    const Frame a = renderFrame(scene, z), b = renderFrame(scene, painter);
    // Every cube shows...
    std::set<uint32_t> seen(a.triangle_id.begin(), a.triangle_id.end());
    for (int cube = 0; cube < kCubes; ++cube)
      EXPECT_TRUE(seen.lower_bound(12u * cube + 1) != seen.end() &&
                  *seen.lower_bound(12u * cube + 1) <= 12u * cube + 12)
          << "cube " << cube;
    // ... and the second is partly hidden by the first: the order matters here.
    Scene second = scene;
    second.objects = {scene.objects[1]};
    const Frame alone = renderFrame(second, z);
    auto pixels = [](const Frame& f, uint32_t first_id) {
      int n = 0;
      for (uint32_t id : f.triangle_id) n += id >= first_id && id < first_id + 12;
      return n;
    };
    EXPECT_GT(pixels(alone, 1), pixels(a, 13) + 50);
    expectSameFrames(a, b, "msaa " + std::to_string(msaa));
  }
}

TEST(Painter, DiffersFromTheDepthBufferOnInterpenetratingTriangles) {
  // A leans from z = -0.6 (left, near) to z = 0.8 (right, far): its average depth is behind B's,
  // flat at z = 0, so the painter draws A first and B over all of it. The z-buffer shows A left
  // of where they cross (x = 3/7 of the way, window x 27.4 of 64) and B right of it.
  constexpr int kW = 64, kH = 32;
  Scene scene = clipSpaceScene();
  Mesh m;
  m.positions = {{-1, -1, -0.6f}, {1, -1, 0.8f}, {1, 1, 0.8f},
                 {-1, -1, 0.0f},  {1, -1, 0.0f}, {1, 1, 0.0f}};
  m.indices = {0, 1, 2, 3, 4, 5};
  scene.objects.push_back(unlitObject(m));
  const Frame z = renderFrame(scene, sized(kW, kH));
  const Frame painter = renderFrame(scene, sized(kW, kH, Visibility::kPainter));
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const uint32_t id = z.idAt(x, y);
      if (id == kNoTriangle) {
        EXPECT_EQ(painter.idAt(x, y), kNoTriangle) << x << "," << y;
        continue;
      }
      // Both triangles cover the same pixels (they share their window x and y).
      EXPECT_EQ(painter.idAt(x, y), 2u) << x << "," << y;
      if (x <= 26) {
        EXPECT_EQ(id, 1u) << x << "," << y;
      }
      if (x >= 28) {
        EXPECT_EQ(id, 2u) << x << "," << y;
      }
      // The depth AOV is the painted triangle's: B's plane, 0.5, even where A is nearer.
      EXPECT_NEAR(painter.depthAt(x, y), 0.5f, 1e-6f) << x << "," << y;
    }
  }
  EXPECT_EQ(z.idAt(10, 30), 1u);  // the pixels above hold something to compare
  EXPECT_EQ(z.idAt(60, 25), 2u);
}

TEST(Painter, SameImageForAnyWorkerCountAndSimdLevel) {
  const Scene scene = scatteredScene();
  for (int msaa : {1, 4}) {
    RenderOptions options = sized(211, 157, Visibility::kPainter);
    options.msaa = msaa;
    const Frame one = renderFrame(scene, options, 1, SimdLevel::kScalar);
    const Frame zbuffer = renderFrame(scene, sized(211, 157), 1);
    EXPECT_NE(one.triangle_id, zbuffer.triangle_id);  // the spheres cross: the orders differ
    for (int workers : {1, 2, 4})
      for (SimdLevel simd :
           {SimdLevel::kScalar, SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512})
        expectSameFrames(one, renderFrame(scene, options, workers, simd),
                         std::to_string(workers) + " workers, simd " +
                             std::to_string(static_cast<int>(simd)) + ", msaa " +
                             std::to_string(msaa));
  }
}

TEST(Painter, AllocatesNothingPerFrameAfterWarmUpWithEdges) {
  Scene scene = scatteredScene();
  CpuRenderer renderer(3);
  RenderOptions options = sized(160, 120, Visibility::kPainter);
  options.edges.show = true;
  options.edges.width = 2.0f;
  Frame frame;
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      g_allocations = 0;
      g_count_allocations = true;
    }
    for (int i = 0; i < 3; ++i) {
      scene.objects[0].transform.rotation = quat::fromAxisAngle({0, 1, 0}, 0.1f * i);
      options.msaa = i == 2 ? 4 : 1;
      renderer.render(scene, options, frame);
    }
  }
  g_count_allocations = false;
  EXPECT_GT(renderer.lastStats().triangles_setup, 1000u);
  EXPECT_EQ(g_allocations.load(), 0u);
}

TEST(Painter, TiesKeepSubmissionOrder) {
  // Two coplanar triangles over the same pixels: equal keys, so the one submitted later is
  // painted later and wins (the z-buffer keeps the first: z < stored fails on equal depths).
  constexpr int kW = 32, kH = 32;
  Scene scene = clipSpaceScene();
  Mesh m;
  m.positions = {{-0.8f, -0.8f, 0.1f}, {0.8f, -0.8f, 0.1f}, {0, 0.8f, 0.1f}};
  m.indices = {0, 1, 2, 0, 1, 2};
  scene.objects.push_back(unlitObject(m));
  EXPECT_EQ(renderFrame(scene, sized(kW, kH, Visibility::kPainter)).idAt(16, 16), 2u);
  EXPECT_EQ(renderFrame(scene, sized(kW, kH)).idAt(16, 16), 1u);
}

TEST(Painter, TiesAcrossChunksAndWorkersKeepSubmissionOrder) {
  // 30,000 copies of one triangle (several setup chunks, several sort parts): the last wins
  // everywhere, with any worker count; a nearer triangle in the middle of the list comes after
  // them all (it sorts in front) and wins where it covers.
  constexpr int kW = 48, kH = 48, kCopies = 30000;
  Scene scene = clipSpaceScene();
  Mesh m;
  m.positions = {{-0.9f, -0.9f, 0.2f},  {0.9f, -0.9f, 0.2f},  {0, 0.9f, 0.2f},
                 {-0.2f, -0.2f, -0.5f}, {0.2f, -0.2f, -0.5f}, {0, 0.2f, -0.5f}};
  for (int i = 0; i < kCopies; ++i) {
    const uint32_t base = i == kCopies / 2 ? 3 : 0;
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
  }
  scene.objects.push_back(unlitObject(m));
  for (int workers : {1, 2, 4}) {
    const Frame f = renderFrame(scene, sized(kW, kH, Visibility::kPainter), workers);
    EXPECT_EQ(f.idAt(24, 24), static_cast<uint32_t>(kCopies / 2 + 1)) << workers;
    EXPECT_EQ(f.idAt(24, 40), static_cast<uint32_t>(kCopies)) << workers;
    EXPECT_EQ(f.idAt(10, 40), static_cast<uint32_t>(kCopies)) << workers;
  }
}

TEST(Painter, ClippedPiecesTakeTheWholeTrianglesPlace) {
  // A triangle through the near plane (one corner in front of it, counted at depth 0) is cut
  // into pieces. Its depths sum to 0 + 0.95 + 0.95 = 1.9, behind a small triangle whose sum is
  // 3 * 0.6: every piece is painted first and the small triangle wins wherever it covers, as if
  // the big one were whole.
  constexpr int kW = 64, kH = 64;
  Scene scene = clipSpaceScene();
  Mesh m;
  m.positions = {{-1.5f, -1.5f, -2.0f}, {1.5f, -1.5f, 0.9f}, {0, 1.5f, 0.9f},
                 {-0.3f, -0.3f, 0.2f},  {0.3f, -0.3f, 0.2f}, {0, 0.3f, 0.2f}};
  m.indices = {3, 4, 5, 0, 1, 2};
  scene.objects.push_back(unlitObject(m));
  CpuRenderer renderer(1);
  Frame f;
  renderer.render(scene, sized(kW, kH, Visibility::kPainter), f);
  EXPECT_GT(renderer.lastStats().triangles_clipped, 0u);
  EXPECT_EQ(f.idAt(32, 32), 1u);
  EXPECT_EQ(f.idAt(32, 56), 2u);  // the big one elsewhere
  // The z-buffer shows the big one at the centre (it is nearer there, about z = 0.15 < 0.6).
  EXPECT_EQ(renderFrame(scene, sized(kW, kH)).idAt(32, 32), 2u);
}

namespace {

// A camera at z = 2 looking down -Z with a 90 degree view on a 64 x 64 image: world (x, y) at
// z = 0 lands on window (32 + 16 x, 32 - 16 y), at z = -1 on (32 + 32 x / 3, 32 - 32 y / 3).
constexpr int kEdgeSize = 64;

Scene edgeScene() {
  Scene scene;
  scene.camera.position = {0, 0, 2};
  scene.camera.target = {0, 0, 0};
  scene.camera.fov_y_degrees = 90.0f;
  scene.camera.near_z = 0.5f;
  scene.camera.far_z = 10.0f;
  return scene;
}

// The front quad's corners on the pixel centres (20.5, 16.5) and (43.5, 47.5), as an OBJ face:
// split into two triangles whose shared diagonal is no outline.
const char* const kFrontQuadObj =
    "v -0.71875 -0.96875 0\nv 0.71875 -0.96875 0\nv 0.71875 0.96875 0\nv -0.71875 0.96875 0\n"
    "f 1 2 3 4\n";

Mesh loadObjText(const std::string& text) {
  const fs::path dir = test::makeTestFolder("tessera_edges");
  const fs::path path = test::writeFile(dir / "quad.obj", text);
  Expected<io::Model> model = io::loadObj(path);
  fs::remove_all(dir);
  EXPECT_TRUE(static_cast<bool>(model));
  return model ? model->mesh : Mesh{};
}

// A quad at z = -1 whose window square is (24.5, 24.5) to (39.5, 39.5): inside the front quad.
Mesh backQuad() {
  Mesh m;
  constexpr float e = 0.703125f;
  m.positions = {{-e, -e, -1}, {e, -e, -1}, {e, e, -1}, {-e, e, -1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.triangle_edges = {0b011, 0b110};  // the outline, as the OBJ loader would mark it
  return m;
}

constexpr uint32_t kRed = 0xff0000ffu;  // RGBA8, R in the low byte

std::set<std::pair<int, int>> redPixels(const Frame& f) {
  std::set<std::pair<int, int>> red;
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x)
      if (f.colorAt(x, y) == kRed) red.insert({x, y});
  return red;
}

// The pixels of a rectangle's outline: rows top and bottom over columns left..right and columns
// left and right over rows top..bottom, each `width` pixels thick about the line.
std::set<std::pair<int, int>> outline(int left, int top, int right, int bottom, int width = 1) {
  std::set<std::pair<int, int>> pixels;
  const int lo = -(width - 1) / 2, hi = width / 2;
  for (int d = lo; d <= hi; ++d) {
    for (int x = left; x <= right; ++x) pixels.insert({x, top + d}), pixels.insert({x, bottom + d});
    for (int y = top; y <= bottom; ++y) pixels.insert({left + d, y}), pixels.insert({right + d, y});
  }
  return pixels;
}

RenderOptions withEdges(float width = 1.0f) {
  RenderOptions options = sized(kEdgeSize, kEdgeSize);
  options.edges.show = true;
  options.edges.color = {1, 0, 0};
  options.edges.width = width;
  return options;
}

}  // namespace

TEST(Edges, CoverExactlyTheOutlineOfAnObjQuadAndNotItsDiagonal) {
  Mesh quad = loadObjText(kFrontQuadObj);
  ASSERT_EQ(quad.triangleCount(), 2u);
  ASSERT_EQ(quad.triangle_edges.size(), 2u);
  Scene scene = edgeScene();
  scene.objects.push_back(unlitObject(quad));
  EXPECT_EQ(redPixels(renderFrame(scene, withEdges())), outline(20, 16, 43, 47));

  // Marked as three outline edges each, the triangles show their diagonal too.
  quad.triangle_edges.clear();
  scene.objects[0] = unlitObject(quad);
  const auto with_diagonal = redPixels(renderFrame(scene, withEdges()));
  EXPECT_TRUE(with_diagonal.contains({32, 31}) || with_diagonal.contains({31, 31}));
  EXPECT_GT(with_diagonal.size(), outline(20, 16, 43, 47).size() + 20);
}

TEST(Edges, LineWidthThickensTheOutlineAcrossEachEdge) {
  Scene scene = edgeScene();
  scene.objects.push_back(unlitObject(loadObjText(kFrontQuadObj)));
  EXPECT_EQ(redPixels(renderFrame(scene, withEdges(3.0f))), outline(20, 16, 43, 47, 3));
  EXPECT_EQ(redPixels(renderFrame(scene, withEdges(2.0f))), outline(20, 16, 43, 47, 2));
}

TEST(Edges, HiddenFacesShowNoEdges) {
  Scene scene = edgeScene();
  scene.objects.push_back(unlitObject(backQuad()));
  // Alone, the back quad shows its outline...
  EXPECT_EQ(redPixels(renderFrame(scene, withEdges())), outline(24, 24, 39, 39));
  // ... and behind the front quad, none of it: only the front quad's outline is drawn.
  scene.objects.push_back(unlitObject(loadObjText(kFrontQuadObj)));
  EXPECT_EQ(redPixels(renderFrame(scene, withEdges())), outline(20, 16, 43, 47));
  // The edges do not write depth: the depth AOV is the triangles' alone.
  RenderOptions plain = sized(kEdgeSize, kEdgeSize);
  const Frame a = renderFrame(scene, withEdges()), b = renderFrame(scene, plain);
  EXPECT_EQ(0, std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float)));
}

TEST(Edges, SameImageForAnyWorkerCountAndSimdLevel) {
  Scene scene = scatteredScene();
  RenderOptions options = sized(160, 120);
  options.edges.show = true;
  options.edges.width = 1.5f;
  options.msaa = 4;
  const Frame one = renderFrame(scene, options, 1, SimdLevel::kScalar);
  EXPECT_NE(one.color, renderFrame(scene, sized(160, 120)).color);
  for (int workers : {2, 4})
    EXPECT_EQ(one.color, renderFrame(scene, options, workers).color) << workers << " workers";
}

TEST(Edges, SharedEdgesAreListedOncePerObject) {
  // makeCube: 24 vertices (four per face), 12 triangles. Unflagged, every triangle edge counts:
  // 12 cube edges and 6 face diagonals, each once although two triangles (and two faces'
  // vertices) share it. Flagged as an OBJ cube's quads would be, the 12 edges alone.
  Scene scene;
  Mesh cube = makeCube();
  scene.objects.push_back(unlitObject(cube));
  std::vector<render::ObjectTransforms> objects = {
      render::makeObjectTransforms(scene.objects[0], float4x4::identity())};
  render::EdgeLines edges;
  LineList lines;
  edges.build(scene, objects, {1, 0, 0}, lines);
  EXPECT_EQ(lines.colors.size(), 18u);
  // Flag each triangle's two edges that are not the longest (the face diagonal).
  for (size_t t = 0; t < cube.triangleCount(); ++t) {
    uint8_t outline = 0;
    for (int k = 0; k < 3; ++k) {
      const float3 a = cube.positions[cube.indices[t * 3 + k]];
      const float3 b = cube.positions[cube.indices[t * 3 + (k + 1) % 3]];
      if (length(b - a) < 1.2f) outline |= static_cast<uint8_t>(1u << k);
    }
    cube.triangle_edges.push_back(outline);
  }
  scene.objects[0] = unlitObject(cube);
  edges.build(scene, objects, {1, 0, 0}, lines);
  EXPECT_EQ(lines.colors.size(), 12u);
  for (size_t i = 0; i < lines.colors.size(); ++i)
    EXPECT_NEAR(length(lines.points[2 * i + 1] - lines.points[2 * i]), 1.0f, 1e-6f) << i;
}

TEST(ObjLoader, MarksThePolygonOutlineOfFansAndEarClippedFaces) {
  // A triangle, a quad (fan: the diagonal 1-3 is inner) and a concave hexagon (ear-clipped).
  const Mesh mesh = loadObjText(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "v 0 0 1\nv 3 0 1\nv 3 2 1\nv 2 2 1\nv 2 1 1\nv 0 1 1\n"
      "f 1 2 3\nf 1 2 3 4\nf 5 6 7 8 9 10\n");
  ASSERT_EQ(mesh.triangleCount(), 1u + 2u + 4u);
  ASSERT_EQ(mesh.triangle_edges.size(), mesh.triangleCount());
  EXPECT_EQ(mesh.triangle_edges[0], kAllTriangleEdges);
  EXPECT_EQ(mesh.triangle_edges[1], 0b011);  // 1-2, 2-3 (3-1 is the diagonal)
  EXPECT_EQ(mesh.triangle_edges[2], 0b110);  // 3-4, 4-1
  // Every polygon side is marked exactly once over its triangles, and no diagonal is.
  int hexagon_sides = 0;
  for (size_t t = 3; t < 7; ++t)
    for (int k = 0; k < 3; ++k) hexagon_sides += (mesh.triangle_edges[t] >> k) & 1;
  EXPECT_EQ(hexagon_sides, 6);
}

TEST(ObjLoader, AllTriangleFilesLeaveTheEdgeFlagsEmpty) {
  const Mesh mesh = loadObjText("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
  EXPECT_EQ(mesh.triangleCount(), 2u);
  EXPECT_TRUE(mesh.triangle_edges.empty());  // empty: every edge an outline
}

namespace {

class PainterEdgesCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::makeTestFolder("tessera_painter_cli");
    test::writeFile(dir_ / "quad.obj", kFrontQuadObj);
  }
  void TearDown() override { fs::remove_all(dir_); }
  test::RunResult run(const std::string& args) {
    return test::runInFolder(dir_, TESSERA_EXE, args);
  }
  // A refused command: its status, a message naming `words`, and no output file.
  void expectRefused(const std::string& args, int status, const std::string& words) {
    const test::RunResult r = run(args + " -o out.png");
    EXPECT_EQ(r.exit_code, status) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out.png")) << args;
  }
  fs::path dir_;
};

}  // namespace

TEST_F(PainterEdgesCli, PainterAndEdgesRender) {
  const std::string common = "render quad.obj --resolution 64,64 --shading unlit --msaa 1 ";
  const test::RunResult z = run(common + "--camera-position 0,0,2 --camera-view-angle 90 -o z.png");
  ASSERT_EQ(z.exit_code, 0) << z.err;
  const test::RunResult p = run(common +
                                "--camera-position 0,0,2 --camera-view-angle 90 "
                                "--visibility painter -o p.png");
  ASSERT_EQ(p.exit_code, 0) << p.err;
  // One flat quad: nothing for the order to change.
  EXPECT_EQ(test::slurp(dir_ / "z.png"), test::slurp(dir_ / "p.png"));
  const test::RunResult e = run(common +
                                "--camera-position 0,0,2 --camera-view-angle 90 --edges "
                                "--edge-color 1,0,0 --line-width 3 -o e.png");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const std::optional<test::DecodedPng> png = test::decodePng((dir_ / "e.png").string());
  ASSERT_TRUE(png);
  auto red = [&](int x, int y) { return png->rgb(x, y) == std::array<int, 3>{255, 0, 0}; };
  EXPECT_TRUE(red(30, 15) && red(30, 16) && red(30, 17));  // the top edge, three pixels thick
  EXPECT_FALSE(red(30, 14) || red(30, 18));
  EXPECT_FALSE(red(32, 31));  // the diagonal is no outline
  // The default edge colour is black.
  ASSERT_EQ(
      run(common + "--camera-position 0,0,2 --camera-view-angle 90 --edges -o k.png").exit_code, 0);
  const std::optional<test::DecodedPng> black = test::decodePng((dir_ / "k.png").string());
  ASSERT_TRUE(black);
  EXPECT_EQ(black->rgb(30, 16), (std::array<int, 3>{0, 0, 0}));
  EXPECT_EQ(black->rgb(30, 20), png->rgb(30, 20));  // inside: the quad's own colour
  EXPECT_NE(black->rgb(30, 20), (std::array<int, 3>{0, 0, 0}));
}

TEST_F(PainterEdgesCli, BadValuesAreUsageErrors) {
  expectRefused("render quad.obj --visibility painters", 2, "flag '--visibility'");
  expectRefused("render quad.obj --edges --edge-color 2,0,0", 2,
                "flag '--edge-color': each channel must be in 0..1");
  expectRefused("render quad.obj --edges --edge-color red", 2, "flag '--edge-color'");
  for (const char* width : {"-1", "0", "nan", "65"})
    expectRefused(std::string("render quad.obj --edges --line-width ") + width, 2,
                  "flag '--line-width': the width must be a number of pixels above 0");
}

TEST_F(PainterEdgesCli, RefusesWhatItCannotDraw) {
  expectRefused("render quad.obj --visibility painter --projection spherical", 1,
                "perspective projection");
  expectRefused("render quad.obj --edges --projection fisheye", 1, "perspective projection");
  expectRefused("render quad.obj --visibility painter --backend vulkan", 1, "cpu backend");
  expectRefused("render quad.obj --edges --backend vulkan-raster", 1, "cpu backend");
  expectRefused("render quad.obj --visibility painter --aov overdraw", 1, "z-buffer's work");
}
