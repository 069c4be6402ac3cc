// glTF 2.0 and GLB loading. Every test builds its own small file: JSON with the buffer in a
// data: URI, a GLB assembled here, or a JSON file beside a .bin.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <tessera/io/model_loader.h>
#include <tessera/scene/color.h>

#include "stb_image_write.h"
#include "temp_folder.h"

namespace tessera::io {
namespace {

namespace fs = std::filesystem;

std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t n = uint32_t{bytes[i]} << 16;
    if (i + 1 < bytes.size()) n |= uint32_t{bytes[i + 1]} << 8;
    if (i + 2 < bytes.size()) n |= bytes[i + 2];
    out += kDigits[(n >> 18) & 63];
    out += kDigits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

template <typename T>
void appendValues(std::vector<uint8_t>& out, const std::vector<T>& values) {
  const size_t at = out.size();
  out.resize(at + values.size() * sizeof(T));
  std::memcpy(out.data() + at, values.data(), values.size() * sizeof(T));
}

constexpr int kByte = 5121;   // UNSIGNED_BYTE
constexpr int kShort = 5123;  // UNSIGNED_SHORT
constexpr int kUint = 5125;   // UNSIGNED_INT
constexpr int kFloat = 5126;

// Builds the binary side of a glTF file: one buffer, one bufferView per accessor. The JSON for
// nodes, meshes and materials is written by each test.
class GltfBuilder {
 public:
  // An accessor over `values` (tightly packed), returning its index.
  template <typename T>
  int accessor(const std::vector<T>& values, int component_type, const std::string& type,
               size_t count, const std::string& extra = "") {
    const int view = bufferView(values);
    accessors_.push_back("{\"bufferView\":" + std::to_string(view) +
                         ",\"componentType\":" + std::to_string(component_type) + ",\"type\":\"" +
                         type + "\",\"count\":" + std::to_string(count) + extra + "}");
    return static_cast<int>(accessors_.size()) - 1;
  }
  int positions(const std::vector<float3>& points) {
    std::vector<float> values;
    for (float3 p : points) values.insert(values.end(), {p.x, p.y, p.z});
    return accessor(values, kFloat, "VEC3", points.size());
  }
  int indices(const std::vector<uint16_t>& values) {
    return accessor(values, kShort, "SCALAR", values.size());
  }
  // A bufferView over `values`, 4-byte aligned, returning its index.
  template <typename T>
  int bufferView(const std::vector<T>& values, const std::string& extra = "") {
    while (bytes_.size() % 4 != 0) bytes_.push_back(0);
    const size_t offset = bytes_.size();
    appendValues(bytes_, values);
    views_.push_back("{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) +
                     ",\"byteLength\":" + std::to_string(values.size() * sizeof(T)) + extra + "}");
    return static_cast<int>(views_.size()) - 1;
  }
  // A raw accessor, written as given.
  int rawAccessor(const std::string& json) {
    accessors_.push_back(json);
    return static_cast<int>(accessors_.size()) - 1;
  }

  // The whole JSON: `body` holds the other top-level members ("nodes": ..., "meshes": ...).
  // `buffer_uri` empty: the buffer in a data: URI; "GLB": no URI (the binary chunk).
  std::string json(const std::string& body, const std::string& buffer_uri = "") const {
    std::string buffer = "{\"byteLength\":" + std::to_string(bytes_.size());
    if (buffer_uri.empty())
      buffer += ",\"uri\":\"data:application/octet-stream;base64," + base64(bytes_) + "\"";
    else if (buffer_uri != "GLB")
      buffer += ",\"uri\":\"" + buffer_uri + "\"";
    buffer += "}";
    std::string out = "{\"asset\":{\"version\":\"2.0\"}";
    if (!bytes_.empty()) {
      out += ",\"buffers\":[" + buffer + "]";
      out += ",\"bufferViews\":[" + joined(views_) + "]";
      out += ",\"accessors\":[" + joined(accessors_) + "]";
    }
    if (!body.empty()) out += "," + body;
    return out + "}";
  }

  // A GLB of the JSON (buffer 0 in the binary chunk).
  std::vector<uint8_t> glb(const std::string& body) const {
    std::string text = json(body, "GLB");
    while (text.size() % 4 != 0) text += ' ';
    std::vector<uint8_t> bin = bytes_;
    while (bin.size() % 4 != 0) bin.push_back(0);
    std::vector<uint8_t> out;
    auto u32 = [&](uint32_t v) { appendValues(out, std::vector<uint32_t>{v}); };
    const size_t total = 12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size());
    u32(0x46546C67);
    u32(2);
    u32(static_cast<uint32_t>(total));
    u32(static_cast<uint32_t>(text.size()));
    u32(0x4E4F534A);
    out.insert(out.end(), text.begin(), text.end());
    if (!bin.empty()) {
      u32(static_cast<uint32_t>(bin.size()));
      u32(0x004E4942);
      out.insert(out.end(), bin.begin(), bin.end());
    }
    return out;
  }

  const std::vector<uint8_t>& bytes() const { return bytes_; }

 private:
  static std::string joined(const std::vector<std::string>& parts) {
    std::string out;
    for (const std::string& part : parts) out += (out.empty() ? "" : ",") + part;
    return out;
  }

  std::vector<uint8_t> bytes_;
  std::vector<std::string> views_;
  std::vector<std::string> accessors_;
};

class GltfFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::makeTestFolder("tessera_io_gltf");
    fs::create_directories(root_ / "model");
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path at(const std::string& relative) const { return root_ / "model" / relative; }
  fs::path write(const fs::path& path, const std::string& bytes) const {
    return test::writeFile(path, bytes);
  }
  fs::path write(const fs::path& path, const std::vector<uint8_t>& bytes) const {
    return write(path, std::string(bytes.begin(), bytes.end()));
  }
  Expected<Model> loadJson(const std::string& json, const std::string& name = "model.gltf") {
    return loadGltf(write(at(name), json));
  }
  Expected<Model> loadJson(const std::string& json, const LoadBudget& budget) {
    return loadGltf(write(at("model.gltf"), json), budget);
  }
  // A budget no count in these tests reaches, to test the checks behind it.
  static LoadBudget unlimited() {
    LoadBudget budget;
    budget.max_triangles = uint64_t{1} << 40;
    return budget;
  }

  fs::path root_;
};

// A PNG of `width` x `height` RGBA texels (row 0 at the top), each RGBA as 0xAABBGGRR.
std::vector<uint8_t> pngBytes(int width, int height, const std::vector<uint32_t>& texels) {
  std::vector<unsigned char> rgba;
  for (uint32_t t : texels)
    for (int shift = 0; shift < 32; shift += 8) rgba.push_back((t >> shift) & 0xff);
  int length = 0;
  unsigned char* png = stbi_write_png_to_mem(rgba.data(), width * 4, width, height, 4, &length);
  std::vector<uint8_t> out(png, png + length);
  STBIW_FREE(png);
  return out;
}

std::array<float3, 3> trianglePositions(const Mesh& mesh, size_t t) {
  return {mesh.positions[mesh.indices[3 * t]], mesh.positions[mesh.indices[3 * t + 1]],
          mesh.positions[mesh.indices[3 * t + 2]]};
}

void expectNear3(float3 actual, float3 expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// The unnormalized geometric normal of triangle t (counter-clockwise is front).
float3 faceNormal(const Mesh& mesh, size_t t) {
  std::array<float3, 3> p = trianglePositions(mesh, t);
  return cross(p[1] - p[0], p[2] - p[0]);
}

bool anyWarningContains(const Model& model, const std::string& text) {
  for (const std::string& warning : model.warnings)
    if (warning.find(text) != std::string::npos) return true;
  return false;
}

std::string allWarnings(const Model& model) {
  std::string out;
  for (const std::string& warning : model.warnings) out += warning + "\n";
  return out;
}

void expectErrorContains(const Expected<Model>& model, const std::string& text) {
  ASSERT_FALSE(model) << "loaded, with warnings:\n" << allWarnings(*model);
  EXPECT_NE(model.error().message.find(text), std::string::npos) << model.error().message;
}

// One triangle in z = 0, counter-clockwise from +z, with +z normals.
const std::vector<float3> kTriangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};

std::string oneMesh(int positions, const std::string& extra_attributes = "",
                    const std::string& primitive_extra = "") {
  return "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(positions) +
         extra_attributes + "}" + primitive_extra + "}]}]";
}

const std::string kOneNodeScene = "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}]";

// ---- Geometry and order ----

TEST_F(GltfFiles, LoadsAnIndexedTriangleWithItsNormals) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  const int n = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1}, kFloat, "VEC3", 3);
  const int i = b.indices({0, 1, 2});
  Expected<Model> model = loadJson(
      b.json(kOneNodeScene + "," +
             oneMesh(p, ",\"NORMAL\":" + std::to_string(n), ",\"indices\":" + std::to_string(i))));
  ASSERT_TRUE(model) << model.error().message;
  const Mesh& mesh = io::flattenedMesh(*model);
  ASSERT_EQ(mesh.triangleCount(), 1u);
  for (size_t c = 0; c < 3; ++c) expectNear3(trianglePositions(mesh, 0)[c], kTriangle[c]);
  ASSERT_EQ(mesh.normals.size(), 3u);
  for (const float3& normal : mesh.normals) expectNear3(normal, {0, 0, 1});
  EXPECT_TRUE(mesh.uvs.empty());
  EXPECT_TRUE(mesh.colors.empty());
  ASSERT_EQ(model->materials.size(), 1u);
  EXPECT_EQ(model->cull_back_faces, std::optional<bool>(true));
  EXPECT_TRUE(model->warnings.empty()) << allWarnings(*model);
}

TEST_F(GltfFiles, NodesAreFlattenedDepthFirstWithComposedTransforms) {
  // Four meshes, each one triangle, told apart by z. Node 0 (mesh 0) has children 1 and 3;
  // node 1 (mesh 1) has child 2 (mesh 2); node 3 has mesh 3. Order: 0, 1, 2, 3.
  GltfBuilder b;
  std::string meshes = "\"meshes\":[";
  for (int m = 0; m < 4; ++m) {
    std::vector<float3> points = kTriangle;
    for (float3& q : points) q.z = static_cast<float>(m);
    meshes += std::string(m ? "," : "") + "{\"primitives\":[{\"attributes\":{\"POSITION\":" +
              std::to_string(b.positions(points)) + "}}]}";
  }
  meshes += "]";
  const std::string nodes =
      "\"nodes\":["
      "{\"mesh\":0,\"children\":[1,3],\"translation\":[10,0,0]},"
      "{\"mesh\":1,\"children\":[2],\"scale\":[2,2,2]},"
      "{\"mesh\":2,\"rotation\":[0,0,0.7071067811865476,0.7071067811865476]},"
      "{\"mesh\":3,\"matrix\":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,5,0,1]}]";
  Expected<Model> model =
      loadJson(b.json("\"scene\":0,\"scenes\":[{\"nodes\":[0]}]," + nodes + "," + meshes));
  ASSERT_TRUE(model) << model.error().message;
  const Mesh& mesh = io::flattenedMesh(*model);
  ASSERT_EQ(mesh.triangleCount(), 4u);
  // Mesh 0: translated by 10.
  expectNear3(trianglePositions(mesh, 0)[1], {11, 0, 0});
  // Mesh 1: scaled by 2, then translated: (1,0,1) -> (12,0,2).
  expectNear3(trianglePositions(mesh, 1)[1], {12, 0, 2});
  // Mesh 2: rotated 90 degrees about z, scaled, translated: (1,0,2) -> (0,1,2) -> (0,2,4) ->
  // (10,2,4).
  expectNear3(trianglePositions(mesh, 2)[1], {10, 2, 4});
  // Mesh 3: the matrix (column-major) moves it up by 5, then the parent by 10: (1,0,3) ->
  // (11,5,3).
  expectNear3(trianglePositions(mesh, 3)[1], {11, 5, 3});
  // Rotation, uniform scale and translation keep generated normals along +z.
  for (const float3& n : mesh.normals) expectNear3(n, {0, 0, 1});
}

TEST_F(GltfFiles, NegativeScaleKeepsFrontFacesFront) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  const int n = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1}, kFloat, "VEC3", 3);
  Expected<Model> model =
      loadJson(b.json("\"scenes\":[{\"nodes\":[0,1]}],\"nodes\":[{\"mesh\":0},"
                      "{\"mesh\":0,\"scale\":[-1,1,1]}]," +
                      oneMesh(p, ",\"NORMAL\":" + std::to_string(n))));
  ASSERT_TRUE(model) << model.error().message;
  const Mesh& mesh = io::flattenedMesh(*model);
  ASSERT_EQ(mesh.triangleCount(), 2u);
  // The mirrored copy lies at negative x and still faces +z: counter-clockwise seen from +z.
  EXPECT_GT(faceNormal(mesh, 0).z, 0.0f);
  EXPECT_GT(faceNormal(mesh, 1).z, 0.0f);
  EXPECT_LT(trianglePositions(mesh, 1)[0].x + trianglePositions(mesh, 1)[1].x +
                trianglePositions(mesh, 1)[2].x,
            0.0f);
  // Its normals, by the inverse transpose, still point the way the face does.
  for (size_t v = 0; v < mesh.vertexCount(); ++v) expectNear3(mesh.normals[v], {0, 0, 1});
}

TEST_F(GltfFiles, NonUniformScaleTransformsNormalsByTheInverseTranspose) {
  // A 45-degree slope x + y = 1 in z, normal (1,1,0)/sqrt 2; scaling x by 2 makes the slope
  // x/2 + y = 1, normal (1,2,0)/sqrt 5.
  GltfBuilder b;
  const int p = b.positions({{1, 0, 0}, {0, 1, 0}, {0, 1, 1}});
  const float h = std::sqrt(0.5f);
  const int n = b.accessor(std::vector<float>{h, h, 0, h, h, 0, h, h, 0}, kFloat, "VEC3", 3);
  Expected<Model> model =
      loadJson(b.json("\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"scale\":[2,1,1]}]," +
                      oneMesh(p, ",\"NORMAL\":" + std::to_string(n))));
  ASSERT_TRUE(model) << model.error().message;
  const float s = 1.0f / std::sqrt(5.0f);
  for (const float3& normal : io::flattenedMesh(*model).normals) expectNear3(normal, {s, 2 * s, 0});
}

TEST_F(GltfFiles, StripsAlternateWindingAndFansShareTheFirstVertex) {
  GltfBuilder b;
  // A strip over a zig-zag of 5 points and a fan over a square: all counter-clockwise from +z.
  const std::vector<float3> strip = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}};
  const std::vector<float3> fan = {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int sp = b.positions(strip);
  const int fp = b.positions(fan);
  const int fi = b.indices({0, 1, 2, 3});
  Expected<Model> model = loadJson(b.json(
      kOneNodeScene + ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
      std::to_string(sp) + "},\"mode\":5},{\"attributes\":{\"POSITION\":" + std::to_string(fp) +
      "},\"indices\":" + std::to_string(fi) + ",\"mode\":6}]}]"));
  ASSERT_TRUE(model) << model.error().message;
  const Mesh& mesh = io::flattenedMesh(*model);
  ASSERT_EQ(mesh.triangleCount(), 5u);  // 3 from the strip, 2 from the fan
  const std::array<std::array<int, 3>, 3> strip_order = {{{0, 1, 2}, {1, 3, 2}, {2, 3, 4}}};
  for (size_t t = 0; t < 3; ++t) {
    // Triangle 1 is (v1, v3, v2) up to rotation: glTF lists it as (v1, v3, v2).
    std::array<float3, 3> p = trianglePositions(mesh, t);
    for (size_t c = 0; c < 3; ++c) expectNear3(p[c], strip[static_cast<size_t>(strip_order[t][c])]);
    EXPECT_GT(faceNormal(mesh, t).z, 0.0f) << "strip triangle " << t;
  }
  const std::array<std::array<int, 3>, 2> fan_order = {{{0, 1, 2}, {0, 2, 3}}};
  for (size_t t = 0; t < 2; ++t) {
    std::array<float3, 3> p = trianglePositions(mesh, 3 + t);
    for (size_t c = 0; c < 3; ++c) expectNear3(p[c], fan[static_cast<size_t>(fan_order[t][c])]);
    EXPECT_GT(faceNormal(mesh, 3 + t).z, 0.0f) << "fan triangle " << t;
  }
}

TEST_F(GltfFiles, NonIndexedTrianglesUseVerticesInOrder) {
  GltfBuilder b;
  std::vector<float3> points = kTriangle;
  for (float3 q : kTriangle) points.push_back(q + float3{0, 0, 1});
  Expected<Model> model = loadJson(b.json(kOneNodeScene + "," + oneMesh(b.positions(points))));
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_EQ(io::flattenedMesh(*model).triangleCount(), 2u);
  expectNear3(trianglePositions(io::flattenedMesh(*model), 1)[2], {0, 1, 1});
  // Generated normals of the flat triangles face +z.
  for (const float3& n : io::flattenedMesh(*model).normals) expectNear3(n, {0, 0, 1});
}

TEST_F(GltfFiles, PointsAndLinesAreSkippedWithAWarning) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  Expected<Model> model = loadJson(b.json(
      kOneNodeScene + ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
      std::to_string(p) + "},\"mode\":0},{\"attributes\":{\"POSITION\":" + std::to_string(p) +
      "},\"mode\":1},{\"attributes\":{\"POSITION\":" + std::to_string(p) + "}}]}]"));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(io::flattenedMesh(*model).triangleCount(), 1u);
  EXPECT_TRUE(anyWarningContains(*model, "1 primitive(s) of points skipped"))
      << allWarnings(*model);
  EXPECT_TRUE(anyWarningContains(*model, "1 primitive(s) of lines skipped")) << allWarnings(*model);
}

TEST_F(GltfFiles, OnlyPointsIsAnError) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  expectErrorContains(loadJson(b.json(kOneNodeScene + "," + oneMesh(p, "", ",\"mode\":0"))),
                      "no triangles in the scene (only points or lines");
}

TEST_F(GltfFiles, DefaultSceneIsTheOneDrawn) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  Expected<Model> model = loadJson(
      b.json("\"scene\":1,\"scenes\":[{\"nodes\":[0]},{\"nodes\":[1]}],\"nodes\":[{\"mesh\":0},"
             "{\"mesh\":0,\"translation\":[0,0,7]}]," +
             oneMesh(p)));
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_EQ(io::flattenedMesh(*model).triangleCount(), 1u);
  EXPECT_FLOAT_EQ(io::flattenedMesh(*model).positions[0].z, 7.0f);
}

TEST_F(GltfFiles, WithoutScenesEveryRootNodeIsDrawn) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  // Node 1 is node 2's child: the roots are 0 and 2, drawn as 0, 2, 1.
  Expected<Model> model =
      loadJson(b.json("\"nodes\":[{\"mesh\":0},{\"mesh\":0,\"translation\":[0,0,1]},"
                      "{\"mesh\":0,\"translation\":[0,0,2],\"children\":[1]}]," +
                      oneMesh(p)));
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_EQ(io::flattenedMesh(*model).triangleCount(), 3u);
  EXPECT_FLOAT_EQ(trianglePositions(io::flattenedMesh(*model), 0)[0].z, 0.0f);
  EXPECT_FLOAT_EQ(trianglePositions(io::flattenedMesh(*model), 1)[0].z, 2.0f);
  EXPECT_FLOAT_EQ(trianglePositions(io::flattenedMesh(*model), 2)[0].z, 3.0f);
}

TEST_F(GltfFiles, CountsTrianglesWithNonFinitePositions) {
  GltfBuilder b;
  std::vector<float3> points = kTriangle;
  for (float3 q : kTriangle) points.push_back(q);
  points[4].y = std::numeric_limits<float>::infinity();
  Expected<Model> model = loadJson(b.json(kOneNodeScene + "," + oneMesh(b.positions(points))));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(io::flattenedMesh(*model).triangleCount(), 2u);
  EXPECT_EQ(model->nonfinite_triangles, 1u);
  EXPECT_TRUE(anyWarningContains(*model, "NaN or infinite")) << allWarnings(*model);
}

// ---- Attributes and materials ----

TEST_F(GltfFiles, VertexColoursFromNormalizedBytesAndFloats) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  const int bytes = b.accessor(std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 51, 0},
                               kByte, "VEC4", 3, ",\"normalized\":true");
  const int floats =
      b.accessor(std::vector<float>{0.25f, 0.5f, 0.75f, 0, 0, 0, 1, 1, 1}, kFloat, "VEC3", 3);
  Expected<Model> model =
      loadJson(b.json(kOneNodeScene + ",\"meshes\":[{\"primitives\":[" +
                      "{\"attributes\":{\"POSITION\":" + std::to_string(p) +
                      ",\"COLOR_0\":" + std::to_string(bytes) + "}}," +
                      "{\"attributes\":{\"POSITION\":" + std::to_string(p) +
                      ",\"COLOR_0\":" + std::to_string(floats) + "}}," +
                      "{\"attributes\":{\"POSITION\":" + std::to_string(p) + "}}]}]"));
  ASSERT_TRUE(model) << model.error().message;
  const std::vector<float4>& colors = io::flattenedMesh(*model).colors;
  ASSERT_EQ(colors.size(), 9u);
  EXPECT_TRUE(colors[0] == (float4{1, 0, 0, 1}));
  EXPECT_NEAR(colors[1].w, 128 / 255.0f, 1e-6f);
  EXPECT_NEAR(colors[2].z, 0.2f, 1e-6f);
  EXPECT_TRUE(colors[3] == (float4{0.25f, 0.5f, 0.75f, 1}));
  EXPECT_TRUE(colors[8] == (float4{1, 1, 1, 1})) << "no COLOR_0: white";
}

TEST_F(GltfFiles, ColourOfAnUnusableTypeIsIgnoredWithAWarning) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  const int bad = b.accessor(std::vector<float>{1, 1, 1, 1, 1, 1}, kFloat, "VEC2", 3);
  Expected<Model> model =
      loadJson(b.json(kOneNodeScene + "," + oneMesh(p, ",\"COLOR_0\":" + std::to_string(bad))));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_TRUE(io::flattenedMesh(*model).colors.empty());
  EXPECT_TRUE(anyWarningContains(*model, "COLOR_0 is ignored")) << allWarnings(*model);
}

TEST_F(GltfFiles, BaseColorFactorAndDoubleSidedAreReadPerMaterial) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  const std::string primitive = "{\"attributes\":{\"POSITION\":" + std::to_string(p) + "}";
  Expected<Model> model = loadJson(
      b.json(kOneNodeScene + ",\"meshes\":[{\"primitives\":[" + primitive + ",\"material\":1}," +
             primitive + ",\"material\":0}," + primitive + ",\"material\":1}]}]," +
             "\"materials\":[{\"doubleSided\":true},"
             "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.25,2,0.5]}}]"));
  ASSERT_TRUE(model) << model.error().message;
  // First-use order: glTF material 1, then 0.
  ASSERT_EQ(model->materials.size(), 2u);
  EXPECT_TRUE(model->materials[0].base_color == (float4{0.5f, 0.25f, 1.0f, 0.5f}));
  EXPECT_FALSE(model->materials[0].double_sided);
  EXPECT_TRUE(model->materials[1].base_color == (float4{1, 1, 1, 1}));
  EXPECT_TRUE(model->materials[1].double_sided);
  EXPECT_EQ(io::flattenedMesh(*model).triangle_materials, (std::vector<uint16_t>{0, 1, 0}));
  EXPECT_EQ(model->cull_back_faces, std::optional<bool>(false));
  EXPECT_TRUE(anyWarningContains(*model, "some materials are double-sided")) << allWarnings(*model);
}

TEST_F(GltfFiles, BaseColorTextureIsDecodedAsSrgbWithItsSamplerAndVFlipped) {
  // 2x2: top row red, bottom row blue (row 0 is the top of the image).
  const uint32_t red = 0xff0000ff, blue = 0xffff0000;
  const std::vector<uint8_t> png = pngBytes(2, 2, {red, red, blue, blue});
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  // glTF (0.25, 0.25) is in the top-left texel: red.
  const int uv =
      b.accessor(std::vector<float>{0.25f, 0.25f, 0.25f, 0.75f, 0.75f, 0.25f}, kFloat, "VEC2", 3);
  Expected<Model> model = loadJson(b.json(
      kOneNodeScene + "," + oneMesh(p, ",\"TEXCOORD_0\":" + std::to_string(uv), ",\"material\":0") +
      ",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}]"
      ",\"textures\":[{\"source\":0,\"sampler\":0}]"
      ",\"samplers\":[{\"magFilter\":9728,\"minFilter\":9729,\"wrapS\":33071,\"wrapT\":33071}]"
      ",\"images\":[{\"uri\":\"data:image/png;base64," +
      base64(png) + "\"}]"));
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_EQ(model->materials.size(), 1u);
  const Material& material = model->materials[0];
  ASSERT_TRUE(material.albedo);
  EXPECT_TRUE(material.albedo->srgb);
  EXPECT_EQ(material.sampler.filter, TextureFilter::kNearest);
  EXPECT_EQ(material.sampler.wrap, TextureWrap::kClamp);
  const std::vector<float2>& uvs = io::flattenedMesh(*model).uvs;
  ASSERT_EQ(uvs.size(), 3u);
  EXPECT_FLOAT_EQ(uvs[0].x, 0.25f);
  EXPECT_FLOAT_EQ(uvs[0].y, 0.75f);
  const float4 top = material.albedo->sample(uvs[0], material.sampler);
  EXPECT_TRUE(top == (float4{1, 0, 0, 1})) << top.x << " " << top.y << " " << top.z;
  const float4 bottom = material.albedo->sample(uvs[1], material.sampler);
  EXPECT_TRUE(bottom == (float4{0, 0, 1, 1})) << bottom.x << " " << bottom.y << " " << bottom.z;
  EXPECT_TRUE(model->warnings.empty()) << allWarnings(*model);
}

TEST_F(GltfFiles, MirroredRepeatIsDrawnAsRepeatWithAWarningAndLinearIsBilinear) {
  const std::vector<uint8_t> png = pngBytes(1, 1, {0xff808080});
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  const int uv = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, kFloat, "VEC2", 3);
  Expected<Model> model = loadJson(b.json(
      kOneNodeScene + "," + oneMesh(p, ",\"TEXCOORD_0\":" + std::to_string(uv), ",\"material\":0") +
      ",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}]"
      ",\"textures\":[{\"source\":0,\"sampler\":0}]"
      ",\"samplers\":[{\"magFilter\":9729,\"wrapS\":33648,\"wrapT\":33648}]"
      ",\"images\":[{\"uri\":\"data:image/png;base64," +
      base64(png) + "\"}]"));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(model->materials[0].sampler.wrap, TextureWrap::kRepeat);
  EXPECT_EQ(model->materials[0].sampler.filter, TextureFilter::kBilinear);
  EXPECT_TRUE(anyWarningContains(*model, "MIRRORED_REPEAT is drawn as REPEAT"))
      << allWarnings(*model);
}

TEST_F(GltfFiles, ImageInAnExternalFileBeneathTheFolderIsLoaded) {
  write(at("textures/wall.png"), pngBytes(1, 1, {0xff00ff00}));
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  const int uv = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, kFloat, "VEC2", 3);
  Expected<Model> model = loadJson(b.json(
      kOneNodeScene + "," + oneMesh(p, ",\"TEXCOORD_0\":" + std::to_string(uv), ",\"material\":0") +
      ",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}]"
      ",\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"textures/wall%2Epng\"}]"));
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_TRUE(model->materials[0].albedo);
  EXPECT_EQ(model->materials[0].albedo->texels[0], 0xff00ff00u);
}

TEST_F(GltfFiles, ImageOutsideTheFolderIsRefusedWithAWarning) {
  write(root_ / "secret.png", pngBytes(1, 1, {0xff00ff00}));
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  Expected<Model> model = loadJson(
      b.json(kOneNodeScene + "," + oneMesh(p, "", ",\"material\":0") +
             ",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}]"
             ",\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"../secret.png\"}]"));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_FALSE(model->materials[0].albedo);
  EXPECT_TRUE(anyWarningContains(*model,
                                 "'../secret.png' refused: it leads out of the model's "
                                 "folder"))
      << allWarnings(*model);
}

TEST_F(GltfFiles, SparseAccessorOverwritesTheListedElements) {
  GltfBuilder b;
  const int base = b.bufferView(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int sparse_indices = b.bufferView(std::vector<uint8_t>{2, 0, 0, 0});
  const int sparse_values = b.bufferView(std::vector<float>{0, 3, 0});
  const int p = b.rawAccessor("{\"bufferView\":" + std::to_string(base) +
                              ",\"componentType\":5126,\"type\":\"VEC3\",\"count\":3,"
                              "\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":" +
                              std::to_string(sparse_indices) +
                              ",\"componentType\":5121},\"values\":{\"bufferView\":" +
                              std::to_string(sparse_values) + "}}}");
  Expected<Model> model = loadJson(b.json(kOneNodeScene + "," + oneMesh(p)));
  ASSERT_TRUE(model) << model.error().message;
  expectNear3(trianglePositions(io::flattenedMesh(*model), 0)[1], {1, 0, 0});
  expectNear3(trianglePositions(io::flattenedMesh(*model), 0)[2], {0, 3, 0});
}

TEST_F(GltfFiles, SparseIndexPastTheCountIsAnError) {
  GltfBuilder b;
  const int base = b.bufferView(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int sparse_indices = b.bufferView(std::vector<uint8_t>{7, 0, 0, 0});
  const int sparse_values = b.bufferView(std::vector<float>{0, 3, 0});
  const int p = b.rawAccessor("{\"bufferView\":" + std::to_string(base) +
                              ",\"componentType\":5126,\"type\":\"VEC3\",\"count\":3,"
                              "\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":" +
                              std::to_string(sparse_indices) +
                              ",\"componentType\":5121},\"values\":{\"bufferView\":" +
                              std::to_string(sparse_values) + "}}}");
  expectErrorContains(loadJson(b.json(kOneNodeScene + "," + oneMesh(p))),
                      "sparse index 7 is past the accessor's 3 elements");
}

// ---- Files and containers ----

TEST_F(GltfFiles, GlbWithABinaryChunkAndAnImageInABufferView) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  const int uv = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, kFloat, "VEC2", 3);
  const int image_view = b.bufferView(pngBytes(1, 1, {0xff0000ff}));
  const std::vector<uint8_t> glb = b.glb(
      kOneNodeScene + "," + oneMesh(p, ",\"TEXCOORD_0\":" + std::to_string(uv), ",\"material\":0") +
      ",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}]"
      ",\"textures\":[{\"source\":0}],\"images\":[{\"bufferView\":" +
      std::to_string(image_view) + ",\"mimeType\":\"image/png\"}]");
  Expected<Model> model = loadGltf(write(at("model.glb"), glb));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(io::flattenedMesh(*model).triangleCount(), 1u);
  ASSERT_TRUE(model->materials[0].albedo);
  EXPECT_EQ(model->materials[0].albedo->texels[0], 0xff0000ffu);

  Expected<Model> from_memory = loadGltfFromMemory(glb, "memory.glb");
  ASSERT_TRUE(from_memory) << from_memory.error().message;
  EXPECT_EQ(io::flattenedMesh(*from_memory).triangleCount(), 1u);
}

TEST_F(GltfFiles, TruncatedGlbIsAnError) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  std::vector<uint8_t> glb = b.glb(kOneNodeScene + "," + oneMesh(p));
  const size_t full = glb.size();
  glb.resize(full - 5);
  expectErrorContains(loadGltf(write(at("cut.glb"), glb)),
                      "cut.glb: truncated GLB: the header says " + std::to_string(full) +
                          " bytes, the file has " + std::to_string(full - 5));
  glb.resize(9);
  expectErrorContains(loadGltf(write(at("stub.glb"), glb)), "stub.glb: truncated GLB");
}

TEST_F(GltfFiles, GlbWhoseBinaryChunkOverrunsTheFileIsAnError) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  std::vector<uint8_t> glb = b.glb(kOneNodeScene + "," + oneMesh(p));
  // The BIN chunk's length claims 8 bytes more than the file holds: exactly what the chunk
  // header's size would hide if it were not counted.
  const uint32_t json_length = [&] {
    uint32_t v;
    std::memcpy(&v, glb.data() + 12, 4);
    return v;
  }();
  const size_t bin_header = 20 + json_length;
  uint32_t bin_length;
  std::memcpy(&bin_length, glb.data() + bin_header, 4);
  bin_length += 8;
  std::memcpy(glb.data() + bin_header, &bin_length, 4);
  expectErrorContains(loadGltf(write(at("over.glb"), glb)),
                      "truncated GLB: the binary chunk claims");
}

TEST_F(GltfFiles, ExternalBufferBeneathTheFolderIsRead) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  write(at("data/triangle.bin"), b.bytes());
  Expected<Model> model =
      loadJson(b.json(kOneNodeScene + "," + oneMesh(p), "data/triangle.bin"), "model.gltf");
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(io::flattenedMesh(*model).triangleCount(), 1u);
}

TEST_F(GltfFiles, BufferOutsideTheFolderIsRefused) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  write(root_ / "outside.bin", b.bytes());
  expectErrorContains(loadJson(b.json(kOneNodeScene + "," + oneMesh(p), "../outside.bin")),
                      "'../outside.bin' refused: it leads out of the model's folder");
  expectErrorContains(
      loadJson(b.json(kOneNodeScene + "," + oneMesh(p), (root_ / "outside.bin").string())),
      "it is an absolute path");
  expectErrorContains(
      loadJson(b.json(kOneNodeScene + "," + oneMesh(p), "https://example.com/outside.bin")),
      "it is a URI");
}

TEST_F(GltfFiles, ExternalBufferOfAModelInMemoryIsRefused) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  const std::string json = b.json(kOneNodeScene + "," + oneMesh(p), "triangle.bin");
  expectErrorContains(
      loadGltfFromMemory(std::span(reinterpret_cast<const uint8_t*>(json.data()), json.size()),
                         "memory.gltf"),
      "'triangle.bin' is an external file, and this model was given in memory");
}

TEST_F(GltfFiles, MissingExternalBufferIsAnError) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  expectErrorContains(loadJson(b.json(kOneNodeScene + "," + oneMesh(p), "absent.bin")),
                      "absent.bin: no such file");
}

TEST_F(GltfFiles, LoadModelPicksGltfAndGlbByExtensionInAnyCase) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  Expected<Model> json = loadModel(write(at("A.GLTF"), b.json(kOneNodeScene + "," + oneMesh(p))));
  ASSERT_TRUE(json) << json.error().message;
  Expected<Model> glb = loadModel(write(at("B.Glb"), b.glb(kOneNodeScene + "," + oneMesh(p))));
  ASSERT_TRUE(glb) << glb.error().message;
  EXPECT_EQ(io::flattenedMesh(*json).triangleCount(), 1u);
  EXPECT_EQ(io::flattenedMesh(*glb).triangleCount(), 1u);
}

// ---- The scene graph: cameras and depth ----

// A glTF camera object of `type` with the given fields.
std::string cameraJson(const std::string& type, const std::string& fields) {
  return "{\"type\":\"" + type + "\",\"" + type + "\":{" + fields + "}}";
}

TEST_F(GltfFiles, CamerasAreReadAndPlacedByTheNodesThatHoldThem) {
  // Camera 0 (perspective) on a root node at z = 5; camera 1 (orthographic) on a child at
  // (0, 2, 0) of a node at (1, 0, 0), turned a quarter about +y (so it looks down -x).
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  const std::string cameras =
      "\"cameras\":[" + cameraJson("perspective", "\"yfov\":0.5,\"znear\":0.25,\"zfar\":50") + "," +
      cameraJson("orthographic", "\"xmag\":3,\"ymag\":2,\"znear\":0,\"zfar\":10") + "]";
  const std::string nodes =
      "\"nodes\":[{\"mesh\":0},{\"camera\":0,\"translation\":[0,0,5]},"
      "{\"translation\":[1,0,0],\"children\":[3]},"
      "{\"camera\":1,\"translation\":[0,2,0],"
      "\"rotation\":[0,0.7071067811865476,0,0.7071067811865476]}]";
  Expected<Model> model = loadJson(
      b.json("\"scenes\":[{\"nodes\":[0,1,2]}]," + nodes + "," + cameras + "," + oneMesh(p)));
  ASSERT_TRUE(model) << model.error().message;
  SceneGraph graph = model->graph;
  ASSERT_EQ(graph.cameras.size(), 2u);
  EXPECT_FALSE(graph.cameras[0].orthographic);
  EXPECT_FLOAT_EQ(graph.cameras[0].yfov_radians, 0.5f);
  EXPECT_FLOAT_EQ(graph.cameras[0].znear, 0.25f);
  EXPECT_FLOAT_EQ(graph.cameras[0].zfar, 50.0f);
  EXPECT_TRUE(graph.cameras[1].orthographic);
  EXPECT_FLOAT_EQ(graph.cameras[1].ymag, 2.0f);
  graph.updateWorld();
  Expected<Camera> first = graph.camera(0, 1.0f, graph.bounds());
  ASSERT_TRUE(first) << first.error().message;
  expectNear3(first->position, {0, 0, 5});
  expectNear3(first->target - first->position, {0, 0, -1});
  EXPECT_NEAR(first->fov_y_degrees, 0.5f * 180.0f / 3.14159265f, 1e-4f);
  EXPECT_FALSE(first->orthographic);
  Expected<Camera> second = graph.camera(1, 1.0f, graph.bounds());
  ASSERT_TRUE(second) << second.error().message;
  expectNear3(second->position, {1, 2, 0});
  // A quarter turn about +y takes the view direction -z to -x, and keeps +y up.
  expectNear3(second->target - second->position, {-1, 0, 0});
  expectNear3(second->up, {0, 1, 0});
  EXPECT_TRUE(second->orthographic);
  EXPECT_FLOAT_EQ(second->ortho_half_height, 2.0f);
  // Past the end: the message counts the cameras.
  Expected<Camera> third = graph.camera(2, 1.0f, graph.bounds());
  ASSERT_FALSE(third);
  EXPECT_NE(third.error().message.find("has 2 cameras"), std::string::npos)
      << third.error().message;
}

TEST_F(GltfFiles, CameraWithAZeroOrNegativeFieldIsSkippedWithAWarning) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  const std::string cameras =
      "\"cameras\":[" + cameraJson("perspective", "\"yfov\":0,\"znear\":0.1") + "," +
      cameraJson("orthographic", "\"xmag\":1,\"ymag\":-2,\"znear\":0,\"zfar\":10") + "," +
      cameraJson("perspective", "\"yfov\":0.7,\"znear\":0.1") + "]";
  Expected<Model> model =
      loadJson(b.json("\"scenes\":[{\"nodes\":[0,1]}],\"nodes\":[{\"mesh\":0},{\"camera\":2}]," +
                      cameras + "," + oneMesh(p)));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_TRUE(anyWarningContains(*model, "camera 0 has yfov")) << allWarnings(*model);
  EXPECT_TRUE(anyWarningContains(*model, "camera 1 has ymag")) << allWarnings(*model);
  // The skipped cameras keep their indices: camera 2 is the file's camera 2.
  SceneGraph graph = model->graph;
  ASSERT_EQ(graph.cameras.size(), 3u);
  graph.updateWorld();
  Expected<Camera> skipped = graph.camera(0, 1.0f, graph.bounds());
  ASSERT_FALSE(skipped);
  EXPECT_NE(skipped.error().message.find("camera 0 was skipped: it has yfov"), std::string::npos)
      << skipped.error().message;
  EXPECT_FALSE(graph.camera(1, 1.0f, graph.bounds()));
  Expected<Camera> usable = graph.camera(2, 1.0f, graph.bounds());
  ASSERT_TRUE(usable) << usable.error().message;
  EXPECT_NEAR(usable->fov_y_degrees, 0.7f * 180.0f / 3.14159265f, 1e-4f);
  EXPECT_EQ(io::flattenedMesh(*model).triangleCount(), 1u);  // the rest of the file is drawn
}

TEST_F(GltfFiles, HierarchyAHundredThousandDeepLoadsWithoutRecursion) {
  // A chain of 100,000 nodes, each 0.001 along x from its parent, the mesh on the last: a
  // recursive walk would overflow the stack long before.
  constexpr int kDepth = 100000;
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  std::string nodes = "\"nodes\":[";
  for (int i = 0; i < kDepth; ++i) {
    nodes += i ? "," : "";
    nodes += i + 1 < kDepth
                 ? "{\"translation\":[0.001,0,0],\"children\":[" + std::to_string(i + 1) + "]}"
                 : "{\"translation\":[0.001,0,0],\"mesh\":0}";
  }
  nodes += "]";
  Expected<Model> model =
      loadJson(b.json("\"scenes\":[{\"nodes\":[0]}]," + nodes + "," + oneMesh(p)));
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_EQ(model->graph.nodes.size(), static_cast<size_t>(kDepth));
  const Mesh mesh = io::flattenedMesh(*model);
  ASSERT_EQ(mesh.triangleCount(), 1u);
  // 100,000 float additions of 0.001 drift from 100 by far less than 0.1.
  EXPECT_NEAR(trianglePositions(mesh, 0)[0].x, 100.0f, 0.1f);
}

// ---- Hostile files ----

TEST_F(GltfFiles, NodeThatIsItsOwnAncestorIsAnError) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  expectErrorContains(
      loadJson(b.json("\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"children\":[1]},"
                      "{\"children\":[2]},{\"children\":[1]}]," +
                      oneMesh(p))),
      "model.gltf: node 1 is its own ancestor");
  expectErrorContains(
      loadJson(b.json("\"nodes\":[{\"mesh\":0,\"children\":[0]}]," + oneMesh(p)), "self.gltf"),
      "self.gltf: node 0 is its own child");
}

TEST_F(GltfFiles, NodeWithTwoParentsIsAnError) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  expectErrorContains(
      loadJson(b.json("\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"children\":[1,2]},"
                      "{\"children\":[3]},{\"children\":[3]},{\"mesh\":0}]," +
                      oneMesh(p))),
      "node 3 is a child of node 1 and of node 2");
}

TEST_F(GltfFiles, ChildIndexPastTheNodesIsAnError) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  expectErrorContains(
      loadJson(b.json("\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"children\":[5]}]," +
                      oneMesh(p))),
      "node 0 lists child 5, but the file has 1 nodes");
}

TEST_F(GltfFiles, AccessorReadingPastItsBufferViewIsAnError) {
  GltfBuilder b;
  const int view = b.bufferView(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int p = b.rawAccessor("{\"bufferView\":" + std::to_string(view) +
                              ",\"byteOffset\":4,\"componentType\":5126,\"type\":\"VEC3\","
                              "\"count\":3}");
  expectErrorContains(loadJson(b.json(kOneNodeScene + "," + oneMesh(p))),
                      "model.gltf: accessor 0 (POSITION of mesh 0 primitive 0): 3 elements of "
                      "12 bytes, 12 apart from byte 4, reach past the end of bufferView 0 (36 "
                      "bytes)");
}

TEST_F(GltfFiles, CountClaimingGigabytesIsRefusedBeforeAllocating) {
  GltfBuilder b;
  b.positions(kTriangle);
  const int huge = b.rawAccessor(
      "{\"bufferView\":0,\"componentType\":5126,\"type\":\"VEC3\",\"count\":1000000000}");
  // The triangle budget refuses it first, from the count alone.
  expectErrorContains(loadJson(b.json(kOneNodeScene + "," + oneMesh(huge))),
                      "333333333 triangles (after instancing), over the budget");
  // Past the budget's reach, the range check against the buffer view does.
  expectErrorContains(loadJson(b.json(kOneNodeScene + "," + oneMesh(huge)), unlimited()),
                      "1000000000 elements of 12 bytes");
  // Without a bufferView an accessor is zeros: its count is bounded by the file's size.
  const int zeros =
      b.rawAccessor("{\"componentType\":5126,\"type\":\"VEC3\",\"count\":1000000000}");
  expectErrorContains(loadJson(b.json(kOneNodeScene + "," + oneMesh(zeros)), unlimited()),
                      "more than the file's size can justify");
}

TEST_F(GltfFiles, ByteStrideSmallerThanTheElementIsAnError) {
  GltfBuilder b;
  const int view = b.bufferView(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}, ",\"byteStride\":8");
  const int p = b.rawAccessor("{\"bufferView\":" + std::to_string(view) +
                              ",\"componentType\":5126,\"type\":\"VEC3\",\"count\":3}");
  expectErrorContains(loadJson(b.json(kOneNodeScene + "," + oneMesh(p))),
                      "has byteStride 8, smaller than the 12-byte element");
}

TEST_F(GltfFiles, InterleavedAttributesFollowTheByteStride) {
  GltfBuilder b;
  // Position and normal interleaved, 24 bytes per vertex.
  const int view =
      b.bufferView(std::vector<float>{0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1},
                   ",\"byteStride\":24");
  const int p = b.rawAccessor("{\"bufferView\":" + std::to_string(view) +
                              ",\"componentType\":5126,\"type\":\"VEC3\",\"count\":3}");
  const int n = b.rawAccessor("{\"bufferView\":" + std::to_string(view) +
                              ",\"byteOffset\":12,\"componentType\":5126,\"type\":\"VEC3\","
                              "\"count\":3}");
  Expected<Model> model =
      loadJson(b.json(kOneNodeScene + "," + oneMesh(p, ",\"NORMAL\":" + std::to_string(n))));
  ASSERT_TRUE(model) << model.error().message;
  for (size_t c = 0; c < 3; ++c) expectNear3(trianglePositions(io::flattenedMesh(*model), 0)[c], kTriangle[c]);
  for (const float3& normal : io::flattenedMesh(*model).normals) expectNear3(normal, {0, 0, 1});
}

TEST_F(GltfFiles, IndexPastTheVerticesIsAnError) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  const int i = b.indices({0, 1, 9});
  expectErrorContains(
      loadJson(b.json(kOneNodeScene + "," + oneMesh(p, "", ",\"indices\":" + std::to_string(i)))),
      "model.gltf: mesh 0 primitive 0: index 9 is past the 3 vertices");
}

TEST_F(GltfFiles, FloatIndicesAreAnError) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  const int i = b.accessor(std::vector<float>{0, 1, 2}, kFloat, "SCALAR", 3);
  expectErrorContains(
      loadJson(b.json(kOneNodeScene + "," + oneMesh(p, "", ",\"indices\":" + std::to_string(i)))),
      "accessor 1 (indices of mesh 0 primitive 0): component type float is not allowed here");
}

TEST_F(GltfFiles, PositionsThatAreNotVec3AreAnError) {
  GltfBuilder b;
  const int p = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, kFloat, "VEC2", 3);
  expectErrorContains(loadJson(b.json(kOneNodeScene + "," + oneMesh(p))),
                      "has 2 components per element");
}

TEST_F(GltfFiles, ImageBufferViewOutsideItsBufferIsRefusedBeforeParsing) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  const std::string json = b.json(kOneNodeScene + "," + oneMesh(p) +
                                  ",\"images\":[{\"bufferView\":1,\"mimeType\":\"image/png\"}]");
  // Add a second bufferView that runs far past the buffer.
  std::string patched = json;
  const std::string views = "\"bufferViews\":[";
  patched.insert(patched.find(views) + views.size(),
                 "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},"
                 "{\"buffer\":0,\"byteOffset\":30,\"byteLength\":4000000},");
  // The positions accessor referred to view 0, still view 0.
  expectErrorContains(loadJson(patched),
                      "image 0 is stored in bufferView 1 (bytes 30 to 4000030), which lies "
                      "outside buffer 0 (36 bytes)");
}

TEST_F(GltfFiles, DeeplyNestedJsonIsRefused) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  std::string extras = std::string(100000, '[') + std::string(100000, ']');
  expectErrorContains(loadJson(b.json(kOneNodeScene + "," + oneMesh(p) + ",\"extras\":" + extras)),
                      "the JSON nests deeper than 64 levels");
}

TEST_F(GltfFiles, ObjectsWorthGigabytesOfParserStructuresAreRefused) {
  // 3 bytes of text per material, 2 KiB per tinygltf::Material: 1.4 GiB from a 1.8 MB file.
  std::string materials = "\"materials\":[{}";
  for (int i = 1; i < 600000; ++i) materials += ",{}";
  materials += "]";
  expectErrorContains(loadJson("{\"asset\":{\"version\":\"2.0\"}," + materials + "}"),
                      "the JSON describes more objects than tessera parses");
}

TEST_F(GltfFiles, InvalidJsonNamesTheLine) {
  expectErrorContains(loadJson("{\"asset\":{\"version\":\"2.0\"},\n\"nodes\":[{]\n}"),
                      "model.gltf: not valid JSON at line 2, column 11: unexpected ']'");
}

TEST_F(GltfFiles, LibraryMessagesAreInTesserasWords) {
  const std::string asset = "{\"asset\":{\"version\":\"2.0\"},";
  expectErrorContains(loadJson(asset + "\"bufferViews\":[{\"byteLength\":4}]}"),
                      "a BufferView lacks its required property 'buffer'");
  expectErrorContains(loadJson("{\"asset\":{}}"), "the required \"asset\" object is missing");
  expectErrorContains(loadJson("[1,2"), "not valid JSON at line 1, column 5: unexpected end of "
                                        "input; expected ']'");
}

TEST_F(GltfFiles, RequiredExtensionsThatAreNotSupportedAreAnError) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  expectErrorContains(loadJson(b.json(kOneNodeScene + "," + oneMesh(p) +
                                      ",\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],"
                                      "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"]")),
                      "requires the extension KHR_draco_mesh_compression");
}

TEST_F(GltfFiles, MissingFileAndNotGltfAreErrors) {
  expectErrorContains(loadGltf(at("absent.gltf")), "absent.gltf: no such file");
  expectErrorContains(loadJson("[1, 2, 3]"), "not an object");
  expectErrorContains(loadJson("{\"nodes\":[]}"), "model.gltf: not a readable glTF file");
}

// ---- Hostile input, round two (issue 22) ----

TEST_F(GltfFiles, IndicesPast32BitsAreErrorsNamingTheElement) {
  // tinygltf reads these into an int: 2^32 would be node 0, 2^31 a negative count.
  const std::string scene = "\"asset\":{\"version\":\"2.0\"},";
  expectErrorContains(loadJson("{" + scene + "\"nodes\":[{\"mesh\":4294967296}]}"),
                      "model.gltf: nodes[0].mesh is 4294967296, out of range (at most 2147483647)");
  expectErrorContains(loadJson("{" + scene + "\"scenes\":[{\"nodes\":[1,4294967296]}]}"),
                      "scenes[0].nodes[1] is 4294967296");
  expectErrorContains(
      loadJson("{" + scene + "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":-4294967295}}]}]}"),
      "meshes[0].primitives[0].attributes.POSITION is -4294967295, out of range (at least "
      "-2147483648)");
  expectErrorContains(
      loadJson("{" + scene + "\"accessors\":[{\"sparse\":{\"count\":2147483648}}]}"),
      "accessors[0].sparse.count is 2147483648");
  // Numbers tessera does not read as integers may be as large as they like.
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  EXPECT_TRUE(loadJson(b.json(kOneNodeScene + "," + oneMesh(p) +
                              ",\"extras\":{\"mesh\":99999999999}"))
                  .ok());
}

TEST_F(GltfFiles, InstancingOverTheTriangleBudgetIsRefusedBeforeFlattening) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  std::string nodes = "\"scene\":0,\"scenes\":[{\"nodes\":[0,1,2,3]}],\"nodes\":[";
  for (int i = 0; i < 4; ++i) nodes += std::string(i ? "," : "") + "{\"mesh\":0}";
  nodes += "]";
  LoadBudget budget;
  budget.max_triangles = 3;
  expectErrorContains(loadJson(b.json(nodes + "," + oneMesh(p)), budget),
                      "4 triangles (after instancing), over the budget of 3; raise it with "
                      "--max-triangles or --memory-limit");
  budget.max_triangles = 4;
  Expected<Model> model = loadJson(b.json(nodes + "," + oneMesh(p)), budget);
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(io::flattenedMesh(*model).triangleCount(), 4u);
}

TEST_F(GltfFiles, BufferFileThatIsAFifoIsRefusedWithoutBlocking) {
  ASSERT_EQ(::mkfifo(at("b.bin").c_str(), 0600), 0);
  const std::string json =
      "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"uri\":\"b.bin\",\"byteLength\":36}]}";
  expectErrorContains(loadJson(json), "b.bin: is a FIFO, not a regular file");
}

TEST_F(GltfFiles, ShortBufferFileIsReportedInTesserasWords) {
  write(at("c.bin"), std::string(20, '\0'));
  const std::string json =
      "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"uri\":\"c.bin\",\"byteLength\":168}]}";
  Expected<Model> model = loadJson(json);
  expectErrorContains(model, "buffer file 'c.bin' is 20 bytes, but the buffer's byteLength is 168");
  EXPECT_EQ(model.error().message.find("tessera-model-folder"), std::string::npos);
}

TEST_F(GltfFiles, MalformedDataUriIsElidedInTheMessage) {
  const std::string uri = "data:application/octet-stream;base64," + std::string(1 << 20, '!');
  Expected<Model> model = loadJson("{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"uri\":\"" +
                                   uri + "\",\"byteLength\":36}]}");
  ASSERT_FALSE(model.ok());
  EXPECT_LT(model.error().message.size(), 400u) << model.error().message.substr(0, 400);
  EXPECT_NE(model.error().message.find("data:application/octet-stream;base64,!!!!..."),
            std::string::npos)
      << model.error().message.substr(0, 400);
}

}  // namespace
}  // namespace tessera::io
