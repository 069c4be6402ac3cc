// Shared by the loader fuzz targets: a private scratch folder, and the invariants every loaded
// Model must keep whatever the input (a broken one aborts, so libFuzzer reports it).
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include <unistd.h>

#include <tessera/io/model_loader.h>

namespace tessera::fuzz {

// A folder of this process's own, made once and removed at exit: in /dev/shm when there is one
// (a file rewritten thousands of times a second on a disk file system costs a flush each time:
// ext4 syncs a file truncated and rewritten), else under the system temp folder.
inline const std::filesystem::path& scratchFolder(const char* format) {
  static const std::filesystem::path folder = [format] {
    const std::string name = "tessera_fuzz_" + std::string(format) + "_" +
                             std::to_string(static_cast<unsigned long>(::getpid()));
    std::error_code error;
    std::filesystem::path path = std::filesystem::path("/dev/shm") / name;
    if (!std::filesystem::create_directories(path, error) || error) {
      path = std::filesystem::temp_directory_path() / name;
      std::filesystem::create_directories(path);
    }
    static struct Remover {
      std::filesystem::path path;
      ~Remover() {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
      }
    } remover{path};
    return path;
  }();
  return folder;
}

inline void writeFile(const std::filesystem::path& path, const uint8_t* data, size_t size) {
  // A new file rather than a truncated one, for the same reason.
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

[[noreturn]] inline void broken(const char* what) {
  std::fprintf(stderr, "broken Model invariant: %s\n", what);
  std::abort();
}

// What the renderer relies on: something to draw, indices in range, attribute arrays empty or one
// per vertex, materials present and indexed in range, normals, points and line ends finite.
inline void checkModel(const Expected<io::Model>& loaded) {
  if (!loaded) {
    if (loaded.error().message.empty()) broken("an error without a message");
    return;
  }
  const io::Model& model = *loaded;
  const Mesh flattened = tessera::io::flattenedMesh(model);
  const Mesh& mesh = flattened;
  const size_t vertices = mesh.vertexCount();
  if (mesh.indices.size() % 3 != 0) broken("index count not a multiple of 3");
  if (mesh.triangleCount() == 0 && model.points.empty() && model.lines.points.empty())
    broken("a model with nothing to draw");
  // Points and lines: finite (the loaders drop the others), colours one per point or none, one
  // colour per segment.
  for (const float3& p : model.points.positions)
    if (!isFinite(p)) broken("a non-finite point");
  if (!model.points.colors.empty() && model.points.colors.size() != model.points.size())
    broken("point colours not one per point");
  if (model.lines.points.size() != 2 * model.lines.colors.size())
    broken("line colours not one per segment");
  for (const float3& p : model.lines.points)
    if (!isFinite(p)) broken("a non-finite line end");
  for (uint32_t index : mesh.indices)
    if (index >= vertices) broken("index past the vertices");
  if (mesh.normals.size() != vertices) broken("normals not one per vertex");
  if (!mesh.uvs.empty() && mesh.uvs.size() != vertices) broken("uvs not one per vertex");
  if (!mesh.colors.empty() && mesh.colors.size() != vertices) broken("colours not one per vertex");
  if (model.materials.empty()) broken("no material");
  if (!mesh.triangle_materials.empty()) {
    if (mesh.triangle_materials.size() != mesh.triangleCount())
      broken("triangle materials not one per triangle");
    for (uint16_t material : mesh.triangle_materials)
      if (material >= model.materials.size()) broken("material index past the materials");
  }
  for (const float3& n : mesh.normals)
    if (!isFinite(n)) broken("a non-finite normal");
  for (const Material& material : model.materials)
    if (material.albedo &&
        material.albedo->texels.size() != static_cast<size_t>(material.albedo->width) *
                                              static_cast<size_t>(material.albedo->height))
      broken("a texture whose texel count is not width * height");
  if (model.nonfinite_triangles > mesh.triangleCount())
    broken("more non-finite triangles than triangles");
}

// A 1x1 PNG, for fuzzed materials to refer to.
inline void writeTinyPng(const std::filesystem::path& path) {
  static const uint8_t kPng[] = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
      0x44, 0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00,
      0x00, 0x1f, 0x15, 0xc4, 0x89, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x44, 0x41, 0x54, 0x78,
      0x9c, 0x63, 0xf8, 0xcf, 0xc0, 0xf0, 0x1f, 0x00, 0x05, 0x00, 0x01, 0xff, 0x89, 0x99,
      0x3d, 0x1d, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  writeFile(path, kPng, sizeof kPng);
}

}  // namespace tessera::fuzz
