// The scene graph: nodes with a parent, a local transform and optional mesh, camera and light.
// A mesh drawn by many nodes is stored once and drawn per instance (instantiate): 10,000
// instances cost 10,000 transforms, not 10,000 meshes.
//
// Order. Nodes are stored parents first (a node's parent has a smaller index), so world
// transforms take one pass over the array, with no recursion a deep file could overflow. The
// glTF loader stores them depth-first from the scene's roots in order (a node before its
// children, children in the file's order), and instances are numbered in node order: triangle
// ids (ARCHITECTURE.md's contract) run over the instances depth-first, each instance's
// triangles in the mesh's order, every instance with ids of its own.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/scene/animation.h>
#include <tessera/scene/scene.h>

namespace tessera {

struct MeshClusters;

constexpr int32_t kNoIndex = -1;

struct GraphNode {
  std::string name;
  int32_t parent = kNoIndex;  // a smaller index, or kNoIndex for a root
  // The local transform: T * R * S * base (Transform). TRS is what animation channels target
  // (translation, rotation, scale); a file's `matrix` goes in `base`, with TRS the identity.
  Transform local;
  int32_t mesh = kNoIndex;    // into SceneGraph::meshes
  int32_t camera = kNoIndex;  // into SceneGraph::cameras
  int32_t light = kNoIndex;   // into the scene's lights (filled by whoever loads them)
  int32_t source = kNoIndex;  // the node's index in its file (glTF), for messages and animation
};

// A mesh with the materials its triangle_materials index, and its clusters.
struct GraphMesh {
  std::string name;
  std::shared_ptr<const Mesh> mesh;
  MaterialList materials;
  std::shared_ptr<const MeshClusters> clusters;  // built by prepareMeshes()
  // The mesh with every triangle's winding reversed, for instances whose world matrix mirrors
  // (glTF: a negative determinant turns the winding clockwise, and front faces stay front).
  // Same vertices, same triangle order: the ids do not change. Made when first needed.
  std::shared_ptr<const Mesh> mirrored;
  std::shared_ptr<const MeshClusters> mirrored_clusters;
};

// A camera of the file, placed by the world transform of the node that holds it: the node's
// origin is the eye, it looks down its -Z with +Y up (glTF 3.10).
struct GraphCamera {
  std::string name;
  bool orthographic = false;
  float yfov_radians = 0.8f;     // perspective: the vertical field of view
  float aspect_ratio = 0.0f;     // perspective: 0 = the image's
  float xmag = 1.0f, ymag = 1.0f;  // orthographic: half the width and height of the view
  float znear = 0.1f;
  float zfar = 0.0f;  // 0: infinite (perspective only), near and far then fit the scene
  // Why the file's camera cannot be used (a zero or negative field), or empty. A skipped camera
  // keeps its place, so that indices are the file's (f3d's --camera-index).
  std::string skipped;
};

struct SceneGraph {
  std::vector<GraphNode> nodes;  // parents first
  std::vector<GraphMesh> meshes;
  std::vector<GraphCamera> cameras;
  // Keyframe clips (glTF animations) over these nodes: Animation::apply, then updateWorld().
  std::vector<Animation> animations;
  std::vector<float4x4> world;  // updateWorld(): one per node

  // An error naming the node or index for a parent not before its child, or an index out of
  // range (a caller's graph built by hand; the loaders build valid ones).
  Expected<void> validate() const;
  // World matrices of every node, parents first: one pass, no recursion.
  void updateWorld();
  // Clusters of every mesh that has none (clusters.h), and each mesh's mirrored copy that an
  // instance needs (after updateWorld).
  void prepareMeshes();
  // Instances drawn: the nodes with a mesh.
  size_t instanceCount() const;
  // Triangles drawn, over every instance.
  size_t drawnTriangleCount() const;
  // The instances as one mesh in world space, in the id order above (the flattening the glTF
  // loader did before the graph): for tools and tests. Mirrored instances have their winding
  // reversed. Materials index the meshes' lists as they are (meshes that share one list share
  // the indices).
  Mesh flatten() const;
  // World bounds of every instance's finite vertices.
  Bounds bounds() const;
  // The camera `index` (into `cameras`) as the first node that holds it sees the scene, for an
  // image of `aspect`: near and far from the file, or fitted to `scene_bounds` when the file
  // leaves far open. An error when no node holds it.
  Expected<Camera> camera(size_t index, float aspect, const Bounds& scene_bounds) const;
};

// Appends one Object per instance to scene.objects, in node order, each with the mesh (or its
// mirrored copy), its clusters, the materials (shared with the mesh, not copied) and
// `transform.base` = the node's world matrix; `object` gives the rest (shading, cull). Call
// updateWorld() and prepareMeshes() first.
void instantiate(const SceneGraph& graph, const Object& object, Scene& scene);

// Per frame (an animation): the world matrices of the instances appended from `first_object`
// by instantiate, after updateWorld(). Allocates nothing.
void updateInstances(const SceneGraph& graph, size_t first_object, Scene& scene);

}  // namespace tessera
