// OBJ materials (MTL), textures and their decoding, and hostile input. The fixture is
// obj_test_files.h's, under its own suite name (GoogleTest wants one fixture type per suite).
#include <gtest/gtest.h>

#include "obj_test_files.h"

namespace tessera::io {
namespace {

class ObjMaterials : public ObjFiles {};

// ---- Materials ----

TEST_F(ObjMaterials, AssignsMaterialsPerTriangleInFirstUseOrder) {
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

TEST_F(ObjMaterials, LoadsEveryLibraryOnAnMtllibLine) {
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

TEST_F(ObjMaterials, MissingMtlFileWarnsAndFallsBackToTheDefaultMaterial) {
  Expected<Model> model = loadObj(writeModel(std::string("mtllib absent.mtl\n") +
                                             kTwoTriangleHeader + "usemtl red\nf 1 2 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->materials.size(), 1u);
  EXPECT_EQ(model->materials[0].base_color, (float4{0.8f, 0.8f, 0.8f, 1}));
  EXPECT_EQ(model->mesh.triangle_materials, (std::vector<uint16_t>{0}));
  EXPECT_TRUE(anyWarningContains(*model, "absent.mtl"));
}

TEST_F(ObjMaterials, ReadsEachMaterialLibraryOnceHoweverOftenNamed) {
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

TEST_F(ObjMaterials, LoadsADiffuseTextureWithOptionsAndSpacesInItsName) {
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

TEST_F(ObjMaterials, ResolvesWindowsStyleTexturePaths) {
  writeSolidPng(at("tex/a.png"), 0xff0000ffu);
  write(at("m.mtl"), "newmtl tex\nmap_Kd .\\tex\\a.png\n");
  Expected<Model> model = loadObj(
      writeModel(std::string("mtllib m.mtl\n") + kTwoTriangleHeader + "usemtl tex\nf 1 2 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_NE(model->materials[0].albedo, nullptr)
      << (model->warnings.empty() ? "" : model->warnings[0]);
  EXPECT_EQ(model->materials[0].albedo->texels[0], 0xff0000ffu);
}

TEST_F(ObjMaterials, RefusesTexturesFromOutsideTheModelFolder) {
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

TEST_F(ObjMaterials, RefusesAnMtlFileFromOutsideTheModelFolder) {
  write(root_ / "outside.mtl", "newmtl red\nKd 1 0 0\n");
  Expected<Model> model = loadObj(writeModel(std::string("mtllib ../outside.mtl\n") +
                                             kTwoTriangleHeader + "usemtl red\nf 1 2 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->materials.size(), 1u);
  EXPECT_EQ(model->materials[0].base_color, (float4{0.8f, 0.8f, 0.8f, 1}));
  EXPECT_TRUE(anyWarningContains(*model, "'../outside.mtl' refused"));
}

TEST_F(ObjMaterials, TextureWithoutKdIsUsedAsItIs) {
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

TEST_F(ObjMaterials, MissingTextureWarnsAndKeepsTheMaterialColour) {
  write(at("m.mtl"), "newmtl tex\nKd 0 1 0\nmap_Kd nowhere.png\n");
  Expected<Model> model = loadObj(
      writeModel(std::string("mtllib m.mtl\n") + kTwoTriangleHeader + "usemtl tex\nf 1 2 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->materials[0].albedo, nullptr);
  EXPECT_EQ(model->materials[0].base_color, (float4{0, 1, 0, 1}));
  EXPECT_TRUE(anyWarningContains(*model, "nowhere.png"));
}

// ---- Textures ----

TEST_F(ObjMaterials, TextureTexelsAreRgbaWithRedLowAndTopRowFirst) {
  writePng(at("t.png"), 2, 2, {0xff0000ffu, 0xff00ff00u, 0x80ff0000u, 0x00123456u});
  Expected<Texture> texture = loadTexture(at("t.png"), /*srgb=*/false);
  ASSERT_TRUE(texture.ok()) << texture.error().message;
  EXPECT_EQ(texture->width, 2);
  EXPECT_EQ(texture->height, 2);
  EXPECT_FALSE(texture->srgb);
  EXPECT_EQ(texture->texels,
            (std::vector<uint32_t>{0xff0000ffu, 0xff00ff00u, 0x80ff0000u, 0x00123456u}));
}

TEST_F(ObjMaterials, RefusesAnImageOverTheSizeLimitBeforeDecoding) {
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

TEST_F(ObjMaterials, RejectsATruncatedImage) {
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

TEST_F(ObjMaterials, DecodesATextureFromMemory) {
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

TEST_F(ObjMaterials, FaceIndexPast32BitsIsAnErrorNotAWrap) {
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

TEST_F(ObjMaterials, NanAndInfPositionsDropTheirTriangles) {
  Expected<Model> model = loadObj(
      writeModel("v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nv 0 -Inf 0\nf 1 2 3\nf 1 2 4\nf 1 5 3\n"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->mesh.triangleCount(), 3u);
  EXPECT_EQ(model->nonfinite_triangles, 2u);  // read as 0, they would have been drawn
  EXPECT_FALSE(isFinite(trianglePositions(model->mesh, 1)[2]));
  EXPECT_FALSE(isFinite(trianglePositions(model->mesh, 2)[1]));
  EXPECT_TRUE(anyWarningContains(*model, "2 triangles have a NaN or infinite vertex"));
}

TEST_F(ObjMaterials, TextureThatIsAFifoIsSkippedWithoutBlocking) {
  writeModel("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  write(at("m.mtl"), "newmtl a\nmap_Kd fifo.png\n");
  ASSERT_EQ(::mkfifo(at("fifo.png").c_str(), 0600), 0);
  // Opening a FIFO for reading blocks until a writer comes: this would hang before the fix.
  Expected<Model> model = loadObj(at("model.obj"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->materials[0].albedo, nullptr);
  EXPECT_TRUE(anyWarningContains(*model, "fifo.png: is a FIFO"));
}

TEST_F(ObjMaterials, AFolderNamedAsATextureIsSaidToBeAFolder) {
  writeModel("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  write(at("m.mtl"), "newmtl a\nmap_Kd tex\n");
  fs::create_directories(at("tex"));
  Expected<Model> model = loadObj(at("model.obj"));
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(anyWarningContains(*model, "tex: is a directory"));
}

TEST_F(ObjMaterials, TrianglesOverTheBudgetAreRefusedBeforeParsing) {
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

TEST_F(ObjMaterials, TextureOverThePixelBudgetFailsTheModel) {
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

TEST_F(ObjMaterials, LibraryWarningsAreInTesserasWords) {
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

TEST_F(ObjMaterials, PngClaimingAHugeSizeIsOverTheBudgetNotUnreadable) {
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
