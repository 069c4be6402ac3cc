// The OBJ tests' fixture: each test writes its own tiny files into a fresh folder
// (io_obj_test.cpp: faces, vertices, bad input; io_obj_materials_test.cpp: materials, textures,
// hostile input). Private to those two files: a copy in each, in an unnamed namespace.
#pragma once

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <tessera/io/image_loader.h>
#include <tessera/io/model_loader.h>

#include "stb_image_write.h"
#include "temp_folder.h"

namespace tessera::io {
namespace {

namespace fs = std::filesystem;

class ObjFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::makeTestFolder("tessera_io_obj");
    fs::create_directories(root_ / "model");
  }
  void TearDown() override { fs::remove_all(root_); }

  // A path beneath the model's folder.
  fs::path at(const std::string& relative) const { return root_ / "model" / relative; }

  fs::path write(const fs::path& path, const std::string& bytes) const {
    return test::writeFile(path, bytes);
  }
  fs::path writeModel(const std::string& text, const std::string& name = "model.obj") const {
    return write(at(name), text);
  }

  // A PNG of `width` x `height` RGBA texels (row 0 at the top), each RGBA as 0xAABBGGRR.
  static void writePng(const fs::path& path, int width, int height,
                       const std::vector<uint32_t>& texels) {
    fs::create_directories(path.parent_path());
    std::vector<unsigned char> bytes;
    for (uint32_t t : texels)
      for (int shift = 0; shift < 32; shift += 8) bytes.push_back((t >> shift) & 0xff);
    ASSERT_NE(stbi_write_png(path.string().c_str(), width, height, 4, bytes.data(), width * 4), 0);
  }
  static void writeSolidPng(const fs::path& path, uint32_t texel) {
    writePng(path, 2, 2, std::vector<uint32_t>(4, texel));
  }

  fs::path root_;
};

inline std::array<float3, 3> trianglePositions(const Mesh& mesh, size_t t) {
  return {mesh.positions[mesh.indices[3 * t]], mesh.positions[mesh.indices[3 * t + 1]],
          mesh.positions[mesh.indices[3 * t + 2]]};
}

inline bool anyWarningContains(const Model& model, const std::string& text) {
  for (const std::string& warning : model.warnings)
    if (warning.find(text) != std::string::npos) return true;
  return false;
}

inline std::string vertexLine(double x, double y, double z) {
  std::string line = "v ";
  for (double value : {x, y, z}) {
    line += std::to_string(value);
    line += ' ';
  }
  line.back() = '\n';
  return line;
}

// "f first first+1 ... last"
inline std::string faceLine(int first, int last) {
  std::string line = "f";
  for (int i = first; i <= last; ++i) {
    line += ' ';
    line += std::to_string(i);
  }
  return line + "\n";
}

inline void expectNear3(float3 actual, float3 expected) {
  EXPECT_NEAR(actual.x, expected.x, 1e-6f);
  EXPECT_NEAR(actual.y, expected.y, 1e-6f);
  EXPECT_NEAR(actual.z, expected.z, 1e-6f);
}

[[maybe_unused]] const char* kTwoTriangleHeader =
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 1 1 0\n"
    "v 0 1 0\n";

}  // namespace
}  // namespace tessera::io
