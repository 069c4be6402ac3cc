// The aiScene's points and lines: meshes of point and line faces (SortByPType gives each kind a
// mesh of its own) and meshes of vertices without faces (a PLY of vertices only), placed at every
// node that draws them, in world space, into Model::points and Model::lines.
#include <algorithm>
#include <cmath>

#include <assimp/material.h>
#include <assimp/scene.h>

#include <tessera/scene/color.h>

#include "assimp_scene.h"

namespace tessera::io::assimp {

namespace {

float unitChannel(float value, float fallback) {
  return std::isfinite(value) ? std::clamp(value, 0.0f, 1.0f) : fallback;
}

// A vertex colour: sRGB-encoded in the formats assimp reads (PLY's bytes), decoded.
float3 vertexColor(const aiColor4D& c) {
  return float3{srgbToLinear(unitChannel(c.r, 1)), srgbToLinear(unitChannel(c.g, 1)),
                srgbToLinear(unitChannel(c.b, 1))};
}

float3 worldPoint(const float4x4& world, const aiVector3D& p) {
  return (world * float4{p.x, p.y, p.z, 1.0f}).xyz();
}

}  // namespace

// A PLY that declares faces draws none of these: its faces are polygons, and one of fewer than 3
// corners is degenerate, or what assimp's reader makes of a truncated file (it reads a face cut
// short as a line); finish() says so.
bool SceneBuilder::hasPointsOrLines(const aiMesh* mesh) const {
  if (mesh == nullptr || mesh->mVertices == nullptr || mesh->mNumVertices == 0) return false;
  if (declared_faces_ > 0) return false;
  if (mesh->mNumFaces == 0) return true;  // vertices only: a point cloud
  return mesh->mFaces != nullptr &&
         (mesh->mPrimitiveTypes & (aiPrimitiveType_POINT | aiPrimitiveType_LINE)) != 0;
}

// Points and line end points one instance of `mesh` adds, for the budget.
uint64_t SceneBuilder::pointCount(const aiMesh& mesh) const {
  if (mesh.mNumFaces == 0) return mesh.mNumVertices;
  uint64_t count = 0;
  for (unsigned f = 0; f < mesh.mNumFaces; ++f)
    if (mesh.mFaces[f].mNumIndices <= 2) count += mesh.mFaces[f].mNumIndices;
  return count;
}

// The material's diffuse (or base) colour, linear as for faces; the default material's without.
float3 SceneBuilder::lineColor(unsigned material) const {
  const float3 fallback = Material{}.base_color.xyz();
  if (material >= scene_.mNumMaterials || scene_.mMaterials[material] == nullptr) return fallback;
  aiColor4D diffuse;
  const aiMaterial* source = scene_.mMaterials[material];
  if (aiGetMaterialColor(source, AI_MATKEY_COLOR_DIFFUSE, &diffuse) != AI_SUCCESS &&
      aiGetMaterialColor(source, AI_MATKEY_BASE_COLOR, &diffuse) != AI_SUCCESS)
    return fallback;
  return float3{unitChannel(diffuse.r, fallback.x), unitChannel(diffuse.g, fallback.y),
                unitChannel(diffuse.b, fallback.z)};
}

// One instance of `mesh` at `world`. Points without vertex colours get 0 for now (a packed colour
// is never 0: its alpha is 255); placePointsAndLines gives them white, or drops every colour when
// no point has one.
void SceneBuilder::placeMesh(const aiMesh& mesh, const float4x4& world, size_t& dropped) {
  const aiColor4D* colors = mesh.mColors[0];
  constexpr uint32_t kNoColor = 0;
  auto addPoint = [&](unsigned v) {
    const float3 p = worldPoint(world, mesh.mVertices[v]);
    if (!isFinite(p)) {
      ++dropped;
      return;
    }
    model_.points.positions.push_back(p);
    model_.points.colors.push_back(colors ? packSrgba8(float4{vertexColor(colors[v]), 1.0f})
                                          : kNoColor);
  };
  if (mesh.mNumFaces == 0) {
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) addPoint(v);
    return;
  }
  const float3 material_color = lineColor(mesh.mMaterialIndex);
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mIndices == nullptr) continue;
    if (face.mNumIndices == 1 && face.mIndices[0] < mesh.mNumVertices) {
      addPoint(face.mIndices[0]);
    } else if (face.mNumIndices == 2 && face.mIndices[0] < mesh.mNumVertices &&
               face.mIndices[1] < mesh.mNumVertices) {
      const unsigned a = face.mIndices[0], b = face.mIndices[1];
      const float3 pa = worldPoint(world, mesh.mVertices[a]);
      const float3 pb = worldPoint(world, mesh.mVertices[b]);
      if (!isFinite(pa) || !isFinite(pb)) {
        ++dropped;
        continue;
      }
      const float3 color =
          colors ? (vertexColor(colors[a]) + vertexColor(colors[b])) * 0.5f : material_color;
      model_.lines.add(pa, pb, color);
    }
  }
}

void SceneBuilder::placePointsAndLines(
    const std::vector<std::pair<const aiNode*, int32_t>>& nodes) {
  SceneGraph& graph = model_.graph;
  graph.updateWorld();
  size_t dropped = 0;
  for (size_t i = 0; i < nodes.size(); ++i) {
    const aiNode& node = *nodes[i].first;
    for (unsigned m = 0; m < node.mNumMeshes && node.mMeshes != nullptr; ++m) {
      const unsigned index = node.mMeshes[m];
      if (index < scene_.mNumMeshes && !drawn(scene_.mMeshes[index]) &&
          hasPointsOrLines(scene_.mMeshes[index]))
        placeMesh(*scene_.mMeshes[index], graph.world[i], dropped);
    }
  }
  // PointList's colours are one per point or none: white for points of a colourless mesh beside
  // coloured ones, none at all (the renderer's point colour) when no mesh has any.
  std::vector<uint32_t>& colors = model_.points.colors;
  const bool any = std::any_of(colors.begin(), colors.end(), [](uint32_t c) { return c != 0; });
  if (!any)
    colors.clear();
  else
    for (uint32_t& c : colors)
      if (c == 0) c = 0xffffffffu;
  if (dropped > 0)
    warn(std::to_string(dropped) +
         " points or line segments at a NaN or infinite position are not drawn");
}

}  // namespace tessera::io::assimp
