// The glTF node graph: the scene's roots, the tree check and each node's local transform.
// Private to tessera_io.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/scene/scene.h>

#include "gltf_transforms.h"

namespace tinygltf {
class Model;
struct Node;
}  // namespace tinygltf

namespace tessera::io::gltf {

// Takes a warning about the model file, without the file's name.
using Warn = std::function<void(const std::string&)>;

// The root nodes drawn: the default scene's, else scene 0's, else every node that is no other
// node's child. An error for a scene that lists a node the file does not have.
Expected<std::vector<int>> sceneRoots(const tinygltf::Model& gltf, const std::string& name,
                                      const Warn& warn);

// glTF nodes form trees: child indices in range, no node its own ancestor, at most one parent
// each.
Expected<void> checkNodeTree(const tinygltf::Model& gltf, const std::string& name);

// The node's matrix, or T * R * S from its translation, rotation and scale; malformed parts are
// ignored with a warning.
Matrix localMatrix(const tinygltf::Node& node, size_t index, const Warn& warn);

// The node's local transform for the scene graph: its translation, rotation and scale, or its
// matrix as Transform::base; malformed parts are ignored with a warning (as localMatrix).
Transform localTransform(const tinygltf::Node& node, size_t index, const Warn& warn);

// What the scene draws from `roots`, each node once, counted from accessor counts before a byte
// of a buffer is read: the triangles and vertices the flattened mesh will have (instancing
// included), so that a budget can refuse a file before it is flattened.
struct DrawnCounts {
  uint64_t triangles = 0;
  uint64_t vertices = 0;
  uint64_t points = 0;  // points and line end points (gltf_points.cpp)
};
DrawnCounts countDrawn(const tinygltf::Model& gltf, const std::vector<int>& roots);

}  // namespace tessera::io::gltf
