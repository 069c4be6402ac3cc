// OBJ loading: triangle order, vertices and attributes, bad input, dispatch by extension.
// Materials and textures: io_obj_materials_test.cpp.
#include <gtest/gtest.h>

#include "obj_test_files.h"

namespace tessera::io {
namespace {

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

}  // namespace
}  // namespace tessera::io
