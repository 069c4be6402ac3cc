// OBJ/MTL loading, model dispatch and texture decoding. Every test writes its own tiny files into
// a fresh folder.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <tessera/io/image_loader.h>
#include <tessera/io/model_loader.h>

#include "stb_image_write.h"
#include "temp_folder.h"

namespace tessera::io {
namespace {

namespace fs = std::filesystem;

class ObjFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::makeTestFolder("tessera_io_obj");
    fs::create_directories(root_ / "model");
  }
  void TearDown() override { fs::remove_all(root_); }

  // A path beneath the model's folder.
  fs::path at(const std::string& relative) const { return root_ / "model" / relative; }

  fs::path write(const fs::path& path, const std::string& bytes) const {
    return test::writeFile(path, bytes);
  }
  fs::path writeModel(const std::string& text, const std::string& name = "model.obj") const {
    return write(at(name), text);
  }

  // A PNG of `width` x `height` RGBA texels (row 0 at the top), each RGBA as 0xAABBGGRR.
  static void writePng(const fs::path& path, int width, int height,
                       const std::vector<uint32_t>& texels) {
    fs::create_directories(path.parent_path());
    std::vector<unsigned char> bytes;
    for (uint32_t t : texels)
      for (int shift = 0; shift < 32; shift += 8) bytes.push_back((t >> shift) & 0xff);
    ASSERT_NE(stbi_write_png(path.string().c_str(), width, height, 4, bytes.data(), width * 4), 0);
  }
  static void writeSolidPng(const fs::path& path, uint32_t texel) {
    writePng(path, 2, 2, std::vector<uint32_t>(4, texel));
  }

  fs::path root_;
};

std::array<float3, 3> trianglePositions(const Mesh& mesh, size_t t) {
  return {mesh.positions[mesh.indices[3 * t]], mesh.positions[mesh.indices[3 * t + 1]],
          mesh.positions[mesh.indices[3 * t + 2]]};
}

bool anyWarningContains(const Model& model, const std::string& text) {
  for (const std::string& warning : model.warnings)
    if (warning.find(text) != std::string::npos) return true;
  return false;
}

std::string vertexLine(double x, double y, double z) {
  std::string line = "v ";
  for (double value : {x, y, z}) {
    line += std::to_string(value);
    line += ' ';
  }
  line.back() = '\n';
  return line;
}

// "f first first+1 ... last"
std::string faceLine(int first, int last) {
  std::string line = "f";
  for (int i = first; i <= last; ++i) {
    line += ' ';
    line += std::to_string(i);
  }
  return line + "\n";
}

void expectNear3(float3 actual, float3 expected) {
  EXPECT_NEAR(actual.x, expected.x, 1e-6f);
  EXPECT_NEAR(actual.y, expected.y, 1e-6f);
  EXPECT_NEAR(actual.z, expected.z, 1e-6f);
}

const char* kTwoTriangleHeader =
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 1 1 0\n"
    "v 0 1 0\n";

// ---- Triangle order ----

TEST_F(ObjFiles, QuadIsFanSplitFromItsFirstCorner) {
  // The 0-2 diagonal is the longer one, so a shortest-diagonal split would differ.
  Expected<Model> model =
      loadObj(writeModel("v 0 0 0\nv 1 0 0\nv 3 3 0\nv 0 1 0\n"
                         "f 1 2 3 4\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->mesh.triangleCount(), 2u);
  const std::array<float3, 3> first = trianglePositions(model->mesh, 0);
  const std::array<float3, 3> second = trianglePositions(model->mesh, 1);
  expectNear3(first[0], {0, 0, 0});
  expectNear3(first[1], {1, 0, 0});
  expectNear3(first[2], {3, 3, 0});
  expectNear3(second[0], {0, 0, 0});
  expectNear3(second[1], {3, 3, 0});
  expectNear3(second[2], {0, 1, 0});
}

TEST_F(ObjFiles, TrianglesFollowFaceOrderAcrossGroupsObjectsAndMaterials) {
  write(at("m.mtl"), "newmtl a\nKd 1 0 0\nnewmtl b\nKd 0 1 0\n");
  // Face k starts at x = k, so a triangle's first corner tells which face it came from.
  std::string obj = "mtllib m.mtl\n";
  for (int k = 0; k < 6; ++k)
    obj += vertexLine(k, 0, 0) + vertexLine(k, 1, 0) + vertexLine(k, 1, 1);
  obj +=
      "usemtl a\nf 1 2 3\n"
      "g second\nusemtl b\nf 4 5 6\n"
      "o third\nf 7 8 9\n"
      "usemtl a\nf 10 11 12\n"
      "g fifth\nf 13 14 15\n"
      "usemtl b\nf 16 17 18\n";
  Expected<Model> model = loadObj(writeModel(obj));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->mesh.triangleCount(), 6u);
  for (size_t t = 0; t < 6; ++t)
    EXPECT_EQ(trianglePositions(model->mesh, t)[0].x, static_cast<float>(t)) << "triangle " << t;
  EXPECT_EQ(model->mesh.triangle_materials, (std::vector<uint16_t>{0, 1, 1, 0, 0, 1}));
}

TEST_F(ObjFiles, ConcavePolygonIsEarClippedWithinItsOutline) {
  // An L (area 3) whose first corner cannot see the whole outline: a fan from it would leave the
  // shape. It lies in a tilted plane, mapped by (a, b) -> (a, 0.6 b, 0.8 b), which keeps areas.
  const std::vector<std::array<float, 2>> outline = {{2, 0}, {2, 1}, {1, 1},
                                                     {1, 2}, {0, 2}, {0, 0}};
  std::string obj;
  for (auto [a, b] : outline) obj += vertexLine(a, 0.6f * b, 0.8f * b);
  obj += "f 1 2 3 4 5 6\n";
  Expected<Model> model = loadObj(writeModel(obj));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->mesh.triangleCount(), 4u);
  auto toPlane = [](float3 p) { return std::array<float, 2>{p.x, 0.6f * p.y + 0.8f * p.z}; };
  auto insideL = [](float a, float b) {
    return a > 0 && a < 2 && b > 0 && b < 2 && !(a > 1 && b > 1);
  };
  float total = 0;
  for (size_t t = 0; t < 4; ++t) {
    std::array<float3, 3> p = trianglePositions(model->mesh, t);
    auto [ax, ay] = toPlane(p[0]);
    auto [bx, by] = toPlane(p[1]);
    auto [cx, cy] = toPlane(p[2]);
    const float area = 0.5f * ((bx - ax) * (cy - ay) - (by - ay) * (cx - ax));
    EXPECT_GT(area, 1e-4f) << "triangle " << t << " is flipped or empty";
    EXPECT_TRUE(insideL((ax + bx + cx) / 3, (ay + by + cy) / 3)) << "triangle " << t;
    total += area;
  }
  EXPECT_NEAR(total, 3.0f, 1e-4f);
}

TEST_F(ObjFiles, EarClippingTilesRandomSimplePolygonsExactly) {
  // Star-shaped polygons (random radius per angle) are simple but mostly concave. Triangles that
  // all keep the polygon's winding and add up to its area can neither overlap nor stick out.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> radius(0.2, 1.0);
  for (int polygon = 0; polygon < 40; ++polygon) {
    const int corners = 5 + polygon * 5;  // up to 200
    std::vector<std::array<double, 2>> outline;
    std::string obj;
    for (int i = 0; i < corners; ++i) {
      const double angle = 2 * 3.14159265358979 * i / corners, r = radius(random);
      outline.push_back({r * std::cos(angle), r * std::sin(angle)});
      obj += vertexLine(outline.back()[0], outline.back()[1], 0);
    }
    obj += faceLine(1, corners);
    Expected<Model> model = loadObj(writeModel(obj));
    ASSERT_TRUE(model.ok()) << model.error().message;
    ASSERT_EQ(model->mesh.triangleCount(), size_t(corners - 2));
    double expected = 0;
    for (int i = 0; i < corners; ++i) {
      const auto& [ax, ay] = outline[i];
      const auto& [bx, by] = outline[(i + 1) % corners];
      expected += 0.5 * (ax * by - ay * bx);
    }
    double total = 0;
    for (size_t t = 0; t < model->mesh.triangleCount(); ++t) {
      const std::array<float3, 3> p = trianglePositions(model->mesh, t);
      const double area = 0.5 * ((double(p[1].x) - p[0].x) * (double(p[2].y) - p[0].y) -
                                 (double(p[1].y) - p[0].y) * (double(p[2].x) - p[0].x));
      EXPECT_GE(area, -1e-9) << corners << " corners, triangle " << t;
      total += area;
    }
    EXPECT_NEAR(total, expected, 1e-4) << corners << " corners";
  }
}

TEST_F(ObjFiles, LargeConvexPolygonBecomesAFan) {
  std::string obj;
  const int corners = 200;
  for (int i = 0; i < corners; ++i) {
    const double angle = 2 * 3.14159265358979 * i / corners;
    obj += vertexLine(std::cos(angle), std::sin(angle), 0);
  }
  obj += faceLine(1, corners);
  Expected<Model> model = loadObj(writeModel(obj));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->mesh.triangleCount(), size_t{corners - 2});
  for (size_t t = 0; t < model->mesh.triangleCount(); ++t)
    expectNear3(trianglePositions(model->mesh, t)[0], {1, 0, 0});
}

TEST_F(ObjFiles, NegativeIndicesCountBackFromTheLatestVertex) {
  Expected<Model> model =
      loadObj(writeModel("v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                         "f -3 -2 -1\n"
                         "v 5 5 5\nv 6 5 5\nv 5 6 5\n"
                         "f -3 -2 -1\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->mesh.triangleCount(), 2u);
  expectNear3(trianglePositions(model->mesh, 0)[0], {0, 0, 0});
  expectNear3(trianglePositions(model->mesh, 1)[0], {5, 5, 5});
  expectNear3(trianglePositions(model->mesh, 1)[2], {5, 6, 5});
}

// ---- Vertices and attributes ----

TEST_F(ObjFiles, SharesAVertexOnlyWhenPositionUvAndNormalAllMatch) {
  Expected<Model> model = loadObj(writeModel(std::string(kTwoTriangleHeader) +
                                             "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
                                             "f 1/1 2/2 3/3\n"
                                             "f 1/1 3/3 4/4\n"     // shares corners 1 and 3
                                             "f 1/5 3/3 4/4\n"));  // position 1 with a new uv
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->mesh.vertexCount(), 5u);
  EXPECT_EQ(model->mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 4, 2, 3}));
  ASSERT_EQ(model->mesh.uvs.size(), 5u);
  EXPECT_EQ(model->mesh.uvs[4].x, 0.5f);
  EXPECT_EQ(model->mesh.uvs[4].y, 0.5f);
}

TEST_F(ObjFiles, MissingUvsAreZeroWhenOtherFacesHaveThem) {
  Expected<Model> model = loadObj(writeModel(std::string(kTwoTriangleHeader) + "vt 0.25 0.75\n"
                                                                               "f 1/1 2/1 3/1\n"
                                                                               "f 1 3 4\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->mesh.uvs.size(), model->mesh.vertexCount());
  const float2 missing = model->mesh.uvs[model->mesh.indices[5]];
  EXPECT_EQ(missing.x, 0.0f);
  EXPECT_EQ(missing.y, 0.0f);
  EXPECT_EQ(model->mesh.uvs[model->mesh.indices[0]].y, 0.75f);
}

TEST_F(ObjFiles, NoUvsAnywhereLeavesUvsEmpty) {
  Expected<Model> model = loadObj(writeModel(std::string(kTwoTriangleHeader) + "f 1 2 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(model->mesh.uvs.empty());
}

const char* kCube =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
    "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "f 1 4 3 2\n"   // -z
    "f 5 6 7 8\n"   // +z
    "f 1 2 6 5\n"   // -y
    "f 4 8 7 3\n"   // +y
    "f 1 5 8 4\n"   // -x
    "f 2 3 7 6\n";  // +x

TEST_F(ObjFiles, GeneratesOutwardUnitNormalsWhenTheFileHasNone) {
  Expected<Model> model = loadObj(writeModel(kCube));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const Mesh& mesh = model->mesh;
  ASSERT_EQ(mesh.vertexCount(), 8u);
  ASSERT_EQ(mesh.normals.size(), 8u);
  for (size_t v = 0; v < 8; ++v) {
    EXPECT_NEAR(length(mesh.normals[v]), 1.0f, 1e-5f) << "vertex " << v;
    // Outward: each component leans the way the corner sits from the centre. (Not exactly the
    // diagonal: each quad's two triangles weigh its corners unequally.)
    const float3 n = mesh.normals[v], p = mesh.positions[v];
    EXPECT_GT(n.x * p.x, 0.0f) << "vertex " << v;
    EXPECT_GT(n.y * p.y, 0.0f) << "vertex " << v;
    EXPECT_GT(n.z * p.z, 0.0f) << "vertex " << v;
  }
  EXPECT_TRUE(model->warnings.empty());
}

TEST_F(ObjFiles, GeneratedNormalsDoNotCreaseAtUvSeams) {
  // Two faces folded along the y axis share positions 1 and 2, with different uvs on each side.
  Expected<Model> model =
      loadObj(writeModel("v 0 0 0\nv 0 1 0\nv 1 0 0\nv 0 0 1\n"
                         "vt 0 0\nvt 1 1\n"
                         "f 1/1 3/1 2/1\n"
                         "f 1/2 2/2 4/2\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  const Mesh& mesh = model->mesh;
  ASSERT_EQ(mesh.vertexCount(), 6u);
  for (size_t corner = 0; corner < 2; ++corner) {
    // Corner 0 and 2 of the first face sit where corners 0 and 1 of the second do.
    const uint32_t a = mesh.indices[corner == 0 ? 0 : 2], b = mesh.indices[3 + corner];
    ASSERT_NE(a, b);
    expectNear3(mesh.normals[a], mesh.normals[b]);
    expectNear3(mesh.normals[a], normalize(float3{1, 0, 1}));  // the mean of +z and +x
  }
}

TEST_F(ObjFiles, NormalsMissingOnSomeFacesAreGeneratedForTheWholeMesh) {
  Expected<Model> model = loadObj(writeModel(std::string(kTwoTriangleHeader) +
                                             "vn 1 0 0\n"  // deliberately wrong for this plane
                                             "f 1//1 2//1 3//1\n"
                                             "f 1 3 4\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->mesh.normals.size(), model->mesh.vertexCount());
  for (float3 n : model->mesh.normals) expectNear3(n, {0, 0, 1});
  EXPECT_TRUE(anyWarningContains(*model, "no normals"));
}

TEST_F(ObjFiles, KeepsTheFileNormalsNormalized) {
  Expected<Model> model =
      loadObj(writeModel(std::string(kTwoTriangleHeader) + "vn 0 2 0\n"
                                                           "f 1//1 2//1 3//1\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->mesh.normals.size(), 3u);
  for (float3 n : model->mesh.normals) expectNear3(n, {0, 1, 0});
}

TEST_F(ObjFiles, ReadsVertexColoursOnlyWhenTheFileHasThem) {
  Expected<Model> coloured = loadObj(
      writeModel("v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 0.5\nf 1 2 3\n", "coloured.obj"));
  ASSERT_TRUE(coloured.ok()) << coloured.error().message;
  ASSERT_EQ(coloured->mesh.colors.size(), 3u);
  EXPECT_EQ(coloured->mesh.colors[0], (float4{1, 0, 0, 1}));
  EXPECT_EQ(coloured->mesh.colors[1], (float4{0, 1, 0, 1}));
  EXPECT_EQ(coloured->mesh.colors[2], (float4{0, 0, 0.5f, 1}));

  Expected<Model> plain = loadObj(writeModel("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  EXPECT_TRUE(plain->mesh.colors.empty());
}

TEST_F(ObjFiles, CountsTrianglesWithNonFiniteVerticesAndKeepsThem) {
  // tinyobjloader reads 0e999 as 0 * inf = NaN and 1e39 as a float infinity.
  Expected<Model> model =
      loadObj(writeModel("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0e999 0 0\nv 1e39 1 0\n"
                         "f 1 2 3\n"
                         "f 1 2 4\n"
                         "f 1 5 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->mesh.triangleCount(), 3u);
  EXPECT_EQ(model->nonfinite_triangles, 2u);
  EXPECT_TRUE(anyWarningContains(*model, "2 triangles have a NaN or infinite"));
}

// ---- Materials ----

TEST_F(ObjFiles, AssignsMaterialsPerTriangleInFirstUseOrder) {
  write(at("colours.mtl"),
        "newmtl red\nKd 1 0 0\n"
        "newmtl green\nKd 0 1 0\nd 0.5\n"
        "newmtl blue\nKd 0 0 1\nTr 0.25\n");
  Expected<Model> model =
      loadObj(writeModel(std::string("mtllib colours.mtl\n") + kTwoTriangleHeader +
                         "f 1 2 3\n"
                         "usemtl green\nf 1 2 3 4\n"
                         "usemtl red\nf 1 2 3\n"
                         "usemtl blue\nf 1 2 3\n"
                         "usemtl green\nf 1 2 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->mesh.triangle_materials, (std::vector<uint16_t>{0, 1, 1, 2, 3, 1}));
  ASSERT_EQ(model->materials.size(), 4u);
  EXPECT_EQ(model->materials[0].base_color, (float4{0.8f, 0.8f, 0.8f, 1}));  // the default
  EXPECT_EQ(model->materials[1].base_color, (float4{0, 1, 0, 0.5f}));
  EXPECT_EQ(model->materials[2].base_color, (float4{1, 0, 0, 1}));
  EXPECT_EQ(model->materials[3].base_color, (float4{0, 0, 1, 0.75f}));
  EXPECT_TRUE(model->warnings.empty());
}

TEST_F(ObjFiles, LoadsEveryLibraryOnAnMtllibLine) {
  write(at("a.mtl"), "newmtl red\nKd 1 0 0\n");
  write(at("b.mtl"), "newmtl blue\nKd 0 0 1\n");
  Expected<Model> model =
      loadObj(writeModel(std::string("mtllib a.mtl b.mtl\n") + kTwoTriangleHeader +
                         "usemtl blue\nf 1 2 3\nusemtl red\nf 1 3 4\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->materials.size(), 2u);
  EXPECT_EQ(model->materials[0].base_color, (float4{0, 0, 1, 1}));
  EXPECT_EQ(model->materials[1].base_color, (float4{1, 0, 0, 1}));
}

TEST_F(ObjFiles, MissingMtlFileWarnsAndFallsBackToTheDefaultMaterial) {
  Expected<Model> model = loadObj(writeModel(std::string("mtllib absent.mtl\n") +
                                             kTwoTriangleHeader + "usemtl red\nf 1 2 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->materials.size(), 1u);
  EXPECT_EQ(model->materials[0].base_color, (float4{0.8f, 0.8f, 0.8f, 1}));
  EXPECT_EQ(model->mesh.triangle_materials, (std::vector<uint16_t>{0}));
  EXPECT_TRUE(anyWarningContains(*model, "absent.mtl"));
}

TEST_F(ObjFiles, ReadsEachMaterialLibraryOnceHoweverOftenNamed) {
  Expected<Model> model =
      loadObj(writeModel(std::string("mtllib absent.mtl\n") + kTwoTriangleHeader +
                         "mtllib absent.mtl ./absent.mtl\nf 1 2 3\n"
                         "mtllib absent.mtl\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  size_t mentions = 0;
  for (const std::string& warning : model->warnings)
    mentions += warning.find("absent.mtl") != std::string::npos;
  EXPECT_EQ(mentions, 1u);
}

TEST_F(ObjFiles, LoadsADiffuseTextureWithOptionsAndSpacesInItsName) {
  writeSolidPng(at("my texture.png"), 0xff336699u);
  write(at("m.mtl"), "newmtl tex\nKd 1 1 1\nmap_Kd -s 1 1 1 -clamp on my texture.png\n");
  Expected<Model> model = loadObj(writeModel(std::string("mtllib m.mtl\n") + kTwoTriangleHeader +
                                             "vt 0 0\nusemtl tex\nf 1/1 2/1 3/1\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->materials.size(), 1u);
  const Material& material = model->materials[0];
  ASSERT_NE(material.albedo, nullptr) << (model->warnings.empty() ? "" : model->warnings[0]);
  EXPECT_EQ(material.albedo->width, 2);
  EXPECT_EQ(material.albedo->texels[0], 0xff336699u);
  EXPECT_TRUE(material.albedo->srgb);
  EXPECT_EQ(material.sampler.wrap_s, TextureWrap::kClamp);
  EXPECT_EQ(material.sampler.wrap_t, TextureWrap::kClamp);
  EXPECT_TRUE(model->warnings.empty());
}

TEST_F(ObjFiles, ResolvesWindowsStyleTexturePaths) {
  writeSolidPng(at("tex/a.png"), 0xff0000ffu);
  write(at("m.mtl"), "newmtl tex\nmap_Kd .\\tex\\a.png\n");
  Expected<Model> model = loadObj(
      writeModel(std::string("mtllib m.mtl\n") + kTwoTriangleHeader + "usemtl tex\nf 1 2 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_NE(model->materials[0].albedo, nullptr)
      << (model->warnings.empty() ? "" : model->warnings[0]);
  EXPECT_EQ(model->materials[0].albedo->texels[0], 0xff0000ffu);
}

TEST_F(ObjFiles, RefusesTexturesFromOutsideTheModelFolder) {
  // Every target exists, so only the refusal keeps them out.
  const fs::path outside = root_ / "outside.png";
  writeSolidPng(outside, 0xffffffffu);
  const fs::path link = at("link.png");
  fs::create_symlink(outside, link);
  const std::string absolute = outside.string();
  std::string mtl = "newmtl climbs\nmap_Kd tex/../../outside.png\n";
  mtl += "newmtl absolute\nmap_Kd " + absolute;
  mtl += "\nnewmtl uri\nmap_Kd file://" + absolute;
  mtl += "\nnewmtl web\nmap_Kd http://example.com/outside.png\n";
  mtl += "newmtl linked\nmap_Kd link.png\n";
  mtl += "newmtl drive\nmap_Kd C:\\outside.png\n";
  write(at("m.mtl"), mtl);
  Expected<Model> model = loadObj(writeModel(std::string("mtllib m.mtl\n") + kTwoTriangleHeader +
                                             "usemtl climbs\nf 1 2 3\n"
                                             "usemtl absolute\nf 1 2 3\n"
                                             "usemtl uri\nf 1 2 3\n"
                                             "usemtl web\nf 1 2 3\n"
                                             "usemtl linked\nf 1 2 3\n"
                                             "usemtl drive\nf 1 2 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->materials.size(), 6u);
  for (const Material& material : model->materials) EXPECT_EQ(material.albedo, nullptr);
  EXPECT_TRUE(anyWarningContains(*model, "'tex/../../outside.png' refused"));
  EXPECT_TRUE(anyWarningContains(*model, std::string("'").append(absolute).append("' refused")));
  EXPECT_TRUE(anyWarningContains(*model, "'file://"));
  EXPECT_TRUE(anyWarningContains(*model, "'http://example.com/outside.png' refused"));
  EXPECT_TRUE(anyWarningContains(*model, "'link.png' refused"));
  EXPECT_TRUE(anyWarningContains(*model, "'C:\\outside.png' refused: it is an absolute path"));
}

TEST_F(ObjFiles, RefusesAnMtlFileFromOutsideTheModelFolder) {
  write(root_ / "outside.mtl", "newmtl red\nKd 1 0 0\n");
  Expected<Model> model = loadObj(writeModel(std::string("mtllib ../outside.mtl\n") +
                                             kTwoTriangleHeader + "usemtl red\nf 1 2 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->materials.size(), 1u);
  EXPECT_EQ(model->materials[0].base_color, (float4{0.8f, 0.8f, 0.8f, 1}));
  EXPECT_TRUE(anyWarningContains(*model, "'../outside.mtl' refused"));
}

TEST_F(ObjFiles, TextureWithoutKdIsUsedAsItIs) {
  // tinyobjloader would make the first textured material 0.6 grey and, once a Kd has been seen,
  // the next one black.
  writeSolidPng(at("t.png"), 0xffffffffu);
  write(at("m.mtl"),
        "newmtl first\nmap_Kd t.png\n"
        "newmtl red\nKd 1 0 0\n"
        "newmtl second\nmap_Kd t.png\n"
        "newmtl tinted\nKd 0.25 0.5 1\nmap_Kd t.png\n");
  Expected<Model> model = loadObj(writeModel(std::string("mtllib m.mtl\n") + kTwoTriangleHeader +
                                             "usemtl first\nf 1 2 3\n"
                                             "usemtl red\nf 1 2 3\n"
                                             "usemtl second\nf 1 2 3\n"
                                             "usemtl tinted\nf 1 2 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->materials.size(), 4u);
  EXPECT_EQ(model->materials[0].base_color, (float4{1, 1, 1, 1}));
  EXPECT_EQ(model->materials[1].base_color, (float4{1, 0, 0, 1}));
  EXPECT_EQ(model->materials[2].base_color, (float4{1, 1, 1, 1}));
  EXPECT_EQ(model->materials[3].base_color, (float4{0.25f, 0.5f, 1, 1}));
  EXPECT_NE(model->materials[2].albedo, nullptr);
  // One texture file, decoded once.
  EXPECT_EQ(model->materials[0].albedo, model->materials[2].albedo);
}

TEST_F(ObjFiles, MissingTextureWarnsAndKeepsTheMaterialColour) {
  write(at("m.mtl"), "newmtl tex\nKd 0 1 0\nmap_Kd nowhere.png\n");
  Expected<Model> model = loadObj(
      writeModel(std::string("mtllib m.mtl\n") + kTwoTriangleHeader + "usemtl tex\nf 1 2 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->materials[0].albedo, nullptr);
  EXPECT_EQ(model->materials[0].base_color, (float4{0, 1, 0, 1}));
  EXPECT_TRUE(anyWarningContains(*model, "nowhere.png"));
}

// ---- Bad input ----

TEST_F(ObjFiles, RejectsAFaceIndexPastTheEndNamingFileAndLine) {
  Expected<Model> model =
      loadObj(writeModel(std::string(kTwoTriangleHeader) + "f 1 2 3\n\nf 1 2 99\n", "bad.obj"));
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find("bad.obj:7: face index 99 is past the end (4 positions)"),
            std::string::npos)
      << model.error().message;
}

TEST_F(ObjFiles, RejectsAnUvIndexPastTheEnd) {
  Expected<Model> model =
      loadObj(writeModel(std::string(kTwoTriangleHeader) + "vt 0 0\nf 1/1 2/2 3/1\n"));
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find("model.obj:6: texture coordinate index 2 is past the end"),
            std::string::npos)
      << model.error().message;
}

TEST_F(ObjFiles, RejectsARelativeIndexBeforeTheFirstVertex) {
  Expected<Model> model = loadObj(writeModel("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n"));
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find("model.obj:4: a relative face index reaches before the "
                                       "first position"),
            std::string::npos)
      << model.error().message;
}

TEST_F(ObjFiles, RejectsAZeroIndexNamingTheLine) {
  Expected<Model> model = loadObj(writeModel(std::string(kTwoTriangleHeader) + "f 0 1 2\n"));
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find("model.obj:5:"), std::string::npos) << model.error().message;
}

TEST_F(ObjFiles, RejectsAnEmptyFile) {
  Expected<Model> model = loadObj(writeModel("", "empty.obj"));
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find("empty.obj"), std::string::npos) << model.error().message;
}

TEST_F(ObjFiles, RejectsAFileWithoutFaces) {
  Expected<Model> model = loadObj(writeModel(std::string(kTwoTriangleHeader) + "f 1 2\n"));
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find("nothing to draw: no faces, points or lines"),
            std::string::npos)
      << model.error().message;
}

TEST_F(ObjFiles, RejectsGarbage) {
  std::string garbage;
  std::mt19937 random(7);
  for (int i = 0; i < 4096; ++i) garbage += static_cast<char>(random() & 0xff);
  Expected<Model> model = loadObj(writeModel(garbage, "garbage.obj"));
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find("garbage.obj"), std::string::npos) << model.error().message;
}

TEST_F(ObjFiles, RejectsAFaceWithMoreCornersThanTinyobjloaderRecords) {
  std::string obj;
  for (int i = 0; i < 300; ++i) obj += vertexLine(i, 0, 0);
  obj += "f 1 2 3\n" + faceLine(1, 300);
  Expected<Model> model = loadObj(writeModel(obj));
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find("model.obj:302: a face of 300 corners"), std::string::npos)
      << model.error().message;
}

TEST_F(ObjFiles, RejectsAMissingFile) {
  Expected<Model> model = loadObj(at("absent.obj"));
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find("absent.obj"), std::string::npos) << model.error().message;
}

// ---- Dispatch ----

TEST_F(ObjFiles, LoadModelPicksObjByExtensionInAnyCase) {
  Expected<Model> model =
      loadModel(writeModel(std::string(kTwoTriangleHeader) + "f 1 2 3\n", "MODEL.Obj"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->mesh.triangleCount(), 1u);
}

TEST_F(ObjFiles, LoadModelRejectsAnUnknownExtension) {
  Expected<Model> model = loadModel(writeModel("solid x\n", "shape.xyz"));
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find("shape.xyz"), std::string::npos) << model.error().message;
  EXPECT_NE(model.error().message.find(".obj"), std::string::npos) << model.error().message;
}

// ---- Textures ----

TEST_F(ObjFiles, TextureTexelsAreRgbaWithRedLowAndTopRowFirst) {
  writePng(at("t.png"), 2, 2, {0xff0000ffu, 0xff00ff00u, 0x80ff0000u, 0x00123456u});
  Expected<Texture> texture = loadTexture(at("t.png"), /*srgb=*/false);
  ASSERT_TRUE(texture.ok()) << texture.error().message;
  EXPECT_EQ(texture->width, 2);
  EXPECT_EQ(texture->height, 2);
  EXPECT_FALSE(texture->srgb);
  EXPECT_EQ(texture->texels,
            (std::vector<uint32_t>{0xff0000ffu, 0xff00ff00u, 0x80ff0000u, 0x00123456u}));
}

TEST_F(ObjFiles, RefusesAnImageOverTheSizeLimitBeforeDecoding) {
  // A 24-bit BMP header claiming 20000 x 20000 pixels, with no pixel data behind it.
  std::vector<unsigned char> bmp(54, 0);
  auto put32 = [&](size_t at, uint32_t value) {
    for (int i = 0; i < 4; ++i) bmp[at + i] = (value >> (8 * i)) & 0xff;
  };
  bmp[0] = 'B';
  bmp[1] = 'M';
  put32(2, 54 + 20000u * 20000u * 3u);  // file size as claimed (wraps; stb ignores it)
  put32(10, 54);                        // pixel data offset
  put32(14, 40);                        // BITMAPINFOHEADER
  put32(18, 20000);
  put32(22, 20000);
  bmp[26] = 1;   // planes
  bmp[28] = 24;  // bits per pixel
  const fs::path path = at("huge.bmp");
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bmp.data()), static_cast<std::streamsize>(bmp.size()));
  Expected<Texture> texture = loadTexture(path);
  ASSERT_FALSE(texture.ok());
  EXPECT_NE(texture.error().message.find("huge.bmp: image is 20000x20000"), std::string::npos)
      << texture.error().message;
}

TEST_F(ObjFiles, RejectsATruncatedImage) {
  std::vector<uint32_t> noise(64 * 64);
  std::mt19937 random(3);
  for (uint32_t& texel : noise) texel = random();
  const fs::path full = at("full.png");
  writePng(full, 64, 64, noise);
  std::ifstream in(full, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 1000u);
  const fs::path cut = at("cut.png");
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  Expected<Texture> texture = loadTexture(cut);
  ASSERT_FALSE(texture.ok());
  EXPECT_NE(texture.error().message.find("cut.png"), std::string::npos) << texture.error().message;
  ASSERT_TRUE(loadTexture(full).ok());
}

TEST_F(ObjFiles, DecodesATextureFromMemory) {
  writeSolidPng(at("t.png"), 0xff102030u);
  std::ifstream in(at("t.png"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Expected<Texture> texture =
      decodeTexture(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), "buffer 0");
  ASSERT_TRUE(texture.ok()) << texture.error().message;
  EXPECT_EQ(texture->texels[3], 0xff102030u);
  Expected<Texture> garbage =
      decodeTexture(reinterpret_cast<const unsigned char*>("nonsense"), 8, "buffer 1");
  ASSERT_FALSE(garbage.ok());
  EXPECT_NE(garbage.error().message.find("buffer 1"), std::string::npos);
}

// ---- Hostile input, round two (issue 22) ----

std::string errorOf(const Expected<Model>& model) {
  return model ? std::string("(loaded)") : model.error().message;
}

TEST_F(ObjFiles, FaceIndexPast32BitsIsAnErrorNotAWrap) {
  // tinyobjloader reads 4294967299 as 3 and 99999999999999999999 as -1 (the last vertex).
  for (const std::string index : {"4294967299", "99999999999999999999", "-2147483649"}) {
    Expected<Model> model =
        loadObj(writeModel("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 " + index + "\n"));
    ASSERT_FALSE(model.ok()) << index;
    EXPECT_NE(errorOf(model).find("model.obj:5: face index " + index + " is out of range"),
              std::string::npos)
        << errorOf(model);
  }
  // The largest index that fits is only past the end.
  EXPECT_NE(errorOf(loadObj(writeModel("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2147483647\n")))
                .find("past the end"),
            std::string::npos);
}

TEST_F(ObjFiles, NanAndInfPositionsDropTheirTriangles) {
  Expected<Model> model = loadObj(
      writeModel("v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nv 0 -Inf 0\nf 1 2 3\nf 1 2 4\nf 1 5 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->mesh.triangleCount(), 3u);
  EXPECT_EQ(model->nonfinite_triangles, 2u);  // read as 0, they would have been drawn
  EXPECT_FALSE(isFinite(trianglePositions(model->mesh, 1)[2]));
  EXPECT_FALSE(isFinite(trianglePositions(model->mesh, 2)[1]));
  EXPECT_TRUE(anyWarningContains(*model, "2 triangles have a NaN or infinite vertex"));
}

TEST_F(ObjFiles, TextureThatIsAFifoIsSkippedWithoutBlocking) {
  writeModel("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  write(at("m.mtl"), "newmtl a\nmap_Kd fifo.png\n");
  ASSERT_EQ(::mkfifo(at("fifo.png").c_str(), 0600), 0);
  // Opening a FIFO for reading blocks until a writer comes: this would hang before the fix.
  Expected<Model> model = loadObj(at("model.obj"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->materials[0].albedo, nullptr);
  EXPECT_TRUE(anyWarningContains(*model, "fifo.png: is a FIFO"));
}

TEST_F(ObjFiles, AFolderNamedAsATextureIsSaidToBeAFolder) {
  writeModel("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  write(at("m.mtl"), "newmtl a\nmap_Kd tex\n");
  fs::create_directories(at("tex"));
  Expected<Model> model = loadObj(at("model.obj"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(anyWarningContains(*model, "tex: is a directory"));
}

TEST_F(ObjFiles, TrianglesOverTheBudgetAreRefusedBeforeParsing) {
  LoadBudget budget;
  budget.max_triangles = 2;
  Expected<Model> model =
      loadObj(writeModel("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 2 3\n"), budget);
  EXPECT_NE(errorOf(model).find("3 triangles, over the budget of 2; raise it with "
                                "--max-triangles or --memory-limit"),
            std::string::npos)
      << errorOf(model);
  budget.max_triangles = 3;
  EXPECT_TRUE(loadObj(at("model.obj"), budget).ok());
}

TEST_F(ObjFiles, TextureOverThePixelBudgetFailsTheModel) {
  writeModel("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  write(at("m.mtl"), "newmtl a\nmap_Kd t.png\n");
  writePng(at("t.png"), 4, 4, std::vector<uint32_t>(16, 0xffffffffu));
  LoadBudget budget;
  budget.max_texture_pixels = 15;
  EXPECT_NE(errorOf(loadObj(at("model.obj"), budget))
                .find("t.png: image is 4x4 (16 pixels), over the budget of 15 pixels per texture; "
                      "raise it with --max-texture-pixels"),
            std::string::npos);
  budget.max_texture_pixels = 16;
  Expected<Model> model = loadObj(at("model.obj"), budget);
  ASSERT_TRUE(model.ok());
  EXPECT_NE(model->materials[0].albedo, nullptr);
}

TEST_F(ObjFiles, LibraryWarningsAreInTesserasWords) {
  write(at("m.mtl"), "newmtl a\nd 0.5\nTr 0.5\n");
  Expected<Model> model = loadObj(writeModel(
      "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl missing\nf 1 2 3\nusemtl a\nf 1 2 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(anyWarningContains(
      *model, "usemtl 'missing': no such material in the MTL files; the default is used"));
  EXPECT_TRUE(anyWarningContains(*model, "material 'a' sets both d and Tr; d is used"));
  for (const std::string& warning : model->warnings) {
    EXPECT_EQ(warning.find("not found in .mtl"), std::string::npos) << warning;
    EXPECT_EQ(warning.find("Use the value of"), std::string::npos) << warning;
  }
}

TEST_F(ObjFiles, PngClaimingAHugeSizeIsOverTheBudgetNotUnreadable) {
  // Only a signature and an IHDR claiming 100000 x 100000: stb's header scan gives up on it
  // ("unknown image type").
  std::string png = "\x89PNG\r\n\x1a\n";
  png += std::string("\0\0\0\x0dIHDR", 8);
  png += std::string("\x00\x01\x86\xa0\x00\x01\x86\xa0\x08\x00\x00\x00\x00", 13);
  png += std::string(4, '\0');
  Expected<Texture> texture = loadTexture(write(at("huge.png"), png));
  ASSERT_FALSE(texture.ok());
  EXPECT_NE(texture.error().message.find("huge.png: image is 100000x100000"), std::string::npos)
      << texture.error().message;
  EXPECT_EQ(texture.error().message.find("unknown image type"), std::string::npos);
}

}  // namespace
}  // namespace tessera::io
