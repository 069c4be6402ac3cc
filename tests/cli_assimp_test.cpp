// The CLI with formats read through assimp: a PLY rendered to PNG, and the readers list.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "decode.h"
#include "run_process.h"
#include "temp_folder.h"

namespace {

namespace fs = std::filesystem;
using tessera::test::DecodedPng;
using tessera::test::RunResult;

class CliAssimp : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = tessera::test::makeTestFolder("tessera_cli_assimp"); }
  void TearDown() override { fs::remove_all(dir_); }
  RunResult run(const std::string& args) {
    return tessera::test::runInFolder(dir_, TESSERA_EXE, args);
  }
  fs::path dir_;
};

// A unit cube, the six faces as quads with per-vertex colours.
const char* kCubePly =
    "ply\nformat ascii 1.0\nelement vertex 8\n"
    "property float x\nproperty float y\nproperty float z\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    "element face 6\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 255 255 0\n"
    "0 0 1 255 0 255\n1 0 1 0 255 255\n1 1 1 255 255 255\n0 1 1 128 128 128\n"
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 1 2 6 5\n4 0 4 7 3\n";

TEST_F(CliAssimp, RendersAPlyWithASensibleShareOfTheFrameCovered) {
  tessera::test::writeFile(dir_ / "cube.ply", kCubePly);
  RunResult r = run("render cube.ply --resolution 160,120 -o out.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  DecodedPng png;
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "out.png").string(), png));
  ASSERT_EQ(png.width, 160);
  ASSERT_EQ(png.height, 120);
  // The corner is background (the camera frames the model in the middle).
  const auto background = png.rgb(0, 0);
  size_t covered = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) {
      const auto c = png.rgb(x, y);
      int difference = 0;
      for (int i = 0; i < 3; ++i) difference += std::abs(c[i] - background[i]);
      covered += difference > 12;
    }
  const double share = static_cast<double>(covered) / (png.width * png.height);
  EXPECT_GT(share, 0.10) << covered;
  EXPECT_LT(share, 0.90) << covered;
}

TEST_F(CliAssimp, ReadersListNamesTesserasAndAssimpsFormats) {
  RunResult r = run("info --readers-list");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* expected : {".ply", ".fbx", ".dae", ".off", ".3ds", ".3mf", "PLY", "FBX", ".obj",
                               ".gltf", ".glb", ".stl", "assimp", "tessera"})
    EXPECT_NE(r.out.find(expected), std::string::npos) << expected << "\n" << r.out;
}

TEST_F(CliAssimp, UnreadableFileFailsWithOneLine) {
  tessera::test::writeFile(dir_ / "broken.fbx", std::string(500, 'q'));
  RunResult r = run("render broken.fbx -o out.png");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("broken.fbx: assimp cannot read it: "), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out.png"));
}

}  // namespace
