// Draco-compressed glTF (KHR_draco_mesh_compression): every file is built here, its stream
// encoded by libdraco's own encoder from a small mesh, and loaded through tessera's glTF loader.
// In a build without Draco only the refusal is tested.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <tessera/io/model_loader.h>

#include "gltf_test_files.h"

#if TESSERA_HAS_DRACO
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wpedantic"
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#pragma GCC diagnostic pop
#endif

namespace tessera::io {
namespace {

using namespace gltf_test;  // NOLINT(google-build-using-namespace): the tests' own helpers

#if TESSERA_HAS_DRACO

// A unit cube, 12 triangles counter-clockwise from outside, with per-face normals and uvs: the
// uncompressed mesh every test compares with, triangle by triangle.
struct Corner {
  float3 position;
  float3 normal;
  float2 uv;  // glTF's: v = 0 at the top of the image
};
std::vector<std::array<Corner, 3>> cubeTriangles() {
  std::vector<std::array<Corner, 3>> out;
  const float3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {-1.0f, 1.0f}) {
      const float3 n = axes[axis] * sign;
      const float3 u = axes[(axis + 1) % 3], v = axes[(axis + 2) % 3];
      // Corners of the face at +-1 along n, counter-clockwise seen from outside.
      auto at = [&](float a, float b) {
        const float3 p = n + u * a + v * (sign > 0 ? b : -b);
        return Corner{p, n, {(a + 1) / 2, (b + 1) / 2}};
      };
      out.push_back({at(-1, -1), at(1, -1), at(1, 1)});
      out.push_back({at(-1, -1), at(1, 1), at(-1, 1)});
    }
  return out;
}

constexpr float kPositionStep = 2.0f / (1 << 14);  // 14-bit quantization of a 2-unit cube

// The Draco stream of `triangles` and its attribute ids, plus what the decoder makes of it.
struct Encoded {
  std::vector<uint8_t> bytes;
  int position_id = -1, normal_id = -1, uv_id = -1;
  uint32_t points = 0, faces = 0;
  std::vector<std::array<float3, 3>> decoded_faces;  // positions, in the decoder's face order
};

Encoded encode(const std::vector<std::array<Corner, 3>>& triangles) {
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(static_cast<int>(triangles.size()));
  const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int nrm = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
  const int tex = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
  for (size_t f = 0; f < triangles.size(); ++f) {
    const auto& t = triangles[f];
    const draco::FaceIndex face(static_cast<uint32_t>(f));
    builder.SetAttributeValuesForFace(pos, face, &t[0].position, &t[1].position, &t[2].position);
    builder.SetAttributeValuesForFace(nrm, face, &t[0].normal, &t[1].normal, &t[2].normal);
    builder.SetAttributeValuesForFace(tex, face, &t[0].uv, &t[1].uv, &t[2].uv);
  }
  std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  EXPECT_NE(mesh, nullptr);
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(*mesh, &buffer);
  EXPECT_TRUE(status.ok()) << status.error_msg_string();
  Encoded out;
  out.bytes.assign(buffer.data(), buffer.data() + buffer.size());
  out.position_id = static_cast<int>(mesh->attribute(pos)->unique_id());
  out.normal_id = static_cast<int>(mesh->attribute(nrm)->unique_id());
  out.uv_id = static_cast<int>(mesh->attribute(tex)->unique_id());

  draco::DecoderBuffer in;
  in.Init(buffer.data(), buffer.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&in);
  EXPECT_TRUE(decoded.ok());
  const draco::Mesh& m = *decoded.value();
  out.points = m.num_points();
  out.faces = m.num_faces();
  const draco::PointAttribute* p = m.GetNamedAttribute(draco::GeometryAttribute::POSITION);
  for (uint32_t f = 0; f < m.num_faces(); ++f) {
    std::array<float3, 3> face;
    for (int c = 0; c < 3; ++c)
      p->GetMappedValue(m.face(draco::FaceIndex(f))[c], &face[static_cast<size_t>(c)]);
    out.decoded_faces.push_back(face);
  }
  return out;
}

// A glTF of one Draco primitive (buffer 0 holds the stream) drawn by a node with `node_extra`
// ("translation" and such); `points` and `corners` are the counts the accessors declare.
struct DracoGltf {
  GltfBuilder builder;
  std::string body;
};
DracoGltf dracoGltf(const Encoded& e, const std::string& node_extra, uint32_t points,
                    uint32_t corners, size_t stream_bytes) {
  DracoGltf out;
  GltfBuilder& b = out.builder;
  const int view = b.bufferView(std::vector<uint8_t>(
      e.bytes.begin(), e.bytes.begin() + static_cast<std::ptrdiff_t>(stream_bytes)));
  const std::string n = std::to_string(points);
  const int p = b.rawAccessor("{\"componentType\":5126,\"type\":\"VEC3\",\"count\":" + n +
                              ",\"min\":[-1,-1,-1],\"max\":[1,1,1]}");
  const int nr = b.rawAccessor("{\"componentType\":5126,\"type\":\"VEC3\",\"count\":" + n + "}");
  const int uv = b.rawAccessor("{\"componentType\":5126,\"type\":\"VEC2\",\"count\":" + n + "}");
  const int i = b.rawAccessor(
      "{\"componentType\":5125,\"type\":\"SCALAR\",\"count\":" + std::to_string(corners) + "}");
  auto id = [](int v) { return std::to_string(v); };
  out.body =
      "\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],"
      "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],"
      "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0" +
      node_extra +
      "}],"
      "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
      id(p) + ",\"NORMAL\":" + id(nr) + ",\"TEXCOORD_0\":" + id(uv) + "},\"indices\":" + id(i) +
      ",\"extensions\":{\"KHR_draco_mesh_compression\":{\"bufferView\":" + id(view) +
      ",\"attributes\":{\"POSITION\":" + id(e.position_id) + ",\"NORMAL\":" + id(e.normal_id) +
      ",\"TEXCOORD_0\":" + id(e.uv_id) + "}}}}]}]";
  return out;
}

DracoGltf dracoGltf(const Encoded& e, const std::string& node_extra = "") {
  return dracoGltf(e, node_extra, e.points, 3 * e.faces, e.bytes.size());
}

// The original corner whose position is nearest `p`, within the quantization step.
const Corner* originalCorner(const std::array<Corner, 3>& triangle, float3 p) {
  for (const Corner& c : triangle)
    if (length(c.position - p) < 2 * kPositionStep) return &c;
  return nullptr;
}

TEST_F(GltfFiles, DracoPrimitiveLoadsAsTheUncompressedMeshInTheDecodersOrder) {
  const std::vector<std::array<Corner, 3>> cube = cubeTriangles();
  const Encoded e = encode(cube);
  ASSERT_EQ(e.faces, cube.size());
  // The node's transform applies to the decoded mesh: world = 2 p + (10, 0, 0).
  DracoGltf file = dracoGltf(e, ",\"translation\":[10,0,0],\"scale\":[2,2,2]");
  for (bool glb : {false, true}) {
    SCOPED_TRACE(glb ? "GLB" : "glTF");
    Expected<Model> model = glb ? loadGltf(write(at("cube.glb"), file.builder.glb(file.body)))
                                : loadJson(file.builder.json(file.body));
    ASSERT_TRUE(model) << model.error().message;
    EXPECT_TRUE(model->warnings.empty()) << allWarnings(*model);
    const Mesh mesh = io::flattenedMesh(*model);
    ASSERT_EQ(mesh.triangleCount(), cube.size());
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      // Triangle t is the decoder's face t (the id AOV's order), at the node's transform.
      const std::array<float3, 3> world = trianglePositions(mesh, t);
      std::array<float3, 3> local;
      for (size_t c = 0; c < 3; ++c) {
        local[c] = (world[c] - float3{10, 0, 0}) * 0.5f;
        expectNear3(local[c], e.decoded_faces[t][c], 1e-5f);
      }
      // ...which is one of the cube's triangles, same winding, with its normals and uvs.
      const auto original = std::find_if(cube.begin(), cube.end(), [&](const auto& tri) {
        return originalCorner(tri, local[0]) && originalCorner(tri, local[1]) &&
               originalCorner(tri, local[2]);
      });
      ASSERT_NE(original, cube.end()) << "triangle " << t << " is not one of the cube's";
      EXPECT_GT(dot(faceNormal(mesh, t), original->at(0).normal), 0.0f) << "winding of " << t;
      for (size_t c = 0; c < 3; ++c) {
        const uint32_t v = mesh.indices[3 * t + c];
        const Corner* corner = originalCorner(*original, local[c]);
        expectNear3(normalize(mesh.normals[v]), corner->normal, 0.01f);
        EXPECT_NEAR(mesh.uvs[v].x, corner->uv.x, 1e-3f);
        EXPECT_NEAR(mesh.uvs[v].y, 1.0f - corner->uv.y, 1e-3f);  // tessera's v is flipped
      }
    }
  }
}

TEST_F(GltfFiles, TruncatedDracoStreamIsAnErrorNamingTheFileAndPrimitive) {
  const Encoded e = encode(cubeTriangles());
  for (size_t keep : {size_t{3}, size_t{12}, e.bytes.size() / 2, e.bytes.size() - 1}) {
    SCOPED_TRACE("bytes kept: " + std::to_string(keep));
    DracoGltf file = dracoGltf(e, "", e.points, 3 * e.faces, keep);
    expectErrorContains(loadJson(file.builder.json(file.body)), "model.gltf: mesh 0 primitive 0");
  }
}

TEST_F(GltfFiles, CorruptDracoStreamIsAnErrorOrAMeshNeverACrash) {
  const Encoded e = encode(cubeTriangles());
  Encoded bad = e;
  bad.bytes[0] = 'X';  // not "DRACO"
  DracoGltf file = dracoGltf(bad);
  expectErrorContains(loadJson(file.builder.json(file.body)),
                      "model.gltf: mesh 0 primitive 0: the Draco stream (" +
                          std::to_string(e.bytes.size()) + " bytes) is not a Draco triangle mesh");
  // Every other byte past the header overwritten in turn: whatever the decoder makes of it, the
  // load ends in a mesh or in one message naming the primitive.
  size_t errors = 0;
  for (size_t at = 11; at < e.bytes.size(); at += 2) {
    for (uint8_t value : {uint8_t{0x00}, uint8_t{0xff}}) {
      bad = e;
      bad.bytes[at] = value;
      file = dracoGltf(bad);
      Expected<Model> model = loadJson(file.builder.json(file.body));
      if (model) continue;
      ++errors;
      EXPECT_NE(model.error().message.find("model.gltf: mesh 0 primitive 0"), std::string::npos)
          << model.error().message;
    }
  }
  EXPECT_GT(errors, 0u);
}

TEST_F(GltfFiles, DecodedCountsOverTheBudgetAreRefused) {
  const Encoded e = encode(cubeTriangles());
  ASSERT_GT(e.points, e.faces);
  // 12 triangles and 12 vertices allowed: the cube's 12 triangles fit, its vertices do not.
  LoadBudget budget;
  budget.memory_bytes = 3000;  // vertices: max(triangles, 3000 / 256)
  budget.max_triangles = e.faces;
  ASSERT_EQ(budget.vertices(), e.faces);
  DracoGltf honest = dracoGltf(e);
  expectErrorContains(loadJson(honest.builder.json(honest.body), budget),
                      "vertices (after instancing), over the budget of 12");
  // Accessors that understate the counts pass that check; the decoded counts do not.
  DracoGltf understated = dracoGltf(e, "", 4, 3 * e.faces, e.bytes.size());
  expectErrorContains(
      loadJson(understated.builder.json(understated.body), budget),
      "model.gltf: " + std::to_string(e.points) +
          " vertices (with the Draco stream of mesh 0 primitive 0), over the budget of 12");
  // Within the budget, an understated count is still refused: it is what instancing was
  // counted with.
  expectErrorContains(loadJson(understated.builder.json(understated.body)),
                      "the Draco stream decodes to " + std::to_string(e.points) +
                          " values, the accessor declares 4");
}

TEST_F(GltfFiles, OverstatedDracoCountsAreAWarning) {
  const Encoded e = encode(cubeTriangles());
  DracoGltf file = dracoGltf(e, "", e.points + 5, 3 * e.faces + 3, e.bytes.size());
  Expected<Model> model = loadJson(file.builder.json(file.body));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(io::flattenedMesh(*model).triangleCount(), e.faces);
  EXPECT_TRUE(anyWarningContains(
      *model, "the Draco stream decodes to " + std::to_string(3 * e.faces) +
                  " indices, the accessor declares " + std::to_string(3 * e.faces + 3)))
      << allWarnings(*model);
}

TEST_F(GltfFiles, DracoAttributeIdTheStreamLacksIsAnError) {
  Encoded e = encode(cubeTriangles());
  e.normal_id = 17;
  DracoGltf file = dracoGltf(e);
  expectErrorContains(loadJson(file.builder.json(file.body)),
                      "mesh 0 primitive 0: the Draco stream has no attribute 17 (NORMAL)");
}

// COLOR_0 as normalized bytes: converted to the accessor's type and normalized as glTF says.
TEST_F(GltfFiles, DracoColoursAreNormalizedBytes) {
  const float p[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const uint8_t c[3][4] = {{255, 0, 0, 255}, {0, 255, 0, 128}, {0, 0, 51, 0}};
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(1);
  const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int col = builder.AddAttribute(draco::GeometryAttribute::COLOR, 4, draco::DT_UINT8,
                                       /*normalized=*/true);
  builder.SetAttributeValuesForFace(pos, draco::FaceIndex(0), p[0], p[1], p[2]);
  builder.SetAttributeValuesForFace(col, draco::FaceIndex(0), c[0], c[1], c[2]);
  std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  ASSERT_NE(mesh, nullptr);
  draco::Encoder encoder;
  draco::EncoderBuffer buffer;
  ASSERT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &buffer).ok());
  GltfBuilder b;
  const int view = b.bufferView(std::vector<uint8_t>(buffer.data(), buffer.data() + buffer.size()));
  b.rawAccessor(R"({"componentType":5126,"type":"VEC3","count":3})");
  b.rawAccessor(R"({"componentType":5121,"normalized":true,"type":"VEC4","count":3})");
  b.rawAccessor(R"({"componentType":5123,"type":"SCALAR","count":3})");
  const std::string body =
      kOneNodeScene +
      ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,"
      "\"COLOR_0\":1},\"indices\":2,\"extensions\":{\"KHR_draco_mesh_compression\":{"
      "\"bufferView\":" +
      std::to_string(view) +
      ",\"attributes\":{\"POSITION\":" + std::to_string(mesh->attribute(pos)->unique_id()) +
      ",\"COLOR_0\":" + std::to_string(mesh->attribute(col)->unique_id()) + "}}}}]}]";
  Expected<Model> model = loadJson(b.json(body));
  ASSERT_TRUE(model) << model.error().message;
  const Mesh flat = io::flattenedMesh(*model);
  ASSERT_EQ(flat.triangleCount(), 1u);
  ASSERT_EQ(flat.colors.size(), flat.positions.size());
  for (size_t corner = 0; corner < 3; ++corner) {
    const uint32_t v = flat.indices[corner];
    // Which input corner this is, by its position (the encoder may rotate the face).
    size_t k = 0;
    while (k < 3 && length(flat.positions[v] - float3{p[k][0], p[k][1], p[k][2]}) > 1e-3f) ++k;
    ASSERT_LT(k, 3u);
    EXPECT_NEAR(flat.colors[v].x, c[k][0] / 255.0f, 1e-6f);
    EXPECT_NEAR(flat.colors[v].y, c[k][1] / 255.0f, 1e-6f);
    EXPECT_NEAR(flat.colors[v].z, c[k][2] / 255.0f, 1e-6f);
    EXPECT_NEAR(flat.colors[v].w, c[k][3] / 255.0f, 1e-6f);
  }
}

// With the extension only used (not required) the file may carry uncompressed data too; a build
// with Draco draws the stream (the extension says the compressed data must be used).
TEST_F(GltfFiles, DracoStreamIsDrawnRatherThanTheFallback) {
  const Encoded e = encode(cubeTriangles());
  GltfBuilder b;
  const int view = b.bufferView(e.bytes);
  // A fallback of the same counts (as the extension has it) that differs from the stream: every
  // point far away.
  const int p = b.positions(std::vector<float3>(e.points, float3{50, 50, 50}));
  std::vector<uint16_t> fallback_indices(3 * e.faces);
  for (size_t k = 0; k < fallback_indices.size(); ++k)
    fallback_indices[k] = static_cast<uint16_t>(k % e.points);
  const int i = b.indices(fallback_indices);
  const std::string body =
      kOneNodeScene + "," +
      oneMesh(p, "",
              ",\"indices\":" + std::to_string(i) +
                  ",\"extensions\":{\"KHR_draco_mesh_compression\":{\"bufferView\":" +
                  std::to_string(view) +
                  ",\"attributes\":{\"POSITION\":" + std::to_string(e.position_id) + "}}}") +
      ",\"extensionsUsed\":[\"KHR_draco_mesh_compression\"]";
  Expected<Model> model = loadJson(b.json(body));
  ASSERT_TRUE(model) << model.error().message;
  const Mesh mesh = io::flattenedMesh(*model);
  ASSERT_EQ(mesh.triangleCount(), e.faces);
  for (size_t t = 0; t < mesh.triangleCount(); ++t)
    for (size_t c = 0; c < 3; ++c)
      expectNear3(trianglePositions(mesh, t)[c], e.decoded_faces[t][c]);
}

// A real file: Khronos's 2CylinderEngine sample, Draco-compressed, as Debian's assimp package
// ships it (its accessors declare exactly what the streams decode to).
TEST_F(GltfFiles, KhronosDracoSampleLoadsWithoutWarnings) {
  const fs::path sample = "/usr/share/assimp/models/glTF2/draco/2CylinderEngine.gltf";
  if (!fs::exists(sample))
    GTEST_SKIP() << sample << " is not installed (Debian's assimp-testmodels)";
  Expected<Model> model = loadGltf(sample);
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_TRUE(model->warnings.empty()) << allWarnings(*model);
  EXPECT_EQ(model->graph.meshes.size(), 29u);
  EXPECT_EQ(io::flattenedMesh(*model).triangleCount(), 110336u);
}

// Found by the glTF fuzz target: a Draco POSITION accessor declared VEC2, with a three-value
// min and max, had its decoded points read three floats apart, past the decoded bytes (the
// min/max check). Now the bytes are read as decoded and the file is the attribute's clear error;
// the sanitizer run (scripts/sanitize.sh) runs this test under ASan.
TEST_F(GltfFiles, DracoPositionDeclaredVec2IsAClearErrorNotAnOverread) {
  Expected<Model> model = loadGltf(fs::path(TESSERA_TEST_DATA_DIR) / "draco_vec2_position.glb");
  expectErrorContains(model, "has 2 components per element");
}

#else  // !TESSERA_HAS_DRACO

TEST_F(GltfFiles, DracoPrimitiveLoadsAsTheUncompressedMeshInTheDecodersOrder) {
  GTEST_SKIP() << "this build has no Draco decoder (TESSERA_DRACO off or libdraco-dev missing)";
}

#endif

// In every build: a Draco primitive whose accessors have no data of their own is refused
// without Draco, and read from the stream with it (the stream here is not Draco: an error).
TEST_F(GltfFiles, DracoPrimitiveWithoutFallbackNeedsTheDecoder) {
  GltfBuilder b;
  const int view = b.bufferView(std::vector<uint8_t>{1, 2, 3, 4});
  const int p = b.rawAccessor("{\"componentType\":5126,\"type\":\"VEC3\",\"count\":3}");
  const int i = b.rawAccessor("{\"componentType\":5123,\"type\":\"SCALAR\",\"count\":3}");
  const std::string extension =
      ",\"extensions\":{\"KHR_draco_mesh_compression\":{\"bufferView\":" + std::to_string(view) +
      ",\"attributes\":{\"POSITION\":0}}}";
  const std::string used = ",\"extensionsUsed\":[\"KHR_draco_mesh_compression\"]";
  const std::string file = b.json(
      kOneNodeScene + "," + oneMesh(p, "", ",\"indices\":" + std::to_string(i) + extension) + used);
#if TESSERA_HAS_DRACO
  expectErrorContains(loadJson(file), "model.gltf: mesh 0 primitive 0: the Draco stream (4 bytes)");
#else
  expectErrorContains(loadJson(file),
                      "model.gltf: mesh 0 primitive 0 needs KHR_draco_mesh_compression (this "
                      "build has no Draco decoder)");
  const std::string required =
      b.json(kOneNodeScene + "," + oneMesh(p, "", ",\"indices\":" + std::to_string(i) + extension) +
             used + ",\"extensionsRequired\":[\"KHR_draco_mesh_compression\"]");
  expectErrorContains(loadJson(required),
                      "model.gltf: the file needs KHR_draco_mesh_compression (this build has no "
                      "Draco decoder)");
#endif
}

// A file that carries uncompressed data beside the stream: without Draco it is read from that.
TEST_F(GltfFiles, DracoPrimitiveWithFallbackIsReadWithoutTheDecoder) {
#if TESSERA_HAS_DRACO
  GTEST_SKIP() << "this build decodes Draco: the fallback is not read";
#else
  GltfBuilder b;
  const int view = b.bufferView(std::vector<uint8_t>{1, 2, 3, 4});
  const int p = b.positions(kTriangle);
  const std::string extension =
      ",\"extensions\":{\"KHR_draco_mesh_compression\":{\"bufferView\":" + std::to_string(view) +
      ",\"attributes\":{\"POSITION\":0}}}";
  Expected<Model> model = loadJson(b.json(kOneNodeScene + "," + oneMesh(p, "", extension) +
                                          ",\"extensionsUsed\":[\"KHR_draco_mesh_compression\"]"));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(io::flattenedMesh(*model).triangleCount(), 1u);
  EXPECT_TRUE(anyWarningContains(*model, "uncompressed fallback")) << allWarnings(*model);
#endif
}

}  // namespace
}  // namespace tessera::io
