// glTF 2.0 (JSON and GLB) through tinygltf: the loader's entry points and the flattening of the
// node graph into one mesh in the contract's order. The rest is split by concern:
// gltf_container (checks before tinygltf sees a file), gltf_files (the files a glTF names),
// gltf_nodes (scene roots, the tree check, transforms), gltf_accessors (checked buffer reads)
// and gltf_materials (materials and images). Everything tinygltf hands back is checked before a
// byte of a buffer is read.
#include <tessera/io/model_loader.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <new>
#include <optional>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <tessera/io/image_loader.h>

#include "gltf_accessors.h"
#include "gltf_container.h"
#include "gltf_files.h"
#include "gltf_lights.h"
#include "gltf_materials.h"
#include "gltf_nodes.h"
#include "gltf_transforms.h"
#include "load_budget.h"
#include "model_paths.h"

// The one translation unit that compiles tinygltf itself.
#define TINYGLTF_IMPLEMENTATION
#include "tinygltf_include.h"

namespace tessera::io {

namespace {

namespace fs = std::filesystem;
using namespace gltf;

// tinygltf takes lengths as unsigned int; 2 GiB keeps every offset well inside that.
constexpr uintmax_t kMaxGltfBytes = uintmax_t{2} << 30;
// Distinct warnings listed per file; the rest are counted.
constexpr size_t kMaxWarnings = 20;

// ---- The flattening ----

class Flattener {
 public:
  Flattener(const tinygltf::Model& gltf, std::string name, fs::path folder, uintmax_t source_bytes,
            const LoadBudget& budget, Model& model)
      : gltf_(gltf),
        budget_(budget),
        name_(std::move(name)),
        folder_(std::move(folder)),
        // Accessors without a buffer view are all zeros (before sparse values): their size is
        // not backed by the file, so it is bounded by it.
        implied_bytes_left_(16 * source_bytes + (uintmax_t{1} << 20)),
        model_(model),
        materials_(gltf, name_, folder_, budget, warner(),
                   [this](const std::string& text) { warnAbout(text); }) {}

  Expected<void> run() {
    if (Expected<void> ok = checkExtensions(); !ok) return ok;
    Expected<std::vector<int>> roots = sceneRoots(gltf_, name_, warner());
    if (!roots) return roots.error();
    if (Expected<void> ok = checkNodeTree(gltf_, name_); !ok) return ok;
    if (Expected<void> ok = checkDrawnCounts(*roots); !ok) return ok;

    // Depth-first, a node's own mesh before its children, without recursion (a hierarchy may be
    // as deep as the file is long): the path from the root is the only state, one entry per
    // level with that node's global matrix and its next child.
    struct Level {
      size_t node;
      size_t next_child;
      Matrix global;
    };
    std::vector<Level> path;
    std::vector<char> drawn(gltf_.nodes.size(), 0);
    auto enter = [&](size_t index, const Matrix& parent) -> Expected<void> {
      if (drawn[index]) {
        warn("node " + std::to_string(index) +
             " is reached more than once from the scene's roots; it is drawn once");
        return {};
      }
      drawn[index] = 1;
      const tinygltf::Node& node = gltf_.nodes[index];
      Matrix global = parent * localMatrix(node, index, warner());
      addNodeLight(gltf_, node, index, global, warner(), model_.lights);
      if (node.mesh >= 0) {
        if (static_cast<size_t>(node.mesh) >= gltf_.meshes.size())
          return makeError(name_ + ": node " + std::to_string(index) + " refers to mesh " +
                           std::to_string(node.mesh) + ", but the file has " +
                           std::to_string(gltf_.meshes.size()) + " meshes");
        if (node.skin >= 0)
          warn("skins are not applied: skinned meshes are drawn in their bind pose");
        if (Expected<void> ok = drawMesh(static_cast<size_t>(node.mesh), global); !ok) return ok;
      }
      path.push_back({index, 0, global});
      return {};
    };
    for (int root : *roots) {
      if (Expected<void> ok = enter(static_cast<size_t>(root), Matrix{}); !ok) return ok;
      while (!path.empty()) {
        Level& level = path.back();
        const std::vector<int>& children = gltf_.nodes[level.node].children;
        if (level.next_child == children.size()) {
          path.pop_back();
          continue;
        }
        const auto child = static_cast<size_t>(children[level.next_child++]);
        // `level` is not used past this point: entering a child may move the path.
        const Matrix parent = level.global;
        if (Expected<void> ok = enter(child, parent); !ok) return ok;
      }
    }
    return finish();
  }

 private:
  // ---- Warnings ----

  // A warning about the model file; at most kMaxWarnings distinct ones are listed.
  void warn(const std::string& text) { warnAbout(name_ + ": " + text); }
  Warn warner() {
    return [this](const std::string& text) { warn(text); };
  }
  // A warning that names its own file (a texture's).
  void warnAbout(const std::string& text) {
    if (!warned_.insert(text).second) return;
    if (warned_.size() > kMaxWarnings) {
      ++unlisted_warnings_;
      return;
    }
    model_.warnings.push_back(text);
  }

  // ---- Extensions, scene, node tree ----

  // The budget, before anything is flattened: instancing can multiply a small file into a huge
  // mesh.
  Expected<void> checkDrawnCounts(const std::vector<int>& roots) {
    const DrawnCounts counts = countDrawn(gltf_, roots);
    if (Expected<void> ok = checkBudget(name_, "triangles (after instancing)", counts.triangles,
                                        budget_.triangles(), "--max-triangles");
        !ok)
      return ok;
    return checkBudget(name_, "vertices (after instancing)", counts.vertices, budget_.vertices(),
                       "--max-triangles");
  }

  Expected<void> checkExtensions() {
    for (const std::string& extension : gltf_.extensionsRequired) {
      if (extension == "KHR_mesh_quantization") continue;  // read like any other accessor
      if (extension == "KHR_lights_punctual") continue;    // gltf_lights.cpp
      if (extension == "KHR_texture_transform" || extension.starts_with("KHR_materials_")) {
        warn("extension " + extension + " is not applied");
        continue;
      }
      return makeError(name_ + ": the file requires the extension " + extension +
                       ", which tessera does not support");
    }
    return {};
  }


  // ---- Accessors ----

  std::string accessorName(int accessor, const std::string& role) const {
    return name_ + ": accessor " + std::to_string(accessor) + " (" + role + ")";
  }

  // A reader for `accessor`, its type and component types checked against `allowed_types` and
  // `allowed_components` (empty: any), and its range against its buffer view.
  Expected<ElementReader> reader(int accessor_index, const std::string& role,
                                 std::initializer_list<int> allowed_types,
                                 std::initializer_list<int> allowed_components) {
    if (accessor_index < 0 || static_cast<size_t>(accessor_index) >= gltf_.accessors.size())
      return makeError(name_ + ": " + role + " refers to accessor " +
                       std::to_string(accessor_index) + ", but the file has " +
                       std::to_string(gltf_.accessors.size()));
    const std::string what = accessorName(accessor_index, role);
    const tinygltf::Accessor& accessor = gltf_.accessors[static_cast<size_t>(accessor_index)];
    ElementReader reader;
    reader.components = componentCount(accessor.type);
    reader.component_type = accessor.componentType;
    reader.normalized = accessor.normalized;
    reader.count = accessor.count;
    const int component_bytes = componentBytes(accessor.componentType);
    if (component_bytes == 0)
      return makeError(what + ": component type " + std::to_string(accessor.componentType) +
                       " is not a glTF 2.0 accessor component type");
    if (std::find(allowed_types.begin(), allowed_types.end(), reader.components) ==
        allowed_types.end())
      return makeError(what + ": has " +
                       (reader.components == 0
                            ? std::string("a matrix type")
                            : std::to_string(reader.components) + " components per element") +
                       ", which this attribute cannot have");
    if (allowed_components.size() > 0 &&
        std::find(allowed_components.begin(), allowed_components.end(), accessor.componentType) ==
            allowed_components.end())
      return makeError(what + ": component type " + componentName(accessor.componentType) +
                       " is not allowed here");
    if (reader.count == 0) return makeError(what + ": count is 0");
    const size_t element = static_cast<size_t>(reader.components) * component_bytes;

    if (!accessor.sparse.isSparse && accessor.bufferView >= 0) {
      Expected<std::span<const uint8_t>> bytes = viewBytes(gltf_, accessor.bufferView, what);
      if (!bytes) return bytes.error();
      const tinygltf::BufferView& view =
          gltf_.bufferViews[static_cast<size_t>(accessor.bufferView)];
      reader.stride = view.byteStride != 0 ? view.byteStride : element;
      if (reader.stride < element)
        return makeError(what + ": bufferView " + std::to_string(accessor.bufferView) +
                         " has byteStride " + std::to_string(view.byteStride) +
                         ", smaller than the " + std::to_string(element) + "-byte element");
      if (!fits(accessor.byteOffset, reader.count, reader.stride, element, bytes->size()))
        return makeError(
            what + ": " + std::to_string(reader.count) + " elements of " + std::to_string(element) +
            " bytes, " + std::to_string(reader.stride) + " apart from byte " +
            std::to_string(accessor.byteOffset) + ", reach past the end of bufferView " +
            std::to_string(accessor.bufferView) + " (" + std::to_string(bytes->size()) + " bytes)");
      reader.data = bytes->data() + accessor.byteOffset;
      return reader;
    }

    // Zeros, or a dense copy, with the sparse values written over it: built once per accessor.
    auto cached = dense_.find(accessor_index);
    if (cached == dense_.end()) {
      Expected<std::vector<uint8_t>> dense = densify(accessor, what, element);
      if (!dense) return dense.error();
      cached = dense_.emplace(accessor_index, std::move(dense).value()).first;
    }
    reader.data = cached->second.data();
    reader.stride = element;
    return reader;
  }

  Expected<std::vector<uint8_t>> densify(const tinygltf::Accessor& accessor,
                                         const std::string& what, size_t element) {
    const size_t count = accessor.count;
    std::vector<uint8_t> dense;
    if (accessor.bufferView >= 0) {
      Expected<std::span<const uint8_t>> bytes = viewBytes(gltf_, accessor.bufferView, what);
      if (!bytes) return bytes.error();
      const tinygltf::BufferView& view =
          gltf_.bufferViews[static_cast<size_t>(accessor.bufferView)];
      const size_t stride = view.byteStride != 0 ? view.byteStride : element;
      if (stride < element)
        return makeError(what + ": bufferView byteStride " + std::to_string(view.byteStride) +
                         " is smaller than the " + std::to_string(element) + "-byte element");
      if (!fits(accessor.byteOffset, count, stride, element, bytes->size()))
        return makeError(what + ": " + std::to_string(count) +
                         " elements reach past the end of "
                         "bufferView " +
                         std::to_string(accessor.bufferView));
      dense.resize(count * element);
      for (size_t i = 0; i < count; ++i)
        std::memcpy(dense.data() + i * element, bytes->data() + accessor.byteOffset + i * stride,
                    element);
    } else {
      // count <= implied_bytes_left_ / element, checked without multiplying.
      if (count > implied_bytes_left_ / element)
        return makeError(what + ": " + std::to_string(count) +
                         " elements without a bufferView: more than the file's size can "
                         "justify");
      implied_bytes_left_ -= count * element;
      dense.assign(count * element, 0);
    }
    if (!accessor.sparse.isSparse) return dense;

    const auto& sparse = accessor.sparse;
    const std::string sparse_what = what + ": sparse";
    if (sparse.count <= 0 || static_cast<size_t>(sparse.count) > count)
      return makeError(sparse_what + " count " + std::to_string(sparse.count) +
                       " is not between 1 and the accessor's count " + std::to_string(count));
    const auto sparse_count = static_cast<size_t>(sparse.count);
    const int index_bytes = componentBytes(sparse.indices.componentType);
    if (sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      return makeError(sparse_what + " indices must be unsigned byte, short or int");
    Expected<std::span<const uint8_t>> indices = viewBytes(gltf_, sparse.indices.bufferView, sparse_what);
    if (!indices) return indices.error();
    Expected<std::span<const uint8_t>> values = viewBytes(gltf_, sparse.values.bufferView, sparse_what);
    if (!values) return values.error();
    if (sparse.indices.byteOffset < 0 || !fits(static_cast<uint64_t>(sparse.indices.byteOffset),
                                               sparse_count, static_cast<uint64_t>(index_bytes),
                                               static_cast<uint64_t>(index_bytes), indices->size()))
      return makeError(sparse_what + " indices reach past the end of their bufferView");
    if (sparse.values.byteOffset < 0 || !fits(static_cast<uint64_t>(sparse.values.byteOffset),
                                              sparse_count, element, element, values->size()))
      return makeError(sparse_what + " values reach past the end of their bufferView");
    ElementReader index_reader;
    index_reader.data = indices->data() + sparse.indices.byteOffset;
    index_reader.stride = static_cast<size_t>(index_bytes);
    index_reader.count = sparse_count;
    index_reader.components = 1;
    index_reader.component_type = sparse.indices.componentType;
    const uint8_t* value_bytes = values->data() + sparse.values.byteOffset;
    for (size_t i = 0; i < sparse_count; ++i) {
      const uint32_t target = index_reader.index(i);
      if (target >= count)
        return makeError(sparse_what + " index " + std::to_string(target) +
                         " is past the accessor's " + std::to_string(count) + " elements");
      std::memcpy(dense.data() + size_t{target} * element, value_bytes + i * element, element);
    }
    return dense;
  }

  // An optional attribute: a reader, or nothing with a warning when it cannot be used.
  std::optional<ElementReader> optionalAttribute(const tinygltf::Primitive& primitive,
                                                 const std::string& semantic,
                                                 const std::string& where, size_t vertex_count,
                                                 std::initializer_list<int> types,
                                                 std::initializer_list<int> components,
                                                 Expected<void>& fatal) {
    auto it = primitive.attributes.find(semantic);
    if (it == primitive.attributes.end()) return std::nullopt;
    Expected<ElementReader> attribute =
        reader(it->second, semantic + " of " + where, types, components);
    if (!attribute) {
      // Out-of-range data is a broken file; an unusable type is only an unusable attribute.
      const std::string& message = attribute.error().message;
      if (message.find("past the end") != std::string::npos ||
          message.find("lies outside") != std::string::npos ||
          message.find("justify") != std::string::npos) {
        fatal = attribute.error();
        return std::nullopt;
      }
      warn(message.substr(name_.size() + 2) + "; " + semantic + " is ignored");
      return std::nullopt;
    }
    if (attribute->count != vertex_count) {
      warn(where + ": " + semantic + " has " + std::to_string(attribute->count) + " elements for " +
           std::to_string(vertex_count) + " positions; it is ignored");
      return std::nullopt;
    }
    return *attribute;
  }


  // ---- Meshes ----

  Expected<void> drawMesh(size_t mesh_index, const Matrix& global) {
    const tinygltf::Mesh& mesh = gltf_.meshes[mesh_index];
    const bool mirrored = determinant3(global) < 0;
    const std::array<double, 9> normal_matrix = normalMatrix(global);
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const std::string where =
          "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(p);
      Expected<void> ok = drawPrimitive(mesh.primitives[p], where, global, normal_matrix, mirrored);
      if (!ok) return ok;
    }
    return {};
  }

  Expected<void> drawPrimitive(const tinygltf::Primitive& primitive, const std::string& where,
                               const Matrix& global, const std::array<double, 9>& normal_matrix,
                               bool mirrored) {
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      ++skipped_by_mode_[mode];
      return {};
    }
    if (!primitive.targets.empty()) warn("morph targets are not applied");
    auto position_it = primitive.attributes.find("POSITION");
    if (position_it == primitive.attributes.end()) {
      warn(where + " has no POSITION and is skipped");
      return {};
    }
    // KHR_mesh_quantization allows integer positions, normals and texture coordinates.
    Expected<ElementReader> positions =
        reader(position_it->second, "POSITION of " + where, {3}, {});
    if (!positions) return positions.error();
    const size_t vertex_count = positions->count;

    std::optional<ElementReader> indices;
    size_t corner_count = vertex_count;
    if (primitive.indices >= 0) {
      Expected<ElementReader> read =
          reader(primitive.indices, "indices of " + where, {1},
                 {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
      if (!read) return read.error();
      indices = *read;
      corner_count = indices->count;
    }
    size_t triangle_count = 0;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      triangle_count = corner_count / 3;
      if (corner_count % 3 != 0)
        warn(where + ": " + std::to_string(corner_count % 3) +
             " indices after the last whole triangle are ignored");
    } else if (corner_count >= 3) {
      triangle_count = corner_count - 2;
    }
    if (triangle_count == 0) {
      warn(where + " has fewer than 3 vertices and is skipped");
      return {};
    }
    Mesh& out = model_.mesh;
    // countDrawn counted these in advance; this holds the mesh to the same budget should the two
    // ever disagree.
    const size_t new_vertices = std::min(vertex_count, 3 * triangle_count);
    if (triangle_count > budget_.triangles() - std::min<uint64_t>(budget_.triangles(),
                                                                   out.triangleCount()) ||
        new_vertices > budget_.vertices() - std::min<uint64_t>(budget_.vertices(),
                                                                out.vertexCount()))
      return makeError(name_ + ": the scene flattens to more than the budget of " +
                       std::to_string(budget_.triangles()) + " triangles or " +
                       std::to_string(budget_.vertices()) +
                       " vertices; raise it with --max-triangles or --memory-limit");

    Expected<void> fatal;
    const std::optional<ElementReader> normals =
        optionalAttribute(primitive, "NORMAL", where, vertex_count, {3}, {}, fatal);
    if (!fatal) return fatal;
    Expected<uint16_t> material = materials_.materialFor(primitive.material, model_.materials);
    if (!material) return material.error();
    int uv_set = 0;
    if (primitive.material >= 0 &&
        static_cast<size_t>(primitive.material) < gltf_.materials.size()) {
      const tinygltf::TextureInfo& info = gltf_.materials[static_cast<size_t>(primitive.material)]
                                              .pbrMetallicRoughness.baseColorTexture;
      if (info.index >= 0) uv_set = std::max(info.texCoord, 0);
    }
    const std::optional<ElementReader> uvs = optionalAttribute(
        primitive, "TEXCOORD_" + std::to_string(uv_set), where, vertex_count, {2}, {}, fatal);
    if (!fatal) return fatal;
    if (!uvs && model_.materials[*material].albedo)
      warn(where + ": its material has a texture but the primitive has no TEXCOORD_" +
           std::to_string(uv_set));
    const std::optional<ElementReader> colors =
        optionalAttribute(primitive, "COLOR_0", where, vertex_count, {3, 4},
                          {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                           TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                          fatal);
    if (!fatal) return fatal;

    // Each vertex of this primitive is emitted once, on first use. The remap is stamped per
    // primitive so it never needs clearing.
    if (remap_stamp_.size() < vertex_count) {
      remap_stamp_.resize(vertex_count, 0);
      remap_vertex_.resize(vertex_count, 0);
    }
    ++stamp_;
    const size_t first_vertex = out.positions.size();
    if (uvs) out.uvs.resize(first_vertex, float2{0, 0});
    if (colors) out.colors.resize(first_vertex, float4{1, 1, 1, 1});
    bool normals_usable = normals.has_value();

    auto vertexOf = [&](size_t corner) -> Expected<uint32_t> {
      const size_t local = indices ? indices->index(corner) : corner;
      if (local >= vertex_count)
        return makeError(name_ + ": " + where + ": index " + std::to_string(local) +
                         " is past the " + std::to_string(vertex_count) + " vertices");
      if (remap_stamp_[local] == stamp_) return remap_vertex_[local];
      const auto vertex = static_cast<uint32_t>(out.positions.size());
      remap_stamp_[local] = stamp_;
      remap_vertex_[local] = vertex;
      out.positions.push_back(
          transformPoint(global, {positions->component(local, 0), positions->component(local, 1),
                                  positions->component(local, 2)}));
      float3 normal{0, 0, 0};
      if (normals) {
        normal = transformNormal(normal_matrix,
                                 {normals->component(local, 0), normals->component(local, 1),
                                  normals->component(local, 2)});
        normals_usable &= normal.x != 0 || normal.y != 0 || normal.z != 0;
      }
      out.normals.push_back(normal);
      if (uvs)  // glTF's v = 0 is the top of the image; tessera's is the bottom.
        out.uvs.push_back({uvs->component(local, 0), 1.0f - uvs->component(local, 1)});
      if (colors)
        out.colors.push_back({colors->component(local, 0), colors->component(local, 1),
                              colors->component(local, 2),
                              colors->components == 4 ? colors->component(local, 3) : 1.0f});
      return vertex;
    };

    for (size_t t = 0; t < triangle_count; ++t) {
      size_t corners[3];
      if (mode == TINYGLTF_MODE_TRIANGLES) {
        corners[0] = 3 * t, corners[1] = 3 * t + 1, corners[2] = 3 * t + 2;
      } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        // Every other triangle is listed clockwise; swap to keep one winding (glTF 3.7.2.1).
        corners[0] = t;
        corners[1] = t + 1 + t % 2;
        corners[2] = t + 2 - t % 2;
      } else {
        corners[0] = 0, corners[1] = t + 1, corners[2] = t + 2;
      }
      // A mirroring transform turns counter-clockwise into clockwise: undo it.
      if (mirrored) std::swap(corners[1], corners[2]);
      bool finite = true;
      for (size_t corner : corners) {
        Expected<uint32_t> vertex = vertexOf(corner);
        if (!vertex) return vertex.error();
        out.indices.push_back(*vertex);
        finite &= isFinite(out.positions[*vertex]);
      }
      out.triangle_materials.push_back(*material);
      if (!finite) ++model_.nonfinite_triangles;
    }
    if (uvs) out.uvs.resize(out.positions.size(), float2{0, 0});
    if (colors) out.colors.resize(out.positions.size(), float4{1, 1, 1, 1});
    if (!normals_usable) {
      if (normals)
        warn(where + ": some normals are zero or not finite; smooth normals are generated");
      generated_normal_ranges_.push_back({first_vertex, out.positions.size()});
    }
    return {};
  }

  Expected<void> finish() {
    Mesh& mesh = model_.mesh;
    if (mesh.triangleCount() == 0) {
      std::string why = "no triangles in the scene";
      if (!skipped_by_mode_.empty()) why += " (only points or lines, which are not drawn)";
      return makeError(name_ + ": " + why);
    }
    // Vertices of different primitives are never shared, so smooth normals over the whole mesh
    // equal each primitive's own; they are copied only where the file gave none.
    if (!generated_normal_ranges_.empty()) {
      Mesh shape;
      shape.positions = mesh.positions;
      shape.indices = mesh.indices;
      generateSmoothNormals(shape);
      for (auto [begin, end] : generated_normal_ranges_)
        std::copy(shape.normals.begin() + static_cast<std::ptrdiff_t>(begin),
                  shape.normals.begin() + static_cast<std::ptrdiff_t>(end),
                  mesh.normals.begin() + static_cast<std::ptrdiff_t>(begin));
    }
    if (!mesh.uvs.empty()) mesh.uvs.resize(mesh.positions.size(), float2{0, 0});
    if (!mesh.colors.empty()) mesh.colors.resize(mesh.positions.size(), float4{1, 1, 1, 1});

    static constexpr const char* kModeNames[] = {"points", "lines", "line loops", "line strips"};
    for (auto [mode, count] : skipped_by_mode_) {
      const std::string what =
          mode >= 0 && mode < 4 ? kModeNames[mode] : "primitives of mode " + std::to_string(mode);
      warn(std::to_string(count) + " primitive(s) of " + what +
           " skipped: only triangles are drawn");
    }
    size_t double_sided = 0;
    for (const Material& material : model_.materials) double_sided += material.double_sided;
    model_.cull_back_faces = double_sided == 0;
    if (double_sided > 0 && double_sided < model_.materials.size())
      warn("some materials are double-sided and some are not; back faces are drawn for all");
    if (model_.nonfinite_triangles > 0)
      model_.warnings.push_back(
          name_ + ": " + std::to_string(model_.nonfinite_triangles) +
          " triangles have a NaN or infinite vertex position (kept so triangle ids stay in load "
          "order; they are not drawn)");
    if (unlisted_warnings_ > 0)
      model_.warnings.push_back(name_ + ": " + std::to_string(unlisted_warnings_) +
                                " more warnings like these");
    return {};
  }

  const tinygltf::Model& gltf_;
  const LoadBudget budget_;
  const std::string name_;
  const fs::path folder_;
  uintmax_t implied_bytes_left_;
  Model& model_;
  MaterialTable materials_;

  std::map<int, std::vector<uint8_t>> dense_;  // sparse or bufferView-less accessors
  std::vector<uint32_t> remap_stamp_, remap_vertex_;
  uint32_t stamp_ = 0;
  std::vector<std::pair<size_t, size_t>> generated_normal_ranges_;
  std::map<int, size_t> skipped_by_mode_;
  std::set<std::string> warned_;
  size_t unlisted_warnings_ = 0;
};

// One of tinygltf's message lines in tessera's words: the ones a hostile file reaches say what
// is wrong without tinygltf's phrasing or its placeholders, and any value is elided.
std::string inOwnWords(std::string line) {
  for (size_t at; (at = line.find(kFolderMarker)) != std::string::npos;)
    line.erase(at, kFolderMarker.size());
  // "File size mismatch : c.bin, requestedBytes 168, but got 100"
  const std::string_view kMismatch = "File size mismatch : ";
  if (line.starts_with(kMismatch)) {
    const size_t requested = line.find(", requestedBytes ");
    const size_t got = line.find(", but got ");
    if (requested != std::string::npos && got != std::string::npos && got > requested) {
      const std::string file = line.substr(kMismatch.size(), requested - kMismatch.size());
      const std::string wanted = line.substr(requested + 17, got - requested - 17);
      return "buffer file '" + elided(file) + "' is " + trimmed(line.substr(got + 10)) +
             " bytes, but the buffer's byteLength is " + wanted;
    }
  }
  // "'buffer' property is missing in BufferView."
  if (const size_t missing = line.find("' property is missing in ");
      line.starts_with("'") && missing != std::string::npos) {
    std::string object = line.substr(missing + 25);
    while (!object.empty() && (object.back() == '.' || object.back() == ' ')) object.pop_back();
    return "a " + elided(object) + " lacks its required property '" +
           elided(line.substr(1, missing - 1)) + "'";
  }
  if (line.starts_with("Unsupported `type` for accessor object"))
    return "an accessor's type is not a glTF type (" + elided(line.substr(line.find("Got") + 3)) +
           ")";
  if (line.starts_with("Failed to decode 'uri' for image["))
    return "image " + numberAfter(line, "image[") + ": its URI cannot be decoded";
  // "Failed to decode 'uri' : data:... in Buffer": the URI can be megabytes long.
  if (line.starts_with("Failed to decode 'uri' : ")) {
    std::string uri = line.substr(25);
    if (uri.ends_with(" in Buffer")) uri.resize(uri.size() - 10);
    return "a buffer's URI cannot be decoded: '" + elided(uri) + "'";
  }
  if (line.starts_with("\"asset\" object not found"))
    return "the required \"asset\" object is missing";
  std::string out;
  size_t begin = 0;
  while (begin < line.size()) {
    size_t end = std::min(line.find(' ', begin), line.size());
    if (!out.empty()) out += ' ';
    out += elided(std::string_view(line).substr(begin, end - begin));
    begin = end + 1;
  }
  return out;
}

// tinygltf's messages are lines ending in '\n'; this joins the first few into one.
std::string joinedLines(const std::string& text) {
  constexpr size_t kMaxLines = 5;
  std::string out;
  size_t lines = 0, begin = 0;
  while (begin < text.size()) {
    size_t end = std::min(text.find('\n', begin), text.size());
    std::string line = trimmed(std::string_view(text).substr(begin, end - begin));
    begin = end + 1;
    if (line.empty()) continue;
    if (++lines > kMaxLines) continue;
    if (!out.empty()) out += "; ";
    out += inOwnWords(line);
  }
  if (lines > kMaxLines) out += "; and " + std::to_string(lines - kMaxLines) + " more";
  return out;
}

Expected<Model> parseGltf(std::span<const uint8_t> bytes, const std::string& name,
                          const fs::path& folder, const LoadBudget& budget) {
  if (bytes.empty()) return makeError(name + ": the file is empty: no triangles");
  if (bytes.size() > kMaxGltfBytes)
    return makeError(name + ": the file is " + std::to_string(bytes.size()) +
                     " bytes; glTF files over 2 GiB are refused");
  const bool binary = bytes.size() >= 4 && readU32(bytes.data()) == kGlbMagic;
  std::string_view json_text;
  if (binary) {
    if (Expected<void> ok = checkGlbContainer(bytes, name); !ok) return ok.error();
    json_text = std::string_view(reinterpret_cast<const char*>(bytes.data()) + 20,
                                 readU32(bytes.data() + 12));
  } else {
    json_text = std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  }
  if (Expected<void> ok = checkJsonShape(json_text, name); !ok) return ok.error();

  ExternalFiles files{folder, name, {}, 0, budget.fileBytes() - std::min<uint64_t>(budget.fileBytes(), bytes.size())};
  tinygltf::TinyGLTF parser;
  parser.SetFsCallbacks({&fileExists, &expandFilePath, &readWholeFile, &refuseWrite, &files});
  parser.SetImageLoader(&keepEncodedImage, nullptr);
  tinygltf::Model gltf;
  std::string errors, library_warnings;
  const std::string base(kFolderMarker.substr(0, kFolderMarker.size() - 1));
  const bool parsed =
      binary ? parser.LoadBinaryFromMemory(&gltf, &errors, &library_warnings, bytes.data(),
                                           static_cast<unsigned int>(bytes.size()), base)
             : parser.LoadASCIIFromString(&gltf, &errors, &library_warnings, json_text.data(),
                                          static_cast<unsigned int>(json_text.size()), base);
  if (!parsed) {
    if (!files.refusals.empty())
      return makeError(name + ": a buffer file cannot be read: " + files.refusals.front());
    std::string message = joinedLines(errors);
    return makeError(name + ": not a readable glTF file: " +
                     (message.empty() ? "tinygltf gave no reason" : message));
  }

  Model model;
  Flattener flattener(gltf, name, folder, bytes.size() + files.bytes_read, budget, model);
  if (Expected<void> ok = flattener.run(); !ok) return ok.error();
  std::string passed_on = joinedLines(library_warnings);
  if (!passed_on.empty()) model.warnings.insert(model.warnings.begin(), name + ": " + passed_on);
  return model;
}

template <typename Load>
Expected<Model> guarded(const std::string& name, Load load) {
  try {
    return load();
  } catch (const std::bad_alloc&) {
    return makeError(name + ": out of memory while loading");
  } catch (const std::length_error&) {
    return makeError(name + ": out of memory while loading");
  } catch (const std::exception& error) {
    // tinygltf and nlohmann::json throw on some malformed input (a zero-length GLB buffer).
    return makeError(name + ": not a readable glTF file: " + inOwnWords(error.what()));
  }
}

}  // namespace

Expected<Model> loadGltfFromMemory(std::span<const uint8_t> bytes, const std::string& name,
                                   const std::filesystem::path& folder, const LoadBudget& budget) {
  return guarded(name, [&] { return parseGltf(bytes, name, folder, budget); });
}

Expected<Model> loadGltf(const std::filesystem::path& path, const LoadBudget& budget) {
  const std::string name = path.string();
  return guarded(name, [&]() -> Expected<Model> {
    Expected<std::vector<unsigned char>> bytes = readRegularFile(path, std::min<uint64_t>(kMaxGltfBytes, budget.fileBytes()), "glTF");
    if (!bytes) return bytes.error();
    fs::path folder = path.parent_path();
    if (folder.empty()) folder = ".";
    return parseGltf(*bytes, name, folder, budget);
  });
}

}  // namespace tessera::io
