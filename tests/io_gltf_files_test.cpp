// glTF's containers and files (GLB chunks, external buffers and images beneath the model's folder),
// and files built to break the loader: cycles in the node graph, accessors and buffer views past
// their ends, counts worth gigabytes, hostile JSON, files that are not what they say. Each must
// give a clear error naming the element (or a warning), never a crash, a hang or an allocation
// the budget did not allow.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <tessera/io/model_loader.h>

#include "gltf_test_files.h"

namespace tessera::io {
namespace {

namespace fs = std::filesystem;
using namespace gltf_test;  // NOLINT(google-build-using-namespace): the tests' own helpers

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
  for (size_t c = 0; c < 3; ++c)
    expectNear3(trianglePositions(io::flattenedMesh(*model), 0)[c], kTriangle[c]);
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
  expectErrorContains(loadJson("[1,2"),
                      "not valid JSON at line 1, column 5: unexpected end of "
                      "input; expected ']'");
}

TEST_F(GltfFiles, RequiredExtensionsThatAreNotSupportedAreAnError) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  expectErrorContains(loadJson(b.json(kOneNodeScene + "," + oneMesh(p) +
                                      ",\"extensionsUsed\":[\"EXT_meshopt_compression\"],"
                                      "\"extensionsRequired\":[\"EXT_meshopt_compression\"]")),
                      "requires the extension EXT_meshopt_compression");
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
      loadJson("{" + scene +
               "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":-4294967295}}]}]}"),
      "meshes[0].primitives[0].attributes.POSITION is -4294967295, out of range (at least "
      "-2147483648)");
  expectErrorContains(
      loadJson("{" + scene + "\"accessors\":[{\"sparse\":{\"count\":2147483648}}]}"),
      "accessors[0].sparse.count is 2147483648");
  // Numbers tessera does not read as integers may be as large as they like.
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  EXPECT_TRUE(
      loadJson(b.json(kOneNodeScene + "," + oneMesh(p) + ",\"extras\":{\"mesh\":99999999999}"))
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
