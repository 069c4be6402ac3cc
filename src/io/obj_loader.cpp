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
#include "obj_polygons.h"
#include "obj_scan.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wpedantic"
#include <tiny_obj_loader.h>
#pragma GCC diagnostic pop

namespace tessera::io {

namespace {

namespace fs = std::filesystem;

static_assert(std::is_same_v<tinyobj::real_t, float>,
              "link the float build of tinyobjloader (tinyobjloader::tinyobjloader)");

constexpr uintmax_t kMaxObjBytes = uintmax_t{2} << 30;
// MTL files are a few kilobytes of text; one this big is not a material library.
constexpr uintmax_t kMaxMtlBytes = uintmax_t{64} << 20;
// Mesh::triangle_materials holds uint16_t.
constexpr size_t kMaxMaterials = size_t{1} << 16;
// Distinct tinyobjloader warnings passed on per file; the rest are counted.
constexpr size_t kMaxLibraryWarnings = 10;

// The text between the first two `quote`s, or empty.
std::string_view between(std::string_view text, char quote) {
  const size_t begin = text.find(quote);
  const size_t end = begin == std::string_view::npos ? begin : text.find(quote, begin + 1);
  if (end == std::string_view::npos) return {};
  return text.substr(begin + 1, end - begin - 1);
}

// One of tinyobjloader's warnings in tessera's words (the ones a file can reach); any other is
// passed on with its values elided.
std::string inOwnWords(const std::string& line) {
  const std::string at_line = numberAfter(line, "line ");
  const std::string where = at_line.empty() ? "" : "line " + at_line + ": ";
  if (line.starts_with("material [")) {
    std::string name(between(line, '\''));
    if (name.empty()) name = trimmed(std::string_view(line).substr(10, line.find(']') - 10));
    return "usemtl '" + elided(name) + "': no such material in the MTL files; the default is used";
  }
  if (line.starts_with("Both `d` and `Tr`"))
    return "material '" + elided(between(line, '"')) + "' sets both d and Tr; d is used";
  if (line.starts_with("Empty group name")) return where + "a group without a name";
  if (line.starts_with("Looks like empty filename for mtllib"))
    return where + "an mtllib line names no file";
  if (line.starts_with("Failed parse `l'") || line.starts_with("Failed parse `p'"))
    return where + "a line or point element with a zero or unreadable index is skipped";
  return elided(line);
}

// Passes tinyobjloader's warnings on, except those this loader reports better itself.
void forwardLibraryWarnings(const std::string& file, const std::string& text,
                            std::vector<std::string>& warnings) {
  static constexpr std::string_view kReplaced[] = {
      "Degenerated face",        "Vertex indices out of bounds", "Vertex normal indices",
      "Vertex texcoord indices", "Failed to load material",      "Material file",
  };
  std::set<std::string> seen;
  size_t skipped = 0;
  size_t begin = 0;
  while (begin < text.size()) {
    size_t end = std::min(text.find('\n', begin), text.size());
    std::string line = trimmed(std::string_view(text).substr(begin, end - begin));
    begin = end + 1;
    // "Degenerated face found\n." leaves a '.' at the start of the next message.
    line.erase(0, line.find_first_not_of(". "));
    if (line.empty()) continue;
    bool replaced = std::any_of(std::begin(kReplaced), std::end(kReplaced),
                                [&](std::string_view prefix) { return line.starts_with(prefix); });
    if (replaced || !seen.insert(line).second) continue;
    if (seen.size() > kMaxLibraryWarnings) {
      ++skipped;
      continue;
    }
    warnings.push_back(file + ": " + inOwnWords(line));
  }
  if (skipped > 0)
    warnings.push_back(file + ": " + std::to_string(skipped) + " more warnings like these");
}

// ---- Material libraries ----

// Reads the MTL libraries the OBJ names, from beneath the OBJ's folder only, so tinyobjloader
// never opens a path itself. tinyobjloader passes names after its own splitting, which treats
// '\' as an escape and so mangles Windows paths, and it stops at the first library of an
// `mtllib` line that loads. So the first call loads every library of every `mtllib` line from
// the text as written (found by the line index) and later calls add nothing. A `usemtl` can then
// also find a material from a library named further down the file.
class FolderMaterialReader : public tinyobj::MaterialReader {
 public:
  FolderMaterialReader(fs::path folder, std::string obj_name,
                       const std::vector<std::string>& libraries,
                       std::vector<std::string>& warnings)
      : folder_(std::move(folder)),
        obj_name_(std::move(obj_name)),
        libraries_(libraries),
        warnings_(warnings) {}

  // Per library material (tinyobjloader's numbering): whether its MTL block set Kd.
  bool hasKd(size_t material) const { return material < has_kd_.size() && has_kd_[material]; }

  bool operator()(const std::string& /*tinyobj_name*/, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* material_map, std::string* /*warn*/,
                  std::string* /*err*/) override {
    if (done_) return true;
    done_ = true;
    // Each library once, however often it is named: a file cannot make us parse one repeatedly.
    std::set<fs::path> seen;
    for (const std::string& text : libraries_)
      for (const std::string& name : libraryNames(text)) load(name, materials, material_map, seen);
    return true;
  }

 private:
  // The names on one `mtllib` line. Exporters write a name with spaces either as it is or with
  // "\ "; a whole line that names an existing file is taken as one name.
  std::vector<std::string> libraryNames(const std::string& text) const {
    std::string whole = trimmed(text);
    if (whole.empty()) return {};
    Expected<fs::path> as_one = resolveReferencedFile(folder_, whole);
    std::error_code error;
    if (as_one && fs::is_regular_file(*as_one, error)) return {whole};
    std::vector<std::string> names;
    std::string current;
    for (size_t i = 0; i < whole.size(); ++i) {
      if (whole[i] == '\\' && i + 1 < whole.size() && whole[i + 1] == ' ') {
        current += ' ';
        ++i;
      } else if (isBlank(whole[i])) {
        if (!current.empty()) names.push_back(std::move(current));
        current.clear();
      } else {
        current += whole[i];
      }
    }
    if (!current.empty()) names.push_back(std::move(current));
    return names;
  }

  void load(const std::string& name, std::vector<tinyobj::material_t>* materials,
            std::map<std::string, int>* material_map, std::set<fs::path>& seen) {
    const std::string fallback = "; its materials fall back to the default";
    Expected<fs::path> path = resolveReferencedFile(folder_, name);
    if (!path) {
      warnings_.push_back(obj_name_ + ": material file '" + name +
                          "' refused: " + path.error().message + fallback);
      return;
    }
    if (!seen.insert(*path).second) return;
    const std::string path_name = path->string();
    Expected<std::vector<unsigned char>> bytes = readRegularFile(*path, kMaxMtlBytes, "MTL");
    if (!bytes) {
      warnings_.push_back(bytes.error().message + fallback);
      return;
    }
    std::stringstream stream(std::string(bytes->begin(), bytes->end()));
    const std::set<std::string> with_kd = materialsWithKd(stream);
    stream.clear();
    stream.seekg(0);
    std::string mtl_warnings, mtl_errors;
    const size_t first = materials->size();
    tinyobj::LoadMtl(material_map, materials, &stream, &mtl_warnings, &mtl_errors);
    for (size_t i = first; i < materials->size(); ++i)
      has_kd_.push_back(with_kd.contains((*materials)[i].name));
    forwardLibraryWarnings(path_name, mtl_warnings + mtl_errors, warnings_);
  }

  fs::path folder_;
  std::string obj_name_;
  const std::vector<std::string>& libraries_;
  std::vector<std::string>& warnings_;
  std::vector<char> has_kd_;
  bool done_ = false;
};

// Turns MTL materials into tessera materials, loading each texture once.
class MaterialBuilder {
 public:
  MaterialBuilder(fs::path folder, std::string obj_name, std::vector<std::string>& warnings,
                  const LoadBudget& budget)
      : folder_(std::move(folder)),
        obj_name_(std::move(obj_name)),
        warnings_(warnings),
        textures_(budget) {}

  // A texture over the budget: the model cannot be loaded.
  const std::optional<Error>& fatal() const { return fatal_; }

  Material build(const tinyobj::material_t& source, bool has_kd) {
    Material material;
    auto channel = [](float value, float fallback) {
      return std::isfinite(value) ? std::clamp(value, 0.0f, 1.0f) : fallback;
    };
    // Kd is taken as linear, like a glTF base colour factor: MTL does not say, and it is the
    // value a renderer multiplies by. `d` (or 1 - `Tr`, tinyobjloader's reading) is alpha.
    float3 kd{channel(source.diffuse[0], 0.8f), channel(source.diffuse[1], 0.8f),
              channel(source.diffuse[2], 0.8f)};
    float alpha = channel(source.dissolve, 1.0f);
    if (!source.diffuse_texname.empty()) {
      if (!has_kd) kd = float3{1, 1, 1};
      const tinyobj::texture_option_t& options = source.diffuse_texopt;
      const bool srgb = !equalsIgnoreCase(options.colorspace, "linear");
      material.albedo = texture(source.diffuse_texname, srgb, source.name);
      material.sampler.wrap = options.clamp ? TextureWrap::kClamp : TextureWrap::kRepeat;
      bool moved = false;
      for (int i = 0; i < 3; ++i)
        moved |= options.origin_offset[i] != 0.0f || options.scale[i] != 1.0f;
      if (moved)
        warnings_.push_back(obj_name_ + ": material '" + source.name +
                            "': texture offset and scale (-o, -s) are not supported; ignored");
    }
    material.base_color = float4{kd, alpha};
    return material;
  }

 private:
  std::shared_ptr<const Texture> texture(const std::string& reference, bool srgb,
                                         const std::string& material_name) {
    const std::string dropped = "; material '" + material_name + "' is drawn without it";
    Expected<fs::path> path = resolveReferencedFile(folder_, reference);
    if (!path) {
      warnings_.push_back(obj_name_ + ": texture '" + reference +
                          "' refused: " + path.error().message + dropped);
      return nullptr;
    }
    auto key = std::make_pair(path->string(), srgb);
    if (auto cached = cache_.find(key); cached != cache_.end()) return cached->second;
    std::shared_ptr<const Texture>& slot = cache_[key];
    Expected<MaterialTexture> loaded = textures_.load(*path, srgb);
    if (!loaded) {
      if (!fatal_) fatal_ = loaded.error();
      return nullptr;
    }
    if (!loaded->texture) warnings_.push_back(loaded->warning + dropped);
    slot = loaded->texture;
    return slot;
  }

  fs::path folder_;
  std::string obj_name_;
  std::vector<std::string>& warnings_;
  std::map<std::pair<std::string, bool>, std::shared_ptr<const Texture>> cache_;
  TextureBudget textures_;
  std::optional<Error> fatal_;
};

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
  return checkBudget(name, "vertex positions", lines.positions, budget.vertices(),
                     "--max-triangles");
}

Expected<Model> loadObjChecked(const fs::path& path, const LoadBudget& budget) {
  const std::string name = path.string();
  Expected<RegularFile> file = openRegularFile(path, kMaxObjBytes, "OBJ");
  if (!file) return file.error();
  // The stream owns the descriptor from here on.
  __gnu_cxx::stdio_filebuf<char> buffer(file->release(), std::ios::in | std::ios::binary);
  std::istream in(&buffer);

  const ObjLineIndex lines = scanObjLines(in);
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
  const size_t position_count = attrib.vertices.size() / 3;
  const size_t uv_count = attrib.texcoords.size() / 2;
  const size_t normal_count = attrib.normals.size() / 3;
  size_t face_count = 0, corner_count = 0;
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
    face_count += mesh.num_face_vertices.size();
    corner_count += corners;
  }
  if (face_count == 0) return makeError(name + ": no triangles (the file has no faces)");
  const FaceLocator locate(name,
                           lines.face_lines.size() == face_count ? &lines.face_lines : nullptr);

  auto vec3At = [](const std::vector<float>& values, size_t i) {
    return float3{values[3 * i], values[3 * i + 1], values[3 * i + 2]};
  };
  bool any_uv = false, all_normals = true, normals_usable = true;
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
        any_uv |= index.texcoord_index >= 0;
        if (index.normal_index < 0) {
          all_normals = false;
        } else {
          float3 normal = vec3At(attrib.normals, static_cast<size_t>(index.normal_index));
          normals_usable &= isFinite(normal) && length(normal) > 0.0f;
        }
      }
      ++face;
    }
  }
  if (corner_count > std::numeric_limits<uint32_t>::max())
    return makeError(name + ": too many face corners (" + std::to_string(corner_count) + ")");
  // The simplest honest rule: unless every corner has a usable normal from the file, generate
  // smooth, area-weighted normals for the whole mesh (mixing given and generated normals would
  // shade the seam between them).
  const bool use_file_normals = all_normals && normals_usable;
  if (all_normals && !normals_usable)
    model.warnings.push_back(name +
                             ": some normals are zero or not finite; smooth normals were "
                             "generated for the whole mesh");
  else if (!all_normals && normal_count > 0)
    model.warnings.push_back(name +
                             ": some faces have no normals; smooth normals were generated "
                             "for the whole mesh");
  const bool has_colors = !attrib.colors.empty() && attrib.colors.size() == attrib.vertices.size();

  // ---- Build the indexed mesh ----
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

  face = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    size_t corner = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++face) {
      const size_t n = shape.mesh.num_face_vertices[f];
      polygon.clear();
      polygon_vertices.clear();
      for (size_t c = 0; c < n; ++c, ++corner) {
        const tinyobj::index_t& index = shape.mesh.indices[corner];
        CornerKey key{index.vertex_index, index.texcoord_index,
                      use_file_normals ? index.normal_index : -1};
        auto [slot, added] = vertex_of.try_emplace(key, static_cast<uint32_t>(vertex_of.size()));
        const size_t position = static_cast<size_t>(index.vertex_index);
        if (added) {
          vertex_position.push_back(static_cast<uint32_t>(position));
          mesh.positions.push_back(vec3At(attrib.vertices, position));
          if (any_uv) {
            mesh.uvs.push_back(
                key.uv >= 0 ? float2{attrib.texcoords[2 * key.uv], attrib.texcoords[2 * key.uv + 1]}
                            : float2{0, 0});
          }
          if (use_file_normals)
            mesh.normals.push_back(
                normalize(vec3At(attrib.normals, static_cast<size_t>(key.normal))));
          if (has_colors) {
            // Vertex colours are linear (the architecture's convention); alpha is opaque.
            float3 rgb = vec3At(attrib.colors, position);
            for (int i = 0; i < 3; ++i)
              if (!std::isfinite(rgb[i])) rgb[i] = 1.0f;
            mesh.colors.push_back(float4{rgb, 1.0f});
          }
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
  if (!use_file_normals) {
    // Per OBJ position, so a seam in the texture coordinates does not show as a crease.
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
