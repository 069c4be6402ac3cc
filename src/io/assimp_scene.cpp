// The aiScene walk: nodes parents first into Model::graph, each node's list of meshes stored once
// as one tessera mesh and drawn by every node with the same list, materials in first-use order.
#include "assimp_scene.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>
#include <utility>

#include <assimp/material.h>
#include <assimp/scene.h>

#include <tessera/scene/color.h>

#include "graph_model.h"
#include "model_paths.h"

namespace tessera::io::assimp {

namespace fs = std::filesystem;

namespace {

// Mesh::triangle_materials holds uint16_t.
constexpr size_t kMaxMaterials = size_t{1} << 16;

uint64_t saturatingAdd(uint64_t a, uint64_t b) {
  return a > UINT64_MAX - b ? UINT64_MAX : a + b;
}

// assimp's matrices are row-major with the translation in the fourth column (a4, b4, c4): the
// same column-vector convention as tessera's.
float4x4 toMatrix(const aiMatrix4x4& m) {
  const float rows[4][4] = {{m.a1, m.a2, m.a3, m.a4},
                            {m.b1, m.b2, m.b3, m.b4},
                            {m.c1, m.c2, m.c3, m.c4},
                            {m.d1, m.d2, m.d3, m.d4}};
  float4x4 out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out(r, c) = std::isfinite(rows[r][c]) ? rows[r][c] : 0.0f;
  return out;
}

// A file named `file_name`, in any case, in `folder` (not below it), or empty. DOS-era formats
// (3DS) name "TEST.PNG" for test.png.
fs::path findIgnoringCase(const fs::path& folder, const std::string& file_name) {
  constexpr size_t kMaxEntries = 10000;  // a folder of a million files is not searched through
  std::error_code error;
  size_t seen = 0;
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    if (++seen > kMaxEntries) break;
    if (equalsIgnoreCase(it->path().filename().string(), file_name)) return it->path();
  }
  return {};
}

// The texture a material names, beneath `folder`: as named (in any case), or else, for a name
// the sandbox refuses as absolute (exporters write D:\work\tex.jpg), a file of the same name in
// the model's folder. Empty with `why` set when there is none.
fs::path findTexture(const fs::path& folder, const std::string& reference, std::string& why,
                     bool& moved) {
  moved = false;
  Expected<fs::path> path = resolveReferencedFile(folder, reference);
  std::error_code error;
  if (path && fs::exists(*path, error)) return *path;
  std::string file_name = reference;
  const size_t slash = file_name.find_last_of("/\\");
  if (slash != std::string::npos) file_name.erase(0, slash + 1);
  const bool absolute = !path && path.error().message == "it is an absolute path";
  if (!path && !absolute) {
    why = "refused: " + path.error().message;
    return {};
  }
  const fs::path where = absolute ? folder : path->parent_path();
  if (!file_name.empty() && file_name != "..") {
    const fs::path found = findIgnoringCase(where, file_name);
    if (!found.empty()) {
      Expected<fs::path> inside =
          resolveReferencedFile(folder, found.lexically_relative(folder).string());
      if (inside) {
        moved = absolute;
        return *inside;
      }
    }
  }
  why = absolute ? "refused: it is an absolute path, and no " + file_name + " is beside the model"
                 : "not found";
  return {};
}

float unitChannel(float value, float fallback) {
  return std::isfinite(value) ? std::clamp(value, 0.0f, 1.0f) : fallback;
}

}  // namespace

Expected<void> checkImportedScene(const aiScene& scene, const std::string& name) {
  const auto broken = [&](const std::string& what) {
    return makeError(name + ": assimp cannot read it: " + what);
  };
  if (scene.mNumMeshes > 0 && scene.mMeshes == nullptr) return broken("the mesh list is missing");
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* mesh = scene.mMeshes[m];
    const std::string label = "mesh " + std::to_string(m);
    if (mesh == nullptr) return broken(label + " is missing");
    if (mesh->mNumVertices > 0 && mesh->mVertices == nullptr)
      return broken(label + " has no vertex positions");
    if (mesh->mNumFaces > 0 && mesh->mFaces == nullptr) return broken(label + " has no faces");
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices == 0 || face.mIndices == nullptr)
        return broken(label + ", face " + std::to_string(f) + " has no vertices");
      for (unsigned i = 0; i < face.mNumIndices; ++i)
        if (face.mIndices[i] >= mesh->mNumVertices)
          return broken(label + ", face " + std::to_string(f) + " uses vertex " +
                        std::to_string(face.mIndices[i]) + " of " +
                        std::to_string(mesh->mNumVertices));
    }
  }
  // The nodes, without recursion; a node reached twice is a broken tree.
  std::vector<const aiNode*> stack;
  if (scene.mRootNode != nullptr) stack.push_back(scene.mRootNode);
  std::unordered_set<const aiNode*> seen;
  while (!stack.empty()) {
    const aiNode* node = stack.back();
    stack.pop_back();
    if (node == nullptr) return broken("a node is missing");
    if (!seen.insert(node).second) return broken("the node tree has a cycle");
    if (node->mNumMeshes > 0 && node->mMeshes == nullptr)
      return broken("a node's meshes are missing");
    for (unsigned i = 0; i < node->mNumMeshes; ++i)
      if (node->mMeshes[i] >= scene.mNumMeshes)
        return broken("node " + singleQuoted(node->mName.C_Str()) + " refers to mesh " +
                      std::to_string(node->mMeshes[i]) + " of " + std::to_string(scene.mNumMeshes));
    if (node->mNumChildren > 0 && node->mChildren == nullptr)
      return broken("a node's children are missing");
    for (unsigned i = 0; i < node->mNumChildren; ++i) stack.push_back(node->mChildren[i]);
  }
  return {};
}

Expected<void> SceneBuilder::run() {
  if (scene_.mRootNode != nullptr && scene_.mNumMeshes == 0)
    return makeError(name_ +
                     ": nothing to draw: no faces, points or lines (the file holds no "
                     "meshes" +
                     (scene_.mNumCameras || scene_.mNumLights ? ", only cameras or lights)" : ")"));
  if (scene_.mRootNode == nullptr || (scene_.mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    return makeError(name_ + ": assimp cannot read it: the file holds no complete scene");
  const std::vector<std::pair<const aiNode*, int32_t>> nodes = walkNodes();
  if (Expected<void> ok = checkCounts(nodes); !ok) return ok;
  for (const auto& [node, parent] : nodes)
    if (Expected<void> ok = addNode(*node, parent); !ok) return ok;
  placePointsAndLines(nodes);
  return finish();
}

std::vector<std::pair<const aiNode*, int32_t>> SceneBuilder::walkNodes() {
  // Without recursion (a hierarchy may be as deep as the file is long): a stack of nodes still
  // to visit, each with its parent's index in the output, pushed in reverse so children keep
  // their order. A node reached twice (assimp builds trees, but a broken file is hostile) once.
  std::vector<std::pair<const aiNode*, int32_t>> out, stack{{scene_.mRootNode, kNoIndex}};
  std::unordered_set<const aiNode*> seen;
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    if (node == nullptr || !seen.insert(node).second) continue;
    const auto index = static_cast<int32_t>(out.size());
    out.emplace_back(node, parent);
    for (unsigned i = node->mNumChildren; i-- > 0;)
      if (node->mChildren != nullptr) stack.emplace_back(node->mChildren[i], index);
  }
  return out;
}

// A mesh whose faces are triangles (after aiProcess_Triangulate and SortByPType, a mesh holds
// one kind of primitive).
bool SceneBuilder::drawn(const aiMesh* mesh) const {
  return mesh != nullptr && (mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) &&
         mesh->mNumFaces > 0 && mesh->mFaces != nullptr && mesh->mVertices != nullptr;
}

// The budget, before anything is copied: instancing can multiply a small file into a huge mesh.
Expected<void> SceneBuilder::checkCounts(
    const std::vector<std::pair<const aiNode*, int32_t>>& nodes) {
  uint64_t triangles = 0, vertices = 0, points = 0;
  std::map<unsigned, uint64_t> mesh_points;
  for (const auto& [node, parent] : nodes) {
    for (unsigned i = 0; i < node->mNumMeshes && node->mMeshes != nullptr; ++i) {
      const unsigned index = node->mMeshes[i];
      if (index >= scene_.mNumMeshes) continue;
      if (!drawn(scene_.mMeshes[index])) {
        if (!hasPointsOrLines(scene_.mMeshes[index])) continue;
        auto [known, added] = mesh_points.try_emplace(index, 0);
        if (added) known->second = pointCount(*scene_.mMeshes[index]);
        points = saturatingAdd(points, known->second);
        continue;
      }
      triangles = saturatingAdd(triangles, scene_.mMeshes[index]->mNumFaces);
      vertices = saturatingAdd(vertices, scene_.mMeshes[index]->mNumVertices);
    }
  }
  if (Expected<void> ok = checkBudget(name_, "triangles (after instancing)", triangles,
                                      budget_.triangles(), "--max-triangles");
      !ok)
    return ok;
  if (Expected<void> ok = checkBudget(name_, "vertices (after instancing)", vertices,
                                      budget_.vertices(), "--max-triangles");
      !ok)
    return ok;
  return checkBudget(name_, "points and line end points (after instancing)", points,
                     budget_.points(), "");
}

Expected<void> SceneBuilder::addNode(const aiNode& node, int32_t parent) {
  GraphNode out;
  out.name = node.mName.C_Str();
  out.parent = parent;
  out.source = static_cast<int32_t>(model_.graph.nodes.size());
  out.local.base = toMatrix(node.mTransformation);
  std::vector<unsigned> meshes;
  for (unsigned i = 0; i < node.mNumMeshes && node.mMeshes != nullptr; ++i) {
    const unsigned index = node.mMeshes[i];
    if (index >= scene_.mNumMeshes)
      return makeError(name_ + ": assimp cannot read it: node " + singleQuoted(out.name) +
                       " refers to mesh " + std::to_string(index) + " of " +
                       std::to_string(scene_.mNumMeshes));
    if (drawn(scene_.mMeshes[index])) meshes.push_back(index);
  }
  if (!meshes.empty()) {
    Expected<int32_t> mesh = meshFor(meshes);
    if (!mesh) return mesh.error();
    out.mesh = *mesh;
    model_.nonfinite_triangles += mesh_nonfinite_[static_cast<size_t>(*mesh)];
  }
  model_.graph.nodes.push_back(std::move(out));
  return {};
}

Expected<int32_t> SceneBuilder::meshFor(const std::vector<unsigned>& meshes) {
  if (auto found = graph_mesh_.find(meshes); found != graph_mesh_.end()) return found->second;
  auto mesh = std::make_shared<Mesh>();
  size_t nonfinite = 0;
  bool all_normals = true;
  for (unsigned index : meshes) {
    const aiMesh& in = *scene_.mMeshes[index];
    all_normals &= in.mNormals != nullptr;
    if (Expected<void> ok = appendMesh(in, *mesh, nonfinite); !ok) return ok.error();
  }
  if (!all_normals) generateSmoothNormals(*mesh);
  GraphMesh out;
  out.name = scene_.mMeshes[meshes.front()]->mName.C_Str();
  out.mesh = std::move(mesh);
  const auto index = static_cast<int32_t>(model_.graph.meshes.size());
  model_.graph.meshes.push_back(std::move(out));
  mesh_nonfinite_.push_back(nonfinite);
  graph_mesh_.emplace(meshes, index);
  return index;
}

Expected<void> SceneBuilder::appendMesh(const aiMesh& in, Mesh& out, size_t& nonfinite) {
  Expected<uint16_t> material = materialFor(in.mMaterialIndex);
  if (!material) return material.error();
  const auto base = static_cast<uint32_t>(out.positions.size());
  const aiVector3D* uvs = in.mTextureCoords[0];
  const aiColor4D* colors = in.mColors[0];
  // A mesh without UVs or colours beside one with them: zero UVs, white.
  if (uvs != nullptr && out.uvs.size() < base) out.uvs.resize(base, float2{0, 0});
  if (colors != nullptr && out.colors.size() < base) out.colors.resize(base, float4{1, 1, 1, 1});
  for (unsigned v = 0; v < in.mNumVertices; ++v) {
    const aiVector3D& p = in.mVertices[v];
    out.positions.push_back(float3{p.x, p.y, p.z});
    if (in.mNormals != nullptr) {
      const aiVector3D& n = in.mNormals[v];
      const float3 unit = safeNormalize(float3{n.x, n.y, n.z});
      out.normals.push_back(unit == float3{0, 0, 0} ? float3{0, 0, 1} : unit);
    }
    if (uvs != nullptr) {
      const float u = uvs[v].x, w = uvs[v].y;
      out.uvs.push_back(float2{std::isfinite(u) ? u : 0.0f, std::isfinite(w) ? w : 0.0f});
    } else if (!out.uvs.empty()) {
      out.uvs.push_back(float2{0, 0});
    }
    if (colors != nullptr) {
      const aiColor4D& c = colors[v];
      // The formats assimp reads store display colours (PLY's 0-255 bytes): sRGB-encoded.
      out.colors.push_back(float4{srgbToLinear(unitChannel(c.r, 1)),
                                  srgbToLinear(unitChannel(c.g, 1)),
                                  srgbToLinear(unitChannel(c.b, 1)), unitChannel(c.a, 1)});
    } else if (!out.colors.empty()) {
      out.colors.push_back(float4{1, 1, 1, 1});
    }
  }
  for (unsigned f = 0; f < in.mNumFaces; ++f) {
    const aiFace& face = in.mFaces[f];
    if (face.mNumIndices != 3 || face.mIndices == nullptr) continue;  // not drawn (SortByPType)
    bool finite = true;
    for (unsigned c = 0; c < 3; ++c) {
      const unsigned index = face.mIndices[c];
      if (index >= in.mNumVertices)
        return makeError(name_ + ": assimp cannot read it: mesh " + singleQuoted(in.mName.C_Str()) +
                         " has a face with vertex " + std::to_string(index) + " of " +
                         std::to_string(in.mNumVertices));
      out.indices.push_back(base + index);
      finite &= isFinite(out.positions[base + index]);
    }
    if (!finite) ++nonfinite;
    out.triangle_materials.push_back(*material);
  }
  if (in.mNormals == nullptr && !out.normals.empty())
    out.normals.resize(out.positions.size(), float3{0, 0, 1});  // replaced: generated
  return {};
}

Expected<uint16_t> SceneBuilder::materialFor(unsigned index) {
  if (auto found = material_index_.find(index); found != material_index_.end())
    return found->second;
  if (model_.materials.size() == kMaxMaterials)
    return makeError(name_ + ": more than " + std::to_string(kMaxMaterials) + " materials in use");
  Material material;
  if (index < scene_.mNumMaterials && scene_.mMaterials[index] != nullptr) {
    const aiMaterial& source = *scene_.mMaterials[index];
    aiString label_name;
    source.Get(AI_MATKEY_NAME, label_name);
    const std::string label =
        "material " + std::to_string(index) +
        (label_name.length ? " " + singleQuoted(label_name.C_Str()) : std::string());
    material = buildMaterial(source, label);
    if (fatal_) return *fatal_;
  }
  const auto out = static_cast<uint16_t>(model_.materials.size());
  model_.materials.push_back(std::move(material));
  material_index_.emplace(index, out);
  return out;
}

Material SceneBuilder::buildMaterial(const aiMaterial& source, const std::string& label) {
  Material material;
  aiColor4D diffuse;
  const bool has_color =
      aiGetMaterialColor(&source, AI_MATKEY_COLOR_DIFFUSE, &diffuse) == AI_SUCCESS ||
      aiGetMaterialColor(&source, AI_MATKEY_BASE_COLOR, &diffuse) == AI_SUCCESS;
  if (has_color)
    material.base_color = float4{unitChannel(diffuse.r, 0.8f), unitChannel(diffuse.g, 0.8f),
                                 unitChannel(diffuse.b, 0.8f), 1.0f};
  float opacity = 1.0f;
  if (aiGetMaterialFloat(&source, AI_MATKEY_OPACITY, &opacity) == AI_SUCCESS) {
    // Exporters write 0 where they mean "not set" often enough that an invisible model is the
    // likelier mistake.
    if (opacity > 0.0f && opacity < 1.0f)
      material.base_color.w = opacity;
    else if (!(opacity > 0.0f))
      warn(label + " has opacity " + std::to_string(opacity) + ": it is drawn opaque");
  }
  int two_sided = 0;
  if (aiGetMaterialInteger(&source, AI_MATKEY_TWOSIDED, &two_sided) == AI_SUCCESS)
    material.double_sided = two_sided != 0;
  aiString path;
  if (source.GetTexture(aiTextureType_DIFFUSE, 0, &path) == AI_SUCCESS ||
      source.GetTexture(aiTextureType_BASE_COLOR, 0, &path) == AI_SUCCESS) {
    material.albedo = texture(path.C_Str(), label);
    // A black diffuse colour beside a texture is an exporter's "the texture says it".
    if (material.albedo && material.base_color.x == 0 && material.base_color.y == 0 &&
        material.base_color.z == 0)
      material.base_color = float4{1, 1, 1, material.base_color.w};
  }
  return material;
}

std::shared_ptr<const Texture> SceneBuilder::texture(const std::string& reference,
                                                     const std::string& label) {
  const std::string dropped = "; " + label + " is drawn without its texture";
  if (auto cached = texture_cache_.find(reference); cached != texture_cache_.end())
    return cached->second;
  std::shared_ptr<const Texture>& slot = texture_cache_[reference];
  Expected<MaterialTexture> decoded = MaterialTexture{};
  if (const aiTexture* embedded = scene_.GetEmbeddedTexture(reference.c_str())) {
    if (embedded->mHeight != 0 || embedded->pcData == nullptr) {
      warn("texture " + singleQuoted(elided(reference)) + " is embedded as raw texels, not read" +
           dropped);
      return nullptr;
    }
    // mHeight 0: a compressed image (PNG, JPEG...) of mWidth bytes.
    decoded =
        textures_.decode(reinterpret_cast<const unsigned char*>(embedded->pcData), embedded->mWidth,
                         name_ + " texture " + singleQuoted(elided(reference)),
                         /*srgb=*/true);
  } else if (folder_.empty()) {
    warn("texture " + singleQuoted(elided(reference)) +
         " is an external file, and this model was given in memory" + dropped);
    return nullptr;
  } else {
    std::string why;
    bool moved = false;
    const fs::path path = findTexture(folder_, reference, why, moved);
    if (path.empty()) {
      warn("texture " + singleQuoted(elided(reference)) + " " + why + dropped);
      return nullptr;
    }
    if (moved)
      warn("texture " + singleQuoted(elided(reference)) + " is an absolute path; " +
           path.filename().string() + " beside the model is used");
    decoded = textures_.load(path, /*srgb=*/true);
  }
  if (!decoded) {
    if (!fatal_) fatal_ = decoded.error();
    return nullptr;
  }
  if (!decoded->texture) {
    warn(decoded->warning + dropped);
    return nullptr;
  }
  slot = decoded->texture;
  return slot;
}

Expected<void> SceneBuilder::finish() {
  if (model_.graph.drawnTriangleCount() == 0 && model_.points.empty() &&
      model_.lines.points.empty())
    return makeError(name_ + ": nothing to draw: no faces, points or lines in the scene" +
                     (declared_faces_ > 0
                          ? " (the header declares " + std::to_string(declared_faces_) +
                                " faces; is the file cut short?)"
                          : ""));
  if (declared_faces_ > 0) {
    size_t degenerate = 0;
    for (unsigned i = 0; i < scene_.mNumMeshes; ++i)
      degenerate += scene_.mMeshes[i] != nullptr && !drawn(scene_.mMeshes[i]);
    if (degenerate > 0)
      warn(std::to_string(degenerate) +
           " mesh(es) of PLY faces with fewer than 3 corners (or none) are not drawn");
  }
  if (scene_.mNumAnimations > 0) warn("animations are not played (assimp formats)");
  if (scene_.mNumCameras > 0 || scene_.mNumLights > 0)
    warn("the file's cameras and lights are not used");
  finishGraphModel(model_, name_, unlisted_warnings_);
  return {};
}

void SceneBuilder::warn(const std::string& text) {
  const std::string line = name_ + ": " + text;
  if (!warned_.insert(line).second) return;
  if (warned_.size() > kMaxWarnings) {
    ++unlisted_warnings_;
    return;
  }
  model_.warnings.push_back(line);
}

}  // namespace tessera::io::assimp
