// glTF animations end to end: a cube whose node is moved (linear), turned (linear, slerp) and
// scaled (step) by a file written here; the loader's clip against the keyframes, the node's
// transform at t against the interpolation computed here, and `tessera render --animation-index`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <tessera/io/model_loader.h>
#include <tessera/scene/animation.h>
#include <tessera/scene/graph.h>

#include "animated_cube_file.h"
#include "decode.h"
#include "run_process.h"
#include "temp_folder.h"

namespace fs = std::filesystem;

namespace tessera {
namespace {

class GltfAnimation : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::makeTestFolder("tessera_gltf_animation");
    test::AnimatedCubeFile().write(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(GltfAnimation, TheClipMovesTheNodeAsTheKeyframesSay) {
  Expected<io::Model> model = io::loadModel(dir_ / "cube.gltf");
  ASSERT_TRUE(model.ok()) << model.error().message;
  SceneGraph& graph = model->graph;
  ASSERT_EQ(graph.animations.size(), 1u);
  const Animation& clip = graph.animations[0];
  EXPECT_EQ(clip.name, "move");
  EXPECT_EQ(clip.channels.size(), 3u);
  EXPECT_FLOAT_EQ(clip.duration(), 2.0f);
  EXPECT_EQ(clip.samplers[2].interpolation, Interpolation::kStep);

  // t = 1.5: half way from key 1 to key 2.
  clip.apply(1.5f, graph);
  graph.updateWorld();
  const Transform& local = graph.nodes[0].local;
  EXPECT_NEAR(local.translation.x, 2.0f, 1e-6f);
  EXPECT_NEAR(local.translation.y, 0.5f, 1e-6f);
  EXPECT_NEAR(local.scale.x, 0.5f, 1e-6f);  // stepped: key 1's until t = 2
  const quat q = quat::fromAxisAngle({0, 1, 0}, 135.0f * 3.14159265f / 180.0f);
  EXPECT_NEAR(std::abs(local.rotation.x * q.x + local.rotation.y * q.y + local.rotation.z * q.z +
                       local.rotation.w * q.w),
              1.0f, 1e-5f);
  // The world matrix moves the cube's corner (0.5, 0.5, 0.5) by T * R * S.
  const float4 corner = graph.world[0] * float4{0.5f, 0.5f, 0.5f, 1.0f};
  const float3 expected = float3{2.0f, 0.5f, 0.0f} + rotate(q, float3{0.25f, 0.25f, 0.25f});
  EXPECT_NEAR(corner.x, expected.x, 1e-5f);
  EXPECT_NEAR(corner.y, expected.y, 1e-5f);
  EXPECT_NEAR(corner.z, expected.z, 1e-5f);
}

TEST_F(GltfAnimation, RenderPlaysTheClipFrameByFrame) {
  test::RunResult r = test::runInFolder(
      dir_, TESSERA_EXE,
      "render cube.gltf --animation-index 0 --fps 4 --resolution 48x32 -o f/{frame}.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // 2 s at 4 fps: 8 frames, the last at 1.75 s (a loop joins it to the first).
  EXPECT_TRUE(fs::exists(dir_ / "f" / "0007.png"));
  EXPECT_FALSE(fs::exists(dir_ / "f" / "0008.png"));
  std::optional<test::DecodedPng> first = test::decodePng((dir_ / "f" / "0000.png").string());
  std::optional<test::DecodedPng> later = test::decodePng((dir_ / "f" / "0005.png").string());
  ASSERT_TRUE(first && later);
  EXPECT_NE(first->samples, later->samples);  // the cube moved
  r = test::runInFolder(dir_, TESSERA_EXE,
                        "render cube.gltf --animation-index 0 --frame-range 2:3 -o r/{frame}.png "
                        "--resolution 48x32");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "r" / "0000.png"));
  EXPECT_FALSE(fs::exists(dir_ / "r" / "0002.png"));

  r = test::runInFolder(dir_, TESSERA_EXE, "render cube.gltf --animation-index 1 -o x.gif");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("has 1 animation (--animation-index 0 to 0)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.gif"));
  r = test::runInFolder(dir_, TESSERA_EXE, "render cube.gltf --animation-index 0 -o one.png");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "one.png"));
}

TEST_F(GltfAnimation, AClipWithTimesNotIncreasingIsSkippedWithAWarning) {
  // Key times 0, 1, 2 become 0, 2, 2: the sampler is unplayable, the cube still loads.
  std::string bin;
  {
    std::ifstream in(dir_ / "cube.bin", std::ios::binary);
    bin.assign(std::istreambuf_iterator<char>(in), {});
  }
  const float two = 2.0f;
  const size_t times_offset = 96 + 72;
  std::memcpy(bin.data() + times_offset + 4, &two, 4);
  std::ofstream(dir_ / "cube.bin", std::ios::binary) << bin;
  Expected<io::Model> model = io::loadModel(dir_ / "cube.gltf");
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_TRUE(model->graph.animations.empty());
  bool warned = false;
  for (const std::string& w : model->warnings)
    warned = warned || (w.find("must increase") != std::string::npos &&
                        w.find("animation") != std::string::npos);
  EXPECT_TRUE(warned);
}

}  // namespace
}  // namespace tessera
