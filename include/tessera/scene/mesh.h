// Indexed triangle mesh. Every attribute array is either empty or has one entry per vertex.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include <tessera/math/vec.h>

namespace tessera {

// Mesh::triangle_edges: bit k set when the triangle's edge from corner k to corner (k + 1) % 3
// is a side of the polygon it came from (not a diagonal of its triangulation).
constexpr uint8_t kAllTriangleEdges = 0b111;

struct Bounds {
  // Empty: min above max. Infinite, so that any finite position, however large, sets them.
  float3 min{std::numeric_limits<float>::infinity()};
  float3 max{-std::numeric_limits<float>::infinity()};

  bool empty() const { return min.x > max.x; }
  void add(float3 p) {
    min = tessera::min(min, p);
    max = tessera::max(max, p);
  }
  float3 center() const { return (min + max) * 0.5f; }
  float3 extent() const { return max - min; }
  float radius() const { return empty() ? 0.0f : 0.5f * length(extent()); }
};

// Per-vertex arrays: positions, normals, uvs, colors, tangents; generateTangents copies each when
// it splits a vertex (a new one must be added there: src/scene/tangents.cpp, copyVertex).
struct Mesh {
  std::vector<float3> positions;
  std::vector<float3> normals;  // empty: generate them (generateSmoothNormals) or draw flat
  std::vector<float2> uvs;      // TEXCOORD_0; empty: no texture coordinates
  // TEXCOORD_1 (glTF); empty: none, and a map that reads set 1 reads `uvs` instead. Only a glTF
  // primitive whose material reads set 1 fills it.
  std::vector<float2> uvs1;
  std::vector<float4> colors;  // linear RGBA; empty: white
  // Tangent space for normal maps (glTF's TANGENT): xyz along +u, unit; w = +-1, the bitangent is
  // cross(normal, xyz) * w (along +v). Empty: none (generateTangents, tangents.h, makes them).
  std::vector<float4> tangents;
  std::vector<uint32_t> indices;             // three per triangle
  std::vector<uint16_t> triangle_materials;  // one per triangle, index into Object::materials;
                                             // empty: material 0 everywhere
  // One per triangle: which of its edges are polygon outline (kAllTriangleEdges' bits), for
  // RenderOptions::edges. Empty: every edge of every triangle.
  std::vector<uint8_t> triangle_edges;

  size_t vertexCount() const { return positions.size(); }
  size_t triangleCount() const { return indices.size() / 3; }

  // Bounds of the finite positions.
  Bounds bounds() const;
};

// `v` at unit length, also when its length overflows or underflows float (a huge or tiny
// model's cross products); (0, 0, 0) for a zero or non-finite `v`.
float3 safeNormalize(float3 v);

// Smooth, area-weighted vertex normals (each face adds its unnormalized cross product).
// Vertices that no finite, non-degenerate face touches get (0, 0, 1).
void generateSmoothNormals(Mesh& mesh);

// Tangents for normal maps: generateTangents (tangents.h, MikkTSpace).

}  // namespace tessera
