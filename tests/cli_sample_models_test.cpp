// Sample models nobody here wrote (Debian's assimp-testmodels), rendered by the CLI and compared
// with their reference images in tests/reference.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "reference.h"
#include "run_process.h"
#include "temp_folder.h"

namespace {

namespace fs = std::filesystem;

const fs::path kSamples = "/usr/share/assimp/models/glTF2";

class CliSampleModels : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = tessera::test::makeTestFolder("tessera_cli_samples"); }
  void TearDown() override { fs::remove_all(dir_); }
  tessera::test::RunResult run(const std::string& args) {
    return tessera::test::runInFolder(dir_, TESSERA_EXE, args);
  }
  fs::path dir_;
};

// KHR_texture_transform's test model: six quads whose offset, rotation and scale each show a
// green marker (or the whole texture) where applied as the extension says, yellow where not
// applied and red where rotated the wrong way. Unlit, so that only the sampling shows.
TEST_F(CliSampleModels, TextureTransformTestShowsEverySquareCorrect) {
  const fs::path model = kSamples / "textureTransform" / "TextureTransformTest.gltf";
  ASSERT_TRUE(fs::exists(model)) << model << ": scripts/setup.sh installs assimp-testmodels";
  const std::string out = (dir_ / "transform.png").string();
  tessera::test::RunResult r =
      run("render '" + model.string() + "' --resolution 240,180 --shading unlit -o '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << "warned: " << r.err;  // the extension is applied, not skipped
  tessera::test::expectMatchesReference(out, "texture_transform_gltf", {2, 6});
}

// KHR_materials_clearcoat's test model, front on: tessera draws the base layer (the extension's
// coat is not read), so the "Base layer" and "Coated" columns match and "Coating only" is the
// black base; the base normal map's ridges show in its row. The labels are an unlit texture.
TEST_F(CliSampleModels, ClearCoatTestDrawsItsBaseLayer) {
  const fs::path model = kSamples / "ClearCoat-glTF" / "ClearCoatTest.gltf";
  ASSERT_TRUE(fs::exists(model)) << model << ": scripts/setup.sh installs assimp-testmodels";
  const std::string out = (dir_ / "clearcoat.png").string();
  tessera::test::RunResult r = run(
      "render '" + model.string() +
      "' --resolution 240,300 --camera-position -2.1,0.3,30 --camera-focal-point -2.1,0.3,0 -o '" +
      out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  tessera::test::expectMatchesReference(out, "clearcoat_gltf", {2, 6});
}

// KHR_materials_pbrSpecularGlossiness's textured box: drawn through the metallic-roughness
// fallback the file carries (the Cesium logo on every face), as glTF readers without the
// extension must.
TEST_F(CliSampleModels, SpecularGlossinessBoxDrawsItsFallback) {
  const fs::path model = kSamples / "BoxTextured-glTF-pbrSpecularGlossiness" / "BoxTextured.gltf";
  ASSERT_TRUE(fs::exists(model)) << model << ": scripts/setup.sh installs assimp-testmodels";
  const std::string out = (dir_ / "specgloss.png").string();
  tessera::test::RunResult r =
      run("render '" + model.string() + "' --resolution 240,180 -o '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  tessera::test::expectMatchesReference(out, "box_specular_glossiness_gltf", {2, 6});
}

// A box whose material reads its base colour through TEXCOORD_0 and its metallic-roughness map
// (the same image) through TEXCOORD_1, as glTF lets each textureInfo choose: the texture's green
// and white shapes on every face, each face's roughness from the other set, no warning.
TEST_F(CliSampleModels, BoxTexcoordsReadsEachMapThroughItsOwnSet) {
  const fs::path model = kSamples / "BoxTexcoords-glTF" / "boxTexcoords.gltf";
  ASSERT_TRUE(fs::exists(model)) << model << ": scripts/setup.sh installs assimp-testmodels";
  const std::string out = (dir_ / "box_texcoords.png").string();
  tessera::test::RunResult r =
      run("render '" + model.string() + "' --resolution 240,180 -o '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("TEXCOORD"), std::string::npos) << "warned: " << r.err;
  tessera::test::expectMatchesReference(out, "box_texcoords_gltf", {2, 6});
}

}  // namespace
