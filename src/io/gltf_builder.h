// The glTF loader's builder: from a parsed tinygltf::Model to io::Model's scene graph. Private to
// tessera_io. Split by concern: gltf_builder.cpp (the node walk, cameras, warnings, the end),
// gltf_reader.cpp (checked accessor reads), gltf_primitives.cpp (meshes and their primitives),
// gltf_points.cpp (points and lines, placed per node in world space), gltf_draco.h
// (Draco-compressed primitives).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <tessera/io/model_loader.h>

#include "gltf_accessors.h"
#include "gltf_draco.h"
#include "gltf_materials.h"
#include "gltf_nodes.h"

namespace tinygltf {
class Model;
struct Animation;
struct AnimationSampler;
struct Primitive;
struct Accessor;
}  // namespace tinygltf

namespace tessera::io::gltf {

// Distinct warnings listed per file; the rest are counted.
constexpr size_t kMaxWarnings = 20;

class GraphBuilder {
 public:
  GraphBuilder(const tinygltf::Model& gltf, std::string name, std::filesystem::path folder,
               uintmax_t source_bytes, const LoadBudget& budget, Model& model)
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

  Expected<void> run();

 private:
  // gltf_builder.cpp
  void warn(const std::string& text);
  Warn warner();
  void warnAbout(const std::string& text);
  Expected<void> checkDrawnCounts(const std::vector<int>& roots);
  Expected<void> checkExtensions();
  Expected<void> addNode(size_t index, int32_t parent);
  void readCameras();
  void placeLights();
  Expected<void> finish();

  // gltf_reader.cpp
  std::string accessorName(int accessor, const std::string& role) const;
  Expected<ElementReader> reader(int accessor_index, const std::string& role,
                                 std::initializer_list<int> allowed_types,
                                 std::initializer_list<int> allowed_components);
  // The primitive's COLOR_0 (RGB or RGBA; floats, or normalized bytes or shorts), or none.
  std::optional<ElementReader> colorAttribute(const tinygltf::Primitive& primitive,
                                              const std::string& where, size_t vertex_count,
                                              Expected<void>& fatal);
  // The primitive's `indices` accessor (scalar unsigned bytes, shorts or ints), or none when it
  // has no indices.
  Expected<std::optional<ElementReader>> indexReader(const tinygltf::Primitive& primitive,
                                                     const std::string& where);
  Expected<std::vector<uint8_t>> densify(const tinygltf::Accessor& accessor,
                                         const std::string& what, size_t element);
  std::optional<ElementReader> optionalAttribute(const tinygltf::Primitive& primitive,
                                                 const std::string& semantic,
                                                 const std::string& where, size_t vertex_count,
                                                 std::initializer_list<int> types,
                                                 std::initializer_list<int> components,
                                                 Expected<void>& fatal);

  // gltf_animations.cpp
  void readAnimations();
  Expected<Animation> readAnimation(const tinygltf::Animation& in, const std::string& name,
                                    const std::vector<int32_t>& graph_node);
  Expected<AnimationSampler> readSampler(const tinygltf::AnimationSampler& in, bool rotation,
                                         const std::string& what);

  // gltf_points.cpp
  struct PointsAndLines {
    PointList points;  // colours always given: one per point
    LineList lines;
  };
  float3 baseColorOf(int material) const;
  Expected<void> readPointsOrLines(const tinygltf::Primitive& primitive, int mode,
                                   const std::string& where, PointsAndLines& out);
  Expected<const PointsAndLines*> pointsAndLinesOf(size_t mesh_index);
  Expected<void> placePointsAndLines();

  // gltf_primitives.cpp
  // The graph mesh of glTF mesh `mesh_index`, read on first use.
  Expected<int32_t> meshFor(size_t mesh_index);
  Expected<void> drawMesh(size_t mesh_index, Mesh& out);
  void addTangents(Mesh& out);
  Expected<void> drawPrimitive(const tinygltf::Primitive& primitive, const std::string& where,
                               Mesh& out);
  // One triangle primitive's readers, and which of Mesh's optional attributes its vertices fill.
  struct PrimitiveReaders {
    int mode = 0;  // TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN
    size_t vertex_count = 0, triangle_count = 0;
    ElementReader positions;
    std::optional<ElementReader> indices;  // none: the vertices in order
    std::optional<ElementReader> normals, uvs, uvs1, colors, tangents;
    uint16_t material = 0;
    bool keep_uvs = false, keep_uvs1 = false, keep_tangents = false;
    bool normal_mapped = false;  // UVs and a normal map: tangents generated where none are given
  };
  Expected<std::optional<ElementReader>> cornerIndices(const tinygltf::Primitive& primitive,
                                                       const std::string& where);
  size_t triangleCount(int mode, size_t corner_count, const std::string& where);
  Expected<void> checkStoredBudget(size_t triangle_count, size_t vertex_count) const;
  Expected<void> readVertexAttributes(const tinygltf::Primitive& primitive,
                                      const std::string& where, PrimitiveReaders& readers,
                                      Mesh& out);
  Expected<void> drawTriangles(const PrimitiveReaders& readers, const std::string& where,
                               Mesh& out);
  Expected<uint32_t> vertexOf(size_t corner, const PrimitiveReaders& readers,
                              const std::string& where, bool& normals_usable, Mesh& out);
  void finishPrimitive(const PrimitiveReaders& readers, const std::string& where,
                       size_t first_vertex, bool normals_usable, Mesh& out);
  struct UvReaders {
    std::optional<ElementReader> set0, set1;  // TEXCOORD_0; TEXCOORD_1 when the material reads it
    bool keep_set1 = false;                   // the primitive's vertices go into Mesh::uvs1
  };
  Expected<UvReaders> uvReaders(const tinygltf::Primitive& primitive, const Material& material,
                                const std::string& where, size_t vertex_count, Mesh& out);
  // Whether the primitive's geometry comes from its Draco stream, decoded into draco_.
  Expected<bool> readDraco(const tinygltf::Primitive& primitive, const std::string& where);

  const tinygltf::Model& gltf_;
  const LoadBudget budget_;
  const std::string name_;
  const std::filesystem::path folder_;
  uintmax_t implied_bytes_left_;
  Model& model_;
  MaterialTable materials_;

  std::map<int, std::vector<uint8_t>> dense_;  // sparse or bufferView-less accessors
  // The Draco primitive being drawn: reader() reads its accessors from the decoded stream.
  std::optional<DracoPrimitive> draco_;
  std::vector<uint32_t> remap_stamp_, remap_vertex_;
  uint32_t stamp_ = 0;
  std::vector<std::pair<size_t, size_t>> generated_normal_ranges_;  // of the mesh being read
  // Vertices of normal-mapped primitives without TANGENT: generateTangents' (of the mesh being
  // read), from the UV set of the primitive's normal map.
  struct TangentRange {
    size_t begin, end;
    int uv_set;
  };
  std::vector<TangentRange> generated_tangent_ranges_;
  bool tangents_refused_ = false;  // a TANGENT of the mesh was unusable: no normal map on it
  std::map<int, size_t> skipped_by_mode_;
  std::map<size_t, PointsAndLines> mesh_points_;  // per glTF mesh, in its space, while placing
  std::set<std::string> warned_;
  size_t unlisted_warnings_ = 0;
  std::vector<int32_t> graph_mesh_;     // per glTF mesh: its graph mesh, or kNoIndex
  std::vector<int32_t> graph_camera_;   // per glTF camera: its graph camera, or kNoIndex
  std::vector<size_t> mesh_nonfinite_;  // per graph mesh: triangles with a non-finite vertex
  uint64_t stored_triangles_ = 0, stored_vertices_ = 0;
};

}  // namespace tessera::io::gltf
