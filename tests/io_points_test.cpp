// Points and lines from the loaders (issue 20): OBJ `p` and `l` elements and vertex-only files,
// glTF POINTS / LINES / LINE_LOOP / LINE_STRIP under transformed nodes, PLY files of vertices
// only (through assimp), the budget, the scene they make and a render of a model of lines.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <tessera/io/model_loader.h>
#include <tessera/model/model_scene.h>
#include <tessera/scene/color.h>

#include "decode.h"
#include "gltf_test_files.h"
#include "run_process.h"

namespace tessera::io {
namespace {

namespace fs = std::filesystem;
using namespace gltf_test;  // NOLINT(google-build-using-namespace): the tests' own helpers

// GltfFiles gives a test folder (at, write) and the glTF builder; the OBJ and PLY tests use it
// too.
using PointFiles = GltfFiles;

const float3 kDefaultGrey = Material{}.base_color.xyz();

// A point's packed sRGB colour in linear light, and the most 8-bit quantizing moves it there.
float3 linearOf(uint32_t packed) {
  return {decodeSrgb8(static_cast<uint8_t>(packed)), decodeSrgb8(static_cast<uint8_t>(packed >> 8)),
          decodeSrgb8(static_cast<uint8_t>(packed >> 16))};
}
constexpr float kPacked = 0.005f;

// ---- OBJ ----

TEST_F(PointFiles, ObjPointElementsArePointsWithSrgbColoursDecoded) {
  Expected<Model> model = loadObj(write(at("p.obj"),
                                        "v 1 2 3 1 0.5 0\n"
                                        "v 4 5 6 0 0 1\n"
                                        "v 7 8 9 0.2 0.2 0.2\n"
                                        "p 1 3\n"
                                        "p -2\n"));
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_EQ(model->points.size(), 3u);
  expectNear3(model->points.positions[0], {1, 2, 3});
  expectNear3(model->points.positions[1], {7, 8, 9});
  expectNear3(model->points.positions[2], {4, 5, 6});  // -2: relative to the three before it
  ASSERT_EQ(model->points.colors.size(), 3u);
  expectNear3(linearOf(model->points.colors[0]), {1, srgbToLinear(0.5f), 0}, kPacked);
  expectNear3(linearOf(model->points.colors[1]), float3(srgbToLinear(0.2f)), kPacked);
  EXPECT_TRUE(model->lines.points.empty());
  EXPECT_EQ(model->mesh.triangleCount(), 0u);
}

TEST_F(PointFiles, ObjPolylinesAreConsecutiveSegmentsInTheirMaterialsColour) {
  write(at("m.mtl"), "newmtl red\nKd 1 0 0\nnewmtl plain\nNs 10\n");
  Expected<Model> model = loadObj(write(at("l.obj"),
                                        "mtllib m.mtl\n"
                                        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                        "l 1 2 3 4\n"
                                        "usemtl red\n"
                                        "l 4/1 1\n"
                                        "usemtl plain\n"
                                        "l 2 4\n"
                                        "l 3\n"));
  ASSERT_TRUE(model) << model.error().message;
  // 3 + 1 + 1 segments, each once: tinyobjloader would repeat those before each usemtl.
  ASSERT_EQ(model->lines.colors.size(), 5u);
  ASSERT_EQ(model->lines.points.size(), 10u);
  const std::vector<float3> ends = {{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 0},
                                    {0, 1, 0}, {0, 1, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (size_t i = 0; i < ends.size(); ++i) expectNear3(model->lines.points[i], ends[i]);
  expectNear3(model->lines.colors[0], kDefaultGrey);
  expectNear3(model->lines.colors[3], {1, 0, 0});
  expectNear3(model->lines.colors[4], kDefaultGrey);  // a material without Kd
  EXPECT_TRUE(model->points.empty());
}

TEST_F(PointFiles, ObjOfVerticesOnlyDrawsEveryVertexAsAPoint) {
  Expected<Model> model =
      loadObj(write(at("cloud.obj"), "# a cloud\nv 0 0 0\nv 1 0 0\nv 0 2 0\nv 0 0 -3\n"));
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_EQ(model->points.size(), 4u);
  expectNear3(model->points.positions[3], {0, 0, -3});
  EXPECT_TRUE(model->points.colors.empty());  // no colours: the renderer's point colour
}

TEST_F(PointFiles, ObjPointsBesideFacesKeepTheMesh) {
  Expected<Model> model =
      loadObj(write(at("both.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\np 4\n"));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(model->mesh.triangleCount(), 1u);
  ASSERT_EQ(model->points.size(), 1u);  // only the `p` vertex, not every vertex
  expectNear3(model->points.positions[0], {5, 5, 5});
}

TEST_F(PointFiles, ObjPointIndexPastTheEndNamesItsLine) {
  expectErrorContains(loadObj(write(at("bad.obj"), "v 0 0 0\nv 1 0 0\n\nl 1 2\np 9\n")),
                      "bad.obj:5: point index 9 is past the end (2 positions)");
}

TEST_F(PointFiles, ObjWithNothingToDrawSaysSo) {
  expectErrorContains(loadObj(write(at("nothing.obj"), "# nothing\no empty\n")),
                      "nothing.obj: nothing to draw: no faces, points or lines");
}

TEST_F(PointFiles, ObjPointsOverTheBudgetAreRefusedNamingTheFlag) {
  LoadBudget budget;
  budget.memory_bytes = 64 * 3;  // LoadBudget::points() = 3
  budget.max_triangles = 10;
  const fs::path cloud = write(at("cloud.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n");
  expectErrorContains(loadObj(cloud, budget),
                      "4 points and line end points, over the budget of 3; raise it with "
                      "--memory-limit");
  // Two segments of a polyline: four end points.
  expectErrorContains(
      loadObj(write(at("lines.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\n"), budget),
      "4 points and line end points, over the budget of 3");
  budget.memory_bytes = 64 * 4;
  EXPECT_TRUE(loadObj(cloud, budget));
  // A cloud is held to the points budget, not to the (smaller) mesh vertex budget.
  budget.memory_bytes = 64 * 8;  // 8 points; 2 mesh vertices (memory limit / 256)
  budget.max_triangles = 1;
  ASSERT_LT(budget.vertices(), 4u);
  EXPECT_TRUE(loadObj(cloud, budget));
}

TEST(LoadBudgetPoints, TenMillionPointsFitTheDefaultBudget) {
  EXPECT_GE(LoadBudget{}.points(), 10'000'000u);
  EXPECT_EQ(LoadBudget{}.points(), LoadBudget::kDefaultMemoryBytes / 64);
}

// ---- glTF ----

// A mesh of one POINTS, one LINES (indexed), one LINE_LOOP and one LINE_STRIP primitive over the
// same three positions, drawn by a node translated by (10, 0, 0) and by its child, a further
// (0, 5, 0) on.
std::string pointsAndLinesGltf(GltfBuilder& b) {
  const int p = b.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int color = b.accessor(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1}, kFloat, "VEC3", 3);
  const int lines = b.indices({0, 1, 1, 2});
  auto primitive = [&](int mode, const std::string& extra) {
    return "{\"attributes\":{\"POSITION\":" + std::to_string(p) + extra +
           "},\"mode\":" + std::to_string(mode);
  };
  return b.json(
      "\"scenes\":[{\"nodes\":[0]}],"
      "\"nodes\":[{\"mesh\":0,\"translation\":[10,0,0],\"children\":[1]},"
      "{\"mesh\":0,\"translation\":[0,5,0]}],"
      "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0.5,1,1]}}],"
      "\"meshes\":[{\"primitives\":[" +
      primitive(0, ",\"COLOR_0\":" + std::to_string(color)) + "}," + primitive(1, "") +
      ",\"indices\":" + std::to_string(lines) + ",\"material\":0}," + primitive(2, "") + "}," +
      primitive(3, "") + "}]}]");
}

TEST_F(PointFiles, GltfPointAndLineModesArePlacedAtEveryNodesWorldMatrix) {
  GltfBuilder b;
  Expected<Model> model = loadJson(pointsAndLinesGltf(b));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_TRUE(model->warnings.empty()) << allWarnings(*model);
  // Two instances of three points.
  ASSERT_EQ(model->points.size(), 6u);
  expectNear3(model->points.positions[0], {10, 0, 0});
  expectNear3(model->points.positions[2], {10, 1, 0});
  expectNear3(model->points.positions[4], {11, 5, 0});  // the child: (10, 5, 0) + (1, 0, 0)
  ASSERT_EQ(model->points.colors.size(), 6u);
  expectNear3(linearOf(model->points.colors[1]), {0, 1, 0},
              kPacked);  // COLOR_0, no material: white factor
  // Per instance: LINES 2 segments, LINE_LOOP 3, LINE_STRIP 2.
  ASSERT_EQ(model->lines.colors.size(), 14u);
  const std::vector<float3>& ends = model->lines.points;
  expectNear3(ends[0], {10, 0, 0});  // LINES 0-1
  expectNear3(ends[1], {11, 0, 0});
  expectNear3(ends[2], {11, 0, 0});  // LINES 1-2
  expectNear3(ends[3], {10, 1, 0});
  expectNear3(model->lines.colors[0], {0, 0.5f, 1});  // baseColorFactor
  expectNear3(ends[8], {10, 1, 0});                   // the loop's closing segment 2-0
  expectNear3(ends[9], {10, 0, 0});
  expectNear3(model->lines.colors[4], {1, 1, 1});  // no material: glTF's white
  expectNear3(ends[12], {11, 0, 0});               // the strip's second segment 1-2
  expectNear3(ends[13], {10, 1, 0});
  expectNear3(ends[14], {10, 5, 0});  // the child's LINES
  EXPECT_EQ(flattenedMesh(*model).triangleCount(), 0u);
}

TEST_F(PointFiles, GltfPointsOverTheBudgetAreRefusedAfterInstancing) {
  GltfBuilder b;
  LoadBudget budget;
  budget.memory_bytes = 64 * 33;  // 33 points; the file has 6 points and 14 segments
  budget.max_triangles = 10;
  expectErrorContains(loadJson(pointsAndLinesGltf(b), budget),
                      "34 points and line end points (after instancing), over the budget of 33; "
                      "raise it with --memory-limit");
  budget.memory_bytes = 64 * 34;
  EXPECT_TRUE(loadJson(pointsAndLinesGltf(b), budget));
}

// ---- PLY (assimp) ----

const char* kPlyHeader =
    "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";

void expectPlyCloud(const Expected<Model>& model) {
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_EQ(model->points.size(), 3u);
  expectNear3(model->points.positions[0], {0.5f, 0, 0});
  expectNear3(model->points.positions[2], {0, 0, -2});
  ASSERT_EQ(model->points.colors.size(), 3u);
  expectNear3(linearOf(model->points.colors[0]), {1, srgbToLinear(128 / 255.0f), 0}, kPacked);
  expectNear3(linearOf(model->points.colors[2]), {0, 0, 1}, kPacked);
  EXPECT_EQ(flattenedMesh(*model).triangleCount(), 0u);
}

TEST_F(PointFiles, AsciiPlyOfVerticesOnlyIsAColouredPointCloud) {
  if (!hasAssimp()) GTEST_SKIP() << "built without assimp";
  const std::string text = std::string("ply\nformat ascii 1.0\n") + kPlyHeader +
                           "0.5 0 0 255 128 0\n0 1 0 0 255 0\n0 0 -2 0 0 255\n";
  expectPlyCloud(loadModel(write(at("cloud.ply"), text)));
}

TEST_F(PointFiles, BinaryPlyOfVerticesOnlyIsAColouredPointCloud) {
  if (!hasAssimp()) GTEST_SKIP() << "built without assimp";
  std::string bytes = std::string("ply\nformat binary_little_endian 1.0\n") + kPlyHeader;
  const float xyz[3][3] = {{0.5f, 0, 0}, {0, 1, 0}, {0, 0, -2}};
  const uint8_t rgb[3][3] = {{255, 128, 0}, {0, 255, 0}, {0, 0, 255}};
  for (int v = 0; v < 3; ++v) {
    bytes.append(reinterpret_cast<const char*>(xyz[v]), sizeof xyz[v]);
    bytes.append(reinterpret_cast<const char*>(rgb[v]), sizeof rgb[v]);
  }
  expectPlyCloud(loadModel(write(at("cloud.ply"), bytes)));
}

// Read by ply_points.cpp, not assimp: big-endian doubles, float colours in 0..1 and a property
// it does not use.
TEST_F(PointFiles, BigEndianPlyOfDoublesWithFloatColoursIsAPointCloud) {
  if (!hasAssimp()) GTEST_SKIP() << "built without assimp";
  std::string bytes =
      "ply\nformat binary_big_endian 1.0\ncomment made by hand\nelement vertex 2\n"
      "property double x\nproperty double y\nproperty double z\nproperty float intensity\n"
      "property float red\nproperty float green\nproperty float blue\nend_header\n";
  auto big = [&](auto value) {
    char raw[sizeof value];
    std::memcpy(raw, &value, sizeof value);
    bytes.append(std::rbegin(raw), std::rend(raw));
  };
  for (double v : {1.5, -2.0, 3.0}) big(v);
  for (float v : {9.0f, 0.5f, 0.0f, 1.0f}) big(v);
  for (double v : {0.0, 0.0, 1e300}) big(v);  // past float: not drawn
  for (float v : {9.0f, 0.5f, 0.0f, 1.0f}) big(v);
  Expected<Model> model = loadModel(write(at("big.ply"), bytes));
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_EQ(model->points.size(), 1u);
  expectNear3(model->points.positions[0], {1.5f, -2, 3});
  expectNear3(linearOf(model->points.colors[0]), {srgbToLinear(0.5f), 0, 1}, kPacked);
  EXPECT_TRUE(anyWarningContains(*model, "1 points at a NaN or infinite position"))
      << allWarnings(*model);
}

TEST_F(PointFiles, PlyCloudShorterThanItsHeaderIsAnError) {
  if (!hasAssimp()) GTEST_SKIP() << "built without assimp";
  std::string binary = std::string("ply\nformat binary_little_endian 1.0\n") + kPlyHeader;
  binary += std::string(15 * 2 + 7, '\0');  // two vertices and a half
  expectErrorContains(loadModel(write(at("short.ply"), binary)),
                      "short.ply: the file ends before its 3 vertices");
  const std::string ascii = std::string("ply\nformat ascii 1.0\n") + kPlyHeader +
                            "0 0 0 1 2 3\n0 0 zero 1 2 3\n0 0 0 1 2 3\n";
  expectErrorContains(loadModel(write(at("word.ply"), ascii)),
                      "word.ply: vertex 2: property 'z' is not a number");
}

TEST_F(PointFiles, PlyPointsOverTheBudgetAreRefusedFromTheHeader) {
  if (!hasAssimp()) GTEST_SKIP() << "built without assimp";
  // 40 points, the budget 39 (a memory limit of 2496 bytes, past the file's size; far too
  // little for assimp's child process, which is why the header check must come first).
  std::string text = std::string("ply\nformat ascii 1.0\n") + kPlyHeader;
  text.replace(text.find("vertex 3"), 8, "vertex 40");
  for (int v = 0; v < 40; ++v) text += "0 0 0 1 2 3\n";
  LoadBudget budget;
  budget.memory_bytes = 64 * 39;
  budget.max_triangles = 10;
  ASSERT_LT(text.size(), budget.memory_bytes);
  expectErrorContains(loadModel(write(at("cloud.ply"), text), budget),
                      "40 vertices (points: the file has no faces), over the budget of 39; raise "
                      "it with --memory-limit");
}

// ---- Real files: Debian's assimp-testmodels, when installed ----

const fs::path kAssimpModels = "/usr/share/assimp/models";

TEST(PointTestModels, ObjPointsLinesAndMixedFromAssimpsTestModels) {
  if (!fs::exists(kAssimpModels / "OBJ/testmixed.obj")) GTEST_SKIP() << "no assimp-testmodels";
  Expected<Model> lines = loadObj(kAssimpModels / "OBJ/testline.obj");
  ASSERT_TRUE(lines) << lines.error().message;
  EXPECT_EQ(lines->lines.colors.size(), 18u);  // six 4-vertex polylines
  EXPECT_TRUE(lines->points.empty());
  Expected<Model> points = loadObj(kAssimpModels / "OBJ/testpoints.obj");
  ASSERT_TRUE(points) << points.error().message;
  EXPECT_EQ(points->points.size(), 24u);
  Expected<Model> mixed = loadObj(kAssimpModels / "OBJ/testmixed.obj");
  ASSERT_TRUE(mixed) << mixed.error().message;
  EXPECT_EQ(mixed->lines.colors.size(), 18u);
  EXPECT_EQ(mixed->points.size(), 24u);
  EXPECT_EQ(mixed->mesh.triangleCount(), 12u);                             // six quads
  Expected<Model> cloud = loadObj(kAssimpModels / "OBJ/point_cloud.obj");  // MeshLab's
  ASSERT_TRUE(cloud) << cloud.error().message;
  EXPECT_EQ(cloud->points.size(), 3u);
}

TEST(PointTestModels, PlyPointsAndAc3dLinesFromAssimpsTestModels) {
  if (!hasAssimp() || !fs::exists(kAssimpModels / "PLY/points.ply"))
    GTEST_SKIP() << "no assimp or no assimp-testmodels";
  Expected<Model> ply = loadModel(kAssimpModels / "PLY/points.ply");
  ASSERT_TRUE(ply) << ply.error().message;
  ASSERT_EQ(ply->points.size(), 4u);
  ASSERT_EQ(ply->points.colors.size(), 4u);
  expectNear3(linearOf(ply->points.colors[1]), {1, 0, 1}, kPacked);
  expectNear3(ply->points.positions[1], {0, 0, 1});
  // AC3D's line surfaces through assimp: an open polyline of 5 references (the last repeats
  // the first) and a closed one of 4: four segments each.
  Expected<Model> open = loadModel(kAssimpModels / "AC/openLine.ac");
  ASSERT_TRUE(open) << open.error().message;
  EXPECT_EQ(open->lines.colors.size(), 4u);
  Expected<Model> closed = loadModel(kAssimpModels / "AC/closedLine.ac");
  ASSERT_TRUE(closed) << closed.error().message;
  EXPECT_EQ(closed->lines.colors.size(), 4u);
}

// ---- The scene ----

TEST_F(PointFiles, ModelSceneHoldsThePointsAndIsFramedByThem) {
  Expected<Model> model =
      loadObj(write(at("cloud.obj"), "v -1 0 0 1 1 1\nv 3 2 0 1 1 1\nv 0 0 -4 0 0 0\n"));
  ASSERT_TRUE(model) << model.error().message;
  const Bounds bounds = model::modelBounds(*model);
  expectNear3(bounds.min, {-1, 0, -4});
  expectNear3(bounds.max, {3, 2, 0});
  Expected<Scene> scene = model::makeModelScene(std::move(*model), at("cloud.obj"), {});
  ASSERT_TRUE(scene) << scene.error().message;
  ASSERT_EQ(scene->points.size(), 3u);
  EXPECT_EQ(scene->points.colors.size(), 3u);
  EXPECT_EQ(scene->triangleCount(), 0u);
  expectNear3(scene->bounds().min, {-1, 0, -4});
  expectNear3(scene->bounds().max, {3, 2, 0});
}

TEST_F(PointFiles, FarAwayPointsAreFittedWithTheModel) {
  Expected<Model> model = loadObj(write(at("far.obj"), "v 1e10 0 0\nv 1.000001e10 0 0\nl 1 2\n"));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(model::fitModelScale(*model, at("far.obj"), /*keep_coordinates=*/false), "");
  const Bounds bounds = model::modelBounds(*model);
  EXPECT_LT(std::abs(bounds.center().x), 1.0f);
  EXPECT_GT(bounds.extent().x, 0.1f);
}

// ---- tessera render and info ----

class PointCli : public PointFiles {};

TEST_F(PointCli, AModelOfLinesRendersItsLines) {
  // A red cross through the origin, the framing camera's target.
  write(at("lines.mtl"), "newmtl red\nKd 1 0 0\n");
  write(at("cross.obj"),
        "mtllib lines.mtl\nusemtl red\nv -1 0 0\nv 1 0 0\nv 0 -1 0\nv 0 1 0\nl 1 2\nl 3 4\n");
  const test::RunResult run =
      test::runInFolder(at(""), TESSERA_EXE, "render cross.obj -o cross.png --resolution 64,64");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::optional<test::DecodedPng> png = test::decodePng(at("cross.png").string());
  ASSERT_TRUE(png);
  const std::array<int, 3> background = png->rgb(0, 0);
  int red = 0;
  for (int y = 0; y < png->height; ++y)
    for (int x = 0; x < png->width; ++x) {
      const std::array<int, 3> c = png->rgb(x, y);
      red += c != background && c[0] > 150 && c[1] < 60 && c[2] < 60;
    }
  EXPECT_GT(red, 40) << "the cross's pixels, of 64 x 64";
  const std::array<int, 3> centre = png->rgb(32, 32);
  const std::array<int, 3> left = png->rgb(31, 31);
  EXPECT_TRUE(centre[0] > 150 || left[0] > 150) << "the lines cross at the centre";

  const test::RunResult info = test::runInFolder(at(""), TESSERA_EXE, "info cross.obj");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("points:     0\n"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("lines:      2 segments\n"), std::string::npos) << info.out;
}

// A model of points alone renders (the points drawn once the point pass is in the build); a
// model of nothing but points was "no finite vertices" before its points counted.
TEST_F(PointCli, AModelOfPointsAloneRenders) {
  write(at("cloud.obj"), "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\n");
  const test::RunResult run =
      test::runInFolder(at(""), TESSERA_EXE, "render cloud.obj -o cloud.png --resolution 32,32");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("0 triangles"), std::string::npos) << run.out;
  EXPECT_TRUE(fs::exists(at("cloud.png")));
}

}  // namespace
}  // namespace tessera::io
