// glTF 2.0 loading: geometry, attributes and materials, the scene graph. Every test builds its own
// small file (gltf_test_files.h); containers (GLB, external files) and hostile files are in
// io_gltf_files_test.cpp.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <tessera/io/model_loader.h>
#include <tessera/scene/color.h>

#include "gltf_test_files.h"

namespace tessera::io {
namespace {

namespace fs = std::filesystem;
using namespace gltf_test;  // NOLINT(google-build-using-namespace): the tests' own helpers

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

TEST_F(GltfFiles, PointsAndLinesBesideTrianglesAreLoaded) {
  GltfBuilder b;
  const int p = b.positions(kTriangle);
  Expected<Model> model = loadJson(b.json(
      kOneNodeScene + ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
      std::to_string(p) + "},\"mode\":0},{\"attributes\":{\"POSITION\":" + std::to_string(p) +
      "},\"mode\":1},{\"attributes\":{\"POSITION\":" + std::to_string(p) + "}}]}]"));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(io::flattenedMesh(*model).triangleCount(), 1u);
  EXPECT_EQ(model->points.size(), 3u);
  EXPECT_EQ(model->lines.colors.size(), 1u);  // LINES of 3 vertices: one whole segment
  EXPECT_TRUE(anyWarningContains(*model, "1 vertex after the last whole line segment is ignored"))
      << allWarnings(*model);
}

TEST_F(GltfFiles, NothingToDrawIsAnError) {
  GltfBuilder b;
  // A line strip of one vertex has no segment.
  const int p = b.positions({{0, 0, 0}});
  expectErrorContains(loadJson(b.json(kOneNodeScene + "," + oneMesh(p, "", ",\"mode\":3"))),
                      "nothing to draw: no faces, points or lines");
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
  EXPECT_EQ(material.sampler.wrap_s, TextureWrap::kClamp);
  EXPECT_EQ(material.sampler.wrap_t, TextureWrap::kClamp);
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

// Each axis its own wrap mode, MIRRORED_REPEAT among them, with no warning; linear filtering
// without a minification filter is trilinear (tessera's choice), with LINEAR bilinear.
TEST_F(GltfFiles, WrapModesPerAxisMirroredRepeatAndTheFilter) {
  const std::vector<uint8_t> png = pngBytes(1, 1, {0xff808080});
  struct Case {
    const char* sampler;
    TextureWrap s, t;
    TextureFilter filter;
  };
  for (const Case& c :
       {Case{"\"magFilter\":9729,\"wrapS\":33648,\"wrapT\":33071", TextureWrap::kMirroredRepeat,
             TextureWrap::kClamp, TextureFilter::kTrilinear},
        Case{"\"magFilter\":9729,\"minFilter\":9729,\"wrapT\":33648", TextureWrap::kRepeat,
             TextureWrap::kMirroredRepeat, TextureFilter::kBilinear},
        Case{"\"minFilter\":9984,\"wrapS\":33071", TextureWrap::kClamp, TextureWrap::kRepeat,
             TextureFilter::kNearest}}) {
    GltfBuilder b;
    const int p = b.positions(kTriangle);
    const int uv = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, kFloat, "VEC2", 3);
    Expected<Model> model = loadJson(b.json(
        kOneNodeScene + "," +
        oneMesh(p, ",\"TEXCOORD_0\":" + std::to_string(uv), ",\"material\":0") +
        ",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}]"
        ",\"textures\":[{\"source\":0,\"sampler\":0}]"
        ",\"samplers\":[{" +
        c.sampler + "}],\"images\":[{\"uri\":\"data:image/png;base64," + base64(png) + "\"}]"));
    ASSERT_TRUE(model) << model.error().message;
    const Sampler& sampler = model->materials[0].sampler;
    EXPECT_EQ(sampler.wrap_s, c.s) << c.sampler;
    EXPECT_EQ(sampler.wrap_t, c.t) << c.sampler;
    EXPECT_EQ(sampler.filter, c.filter) << c.sampler;
    EXPECT_TRUE(model->warnings.empty()) << allWarnings(*model);
  }
}

// KHR_texture_transform on the baseColorTexture: offset, rotation, scale and texCoord read, the
// extension required without a warning; a member that is not a finite number leaves the
// transform out, with a warning naming the material.
TEST_F(GltfFiles, TextureTransformIsReadAndANonFiniteOneIsLeftOutWithAWarning) {
  const std::vector<uint8_t> png = pngBytes(1, 1, {0xff808080});
  auto load = [&](const std::string& extension) {
    GltfBuilder b;
    const int p = b.positions(kTriangle);
    const int uv = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, kFloat, "VEC2", 3);
    return loadJson(
        b.json(kOneNodeScene + "," +
               oneMesh(p, ",\"TEXCOORD_0\":" + std::to_string(uv), ",\"material\":0") +
               ",\"materials\":[{\"name\":\"moved\",\"pbrMetallicRoughness\":{\"baseColorTexture\":"
               "{\"index\":0,\"extensions\":{\"KHR_texture_transform\":" +
               extension +
               "}}}}],\"textures\":[{\"source\":0}]"
               ",\"extensionsUsed\":[\"KHR_texture_transform\"]"
               ",\"extensionsRequired\":[\"KHR_texture_transform\"]"
               ",\"images\":[{\"uri\":\"data:image/png;base64," +
               base64(png) + "\"}]"));
  };
  Expected<Model> model =
      load("{\"offset\":[0.5,-0.25],\"rotation\":0.75,\"scale\":[2,3],\"texCoord\":0}");
  ASSERT_TRUE(model) << model.error().message;
  const TextureTransform& t = model->materials[0].sampler.transform;
  EXPECT_EQ(t.offset.x, 0.5f);
  EXPECT_EQ(t.offset.y, -0.25f);
  EXPECT_EQ(t.rotation, 0.75f);
  EXPECT_EQ(t.scale.x, 2.0f);
  EXPECT_EQ(t.scale.y, 3.0f);
  EXPECT_EQ(model->materials[0].sampler.texcoord, 0);
  EXPECT_TRUE(model->warnings.empty()) << allWarnings(*model);
  for (const char* bad : {"{\"offset\":[1e39,0]}", "{\"scale\":\"large\"}", "{\"rotation\":[1]}",
                          "{\"offset\":[1]}"}) {
    model = load(bad);
    ASSERT_TRUE(model) << model.error().message;
    EXPECT_TRUE(model->materials[0].albedo) << bad;
    EXPECT_TRUE(model->materials[0].sampler.transform.identity()) << bad;
    EXPECT_TRUE(anyWarningContains(*model,
                                   "material 0 'moved' baseColorTexture: "
                                   "KHR_texture_transform holds something other than"))
        << bad << ": " << allWarnings(*model);
  }
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

}  // namespace
}  // namespace tessera::io
