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

#include "decode.h"
#include "run_process.h"
#include "temp_folder.h"

namespace fs = std::filesystem;

namespace tessera {
namespace {

// The cube's 8 corners and 12 triangles, then the animation's arrays, in one buffer.
struct AnimatedCubeFile {
  std::vector<float> positions;
  std::vector<uint16_t> indices;
  std::vector<float> times{0.0f, 1.0f, 2.0f};
  std::vector<float> translations{0, 0, 0, 2, 0, 0, 2, 1, 0};
  std::vector<float> rotations;  // about Y: 0, 90 and 180 degrees
  std::vector<float> scales{1, 1, 1, 0.5f, 0.5f, 0.5f, 1, 1, 1};

  AnimatedCubeFile() {
    for (int i = 0; i < 8; ++i)
      for (int a = 0; a < 3; ++a) positions.push_back((i >> a) & 1 ? 0.5f : -0.5f);
    const uint16_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces)
      for (uint16_t i : {f[0], f[1], f[2], f[0], f[2], f[3]}) indices.push_back(i);
    for (float degrees : {0.0f, 90.0f, 180.0f}) {
      const quat q = quat::fromAxisAngle({0, 1, 0}, degrees * 3.14159265f / 180.0f);
      rotations.insert(rotations.end(), {q.x, q.y, q.z, q.w});
    }
  }

  void write(const fs::path& folder) const {
    std::string bytes;
    auto append = [&](const void* data, size_t size) {
      bytes.append(static_cast<const char*>(data), size);
      while (bytes.size() % 4) bytes.push_back('\0');
    };
    std::vector<size_t> offsets;
    auto add = [&](const auto& v) {
      offsets.push_back(bytes.size());
      append(v.data(), v.size() * sizeof(v[0]));
    };
    add(positions), add(indices), add(times), add(translations), add(rotations), add(scales);
    std::ofstream(folder / "cube.bin", std::ios::binary) << bytes;
    auto view = [&](int i, size_t length) {
      return "{\"buffer\":0,\"byteOffset\":" + std::to_string(offsets[i]) +
             ",\"byteLength\":" + std::to_string(length) + "}";
    };
    const std::string json =
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
        "\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
        "\"buffers\":[{\"uri\":\"cube.bin\",\"byteLength\":" + std::to_string(bytes.size()) +
        "}],\"bufferViews\":[" + view(0, 96) + "," + view(1, 72) + "," + view(2, 12) + "," +
        view(3, 36) + "," + view(4, 48) + "," + view(5, 36) + "],"
        "\"accessors\":["
        "{\"bufferView\":0,\"componentType\":5126,\"count\":8,\"type\":\"VEC3\","
        "\"min\":[-0.5,-0.5,-0.5],\"max\":[0.5,0.5,0.5]},"
        "{\"bufferView\":1,\"componentType\":5123,\"count\":36,\"type\":\"SCALAR\"},"
        "{\"bufferView\":2,\"componentType\":5126,\"count\":3,\"type\":\"SCALAR\","
        "\"min\":[0],\"max\":[2]},"
        "{\"bufferView\":3,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
        "{\"bufferView\":4,\"componentType\":5126,\"count\":3,\"type\":\"VEC4\"},"
        "{\"bufferView\":5,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}],"
        "\"animations\":[{\"name\":\"move\",\"samplers\":["
        "{\"input\":2,\"output\":3},{\"input\":2,\"output\":4,\"interpolation\":\"LINEAR\"},"
        "{\"input\":2,\"output\":5,\"interpolation\":\"STEP\"}],\"channels\":["
        "{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"translation\"}},"
        "{\"sampler\":1,\"target\":{\"node\":0,\"path\":\"rotation\"}},"
        "{\"sampler\":2,\"target\":{\"node\":0,\"path\":\"scale\"}}]}]}";
    std::ofstream(folder / "cube.gltf") << json;
  }
};

class GltfAnimation : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::makeTestFolder("tessera_gltf_animation");
    AnimatedCubeFile().write(dir_);
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
