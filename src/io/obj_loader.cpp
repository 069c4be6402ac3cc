// Wavefront OBJ + MTL through tinyobjloader. tinyobjloader does the parsing; everything it hands
// back is validated here, polygons are split here (the triangle-id contract fixes the order), and
// every file the model refers to is opened here, only from beneath the model's folder.
#include <tessera/io/model_loader.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <new>
#include <numbers>
#include <optional>
#include <set>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <ext/stdio_filebuf.h>

#include <tessera/io/image_loader.h>

#include "load_budget.h"
#include "model_paths.h"
#include "obj_materials.h"
#include "obj_points.h"
#include "obj_polygons.h"
#include "obj_scan.h"

namespace tessera::io {

namespace {

namespace fs = std::filesystem;

static_assert(std::is_same_v<tinyobj::real_t, float>,
              "link the float build of tinyobjloader (tinyobjloader::tinyobjloader)");

constexpr uintmax_t kMaxObjBytes = uintmax_t{2} << 30;
// Mesh::triangle_materials holds uint16_t.
constexpr size_t kMaxMaterials = size_t{1} << 16;

// ---- Assembly ----

// One mesh vertex per distinct (position, uv, normal) triple; -1 for an attribute not used.
struct CornerKey {
  int position, uv, normal;
  bool operator==(const CornerKey&) const = default;
};

struct CornerKeyHash {
  size_t operator()(const CornerKey& key) const noexcept {
    uint64_t h = static_cast<uint32_t>(key.position) * 0x9E3779B97F4A7C15ull;
    h = (h ^ (h >> 31) ^ static_cast<uint32_t>(key.uv)) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 27) ^ static_cast<uint32_t>(key.normal)) * 0x94D049BB133111EBull;
    return static_cast<size_t>(h ^ (h >> 31));
  }
};

// Where a face is, for messages: its line when the line index agrees with tinyobjloader about
// how many faces there are, else its number.
class FaceLocator {
 public:
  FaceLocator(std::string file, const std::vector<uint32_t>* lines)
      : file_(std::move(file)), lines_(lines) {}
  std::string operator()(size_t face) const {
    if (lines_) return file_ + ":" + std::to_string((*lines_)[face]);
    return file_ + ": face " + std::to_string(face + 1);
  }

 private:
  std::string file_;
  const std::vector<uint32_t>* lines_;
};

// tinyobjloader's own failures (a zero or unreadable index) end in "... line N.)".
Error libraryError(const std::string& file, const std::string& message) {
  const std::string text = trimmed(message);
  const std::string line = numberAfter(text, "line ");
  const std::string where = line.empty() ? file + ": " : file + ":" + line + ": ";
  if (text.find("`f'") != std::string::npos)
    return makeError(where +
                     "cannot read the face: an index is 0, not a number, or followed by "
                     "other text");
  if (text.find("`vw'") != std::string::npos)
    return makeError(where + "a vertex weight with a negative joint index");
  if (text.find("`l'") != std::string::npos || text.find("`p'") != std::string::npos)
    return makeError(where + "cannot read a line or point element: an index is 0 or not a number");
  return makeError(where + "cannot read the file (" + elided(text) + ")");
}

std::string pastEnd(const char* what, int index, size_t count, const char* counted) {
  return std::string(what) + " index " + std::to_string(int64_t{index} + 1) + " is past the end (" +
         std::to_string(count) + " " + counted + ")";
}

// What the line scan finds that tinyobjloader would misread, and the budget, checked before
// tinyobjloader allocates anything.
Expected<void> checkScan(const std::string& name, const ObjLineIndex& lines,
                         const LoadBudget& budget) {
  if (!lines.bad_index.empty())
    return makeError(name + ":" + std::to_string(lines.bad_index_line) + ": face index " +
                     lines.bad_index + " is out of range (indices are at most 2147483647)");
  if (Expected<void> ok =
          checkBudget(name, "triangles", lines.triangles, budget.triangles(), "--max-triangles");
      !ok)
    return ok;
  // Without faces the positions are only points, drawn by the point pass: the points budget.
  const bool faces = hasFaceLines(lines);
  if (Expected<void> ok =
          checkBudget(name, "vertex positions", lines.positions,
                      faces ? budget.vertices() : std::max(budget.vertices(), budget.points()),
                      faces ? "--max-triangles" : "");
      !ok)
    return ok;
  return checkBudget(name, "points and line end points", objPointBudgetCount(lines),
                     budget.points(), "");
}

float3 vec3At(const std::vector<float>& values, size_t i) {
  return float3{values[3 * i], values[3 * i + 1], values[3 * i + 2]};
}

struct FaceCounts {
  size_t faces = 0, corners = 0;
};

// The faces tinyobjloader returned, counted, and their lists checked against each other.
Expected<FaceCounts> countFaces(const std::string& name,
                                const std::vector<tinyobj::shape_t>& shapes,
                                const ObjLineIndex& lines) {
  FaceCounts counts;
  for (const tinyobj::shape_t& shape : shapes) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    size_t corners = 0;
    for (unsigned char n : mesh.num_face_vertices) corners += n;
    // A face of 256+ corners wraps tinyobjloader's unsigned char count, so the counts no longer
    // add up to the corner list.
    if (corners != mesh.indices.size()) {
      if (lines.first_long_face_line > 0)
        return makeError(name + ":" + std::to_string(lines.first_long_face_line) + ": a face of " +
                         std::to_string(lines.first_long_face_corners) + " corners; at most " +
                         std::to_string(kMaxFaceCorners) + " are supported");
      return makeError(name + ": a face has more than " + std::to_string(kMaxFaceCorners) +
                       " corners, which is not supported");
    }
    if (mesh.material_ids.size() != mesh.num_face_vertices.size())
      return makeError(name + ": tinyobjloader returned inconsistent face data");
    counts.faces += mesh.num_face_vertices.size();
    counts.corners += corners;
  }
  return counts;
}

// Which attributes the face corners use, every index checked against its list first.
struct CornerUse {
  bool any_uv = false, all_normals = true, normals_usable = true;
};

Expected<CornerUse> checkCorners(const tinyobj::attrib_t& attrib,
                                 const std::vector<tinyobj::shape_t>& shapes,
                                 const FaceLocator& locate) {
  const size_t position_count = attrib.vertices.size() / 3;
  const size_t uv_count = attrib.texcoords.size() / 2;
  const size_t normal_count = attrib.normals.size() / 3;
  CornerUse use;
  size_t face = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    size_t corner = 0;
    for (unsigned char n : shape.mesh.num_face_vertices) {
      for (size_t c = 0; c < n; ++c, ++corner) {
        const tinyobj::index_t& index = shape.mesh.indices[corner];
        // Relative indices resolve against the count so far; one that reaches back too far
        // comes out negative.
        if (index.vertex_index < 0)
          return makeError(locate(face) +
                           ": a relative face index reaches before the first "
                           "position");
        if (static_cast<size_t>(index.vertex_index) >= position_count)
          return makeError(locate(face) + ": " +
                           pastEnd("face", index.vertex_index, position_count, "positions"));
        if (index.texcoord_index < -1)
          return makeError(locate(face) +
                           ": a relative texture coordinate index reaches before "
                           "the first one");
        if (index.texcoord_index >= 0 && static_cast<size_t>(index.texcoord_index) >= uv_count)
          return makeError(
              locate(face) + ": " +
              pastEnd("texture coordinate", index.texcoord_index, uv_count, "texture coordinates"));
        if (index.normal_index < -1)
          return makeError(locate(face) +
                           ": a relative normal index reaches before the first "
                           "normal");
        if (index.normal_index >= 0 && static_cast<size_t>(index.normal_index) >= normal_count)
          return makeError(locate(face) + ": " +
                           pastEnd("normal", index.normal_index, normal_count, "normals"));
        use.any_uv |= index.texcoord_index >= 0;
        if (index.normal_index < 0) {
          use.all_normals = false;
        } else {
          float3 normal = vec3At(attrib.normals, static_cast<size_t>(index.normal_index));
          use.normals_usable &= isFinite(normal) && length(normal) > 0.0f;
        }
      }
      ++face;
    }
  }
  return use;
}

// Smooth normals per OBJ position, so a seam in the texture coordinates does not show as a
// crease.
void smoothNormalsByPosition(Mesh& mesh, const std::vector<uint32_t>& vertex_position,
                             size_t position_count) {
  Mesh by_position;
  by_position.positions.resize(position_count);
  for (size_t v = 0; v < vertex_position.size(); ++v)
    by_position.positions[vertex_position[v]] = mesh.positions[v];
  by_position.indices.reserve(mesh.indices.size());
  for (uint32_t vertex : mesh.indices) by_position.indices.push_back(vertex_position[vertex]);
  generateSmoothNormals(by_position);
  mesh.normals.resize(mesh.positions.size());
  for (size_t v = 0; v < vertex_position.size(); ++v)
    mesh.normals[v] = by_position.normals[vertex_position[v]];
}

// What the mesh is built from.
struct ObjParts {
  const std::string& name;
  const fs::path& folder;
  const tinyobj::attrib_t& attrib;
  const std::vector<tinyobj::shape_t>& shapes;
  const std::vector<tinyobj::material_t>& library_materials;
  const FolderMaterialReader& reader;
  const FaceLocator& locate;
  const LoadBudget& budget;
};

struct MeshChoices {
  bool use_file_normals, any_uv, has_colors;
};

// The mesh's vertex for a new corner `key` of OBJ position `position`: its position and what
// `choices` keep of its texture coordinates, normal and colour.
void appendVertex(const tinyobj::attrib_t& attrib, const MeshChoices& choices, const CornerKey& key,
                  size_t position, Mesh& mesh) {
  mesh.positions.push_back(vec3At(attrib.vertices, position));
  if (choices.any_uv) {
    mesh.uvs.push_back(key.uv >= 0
                           ? float2{attrib.texcoords[2 * key.uv], attrib.texcoords[2 * key.uv + 1]}
                           : float2{0, 0});
  }
  if (choices.use_file_normals)
    mesh.normals.push_back(normalize(vec3At(attrib.normals, static_cast<size_t>(key.normal))));
  if (choices.has_colors) {
    // Vertex colours are linear (the architecture's convention); alpha is opaque.
    float3 rgb = vec3At(attrib.colors, position);
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(rgb[i])) rgb[i] = 1.0f;
    mesh.colors.push_back(float4{rgb, 1.0f});
  }
}

// The indexed mesh: one vertex per distinct corner, polygons split in the contract's order,
// materials in first-use order.
Expected<void> buildMesh(const ObjParts& parts, const MeshChoices& choices, size_t corner_count,
                         Model& model) {
  const auto& [name, folder, attrib, shapes, library_materials, reader, locate, budget] = parts;
  const size_t position_count = attrib.vertices.size() / 3;
  Mesh& mesh = model.mesh;
  std::vector<uint32_t> vertex_position;  // mesh vertex -> OBJ position
  std::unordered_map<CornerKey, uint32_t, CornerKeyHash> vertex_of;
  vertex_of.reserve(std::min<size_t>(corner_count, position_count * 2 + 16));
  // Model material per tinyobjloader material; slot 0 is "no material". Materials are added in
  // the order triangles first use them, so unused ones (and their textures) cost nothing.
  std::vector<int32_t> model_material(library_materials.size() + 1, -1);
  MaterialBuilder materials(folder, name, model.warnings, budget);
  PolygonSplitter splitter;
  std::vector<float3> polygon;
  std::vector<uint32_t> polygon_vertices, local_triangles;

  size_t face = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    size_t corner = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++face) {
      const size_t n = shape.mesh.num_face_vertices[f];
      polygon.clear();
      polygon_vertices.clear();
      for (size_t c = 0; c < n; ++c, ++corner) {
        const tinyobj::index_t& index = shape.mesh.indices[corner];
        CornerKey key{index.vertex_index, index.texcoord_index,
                      choices.use_file_normals ? index.normal_index : -1};
        auto [slot, added] = vertex_of.try_emplace(key, static_cast<uint32_t>(vertex_of.size()));
        const size_t position = static_cast<size_t>(index.vertex_index);
        if (added) {
          vertex_position.push_back(static_cast<uint32_t>(position));
          appendVertex(attrib, choices, key, position, mesh);
        }
        polygon.push_back(mesh.positions[slot->second]);
        polygon_vertices.push_back(slot->second);
      }

      const int library_id = shape.mesh.material_ids[f];
      const size_t material_slot =
          library_id >= 0 && static_cast<size_t>(library_id) < library_materials.size()
              ? static_cast<size_t>(library_id) + 1
              : 0;
      if (model_material[material_slot] < 0) {
        if (model.materials.size() == kMaxMaterials)
          return makeError(locate(face) + ": more than " + std::to_string(kMaxMaterials) +
                           " materials in use");
        model_material[material_slot] = static_cast<int32_t>(model.materials.size());
        model.materials.push_back(material_slot == 0
                                      ? Material{}
                                      : materials.build(library_materials[material_slot - 1],
                                                        reader.hasKd(material_slot - 1)));
      }
      if (materials.fatal()) return *materials.fatal();
      const auto material = static_cast<uint16_t>(model_material[material_slot]);

      local_triangles.clear();
      if (!splitter.split(polygon, local_triangles))
        return makeError(locate(face) +
                         ": the file's concave polygons are too complex to "
                         "triangulate in reasonable time");
      for (size_t t = 0; t < local_triangles.size(); t += 3) {
        bool finite = true;
        for (size_t i = 0; i < 3; ++i) {
          uint32_t vertex = polygon_vertices[local_triangles[t + i]];
          mesh.indices.push_back(vertex);
          finite &= isFinite(mesh.positions[vertex]);
        }
        mesh.triangle_materials.push_back(material);
        mesh.triangle_edges.push_back(PolygonSplitter::outlineEdges(&local_triangles[t], n));
        if (!finite) ++model.nonfinite_triangles;
      }
    }
  }

  if (std::ranges::all_of(mesh.triangle_edges, [](uint8_t e) { return e == kAllTriangleEdges; }))
    mesh.triangle_edges.clear();  // triangles only: every edge an outline
  if (!choices.use_file_normals) smoothNormalsByPosition(mesh, vertex_position, position_count);
  return {};
}

// The simplest honest rule: unless every corner has a usable normal from the file, generate
// smooth, area-weighted normals for the whole mesh (mixing given and generated normals would shade
// the seam between them). Warns when the file's normals are left out.
bool useFileNormals(const std::string& name, const CornerUse& use, size_t normal_count,
                    std::vector<std::string>& warnings) {
  if (use.all_normals && !use.normals_usable)
    warnings.push_back(name +
                       ": some normals are zero or not finite; smooth normals were generated for "
                       "the whole mesh");
  else if (!use.all_normals && normal_count > 0)
    warnings.push_back(name +
                       ": some faces have no normals; smooth normals were generated for the "
                       "whole mesh");
  return use.all_normals && use.normals_usable;
}

Expected<Model> loadObjChecked(const fs::path& path, const LoadBudget& budget) {
  const std::string name = path.string();
  Expected<RegularFile> file = openRegularFile(path, kMaxObjBytes, "OBJ");
  if (!file) return file.error();
  // The stream owns the descriptor from here on.
  __gnu_cxx::stdio_filebuf<char> buffer(file->release(), std::ios::in | std::ios::binary);
  std::istream in(&buffer);

  const ObjLineIndex lines = scanObjLines(in, budget.points() + 1);
  if (in.bad()) return makeError(name + ": read error");
  if (Expected<void> ok = checkScan(name, lines, budget); !ok) return ok.error();
  in.clear();
  in.seekg(0);

  Model model;
  fs::path folder = path.parent_path();
  if (folder.empty()) folder = ".";
  FolderMaterialReader reader(folder, name, lines.material_libraries, model.warnings);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> library_materials;
  std::string library_warnings, library_errors;
  // triangulate = false: polygons are split below, in the contract's order.
  // default_vcols_fallback = false: colours stay empty unless every `v` line has them.
  const bool parsed =
      tinyobj::LoadObj(&attrib, &shapes, &library_materials, &library_warnings, &library_errors,
                       &in, &reader, /*triangulate=*/false, /*default_vcols_fallback=*/false);
  if (!parsed) return libraryError(name, library_errors);
  // tinyobjloader reads nan and inf as 0; they are made what they say, so that their triangles
  // are dropped like any other non-finite one.
  for (uint64_t position : lines.nonfinite_positions)
    if (3 * position + 2 < attrib.vertices.size())
      attrib.vertices[3 * position] = std::numeric_limits<float>::quiet_NaN();
  forwardLibraryWarnings(name, library_warnings, model.warnings);
  if (lines.short_faces > 0)
    model.warnings.push_back(name + ": " + std::to_string(lines.short_faces) +
                             " faces with fewer than 3 corners skipped");

  // ---- Validate what tinyobjloader returned ----
  Expected<FaceCounts> counted = countFaces(name, shapes, lines);
  if (!counted) return counted.error();
  const size_t face_count = counted->faces, corner_count = counted->corners;
  if (Expected<void> ok =
          addObjPointsAndLines(name, attrib, lines, library_materials, reader, model);
      !ok)
    return ok.error();
  if (face_count == 0) {
    if (model.points.empty() && model.lines.points.empty())
      return makeError(name + ": nothing to draw: no faces, points or lines");
    model.materials.push_back(Material{});
    return model;
  }
  const FaceLocator locate(name,
                           lines.face_lines.size() == face_count ? &lines.face_lines : nullptr);

  Expected<CornerUse> use = checkCorners(attrib, shapes, locate);
  if (!use) return use.error();
  if (corner_count > std::numeric_limits<uint32_t>::max())
    return makeError(name + ": too many face corners (" + std::to_string(corner_count) + ")");
  const bool use_file_normals =
      useFileNormals(name, *use, attrib.normals.size() / 3, model.warnings);
  const bool has_colors = !attrib.colors.empty() && attrib.colors.size() == attrib.vertices.size();

  const ObjParts parts{name, folder, attrib, shapes, library_materials, reader, locate, budget};
  if (Expected<void> ok =
          buildMesh(parts, {use_file_normals, use->any_uv, has_colors}, corner_count, model);
      !ok)
    return ok.error();

  if (model.nonfinite_triangles > 0)
    model.warnings.push_back(name + ": " + std::to_string(model.nonfinite_triangles) +
                             " triangles have a NaN or infinite vertex position (kept so triangle "
                             "ids stay in load order; they are not drawn)");
  return model;
}

}  // namespace

Expected<Model> loadObj(const std::filesystem::path& path, const LoadBudget& budget) {
  try {
    return loadObjChecked(path, budget);
  } catch (const std::bad_alloc&) {
    return makeError(path.string() + ": out of memory while loading");
  } catch (const std::length_error&) {
    return makeError(path.string() + ": out of memory while loading");
  }
}

}  // namespace tessera::io
