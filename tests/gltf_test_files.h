// What the glTF loader's tests share: a builder of small glTF and GLB files (JSON with the
// buffer in a data: URI, or a GLB assembled here), the GltfFiles fixture that writes them into a
// test folder, and the checks the tests make of a loaded model.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <tessera/io/model_loader.h>

#include "stb_image_write.h"
#include "temp_folder.h"

namespace tessera::io::gltf_test {
namespace fs = std::filesystem;

inline std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t n = uint32_t{bytes[i]} << 16;
    if (i + 1 < bytes.size()) n |= uint32_t{bytes[i + 1]} << 8;
    if (i + 2 < bytes.size()) n |= bytes[i + 2];
    out += kDigits[(n >> 18) & 63];
    out += kDigits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

template <typename T>
void appendValues(std::vector<uint8_t>& out, const std::vector<T>& values) {
  const size_t at = out.size();
  out.resize(at + values.size() * sizeof(T));
  std::memcpy(out.data() + at, values.data(), values.size() * sizeof(T));
}

constexpr int kByte = 5121;   // UNSIGNED_BYTE
constexpr int kShort = 5123;  // UNSIGNED_SHORT
constexpr int kUint = 5125;   // UNSIGNED_INT
constexpr int kFloat = 5126;

// Builds the binary side of a glTF file: one buffer, one bufferView per accessor. The JSON for
// nodes, meshes and materials is written by each test.
class GltfBuilder {
 public:
  // An accessor over `values` (tightly packed), returning its index.
  template <typename T>
  int accessor(const std::vector<T>& values, int component_type, const std::string& type,
               size_t count, const std::string& extra = "") {
    const int view = bufferView(values);
    accessors_.push_back("{\"bufferView\":" + std::to_string(view) +
                         ",\"componentType\":" + std::to_string(component_type) + ",\"type\":\"" +
                         type + "\",\"count\":" + std::to_string(count) + extra + "}");
    return static_cast<int>(accessors_.size()) - 1;
  }
  int positions(const std::vector<float3>& points) {
    std::vector<float> values;
    for (float3 p : points) values.insert(values.end(), {p.x, p.y, p.z});
    return accessor(values, kFloat, "VEC3", points.size());
  }
  int indices(const std::vector<uint16_t>& values) {
    return accessor(values, kShort, "SCALAR", values.size());
  }
  // A bufferView over `values`, 4-byte aligned, returning its index.
  template <typename T>
  int bufferView(const std::vector<T>& values, const std::string& extra = "") {
    while (bytes_.size() % 4 != 0) bytes_.push_back(0);
    const size_t offset = bytes_.size();
    appendValues(bytes_, values);
    views_.push_back("{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) +
                     ",\"byteLength\":" + std::to_string(values.size() * sizeof(T)) + extra + "}");
    return static_cast<int>(views_.size()) - 1;
  }
  // A raw accessor, written as given.
  int rawAccessor(const std::string& json) {
    accessors_.push_back(json);
    return static_cast<int>(accessors_.size()) - 1;
  }

  // The whole JSON: `body` holds the other top-level members ("nodes": ..., "meshes": ...).
  // `buffer_uri` empty: the buffer in a data: URI; "GLB": no URI (the binary chunk).
  std::string json(const std::string& body, const std::string& buffer_uri = "") const {
    std::string buffer = "{\"byteLength\":" + std::to_string(bytes_.size());
    if (buffer_uri.empty())
      buffer += ",\"uri\":\"data:application/octet-stream;base64," + base64(bytes_) + "\"";
    else if (buffer_uri != "GLB")
      buffer += ",\"uri\":\"" + buffer_uri + "\"";
    buffer += "}";
    std::string out = "{\"asset\":{\"version\":\"2.0\"}";
    if (!bytes_.empty()) {
      out += ",\"buffers\":[" + buffer + "]";
      out += ",\"bufferViews\":[" + joined(views_) + "]";
      out += ",\"accessors\":[" + joined(accessors_) + "]";
    }
    if (!body.empty()) out += "," + body;
    return out + "}";
  }

  // A GLB of the JSON (buffer 0 in the binary chunk).
  std::vector<uint8_t> glb(const std::string& body) const {
    std::string text = json(body, "GLB");
    while (text.size() % 4 != 0) text += ' ';
    std::vector<uint8_t> bin = bytes_;
    while (bin.size() % 4 != 0) bin.push_back(0);
    std::vector<uint8_t> out;
    auto u32 = [&](uint32_t v) { appendValues(out, std::vector<uint32_t>{v}); };
    const size_t total = 12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size());
    u32(0x46546C67);
    u32(2);
    u32(static_cast<uint32_t>(total));
    u32(static_cast<uint32_t>(text.size()));
    u32(0x4E4F534A);
    out.insert(out.end(), text.begin(), text.end());
    if (!bin.empty()) {
      u32(static_cast<uint32_t>(bin.size()));
      u32(0x004E4942);
      out.insert(out.end(), bin.begin(), bin.end());
    }
    return out;
  }

  const std::vector<uint8_t>& bytes() const { return bytes_; }

 private:
  static std::string joined(const std::vector<std::string>& parts) {
    std::string out;
    for (const std::string& part : parts) out += (out.empty() ? "" : ",") + part;
    return out;
  }

  std::vector<uint8_t> bytes_;
  std::vector<std::string> views_;
  std::vector<std::string> accessors_;
};

class GltfFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::makeTestFolder("tessera_io_gltf");
    fs::create_directories(root_ / "model");
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path at(const std::string& relative) const { return root_ / "model" / relative; }
  fs::path write(const fs::path& path, const std::string& bytes) const {
    return test::writeFile(path, bytes);
  }
  fs::path write(const fs::path& path, const std::vector<uint8_t>& bytes) const {
    return write(path, std::string(bytes.begin(), bytes.end()));
  }
  Expected<Model> loadJson(const std::string& json, const std::string& name = "model.gltf") {
    return loadGltf(write(at(name), json));
  }
  Expected<Model> loadJson(const std::string& json, const LoadBudget& budget) {
    return loadGltf(write(at("model.gltf"), json), budget);
  }
  // A budget no count in these tests reaches, to test the checks behind it.
  static LoadBudget unlimited() {
    LoadBudget budget;
    budget.max_triangles = uint64_t{1} << 40;
    return budget;
  }

  fs::path root_;
};

// A PNG of `width` x `height` RGBA texels (row 0 at the top), each RGBA as 0xAABBGGRR.
inline std::vector<uint8_t> pngBytes(int width, int height, const std::vector<uint32_t>& texels) {
  std::vector<unsigned char> rgba;
  for (uint32_t t : texels)
    for (int shift = 0; shift < 32; shift += 8) rgba.push_back((t >> shift) & 0xff);
  int length = 0;
  unsigned char* png = stbi_write_png_to_mem(rgba.data(), width * 4, width, height, 4, &length);
  std::vector<uint8_t> out(png, png + length);
  STBIW_FREE(png);
  return out;
}

inline std::array<float3, 3> trianglePositions(const Mesh& mesh, size_t t) {
  return {mesh.positions[mesh.indices[3 * t]], mesh.positions[mesh.indices[3 * t + 1]],
          mesh.positions[mesh.indices[3 * t + 2]]};
}

inline void expectNear3(float3 actual, float3 expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// The unnormalized geometric normal of triangle t (counter-clockwise is front).
inline float3 faceNormal(const Mesh& mesh, size_t t) {
  std::array<float3, 3> p = trianglePositions(mesh, t);
  return cross(p[1] - p[0], p[2] - p[0]);
}

inline bool anyWarningContains(const Model& model, const std::string& text) {
  for (const std::string& warning : model.warnings)
    if (warning.find(text) != std::string::npos) return true;
  return false;
}

inline std::string allWarnings(const Model& model) {
  std::string out;
  for (const std::string& warning : model.warnings) out += warning + "\n";
  return out;
}

inline void expectErrorContains(const Expected<Model>& model, const std::string& text) {
  ASSERT_FALSE(model) << "loaded, with warnings:\n" << allWarnings(*model);
  EXPECT_NE(model.error().message.find(text), std::string::npos) << model.error().message;
}

// One triangle in z = 0, counter-clockwise from +z, with +z normals.
const std::vector<float3> kTriangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};

inline std::string oneMesh(int positions, const std::string& extra_attributes = "",
                           const std::string& primitive_extra = "") {
  return "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(positions) +
         extra_attributes + "}" + primitive_extra + "}]}]";
}

const std::string kOneNodeScene = "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}]";

}  // namespace tessera::io::gltf_test
