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

}  // namespace
