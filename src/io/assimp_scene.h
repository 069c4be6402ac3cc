// From an imported aiScene to io::Model's scene graph (loadAssimp, model_loader.h). Private to
// tessera_io; built only with assimp (TESSERA_HAS_ASSIMP).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <tessera/io/model_loader.h>

#include "load_budget.h"

struct aiScene;
struct aiNode;
struct aiMesh;
struct aiMaterial;

namespace tessera::io::assimp {

// The scene as assimp's reader left it, before any post-processing: every face with vertices
// and indices in range, every node's meshes in range. assimp's post-processing steps (triangulate,
// join vertices) index without checking, and crash or fail an assertion on a broken face.
Expected<void> checkImportedScene(const aiScene& scene, const std::string& name);

// Distinct warnings listed per file; the rest are counted.
constexpr size_t kMaxWarnings = 20;

class SceneBuilder {
 public:
  // `folder` holds the files the model refers to (textures); empty for a model from memory.
  SceneBuilder(const aiScene& scene, std::string name, std::filesystem::path folder,
               const LoadBudget& budget, Model& model)
      : scene_(scene),
        name_(std::move(name)),
        folder_(std::move(folder)),
        budget_(budget),
        textures_(budget),
        model_(model) {}

  Expected<void> run();
  // The faces the file's header declares (plyDeclaredFaces): when there are any, meshes of
  // points, lines or no faces are not drawn (assimp_points.cpp: hasPointsOrLines).
  void setDeclaredFaces(uint64_t faces) { declared_faces_ = faces; }

 private:
  // The nodes parents first, depth-first from the root, children in order; each node once.
  std::vector<std::pair<const aiNode*, int32_t>> walkNodes();
  bool drawn(const aiMesh* mesh) const;
  Expected<void> checkCounts(const std::vector<std::pair<const aiNode*, int32_t>>& nodes);
  Expected<void> addNode(const aiNode& node, int32_t parent);
  Expected<int32_t> meshFor(const std::vector<unsigned>& meshes);
  Expected<void> appendMesh(const aiMesh& in, Mesh& out, size_t& nonfinite);
  Expected<uint16_t> materialFor(unsigned index);
  Material buildMaterial(const aiMaterial& source, const std::string& label);
  std::shared_ptr<const Texture> texture(const std::string& reference, const std::string& label);
  Expected<void> finish();
  // assimp_points.cpp
  bool hasPointsOrLines(const aiMesh* mesh) const;
  uint64_t pointCount(const aiMesh& mesh) const;
  float3 lineColor(unsigned material) const;
  void placeMesh(const aiMesh& mesh, const float4x4& world, size_t& dropped);
  void placePointsAndLines(const std::vector<std::pair<const aiNode*, int32_t>>& nodes);
  void warn(const std::string& text);

  const aiScene& scene_;
  const std::string name_;
  const std::filesystem::path folder_;
  const LoadBudget budget_;
  TextureBudget textures_;
  Model& model_;
  std::optional<Error> fatal_;  // over a texture budget, found while building a material

  std::map<std::vector<unsigned>, int32_t> graph_mesh_;  // by the node's list of drawn meshes
  std::vector<size_t> mesh_nonfinite_;                   // per graph mesh
  std::map<unsigned, uint16_t> material_index_;          // assimp material -> Model::materials
  std::map<std::string, std::shared_ptr<const Texture>> texture_cache_;
  std::set<std::string> warned_;
  size_t unlisted_warnings_ = 0;
  uint64_t declared_faces_ = 0;
};

}  // namespace tessera::io::assimp
