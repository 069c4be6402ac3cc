// A small animated glTF written by tests: a cube (side 1) whose node is moved (linear), turned
// (linear, slerp) and scaled (step) over 2 s by the clip "move", and optionally a camera.
// Shared by gltf_animation_test.cpp and viewer_window_animation_test.cpp.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <tessera/math/quat.h>

namespace tessera::test {

namespace fs = std::filesystem;

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

  // With a camera: a second root node holds a perspective camera at (0, 0, 6) looking down -Z
  // (yfov 0.3 rad), which the animation does not move.
  bool camera = false;

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
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[" +
        std::string(camera ? "0,1" : "0") + "]}],\"nodes\":[{\"mesh\":0}" +
        (camera ? ",{\"camera\":0,\"translation\":[0,0,6]}],\"cameras\":[{\"type\":"
                  "\"perspective\",\"perspective\":{\"yfov\":0.3,\"znear\":0.1}}]"
                : "]") +
        ","
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
        "\"buffers\":[{\"uri\":\"cube.bin\",\"byteLength\":" +
        std::to_string(bytes.size()) + "}],\"bufferViews\":[" + view(0, 96) + "," + view(1, 72) +
        "," + view(2, 12) + "," + view(3, 36) + "," + view(4, 48) + "," + view(5, 36) +
        "],"
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

}  // namespace tessera::test
