// Model loaders. Every file is treated as hostile: a malformed, truncated or huge file ends in
// one Error naming the file (and line for text formats); never a crash, hang or unbounded
// allocation.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/scene/scene.h>

namespace tessera::io {

struct Model {
  Mesh mesh;                          // triangles in the contract's load order
  std::vector<Material> materials;    // at least one; Mesh::triangle_materials indexes these
  std::vector<std::string> warnings;  // things skipped or replaced (missing MTL, NaN vertices...)
  size_t nonfinite_triangles = 0;     // triangles with a NaN or infinite vertex (kept in the list
                                      // so ids stay in load order; the renderer drops them)
};

// By extension (case-insensitive): .obj.
Expected<Model> loadModel(const std::filesystem::path& path);

// Wavefront OBJ with its MTL files (tinyobjloader). Faces in file order; convex polygons are
// fan-split from their first vertex, concave ones ear-clipped. Missing normals are generated
// (smooth, area-weighted). Materials are listed in the order triangles first use them; faces
// without one get a default Material (0.8 grey). MTL files and textures are read only from
// beneath the OBJ's folder; anything else is skipped with a warning.
Expected<Model> loadObj(const std::filesystem::path& path);

}  // namespace tessera::io
