// STL loading, binary and ASCII. Every test writes its own tiny files into a fresh folder.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <tessera/io/model_loader.h>

namespace tessera::io {
namespace {

namespace fs = std::filesystem;

using Facet = std::array<float3, 3>;

class StlFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    root_ = fs::temp_directory_path() /
            ("tessera_io_stl_" + test + "_" + std::to_string(std::random_device{}()));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path write(const std::string& name, const std::string& bytes) const {
    std::ofstream(root_ / name, std::ios::binary) << bytes;
    return root_ / name;
  }

  fs::path root_;
};

void appendU32(std::string& out, uint32_t value) {
  char bytes[4];
  std::memcpy(bytes, &value, 4);
  out.append(bytes, 4);
}

void appendFloat(std::string& out, float value) {
  char bytes[4];
  std::memcpy(bytes, &value, 4);
  out.append(bytes, 4);
}

// A binary STL: the 80-byte header (padded with zeros), the count, then each facet with a zero
// normal and a zero attribute.
std::string binaryStl(const std::vector<Facet>& facets, const std::string& header = "binary",
                      uint32_t count_override = 0, bool override_count = false) {
  std::string out = header;
  out.resize(80, '\0');
  appendU32(out, override_count ? count_override : static_cast<uint32_t>(facets.size()));
  for (const Facet& facet : facets) {
    for (int i = 0; i < 3; ++i) appendFloat(out, 0.0f);
    for (const float3& p : facet) {
      appendFloat(out, p.x);
      appendFloat(out, p.y);
      appendFloat(out, p.z);
    }
    out += std::string(2, '\0');
  }
  return out;
}

// Two facets of the unit square in z = 0, counter-clockwise seen from +z.
const std::vector<Facet> kSquare = {
    Facet{float3{0, 0, 0}, float3{1, 0, 0}, float3{1, 1, 0}},
    Facet{float3{0, 0, 0}, float3{1, 1, 0}, float3{0, 1, 0}},
};

const char* kAsciiSquare =
    "solid square\n"
    "  facet normal 0 0 1\n"
    "    outer loop\n"
    "      vertex 0 0 0\n"
    "      vertex 1 0 0\n"
    "      vertex 1 1 0\n"
    "    endloop\n"
    "  endfacet\n"
    "  facet normal 0 0 1\n"
    "    outer loop\n"
    "      vertex 0 0 0\n"
    "      vertex 1 1 0\n"
    "      vertex 0 1 0\n"
    "    endloop\n"
    "  endfacet\n"
    "endsolid square\n";

std::array<float3, 3> trianglePositions(const Mesh& mesh, size_t t) {
  return {mesh.positions[mesh.indices[3 * t]], mesh.positions[mesh.indices[3 * t + 1]],
          mesh.positions[mesh.indices[3 * t + 2]]};
}

void expectSquare(const Model& model) {
  const Mesh& mesh = model.mesh;
  ASSERT_EQ(mesh.triangleCount(), 2u);
  EXPECT_EQ(mesh.vertexCount(), 4u) << "the shared diagonal's corners are welded";
  for (size_t t = 0; t < 2; ++t) {
    std::array<float3, 3> corners = trianglePositions(mesh, t);
    for (size_t c = 0; c < 3; ++c) EXPECT_TRUE(corners[c] == kSquare[t][c]) << t << " " << c;
  }
  ASSERT_EQ(mesh.normals.size(), 4u);
  for (const float3& n : mesh.normals) {
    EXPECT_NEAR(n.z, 1.0f, 1e-6f);
    EXPECT_NEAR(length(n), 1.0f, 1e-6f);
  }
  EXPECT_EQ(model.materials.size(), 1u);
  EXPECT_EQ(model.nonfinite_triangles, 0u);
  EXPECT_FALSE(model.cull_back_faces.has_value()) << "STL does not say";
}

bool anyWarningContains(const Model& model, const std::string& text) {
  for (const std::string& warning : model.warnings)
    if (warning.find(text) != std::string::npos) return true;
  return false;
}

TEST_F(StlFiles, BinaryFacetsBecomeTrianglesInOrderWithWeldedVertices) {
  Expected<Model> model = loadStl(write("square.stl", binaryStl(kSquare)));
  ASSERT_TRUE(model) << model.error().message;
  expectSquare(*model);
  EXPECT_TRUE(model->warnings.empty());
}

TEST_F(StlFiles, BinaryWhoseHeaderStartsWithSolidIsReadAsBinary) {
  Expected<Model> model = loadStl(write("solid.stl", binaryStl(kSquare, "solid exported by CAD")));
  ASSERT_TRUE(model) << model.error().message;
  expectSquare(*model);
}

TEST_F(StlFiles, AsciiFacetsBecomeTrianglesInOrder) {
  Expected<Model> model = loadStl(write("square.stl", kAsciiSquare));
  ASSERT_TRUE(model) << model.error().message;
  expectSquare(*model);
}

TEST_F(StlFiles, AsciiAcceptsCrLfCapitalsSignsExponentsAndSeveralSolids) {
  const std::string text =
      "SOLID a\r\nFACET NORMAL 0 0 1\r\nOUTER LOOP\r\nVERTEX +0 0.0e0 -0\r\n"
      "VERTEX 1E0 0 0\r\nVERTEX 1 1.0 0\r\nENDLOOP\r\nENDFACET\r\nENDSOLID a\r\n"
      "solid b\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\n"
      "endloop\nendfacet\n";  // no final endsolid
  Expected<Model> model = loadStl(write("mixed.stl", text));
  ASSERT_TRUE(model) << model.error().message;
  expectSquare(*model);
}

TEST_F(StlFiles, WeldsMinusZeroWithZero) {
  std::vector<Facet> facets = kSquare;
  facets[1][0] = float3{-0.0f, -0.0f, 0.0f};
  Expected<Model> model = loadStl(write("zero.stl", binaryStl(facets)));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(model->mesh.vertexCount(), 4u);
}

TEST_F(StlFiles, AsciiErrorNamesFileAndLine) {
  std::string text = kAsciiSquare;
  text.replace(text.find("vertex 1 1 0"), 12, "vertex 1 x 0");
  Expected<Model> model = loadStl(write("bad.stl", text));
  ASSERT_FALSE(model);
  EXPECT_NE(model.error().message.find("bad.stl:6: expected a number, found 'x'"),
            std::string::npos)
      << model.error().message;
}

TEST_F(StlFiles, AsciiFacetWithFourVerticesIsAnError) {
  std::string text = kAsciiSquare;
  text.insert(text.find("    endloop"), "      vertex 2 2 2\n");
  Expected<Model> model = loadStl(write("quad.stl", text));
  ASSERT_FALSE(model);
  EXPECT_NE(model.error().message.find("quad.stl:2: a facet with more than 3 vertices"),
            std::string::npos)
      << model.error().message;
}

TEST_F(StlFiles, AsciiEndingInsideAFacetIsAnError) {
  std::string text = kAsciiSquare;
  text.resize(text.find("      vertex 1 0 0"));
  Expected<Model> model = loadStl(write("cut.stl", text));
  ASSERT_FALSE(model);
  EXPECT_NE(model.error().message.find("cut.stl:"), std::string::npos) << model.error().message;
  EXPECT_NE(model.error().message.find("the end of the file"), std::string::npos)
      << model.error().message;
}

TEST_F(StlFiles, AsciiWithoutFacetsHasNoTriangles) {
  Expected<Model> model = loadStl(write("empty_solid.stl", "solid nothing\nendsolid nothing\n"));
  ASSERT_FALSE(model);
  EXPECT_NE(model.error().message.find("no triangles"), std::string::npos);
}

TEST_F(StlFiles, TruncatedBinaryIsRefusedNamingBothSizes) {
  std::string bytes = binaryStl(kSquare);
  bytes.resize(bytes.size() - 7);
  Expected<Model> model = loadStl(write("cut.stl", bytes));
  ASSERT_FALSE(model);
  EXPECT_NE(model.error().message.find("cut.stl: truncated or corrupt binary STL: the header says "
                                       "2 facets (184 bytes), the file has 177 bytes"),
            std::string::npos)
      << model.error().message;
}

TEST_F(StlFiles, TruncatedBinaryWithASolidHeaderSaysItIsBinary) {
  std::string bytes = binaryStl(kSquare, "solid from a CAD tool");
  bytes.resize(bytes.size() - 10);
  Expected<Model> model = loadStl(write("cut.stl", bytes));
  ASSERT_FALSE(model);
  EXPECT_NE(model.error().message.find("truncated or corrupt binary STL"), std::string::npos)
      << model.error().message;
}

TEST_F(StlFiles, CountClaimingGigabytesIsRefusedFromTheFileSize) {
  Expected<Model> model =
      loadStl(write("huge.stl", binaryStl(kSquare, "binary", 0xFFFFFFFFu, true)));
  ASSERT_FALSE(model);
  EXPECT_NE(model.error().message.find("the header says 4294967295 facets (214748364834 bytes)"),
            std::string::npos)
      << model.error().message;
}

TEST_F(StlFiles, ShorterThanTheHeaderIsRefused) {
  Expected<Model> model = loadStl(write("tiny.stl", std::string(40, '\x01')));
  ASSERT_FALSE(model);
  EXPECT_NE(model.error().message.find("tiny.stl: truncated binary STL: 40 bytes"),
            std::string::npos)
      << model.error().message;
}

TEST_F(StlFiles, ZeroFacetsHasNoTriangles) {
  Expected<Model> model = loadStl(write("none.stl", binaryStl({})));
  ASSERT_FALSE(model);
  EXPECT_NE(model.error().message.find("no triangles"), std::string::npos);
}

TEST_F(StlFiles, EmptyFileIsAnError) {
  Expected<Model> model = loadStl(write("empty.stl", ""));
  ASSERT_FALSE(model);
  EXPECT_NE(model.error().message.find("empty.stl"), std::string::npos);
}

TEST_F(StlFiles, BytesAfterTheLastFacetAreIgnoredWithAWarning) {
  Expected<Model> model = loadStl(write("padded.stl", binaryStl(kSquare) + "pad"));
  ASSERT_TRUE(model) << model.error().message;
  expectSquare(*model);
  EXPECT_TRUE(anyWarningContains(*model, "3 bytes after the last facet ignored"));
}

TEST_F(StlFiles, NanVertexInBinaryIsCountedNamingTheFacet) {
  std::vector<Facet> facets = kSquare;
  facets[1][2].y = std::numeric_limits<float>::quiet_NaN();
  Expected<Model> model = loadStl(write("nan.stl", binaryStl(facets)));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(model->mesh.triangleCount(), 2u) << "kept, so ids stay in facet order";
  EXPECT_EQ(model->nonfinite_triangles, 1u);
  ASSERT_EQ(model->warnings.size(), 1u);
  EXPECT_NE(model->warnings[0].find("nan.stl: 1 facets have a NaN or infinite vertex (the first "
                                    "at facet 2)"),
            std::string::npos)
      << model->warnings[0];
  for (const float3& n : model->mesh.normals) EXPECT_TRUE(isFinite(n));
}

TEST_F(StlFiles, NanVertexInAsciiIsCountedNamingTheLine) {
  std::string text = kAsciiSquare;
  text.replace(text.find("vertex 0 1 0"), 12, "vertex 0 nan 0");
  Expected<Model> model = loadStl(write("nan.stl", text));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(model->nonfinite_triangles, 1u);
  ASSERT_EQ(model->warnings.size(), 1u);
  EXPECT_NE(model->warnings[0].find("nan.stl: 1 facets have a NaN or infinite vertex (the first "
                                    "at line 13)"),
            std::string::npos)
      << model->warnings[0];
}

TEST_F(StlFiles, AsciiNumbersBeyondFloatBecomeInfiniteOrZero) {
  std::string text = kAsciiSquare;
  text.replace(text.find("vertex 0 1 0"), 12, "vertex 1e-999 1e999 0");
  Expected<Model> model = loadStl(write("range.stl", text));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(model->nonfinite_triangles, 1u);
  const float3 p = trianglePositions(model->mesh, 1)[2];
  EXPECT_EQ(p.x, 0.0f);
  EXPECT_TRUE(std::isinf(p.y));
}

TEST_F(StlFiles, GarbageIsNotAnStlFile) {
  Expected<Model> model = loadStl(write("garbage.stl", "hello world, this is no STL at all"));
  ASSERT_FALSE(model);
  EXPECT_NE(model.error().message.find("garbage.stl"), std::string::npos);
}

TEST_F(StlFiles, LoadsFromMemory) {
  const std::string bytes = binaryStl(kSquare);
  Expected<Model> model = loadStlFromMemory(
      std::span(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()), "memory.stl");
  ASSERT_TRUE(model) << model.error().message;
  expectSquare(*model);
}

TEST_F(StlFiles, LoadModelPicksStlByExtensionInAnyCase) {
  Expected<Model> model = loadModel(write("PART.StL", kAsciiSquare));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(model->mesh.triangleCount(), 2u);
}

}  // namespace
}  // namespace tessera::io
