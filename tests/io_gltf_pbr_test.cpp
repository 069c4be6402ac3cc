// glTF's metallic-roughness materials as tessera reads them (docs/formats.md): factors, maps in
// their colour spaces, tangents, and the bad input that leaves a map out with a warning.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <tessera/io/model_loader.h>

#include "gltf_test_files.h"

namespace tessera::io {
namespace {

using namespace gltf_test;  // NOLINT(google-build-using-namespace)

// A grey (one-channel) PNG.
std::vector<uint8_t> greyPng(int width, int height) {
  std::vector<unsigned char> grey(static_cast<size_t>(width * height), 128);
  int length = 0;
  unsigned char* png = stbi_write_png_to_mem(grey.data(), width, width, height, 1, &length);
  std::vector<uint8_t> out(png, png + length);
  STBIW_FREE(png);
  return out;
}

std::string imageUri(const std::vector<uint8_t>& png) {
  return "{\"uri\":\"data:image/png;base64," + base64(png) + "\"}";
}

// One triangle with normals, UVs and (when `tangents` is not empty) TANGENT, drawn with material
// `material` (JSON); textures 0 and 1 over images 0 (RGBA) and 1 (grey).
class GltfPbr : public GltfFiles {
 protected:
  Expected<Model> loadWith(const std::string& material, const std::vector<float>& tangents = {},
                           size_t tangent_count = 3) {
    GltfBuilder b;
    const int p = b.positions(kTriangle);
    const int n = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1}, kFloat, "VEC3", 3);
    const int uv = b.accessor(std::vector<float>{0, 1, 1, 1, 0, 0}, kFloat, "VEC2", 3);
    std::string attributes =
        ",\"NORMAL\":" + std::to_string(n) + ",\"TEXCOORD_0\":" + std::to_string(uv);
    if (!tangents.empty())
      attributes +=
          ",\"TANGENT\":" + std::to_string(b.accessor(tangents, kFloat, "VEC4", tangent_count));
    return loadJson(b.json(
        kOneNodeScene + "," + oneMesh(p, attributes, ",\"material\":0") + ",\"materials\":[" +
        material + "],\"textures\":[{\"source\":0},{\"source\":1}],\"images\":[" +
        imageUri(pngBytes(2, 2, {0xff2080ffu, 0xff2080ffu, 0xff2080ffu, 0xff2080ffu})) + "," +
        imageUri(greyPng(2, 2)) + "]"));
  }
};

TEST_F(GltfPbr, ReadsFactorsAndMapsInTheirColourSpaces) {
  Expected<Model> model = loadWith(
      "{\"pbrMetallicRoughness\":{\"metallicFactor\":0.25,\"roughnessFactor\":0.5,"
      "\"metallicRoughnessTexture\":{\"index\":0}},\"normalTexture\":{\"index\":0,\"scale\":0.5},"
      "\"occlusionTexture\":{\"index\":0,\"strength\":0.75},\"emissiveTexture\":{\"index\":0},"
      "\"emissiveFactor\":[1,0.5,0.25],\"alphaMode\":\"MASK\",\"alphaCutoff\":0.3}");
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_EQ(model->materials.size(), 1u);
  const Material& m = model->materials[0];
  EXPECT_FLOAT_EQ(m.metallic, 0.25f);
  EXPECT_FLOAT_EQ(m.roughness, 0.5f);
  ASSERT_TRUE(m.metallic_roughness && m.normal && m.occlusion && m.emissive);
  EXPECT_FALSE(m.metallic_roughness.texture->srgb);
  EXPECT_FALSE(m.normal.texture->srgb);
  EXPECT_FALSE(m.occlusion.texture->srgb);
  EXPECT_TRUE(m.emissive.texture->srgb);
  // One image, decoded once per colour space.
  EXPECT_EQ(m.normal.texture, m.metallic_roughness.texture);
  EXPECT_FLOAT_EQ(m.normal_scale, 0.5f);
  EXPECT_FLOAT_EQ(m.occlusion_strength, 0.75f);
  EXPECT_FLOAT_EQ(m.emissive_factor.y, 0.5f);
  EXPECT_EQ(m.alpha_mode, AlphaMode::kMask);
  EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.3f);
  // No TANGENT: generated for the normal map, along +u (glTF's u runs along +x here).
  const Mesh mesh = flattenedMesh(*model);
  ASSERT_EQ(mesh.tangents.size(), 3u);
  EXPECT_NEAR(mesh.tangents[0].x, 1.0f, 1e-6f);
  EXPECT_TRUE(model->warnings.empty()) << allWarnings(*model);
}

TEST_F(GltfPbr, MetallicAndRoughnessDefaultToOne) {
  Expected<Model> model = loadWith("{}");
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(model->materials[0].metallic, 1.0f);
  EXPECT_EQ(model->materials[0].roughness, 1.0f);
  EXPECT_TRUE(flattenedMesh(*model).tangents.empty());  // no normal map: no tangents
}

TEST_F(GltfPbr, BadMapsAreLeftOutWithAWarning) {
  // A texture index past the textures, a grey normal map: each map left out, the rest kept.
  Expected<Model> model = loadWith(
      "{\"pbrMetallicRoughness\":{\"metallicFactor\":0.5,\"metallicRoughnessTexture\":"
      "{\"index\":7}},\"normalTexture\":{\"index\":1},\"emissiveTexture\":{\"index\":0}}");
  ASSERT_TRUE(model) << model.error().message;
  const Material& m = model->materials[0];
  EXPECT_FALSE(m.metallic_roughness);
  EXPECT_FALSE(m.normal);
  EXPECT_TRUE(m.emissive);
  EXPECT_FLOAT_EQ(m.metallic, 0.5f);
  EXPECT_TRUE(anyWarningContains(*model, "texture 7, which does not exist")) << allWarnings(*model);
  EXPECT_TRUE(anyWarningContains(*model, "normalTexture is not an RGB image"))
      << allWarnings(*model);
}

TEST_F(GltfPbr, TangentsOfTheFileAreKeptAndAWrongCountLeavesTheNormalMapOut) {
  const std::vector<float> tangents = {0, 1, 0, -1, 0, 1, 0, -1, 0, 1, 0, -1};
  const std::string mapped = "{\"normalTexture\":{\"index\":0}}";
  Expected<Model> model = loadWith(mapped, tangents);
  ASSERT_TRUE(model) << model.error().message;
  const Mesh mesh = flattenedMesh(*model);
  ASSERT_EQ(mesh.tangents.size(), 3u);
  EXPECT_EQ(mesh.tangents[1].y, 1.0f);
  EXPECT_EQ(mesh.tangents[1].w, -1.0f);
  EXPECT_TRUE(model->warnings.empty()) << allWarnings(*model);
  // Two tangents for three vertices.
  model = loadWith(mapped, {0, 1, 0, 1, 0, 1, 0, 1}, 2);
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_TRUE(flattenedMesh(*model).tangents.empty());
  EXPECT_TRUE(anyWarningContains(*model, "TANGENT has 2 elements")) << allWarnings(*model);
  EXPECT_TRUE(anyWarningContains(*model, "the normal map is left out")) << allWarnings(*model);
}

}  // namespace
}  // namespace tessera::io
