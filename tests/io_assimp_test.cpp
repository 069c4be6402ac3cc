// Formats read through assimp (loadAssimp): tiny PLY, OFF and COLLADA files written by each
// test, the sandbox (SandboxIOSystem), hostile and over-budget files, and every model of
// Debian's assimp-testmodels in the folders issue 20 names.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <assimp/IOStream.hpp>

#include <tessera/io/model_loader.h>
#include <tessera/scene/color.h>

#include "io/assimp_io.h"
#include "temp_folder.h"

namespace tessera::io {
namespace {

namespace fs = std::filesystem;

class AssimpFiles : public ::testing::Test {
 protected:
  void SetUp() override { root_ = test::makeTestFolder("tessera_io_assimp"); }
  void TearDown() override { fs::remove_all(root_); }

  fs::path write(const std::string& name, const std::string& bytes) const {
    return test::writeFile(root_ / name, bytes);
  }

  fs::path root_;
};

// The position of `p` in `mesh`, or -1.
int find(const Mesh& mesh, float3 p) {
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    if (mesh.positions[i] == p) return static_cast<int>(i);
  return -1;
}

// A one-line message that names the file.
void expectOneLineNaming(const Error& error, const fs::path& path) {
  EXPECT_EQ(error.message.find('\n'), std::string::npos) << error.message;
  EXPECT_EQ(error.message.rfind(path.string(), 0), 0u) << error.message;
}

// A 1x1 opaque white PNG.
std::string tinyPng() {
  static const uint8_t kPng[] = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
      0x44, 0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00,
      0x00, 0x1f, 0x15, 0xc4, 0x89, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x44, 0x41, 0x54, 0x78,
      0x9c, 0x63, 0xf8, 0xcf, 0xc0, 0xf0, 0x1f, 0x00, 0x05, 0x00, 0x01, 0xff, 0x89, 0x99,
      0x3d, 0x1d, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  return std::string(reinterpret_cast<const char*>(kPng), sizeof kPng);
}

const char* kAsciiPly =
    "ply\n"
    "format ascii 1.0\n"
    "element vertex 4\n"
    "property float x\nproperty float y\nproperty float z\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    "element face 1\n"
    "property list uchar int vertex_indices\n"
    "end_header\n"
    "0 0 0 255 0 0\n"
    "2 0 0 0 255 0\n"
    "2 3 0 0 0 255\n"
    "0 3 0 188 188 188\n"
    "4 0 1 2 3\n";

TEST_F(AssimpFiles, AsciiPlyQuadBecomesTwoTrianglesWithItsColours) {
  Expected<Model> model = loadModel(write("quad.ply", kAsciiPly));
  ASSERT_TRUE(model) << model.error().message;
  const Mesh mesh = flattenedMesh(*model);
  ASSERT_EQ(mesh.triangleCount(), 2u);
  ASSERT_EQ(mesh.colors.size(), mesh.positions.size());
  const int red = find(mesh, {0, 0, 0}), green = find(mesh, {2, 0, 0}),
            blue = find(mesh, {2, 3, 0}), grey = find(mesh, {0, 3, 0});
  ASSERT_TRUE(red >= 0 && green >= 0 && blue >= 0 && grey >= 0);
  EXPECT_EQ(mesh.colors[red], (float4{1, 0, 0, 1}));
  EXPECT_EQ(mesh.colors[green], (float4{0, 1, 0, 1}));
  EXPECT_EQ(mesh.colors[blue], (float4{0, 0, 1, 1}));
  // 188 is sRGB-encoded: decoded to linear (about 0.5).
  EXPECT_NEAR(mesh.colors[grey].x, srgbToLinear(188.0f / 255.0f), 1e-5f);
  EXPECT_NEAR(mesh.colors[grey].x, 0.5f, 0.01f);
  // Both triangles use all four corners between them, facing +Z (counter-clockwise).
  for (size_t t = 0; t < 2; ++t) {
    const float3 a = mesh.positions[mesh.indices[3 * t]],
                 b = mesh.positions[mesh.indices[3 * t + 1]],
                 c = mesh.positions[mesh.indices[3 * t + 2]];
    EXPECT_GT(cross(b - a, c - a).z, 0.0f) << "triangle " << t;
  }
  EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
}

TEST_F(AssimpFiles, BinaryPlyTriangleKeepsItsPositions) {
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
      "property float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float corners[9] = {0.25f, -1.5f, 2, 4, -1.5f, 2, 0.25f, 7.125f, 2};
  ply.append(reinterpret_cast<const char*>(corners), sizeof corners);
  ply += '\3';
  const int32_t indices[3] = {0, 1, 2};
  ply.append(reinterpret_cast<const char*>(indices), sizeof indices);
  Expected<Model> model = loadModel(write("tri.ply", ply));
  ASSERT_TRUE(model) << model.error().message;
  const Mesh mesh = flattenedMesh(*model);
  ASSERT_EQ(mesh.triangleCount(), 1u);
  for (int i = 0; i < 3; ++i) {
    const float3 p = mesh.positions[mesh.indices[static_cast<size_t>(i)]];
    EXPECT_EQ(p, (float3{corners[3 * i], corners[3 * i + 1], corners[3 * i + 2]})) << i;
  }
}

TEST_F(AssimpFiles, OffCubeLoadsTwelveTriangles) {
  const fs::path path = write("cube.off",
                              "OFF\n# a unit cube\n8 6 0\n"
                              "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                              "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 1 2 6 5\n4 0 4 7 3\n");
  Expected<Model> model = loadModel(path);
  ASSERT_TRUE(model) << model.error().message;
  const Mesh mesh = flattenedMesh(*model);
  EXPECT_EQ(mesh.triangleCount(), 12u);
  const Bounds bounds = mesh.bounds();
  EXPECT_EQ(bounds.min, (float3{0, 0, 0}));
  EXPECT_EQ(bounds.max, (float3{1, 1, 1}));
}

// One triangle geometry drawn by node "a" (moved +5 in x) and by node "c" beneath "b" (moved -5
// in x, then +2 in y); its material's diffuse texture is `texture`.
std::string colladaTwoInstances(const std::string& texture) {
  return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Y_UP</up_axis></asset>
  <library_images><image id="img"><init_from>)" +
         texture + R"(</init_from></image></library_images>
  <library_effects><effect id="fx"><profile_COMMON>
    <newparam sid="surf"><surface type="2D"><init_from>img</init_from></surface></newparam>
    <newparam sid="samp"><sampler2D><source>surf</source></sampler2D></newparam>
    <technique sid="common"><lambert><diffuse><texture texture="samp" texcoord="UV"/></diffuse>
    </lambert></technique>
  </profile_COMMON></effect></library_effects>
  <library_materials><material id="mat"><instance_effect url="#fx"/></material></library_materials>
  <library_geometries><geometry id="tri" name="tri"><mesh>
    <source id="pos"><float_array id="pos-array" count="9">0 0 0 1 0 0 0 1 0</float_array>
      <technique_common><accessor source="#pos-array" count="3" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <source id="uv"><float_array id="uv-array" count="6">0 0 1 0 0 1</float_array>
      <technique_common><accessor source="#uv-array" count="3" stride="2">
        <param name="S" type="float"/><param name="T" type="float"/>
      </accessor></technique_common></source>
    <vertices id="vtx"><input semantic="POSITION" source="#pos"/></vertices>
    <triangles count="1" material="m">
      <input semantic="VERTEX" source="#vtx" offset="0"/>
      <input semantic="TEXCOORD" source="#uv" offset="0" set="0"/>
      <p>0 1 2</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene">
    <node id="a" name="a"><translate>5 0 0</translate>
      <instance_geometry url="#tri"><bind_material><technique_common>
        <instance_material symbol="m" target="#mat"/></technique_common></bind_material>
      </instance_geometry></node>
    <node id="b" name="b"><translate>-5 0 0</translate>
      <node id="c" name="c"><translate>0 2 0</translate>
        <instance_geometry url="#tri"><bind_material><technique_common>
          <instance_material symbol="m" target="#mat"/></technique_common></bind_material>
        </instance_geometry></node></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)";
}

TEST_F(AssimpFiles, ColladaNodesInstanceOneMeshAtTheirWorldPositions) {
  write("tex.png", tinyPng());
  Expected<Model> model = loadModel(write("two.dae", colladaTwoInstances("tex.png")));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(model->graph.meshes.size(), 1u) << "the triangle is stored once";
  EXPECT_EQ(model->graph.instanceCount(), 2u);
  const Mesh mesh = flattenedMesh(*model);
  ASSERT_EQ(mesh.triangleCount(), 2u);
  for (float3 p : {float3{5, 0, 0}, float3{6, 0, 0}, float3{5, 1, 0}, float3{-5, 2, 0},
                   float3{-4, 2, 0}, float3{-5, 3, 0}})
    EXPECT_GE(find(mesh, p), 0) << p.x << "," << p.y << "," << p.z;
  // "c" is a child of "b": its parent is stored before it.
  const auto c = std::find_if(model->graph.nodes.begin(), model->graph.nodes.end(),
                              [](const GraphNode& n) { return n.name == "c"; });
  ASSERT_NE(c, model->graph.nodes.end());
  ASSERT_NE(c->parent, kNoIndex);
  EXPECT_EQ(model->graph.nodes[static_cast<size_t>(c->parent)].name, "b");
  // The texture beneath the model's folder is read, with the UVs.
  ASSERT_FALSE(model->materials.empty());
  ASSERT_TRUE(model->materials[0].albedo);
  EXPECT_EQ(model->materials[0].albedo->width, 1);
  EXPECT_EQ(mesh.uvs.size(), mesh.positions.size());
}

TEST_F(AssimpFiles, TextureOutsideTheFolderIsRefusedWithAWarning) {
  test::writeFile(root_ / "secret.png", tinyPng());
  const fs::path path = write("inner/two.dae", colladaTwoInstances("../secret.png"));
  Expected<Model> model = loadModel(path);
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_FALSE(model->materials.at(0).albedo);
  bool refused = false;
  for (const std::string& w : model->warnings)
    refused |= w.find("secret.png") != std::string::npos &&
               w.find("out of the model's folder") != std::string::npos;
  EXPECT_TRUE(refused) << "no warning about ../secret.png";
}

TEST_F(AssimpFiles, SandboxServesOnlyRegularFilesBeneathTheFolder) {
  const fs::path folder = root_ / "model";
  write("model/inside.bin", "12345");
  write("outside.bin", "secret");
  ASSERT_EQ(::mkfifo((folder / "pipe.bin").c_str(), 0600), 0);
  SandboxIOSystem files((folder / "m.ply").string(), {'p', 'l', 'y'}, folder, 1 << 20);
  // The model itself, from the bytes given.
  std::unique_ptr<Assimp::IOStream> model(files.Open((folder / "m.ply").c_str(), "rb"));
  ASSERT_TRUE(model);
  EXPECT_EQ(model->FileSize(), 3u);
  // A file beneath the folder, by absolute or relative name.
  std::unique_ptr<Assimp::IOStream> inside(files.Open((folder / "inside.bin").c_str(), "rb"));
  ASSERT_TRUE(inside);
  char bytes[8] = {};
  EXPECT_EQ(inside->Read(bytes, 1, sizeof bytes), 5u);
  EXPECT_STREQ(bytes, "12345");
  EXPECT_TRUE(files.Exists("inside.bin"));
  // Outside, absolute elsewhere, a FIFO, writing: refused.
  EXPECT_EQ(files.Open((folder / ".." / "outside.bin").c_str(), "rb"), nullptr);
  EXPECT_EQ(files.Open("/etc/passwd", "rb"), nullptr);
  EXPECT_EQ(files.Open((folder / "pipe.bin").c_str(), "rb"), nullptr);
  EXPECT_EQ(files.Open((folder / "new.bin").c_str(), "wb"), nullptr);
  EXPECT_FALSE(files.Exists("/etc/passwd"));
  ASSERT_GE(files.refusals().size(), 4u);
  EXPECT_NE(files.refusals()[2].find("FIFO"), std::string::npos) << files.refusals()[2];
  EXPECT_TRUE(files.overBudget().empty());
}

TEST_F(AssimpFiles, SandboxCountsBytesAgainstTheBudget) {
  const fs::path folder = root_;
  write("big.bin", std::string(100, 'x'));
  SandboxIOSystem files((folder / "m.ply").string(), std::vector<uint8_t>(50, 'p'), folder, 120);
  EXPECT_EQ(files.Open((folder / "big.bin").c_str(), "rb"), nullptr);
  EXPECT_NE(files.overBudget().find("--memory-limit"), std::string::npos) << files.overBudget();
}

TEST_F(AssimpFiles, TruncatedAndGarbageFilesGiveOneClearLine) {
  const std::string truncated = std::string(kAsciiPly).substr(0, std::strlen(kAsciiPly) - 30);
  for (const fs::path& path :
       {write("truncated.ply", truncated), write("garbage.fbx", std::string(3000, '\x9c')),
        write("garbage.dae", "<COLLADA><library_geometries><geometry"),
        write("garbage.3ds", std::string("\x4d\x4d\xff\xff\xff\x7f", 6) + std::string(64, 'z'))}) {
    Expected<Model> model = loadModel(path);
    ASSERT_FALSE(model) << path;
    expectOneLineNaming(model.error(), path);
    EXPECT_GT(model.error().message.size(), path.string().size() + 10) << model.error().message;
  }
}

// assimp 5.2's PLY reader never returns on some of these (fuzz/corpus/assimp/
// hang_nul_in_keyword.ply) and overflows its arrays on others; tessera's header check refuses
// them first.
TEST_F(AssimpFiles, BrokenPlyHeadersAreRefusedBeforeAssimpSeesThem) {
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n";
  const struct {
    std::string text, expected;
  } cases[] = {
      {"ply\nformat ascii 1.0\nelement vertex 3\nproper" + std::string(1, '\0') +
           "ty float x\nend_header\n0\n0\n0\n",
       "line 4: a control or non-ASCII byte"},
      {header + "property floot y\nend_header\n", "line 5: 'property TYPE NAME'"},
      {"ply\nformat ascii 2.0 1.0\nelement vertex 3\nend_header\n", "line 2: an unknown format"},
      {header + "0 0 0\n", "no end_header"},
      // assimp writes past its vertex arrays (fuzz/corpus/assimp/overflow_vertex_twice.ply).
      {header + "element vertex 2\nproperty float x\nend_header\n0\n0\n0\n0\n0\n",
       "line 5: a second 'vertex' element"},
  };
  for (const auto& c : cases) {
    const fs::path path = write("broken.ply", c.text);
    Expected<Model> model = loadModel(path);
    ASSERT_FALSE(model) << c.expected;
    expectOneLineNaming(model.error(), path);
    EXPECT_NE(model.error().message.find(c.expected), std::string::npos) << model.error().message;
  }
}

// assimp 5.2's COLLADA reader dereferences null on a float_array that declares no values while
// its accessor reads three (fuzz/corpus/assimp/segv_collada_empty_array.dae): the child process
// reading it first crashes, and tessera says so in one line.
TEST_F(AssimpFiles, ACrashInAssimpIsOneLineNotACrash) {
  std::string dae = colladaTwoInstances("tex.png");
  const std::string declared = R"(count="9">0 0 0 1 0 0 0 1 0)";
  ASSERT_NE(dae.find(declared), std::string::npos);
  dae.replace(dae.find(declared), declared.size(), R"(count="0">0 0 0 1 0 0 0 1 0)");
  const fs::path path = write("crash.dae", dae);
  Expected<Model> model = loadModel(path);
  ASSERT_FALSE(model);
  expectOneLineNaming(model.error(), path);
  EXPECT_NE(model.error().message.find("assimp cannot read it: it crashed"), std::string::npos)
      << model.error().message;
}

TEST_F(AssimpFiles, FifoIsRefusedBeforeAssimpSeesIt) {
  const fs::path path = root_ / "pipe.ply";
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  Expected<Model> model = loadModel(path);
  ASSERT_FALSE(model);
  EXPECT_NE(model.error().message.find("FIFO"), std::string::npos) << model.error().message;
}

TEST_F(AssimpFiles, DeclaredCountsOverTheBudgetAreRefusedBeforeAssimpReads) {
  LoadBudget small;
  small.max_triangles = 10;
  std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 5000\n"
      "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  for (int i = 0; i < 5000; ++i) ply += "3 0 1 2\n";
  const fs::path path = write("many.ply", ply);
  Expected<Model> model = loadModel(path, small);
  ASSERT_FALSE(model);
  expectOneLineNaming(model.error(), path);
  EXPECT_NE(model.error().message.find("5000 faces"), std::string::npos) << model.error().message;
  EXPECT_NE(model.error().message.find("--max-triangles"), std::string::npos);
  // The same file loads within the default budget.
  EXPECT_TRUE(loadModel(path));
}

TEST_F(AssimpFiles, HeaderCountsPastTheFileSizeAreRefused) {
  const fs::path ply = write("lie.ply",
                             "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n"
                             "property float x\nproperty float y\nproperty float z\nend_header\n");
  Expected<Model> model = loadModel(ply);
  ASSERT_FALSE(model);
  EXPECT_NE(model.error().message.find("more than the file's"), std::string::npos)
      << model.error().message;
  const fs::path off = write("lie.off", "OFF\n3 2000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  model = loadModel(off);
  ASSERT_FALSE(model);
  EXPECT_NE(model.error().message.find("2000000000 faces"), std::string::npos)
      << model.error().message;
}

TEST_F(AssimpFiles, InstancesOverTheBudgetAreRefusedBeforeCopying) {
  write("tex.png", tinyPng());
  const fs::path path = write("two.dae", colladaTwoInstances("tex.png"));
  LoadBudget one;
  one.max_triangles = 1;
  Expected<Model> model = loadModel(path, one);
  ASSERT_FALSE(model);
  expectOneLineNaming(model.error(), path);
  EXPECT_NE(model.error().message.find("2 triangles (after instancing)"), std::string::npos)
      << model.error().message;
}

TEST_F(AssimpFiles, OnlyPointsIsAPointCloudAndNothingIsAClearError) {
  const fs::path path = write("points.ply",
                              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                              "property float y\nproperty float z\nend_header\n"
                              "0 0 0\n1 0 0\n0 1 0\n");
  Expected<Model> model = loadModel(path);
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(model->points.size(), 3u);  // io_points_test.cpp tests them further
  const fs::path empty = write("empty.ply",
                               "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
                               "property float y\nproperty float z\nend_header\n");
  model = loadModel(empty);
  ASSERT_FALSE(model);
  expectOneLineNaming(model.error(), empty);
  EXPECT_NE(model.error().message.find("nothing to draw: no faces, points or lines"),
            std::string::npos)
      << model.error().message;
}

TEST_F(AssimpFiles, FromMemoryReadsTheBytesAndNothingElse) {
  const std::string text = kAsciiPly;
  Expected<Model> model = loadAssimpFromMemory(
      std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()), "quad.ply");
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(flattenedMesh(*model).triangleCount(), 2u);
  const std::string dae = colladaTwoInstances("tex.png");
  model = loadAssimpFromMemory(std::span(reinterpret_cast<const uint8_t*>(dae.data()), dae.size()),
                               "two.dae");
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_FALSE(model->materials.at(0).albedo);
}

TEST(AssimpFormats, ListsAssimpsFormatsAndKeepsTesserasOwn) {
  ASSERT_TRUE(hasAssimp());
  std::vector<std::string> assimp, own;
  for (const ModelFormat& format : modelFormats()) {
    EXPECT_FALSE(format.name.empty());
    for (const std::string& e : format.extensions)
      (format.reader == "assimp" ? assimp : own).push_back(e);
  }
  for (const char* e : {"ply", "off", "dae", "fbx", "3ds", "3mf", "blend", "x3d"})
    EXPECT_NE(std::find(assimp.begin(), assimp.end(), e), assimp.end()) << e;
  for (const char* e : {"obj", "gltf", "glb", "stl"}) {
    EXPECT_EQ(std::find(assimp.begin(), assimp.end(), e), assimp.end()) << e;
    EXPECT_NE(std::find(own.begin(), own.end(), e), own.end()) << e;
  }
}

// Debian's assimp-testmodels (scripts/setup.sh installs it): every file of the folders issue
// 20 names either loads with triangles or fails with one line naming it; none crashes or hangs.
// Textures and the other files beside the models are not models: files whose extension assimp
// does not list are skipped, extensionless ones are tried.
TEST(AssimpTestModels, EveryModelLoadsOrFailsWithOneLine) {
  const fs::path root = "/usr/share/assimp/models";
  ASSERT_TRUE(fs::is_directory(root)) << root << " is missing: apt-get install assimp-testmodels";
  std::vector<std::string> extensions;
  for (const ModelFormat& format : modelFormats())
    for (const std::string& e : format.extensions) extensions.push_back("." + e);
  size_t loaded = 0, failed = 0;
  for (const char* folder : {"PLY", "OFF", "Collada", "FBX", "3DS", "3MF"}) {
    ASSERT_TRUE(fs::is_directory(root / folder)) << folder;
    size_t in_folder = 0;
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(root / folder)) {
      if (!entry.is_regular_file()) continue;
      std::string extension = entry.path().extension().string();
      std::transform(extension.begin(), extension.end(), extension.begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      const bool listed =
          std::find(extensions.begin(), extensions.end(), extension) != extensions.end();
      if (!listed && !extension.empty()) continue;
      ++in_folder;
      Expected<Model> model = listed ? loadModel(entry.path()) : loadAssimp(entry.path());
      if (model) {
        ++loaded;
        EXPECT_GT(model->graph.drawnTriangleCount() + model->mesh.triangleCount() +
                      model->points.size() + model->lines.colors.size(),
                  0u)
            << entry.path();
      } else {
        ++failed;
        expectOneLineNaming(model.error(), entry.path());
        std::cout << "  " << model.error().message << "\n";
      }
    }
    EXPECT_GT(in_folder, 0u) << folder;
  }
  std::cout << "assimp-testmodels: " << loaded << " loaded, " << failed << " failed\n";
  // Most of them are sound files that assimp reads.
  EXPECT_GT(loaded, 3 * failed);
}

}  // namespace
}  // namespace tessera::io
