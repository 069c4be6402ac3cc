// The glTF builder's meshes: each glTF mesh read once, in its own space, its primitives in
// order (TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN), each vertex emitted on first use. Points and
// lines are gltf_points.cpp's.
#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <utility>

#include <tessera/scene/tangents.h>

#include "gltf_builder.h"
#include "gltf_draco.h"
#include "gltf_transforms.h"
#include "load_budget.h"
#include "tinygltf_include.h"

namespace tessera::io::gltf {

namespace {

// Normals in the mesh's own space: normalized as the file gives them.
constexpr std::array<double, 9> kIdentity3 = {1, 0, 0, 0, 1, 0, 0, 0, 1};

}  // namespace

// ---- Meshes ----

Expected<int32_t> GraphBuilder::meshFor(size_t mesh_index) {
  if (graph_mesh_.size() < gltf_.meshes.size()) graph_mesh_.resize(gltf_.meshes.size(), kNoIndex);
  if (graph_mesh_[mesh_index] != kNoIndex) return graph_mesh_[mesh_index];
  Mesh mesh;
  const size_t nonfinite_before = model_.nonfinite_triangles;
  if (Expected<void> ok = drawMesh(mesh_index, mesh); !ok) return ok.error();
  SceneGraph& graph = model_.graph;
  GraphMesh graph_mesh;
  graph_mesh.name = gltf_.meshes[mesh_index].name;
  graph_mesh.mesh = std::make_shared<const Mesh>(std::move(mesh));
  graph_mesh_[mesh_index] = static_cast<int32_t>(graph.meshes.size());
  graph.meshes.push_back(std::move(graph_mesh));
  mesh_nonfinite_.push_back(model_.nonfinite_triangles - nonfinite_before);
  model_.nonfinite_triangles = nonfinite_before;  // counted per instance (addNode)
  return graph_mesh_[mesh_index];
}

// All primitives of one glTF mesh, in order, into `out`, in the mesh's own space.
Expected<void> GraphBuilder::drawMesh(size_t mesh_index, Mesh& out) {
  const tinygltf::Mesh& mesh = gltf_.meshes[mesh_index];
  generated_normal_ranges_.clear();
  generated_tangent_ranges_.clear();
  tangents_refused_ = false;
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const std::string where =
        "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(p);
    Expected<void> ok = drawPrimitive(mesh.primitives[p], where, out);
    draco_.reset();  // its decoded accessors belong to that primitive alone
    if (!ok) return ok;
  }
  // Vertices of different primitives are never shared, so smooth normals over the whole mesh
  // equal each primitive's own; they are copied only where the file gave none.
  if (!generated_normal_ranges_.empty()) {
    Mesh shape;
    shape.positions = out.positions;
    shape.indices = out.indices;
    generateSmoothNormals(shape);
    for (auto [begin, end] : generated_normal_ranges_)
      std::copy(shape.normals.begin() + static_cast<std::ptrdiff_t>(begin),
                shape.normals.begin() + static_cast<std::ptrdiff_t>(end),
                out.normals.begin() + static_cast<std::ptrdiff_t>(begin));
  }
  if (!out.uvs.empty()) out.uvs.resize(out.positions.size(), float2{0, 0});
  if (!out.uvs1.empty()) out.uvs1.resize(out.positions.size(), float2{0, 0});
  if (!out.colors.empty()) out.colors.resize(out.positions.size(), float4{1, 1, 1, 1});
  addTangents(out);
  return {};
}

// The mesh's tangents: the file's where it gave them, generated (generateTangents: MikkTSpace)
// for normal-mapped primitives without; none at all when a TANGENT was unusable (its normal map
// is left out: the renderer draws normal maps only with tangents). Generating may split vertices
// of those primitives (a mirrored UV seam): they are added at the end of the mesh.
void GraphBuilder::addTangents(Mesh& out) {
  if (tangents_refused_ || out.uvs.size() != out.positions.size()) {
    out.tangents.clear();
    return;
  }
  if (out.tangents.empty()) return;
  out.tangents.resize(out.positions.size(), float4{1, 0, 0, 1});
  // Each primitive's tangents from its normal map's UV set; split vertices count against the
  // budget of the meshes read after this one.
  for (int set = 0; set < 2; ++set) {
    std::vector<VertexRange> ranges;
    for (const TangentRange& r : generated_tangent_ranges_)
      if (r.uv_set == set) ranges.push_back({r.begin, r.end});
    if (!ranges.empty()) stored_vertices_ += generateTangents(out, ranges, set).split_vertices;
  }
}

Expected<void> GraphBuilder::drawPrimitive(const tinygltf::Primitive& primitive,
                                           const std::string& where, Mesh& out) {
  int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    // Points and lines are placed per node in world space (gltf_points.cpp).
    if (mode < TINYGLTF_MODE_POINTS || mode > TINYGLTF_MODE_LINE_STRIP) ++skipped_by_mode_[mode];
    return {};
  }
  if (!primitive.targets.empty()) warn("morph targets are not applied");
  auto position_it = primitive.attributes.find("POSITION");
  if (position_it == primitive.attributes.end()) {
    warn(where + " has no POSITION and is skipped");
    return {};
  }
  Expected<bool> draco = readDraco(primitive, where);
  if (!draco) return draco.error();
  if (*draco) mode = TINYGLTF_MODE_TRIANGLES;  // a Draco mesh decodes to a list of faces
  // KHR_mesh_quantization allows integer positions, normals and texture coordinates.
  Expected<ElementReader> positions = reader(position_it->second, "POSITION of " + where, {3}, {});
  if (!positions) return positions.error();
  Expected<std::optional<ElementReader>> indices = cornerIndices(primitive, where);
  if (!indices) return indices.error();

  PrimitiveReaders readers;
  readers.mode = mode;
  readers.vertex_count = positions->count;
  readers.positions = *positions;
  readers.indices = *indices;
  const size_t corner_count = readers.indices ? readers.indices->count : readers.vertex_count;
  readers.triangle_count = triangleCount(mode, corner_count, where);
  if (readers.triangle_count == 0) {
    warn(where + " has fewer than 3 vertices and is skipped");
    return {};
  }
  if (Expected<void> ok = checkStoredBudget(readers.triangle_count, readers.vertex_count); !ok)
    return ok;
  if (Expected<void> ok = readVertexAttributes(primitive, where, readers, out); !ok) return ok;
  return drawTriangles(readers, where, out);
}

// The primitive's corners as indices into its vertices: the Draco stream's when it has one, else
// its `indices` accessor; none when its vertices are listed in order.
Expected<std::optional<ElementReader>> GraphBuilder::cornerIndices(
    const tinygltf::Primitive& primitive, const std::string& where) {
  if (!draco_) return indexReader(primitive, where);
  return std::optional<ElementReader>{
      ElementReader{reinterpret_cast<const uint8_t*>(draco_->indices.data()), sizeof(uint32_t),
                    draco_->indices.size(), 1, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, false}};
}

// The triangles of a primitive of `corner_count` corners: a list's whole triangles (with a warning
// for the indices left over), all but two of a strip's or a fan's corners.
size_t GraphBuilder::triangleCount(int mode, size_t corner_count, const std::string& where) {
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (corner_count % 3 != 0)
      warn(where + ": " + std::to_string(corner_count % 3) +
           " indices after the last whole triangle are ignored");
    return corner_count / 3;
  }
  return corner_count >= 3 ? corner_count - 2 : 0;
}

// Refuses a primitive that would take the meshes stored so far past the triangle or vertex budget.
Expected<void> GraphBuilder::checkStoredBudget(size_t triangle_count, size_t vertex_count) const {
  // countDrawn counted these in advance (with instancing); this holds the meshes stored to the
  // same budget should the two ever disagree.
  const size_t new_vertices = std::min(vertex_count, 3 * triangle_count);
  if (triangle_count >
          budget_.triangles() - std::min<uint64_t>(budget_.triangles(), stored_triangles_) ||
      new_vertices > budget_.vertices() - std::min<uint64_t>(budget_.vertices(), stored_vertices_))
    return makeError(name_ + ": the meshes hold more than the budget of " +
                     std::to_string(budget_.triangles()) + " triangles or " +
                     std::to_string(budget_.vertices()) +
                     " vertices; raise it with --max-triangles or --memory-limit");
  return {};
}

// The primitive's NORMAL, material, texture coordinates, COLOR_0 and TANGENT into `readers`, with
// which of them its vertices keep in `out`.
Expected<void> GraphBuilder::readVertexAttributes(const tinygltf::Primitive& primitive,
                                                  const std::string& where,
                                                  PrimitiveReaders& readers, Mesh& out) {
  const size_t vertex_count = readers.vertex_count;
  Expected<void> fatal;
  readers.normals = optionalAttribute(primitive, "NORMAL", where, vertex_count, {3}, {}, fatal);
  if (!fatal) return fatal;
  Expected<uint16_t> material = materials_.materialFor(primitive.material, model_.materials);
  if (!material) return material.error();
  readers.material = *material;
  const Material& drawn_with = model_.materials[*material];
  Expected<UvReaders> uv_readers = uvReaders(primitive, drawn_with, where, vertex_count, out);
  if (!uv_readers) return uv_readers.error();
  readers.uvs = uv_readers->set0;
  readers.uvs1 = uv_readers->set1;
  readers.keep_uvs = readers.uvs || readers.uvs1;
  readers.keep_uvs1 = uv_readers->keep_set1;
  readers.colors = colorAttribute(primitive, where, vertex_count, fatal);
  if (!fatal) return fatal;
  // Tangents for the material's normal map: the file's (VEC4, one per vertex), else generated.
  const bool has_tangent = primitive.attributes.count("TANGENT") != 0;
  readers.tangents = optionalAttribute(primitive, "TANGENT", where, vertex_count, {4}, {}, fatal);
  if (!fatal) return fatal;
  readers.normal_mapped = readers.keep_uvs && drawn_with.normal;
  if (has_tangent && !readers.tangents && readers.normal_mapped) {
    warn(where + ": its TANGENT is unusable; the normal map is left out");
    tangents_refused_ = true;
  }
  readers.keep_tangents = readers.tangents || readers.normal_mapped || !out.tangents.empty();
  return {};
}

// The primitive's triangles into `out`, with the vertices they use, then its share of the mesh
// (finishPrimitive).
Expected<void> GraphBuilder::drawTriangles(const PrimitiveReaders& readers,
                                           const std::string& where, Mesh& out) {
  // Each vertex of this primitive is emitted once, on first use. The remap is stamped per
  // primitive so it never needs clearing.
  if (remap_stamp_.size() < readers.vertex_count) {
    remap_stamp_.resize(readers.vertex_count, 0);
    remap_vertex_.resize(readers.vertex_count, 0);
  }
  ++stamp_;
  const size_t first_vertex = out.positions.size();
  if (readers.keep_uvs) out.uvs.resize(first_vertex, float2{0, 0});
  if (readers.colors) out.colors.resize(first_vertex, float4{1, 1, 1, 1});
  if (readers.keep_tangents) out.tangents.resize(first_vertex, float4{1, 0, 0, 1});
  bool normals_usable = readers.normals.has_value();

  for (size_t t = 0; t < readers.triangle_count; ++t) {
    size_t corners[3];
    if (readers.mode == TINYGLTF_MODE_TRIANGLES) {
      corners[0] = 3 * t, corners[1] = 3 * t + 1, corners[2] = 3 * t + 2;
    } else if (readers.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      // Every other triangle is listed clockwise; swap to keep one winding (glTF 3.7.2.1).
      corners[0] = t;
      corners[1] = t + 1 + t % 2;
      corners[2] = t + 2 - t % 2;
    } else {
      corners[0] = 0, corners[1] = t + 1, corners[2] = t + 2;
    }
    bool finite = true;
    for (size_t corner : corners) {
      Expected<uint32_t> vertex = vertexOf(corner, readers, where, normals_usable, out);
      if (!vertex) return vertex.error();
      out.indices.push_back(*vertex);
      finite &= isFinite(out.positions[*vertex]);
    }
    out.triangle_materials.push_back(readers.material);
    if (!finite) ++model_.nonfinite_triangles;
  }
  finishPrimitive(readers, where, first_vertex, normals_usable, out);
  return {};
}

// The mesh vertex of the primitive's `corner`: emitted into `out` on its first use, with the
// attributes `readers` keep. A zero or non-finite normal clears `normals_usable`.
Expected<uint32_t> GraphBuilder::vertexOf(size_t corner, const PrimitiveReaders& readers,
                                          const std::string& where, bool& normals_usable,
                                          Mesh& out) {
  const size_t local = readers.indices ? readers.indices->index(corner) : corner;
  if (local >= readers.vertex_count)
    return makeError(name_ + ": " + where + ": index " + std::to_string(local) + " is past the " +
                     std::to_string(readers.vertex_count) + " vertices");
  if (remap_stamp_[local] == stamp_) return remap_vertex_[local];
  const auto vertex = static_cast<uint32_t>(out.positions.size());
  remap_stamp_[local] = stamp_;
  remap_vertex_[local] = vertex;
  const ElementReader& positions = readers.positions;
  out.positions.push_back(float3{positions.component(local, 0), positions.component(local, 1),
                                 positions.component(local, 2)});
  float3 normal{0, 0, 0};
  const std::optional<ElementReader>& normals = readers.normals;
  if (normals) {
    normal = transformNormal(
        kIdentity3,
        {normals->component(local, 0), normals->component(local, 1), normals->component(local, 2)});
    normals_usable &= normal.x != 0 || normal.y != 0 || normal.z != 0;
  }
  out.normals.push_back(normal);
  // glTF's v = 0 is the top of the image; tessera's is the bottom.
  const std::optional<ElementReader>& uvs = readers.uvs;
  const std::optional<ElementReader>& uvs1 = readers.uvs1;
  const float2 uv0 =
      uvs ? float2{uvs->component(local, 0), 1.0f - uvs->component(local, 1)} : float2{0, 0};
  if (readers.keep_uvs) out.uvs.push_back(uv0);
  if (readers.keep_uvs1)  // set 0 where the primitive has no TEXCOORD_1
    out.uvs1.push_back(uvs1 ? float2{uvs1->component(local, 0), 1.0f - uvs1->component(local, 1)}
                            : uv0);
  const std::optional<ElementReader>& colors = readers.colors;
  if (colors)
    out.colors.push_back({colors->component(local, 0), colors->component(local, 1),
                          colors->component(local, 2),
                          colors->components == 4 ? colors->component(local, 3) : 1.0f});
  const std::optional<ElementReader>& tangents = readers.tangents;
  if (readers.keep_tangents)
    out.tangents.push_back(tangents ? float4{tangents->component(local, 0),
                                             tangents->component(local, 1),
                                             tangents->component(local, 2),
                                             tangents->component(local, 3) < 0.0f ? -1.0f : 1.0f}
                                    : float4{1, 0, 0, 1});
  return vertex;
}

// After the primitive's triangles: `out`'s optional attributes made whole to its last vertex, the
// vertices whose tangents or normals drawMesh generates noted, and the primitive counted against
// the budget.
void GraphBuilder::finishPrimitive(const PrimitiveReaders& readers, const std::string& where,
                                   size_t first_vertex, bool normals_usable, Mesh& out) {
  if (readers.keep_uvs) out.uvs.resize(out.positions.size(), float2{0, 0});
  if (readers.keep_uvs1) out.uvs1.resize(out.positions.size(), float2{0, 0});
  if (readers.colors) out.colors.resize(out.positions.size(), float4{1, 1, 1, 1});
  if (readers.keep_tangents) {
    out.tangents.resize(out.positions.size(), float4{1, 0, 0, 1});
    if (!readers.tangents && readers.normal_mapped)
      generated_tangent_ranges_.push_back(
          {first_vertex, out.positions.size(),
           model_.materials[readers.material].normal.sampler.texcoord});
  }
  stored_triangles_ += readers.triangle_count;
  stored_vertices_ += out.positions.size() - first_vertex;
  if (!normals_usable) {
    if (readers.normals)
      warn(where + ": some normals are zero or not finite; smooth normals are generated");
    generated_normal_ranges_.push_back({first_vertex, out.positions.size()});
  }
}

// The primitive's texture coordinates: TEXCOORD_0 for Mesh::uvs, and TEXCOORD_1 for uvs1 when its
// material reads set 1 (readsTexcoord1) or an earlier primitive of the mesh did. A primitive
// without the set its material reads is drawn with TEXCOORD_0 there, with a warning. Makes `out`'s
// uvs1 whole up to here (set 0 in its place) when this primitive starts it.
Expected<GraphBuilder::UvReaders> GraphBuilder::uvReaders(const tinygltf::Primitive& primitive,
                                                          const Material& material,
                                                          const std::string& where,
                                                          size_t vertex_count, Mesh& out) {
  Expected<void> fatal;
  UvReaders readers;
  readers.set0 = optionalAttribute(primitive, "TEXCOORD_0", where, vertex_count, {2}, {}, fatal);
  if (!fatal) return fatal.error();
  const bool reads_set1 = readsTexcoord1(material);
  if (reads_set1) {
    readers.set1 = optionalAttribute(primitive, "TEXCOORD_1", where, vertex_count, {2}, {}, fatal);
    if (!fatal) return fatal.error();
    if (!readers.set1)
      warn(where + ": its material reads TEXCOORD_1, which the primitive does not have; " +
           "TEXCOORD_0 is read in its place");
  }
  const bool albedo_set1 = material.albedo && material.sampler.texcoord == 1;
  if (material.albedo && !readers.set0 && !(albedo_set1 && readers.set1))
    warn(where + ": its material has a texture but the primitive has no TEXCOORD_" +
         std::to_string(albedo_set1 ? 1 : 0));
  readers.keep_set1 = readers.set1 || reads_set1 || !out.uvs1.empty();
  if (readers.keep_set1 && out.uvs1.empty() && !out.positions.empty()) {
    out.uvs1 = out.uvs;
    out.uvs1.resize(out.positions.size(), float2{0, 0});
  }
  return readers;
}

// KHR_draco_mesh_compression (gltf_draco.h): whether the primitive's geometry comes from its
// Draco stream, decoded into draco_ (reader() then reads its accessors from it). A build without
// Draco reads the uncompressed fallback a file may carry beside the stream, and refuses the
// primitive when there is none.
Expected<bool> GraphBuilder::readDraco(const tinygltf::Primitive& primitive,
                                       const std::string& where) {
  draco_.reset();
  if (primitive.extensions.count(std::string(kDracoExtension)) == 0) return false;
  if (!dracoDecoderBuilt()) {
    auto viewed = [&](int accessor) {
      return accessor >= 0 && static_cast<size_t>(accessor) < gltf_.accessors.size() &&
             gltf_.accessors[static_cast<size_t>(accessor)].bufferView >= 0;
    };
    if (viewed(primitive.attributes.at("POSITION")) &&
        (primitive.indices < 0 || viewed(primitive.indices))) {
      warn(where + " is read from its uncompressed fallback: this build has no Draco decoder");
      return false;
    }
    return makeError(noDracoDecoder(name_ + ": " + where));
  }
  Expected<DracoPrimitive> decoded = decodeDracoPrimitive(
      gltf_, primitive, name_, where, DracoBudget{budget_, stored_triangles_, stored_vertices_});
  if (!decoded) return decoded.error();
  for (const std::string& warning : decoded->warnings) warn(warning);
  draco_ = std::move(decoded).value();
  return true;
}

}  // namespace tessera::io::gltf
