// A mesh split into clusters of consecutive triangles, each with its bounds and a cone that
// holds its face normals, so that a renderer can skip the parts of a mesh outside the view
// (frustum culling) or wholly facing away (back-face culling of whole clusters), before their
// vertices are transformed. Built once per mesh, shared by its instances.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <tessera/scene/mesh.h>

namespace tessera {

struct MeshCluster {
  uint32_t first_triangle = 0, triangle_count = 0;  // consecutive: ids keep their order
  // The vertices its triangles use lie in [first_vertex, end_vertex).
  uint32_t first_vertex = 0, end_vertex = 0;
  Bounds bounds;  // of its triangles' vertices, in the mesh's space
  // Every face normal n (unit, in the mesh's space) of a non-degenerate triangle has
  // dot(n, cone_axis) >= cone_cos. cone_cos <= 0 (or a degenerate triangle, or a non-finite
  // vertex): no back-face test for the cluster.
  float3 cone_axis{0, 0, 1};
  float cone_cos = -1.0f;
  // Over those triangles, rounded down: the smallest altitude to a triangle's longest edge
  // (twice its area over that edge) and the shortest edge, mesh units. How far snapping may move
  // a vertex before a back face could turn to the front follows from them (render/cull.cpp).
  float min_altitude = 0.0f;
  float min_edge = 0.0f;
};

struct MeshClusters {
  // What it was built for: a mesh with other counts is not described by it.
  size_t vertex_count = 0, triangle_count = 0;
  Bounds bounds;       // of every finite vertex the triangles use
  bool finite = true;  // every vertex a triangle uses is finite
  std::vector<MeshCluster> clusters;

  bool describes(const Mesh& mesh) const {
    return mesh.vertexCount() == vertex_count && mesh.triangleCount() == triangle_count;
  }
};

// Triangles per cluster: a few hundred, so a cluster's test costs far less than its vertices.
constexpr uint32_t kClusterTriangles = 256;

// The clusters of `mesh`: runs of kClusterTriangles consecutive triangles. Triangles the
// renderer drops whatever the view (a vertex index past the mesh, a non-finite vertex) add
// nothing to the bounds or the cone.
std::shared_ptr<const MeshClusters> buildClusters(const Mesh& mesh);

// The mesh with each triangle's second and third corner swapped (same vertices, same order of
// triangles): what a mirroring transform draws with its front faces kept in front.
Mesh reversedWinding(const Mesh& mesh);

}  // namespace tessera
