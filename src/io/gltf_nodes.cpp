#include "gltf_nodes.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "tinygltf_include.h"

namespace tessera::io::gltf {

Expected<std::vector<int>> sceneRoots(const tinygltf::Model& gltf, const std::string& name,
                                      const Warn& warn) {
  const size_t node_count = gltf.nodes.size();
  int scene = gltf.defaultScene;
  if (scene >= 0 && static_cast<size_t>(scene) >= gltf.scenes.size()) {
    warn("the default scene " + std::to_string(scene) + " does not exist; scene 0 is drawn");
    scene = -1;
  }
  if (scene < 0 && !gltf.scenes.empty()) scene = 0;
  std::vector<int> roots;
  if (scene >= 0) {
    for (int root : gltf.scenes[static_cast<size_t>(scene)].nodes) {
      if (root < 0 || static_cast<size_t>(root) >= node_count)
        return makeError(name + ": scene " + std::to_string(scene) + " lists node " +
                         std::to_string(root) + ", but the file has " + std::to_string(node_count) +
                         " nodes");
      roots.push_back(root);
    }
    return roots;
  }
  // No scenes: every node that is no other node's child.
  std::vector<char> is_child(node_count, 0);
  for (const tinygltf::Node& node : gltf.nodes)
    for (int child : node.children)
      if (child >= 0 && static_cast<size_t>(child) < node_count)
        is_child[static_cast<size_t>(child)] = 1;
  for (size_t n = 0; n < node_count; ++n)
    if (!is_child[n]) roots.push_back(static_cast<int>(n));
  return roots;
}

// glTF nodes form trees: child indices in range, no node its own ancestor, at most one
// parent each. Cycles first (a depth-first search over the child links, iterative and linear),
// since a cycle reached from elsewhere also gives one of its nodes a second parent.
Expected<void> checkNodeTree(const tinygltf::Model& gltf, const std::string& name) {
  const size_t node_count = gltf.nodes.size();
  for (size_t n = 0; n < node_count; ++n) {
    for (int child : gltf.nodes[n].children) {
      if (child < 0 || static_cast<size_t>(child) >= node_count)
        return makeError(name + ": node " + std::to_string(n) + " lists child " +
                         std::to_string(child) + ", but the file has " +
                         std::to_string(node_count) + " nodes");
      if (static_cast<size_t>(child) == n)
        return makeError(name + ": node " + std::to_string(n) +
                         " is its own child (the node graph must be a tree)");
    }
  }
  enum : char { kUnseen, kOnPath, kDone };
  std::vector<char> state(node_count, kUnseen);
  std::vector<std::pair<size_t, size_t>> path;  // node, next child to visit
  for (size_t start = 0; start < node_count; ++start) {
    if (state[start] != kUnseen) continue;
    state[start] = kOnPath;
    path.push_back({start, 0});
    while (!path.empty()) {
      auto& [node, next] = path.back();
      const std::vector<int>& children = gltf.nodes[node].children;
      if (next == children.size()) {
        state[node] = kDone;
        path.pop_back();
        continue;
      }
      const auto child = static_cast<size_t>(children[next++]);
      if (state[child] == kOnPath)
        return makeError(name + ": node " + std::to_string(child) +
                         " is its own ancestor (its children lead back to it); the node "
                         "graph must be a tree");
      if (state[child] == kUnseen) {
        state[child] = kOnPath;
        path.push_back({child, 0});
      }
    }
  }
  constexpr int kNoParent = -1;
  std::vector<int> parent(node_count, kNoParent);
  for (size_t n = 0; n < node_count; ++n) {
    for (int child : gltf.nodes[n].children) {
      const auto c = static_cast<size_t>(child);
      if (parent[c] != kNoParent)
        return makeError(name + ": node " + std::to_string(c) + " is a child of node " +
                         std::to_string(parent[c]) + " and of node " + std::to_string(n) +
                         " (glTF nodes have at most one parent)");
      parent[c] = static_cast<int>(n);
    }
  }
  return {};
}

Matrix localMatrix(const tinygltf::Node& node, size_t index, const Warn& warn) {
  Matrix local;
  if (node.matrix.size() == 16) {
    std::copy(node.matrix.begin(), node.matrix.end(), local.m.begin());
    return local;
  }
  if (!node.matrix.empty())
    warn("node " + std::to_string(index) + ": a matrix of " + std::to_string(node.matrix.size()) +
         " numbers (16 expected) is ignored");
  Matrix t, r, s;
  if (node.translation.size() == 3) {
    for (int i = 0; i < 3; ++i) t.at(i, 3) = node.translation[static_cast<size_t>(i)];
  } else if (!node.translation.empty()) {
    warn("node " + std::to_string(index) + ": a translation that is not 3 numbers is ignored");
  }
  if (node.rotation.size() == 4) {
    double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
    const double len = std::sqrt(x * x + y * y + z * z + w * w);
    if (len > 0 && std::isfinite(len)) {
      x /= len, y /= len, z /= len, w /= len;
      r.at(0, 0) = 1 - 2 * (y * y + z * z);
      r.at(1, 0) = 2 * (x * y + w * z);
      r.at(2, 0) = 2 * (x * z - w * y);
      r.at(0, 1) = 2 * (x * y - w * z);
      r.at(1, 1) = 1 - 2 * (x * x + z * z);
      r.at(2, 1) = 2 * (y * z + w * x);
      r.at(0, 2) = 2 * (x * z + w * y);
      r.at(1, 2) = 2 * (y * z - w * x);
      r.at(2, 2) = 1 - 2 * (x * x + y * y);
    } else {
      warn("node " + std::to_string(index) + ": a zero or non-finite rotation is ignored");
    }
  } else if (!node.rotation.empty()) {
    warn("node " + std::to_string(index) + ": a rotation that is not 4 numbers is ignored");
  }
  if (node.scale.size() == 3) {
    for (int i = 0; i < 3; ++i) s.at(i, i) = node.scale[static_cast<size_t>(i)];
  } else if (!node.scale.empty()) {
    warn("node " + std::to_string(index) + ": a scale that is not 3 numbers is ignored");
  }
  return t * r * s;  // glTF: T * R * S
}

Transform localTransform(const tinygltf::Node& node, size_t index, const Warn& warn) {
  Transform local;
  if (node.matrix.size() == 16) {
    float4x4 m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = toFloat(node.matrix[static_cast<size_t>(c * 4 + r)]);
    local.base = m;
    return local;
  }
  // The warnings are localMatrix's.
  const Matrix checked = localMatrix(node, index, warn);
  (void)checked;
  if (node.translation.size() == 3)
    local.translation = {toFloat(node.translation[0]), toFloat(node.translation[1]),
                         toFloat(node.translation[2])};
  if (node.rotation.size() == 4) {
    double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
    const double len = std::sqrt(x * x + y * y + z * z + w * w);
    if (len > 0 && std::isfinite(len))
      local.rotation = quat{static_cast<float>(x / len), static_cast<float>(y / len),
                            static_cast<float>(z / len), static_cast<float>(w / len)};
  }
  if (node.scale.size() == 3)
    local.scale = {toFloat(node.scale[0]), toFloat(node.scale[1]), toFloat(node.scale[2])};
  return local;
}

}  // namespace tessera::io::gltf

namespace tessera::io::gltf {

namespace {

// Saturating: a hostile file's counts cannot wrap the total.
uint64_t addCapped(uint64_t a, uint64_t b) {
  return a > UINT64_MAX - b ? UINT64_MAX : a + b;
}

uint64_t multiplyCapped(uint64_t a, uint64_t b) {
  return b != 0 && a > UINT64_MAX / b ? UINT64_MAX : a * b;
}

// What one mesh adds each time a node draws it, from accessor counts alone (as drawPrimitive
// counts: triangles from the index count, or the vertex count without indices).
DrawnCounts meshCounts(const tinygltf::Model& gltf, const tinygltf::Mesh& mesh) {
  DrawnCounts counts;
  auto accessorCount = [&](int index) -> uint64_t {
    if (index < 0 || static_cast<size_t>(index) >= gltf.accessors.size()) return 0;
    return gltf.accessors[static_cast<size_t>(index)].count;
  };
  for (const tinygltf::Primitive& primitive : mesh.primitives) {
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) continue;
    const uint64_t vertices = accessorCount(position->second);
    const uint64_t corners = primitive.indices >= 0 ? accessorCount(primitive.indices) : vertices;
    if (mode == TINYGLTF_MODE_POINTS) {
      counts.points = addCapped(counts.points, corners);
      continue;
    }
    if (mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP ||
        mode == TINYGLTF_MODE_LINE_STRIP) {
      // Two end points per segment, as gltf_points.cpp's segmentCount.
      uint64_t segments = corners >= 2 ? corners - 1 : 0;
      if (mode == TINYGLTF_MODE_LINE) segments = corners / 2;
      if (mode == TINYGLTF_MODE_LINE_LOOP && corners >= 2) segments = corners;
      counts.points = addCapped(counts.points, multiplyCapped(2, segments));
      continue;
    }
    uint64_t triangles = 0;
    if (mode == TINYGLTF_MODE_TRIANGLES)
      triangles = corners / 3;
    else if ((mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) &&
             corners >= 3)
      triangles = corners - 2;
    if (triangles == 0) continue;
    counts.triangles = addCapped(counts.triangles, triangles);
    counts.vertices = addCapped(counts.vertices, std::min(vertices, multiplyCapped(3, triangles)));
  }
  return counts;
}

}  // namespace

DrawnCounts countDrawn(const tinygltf::Model& gltf, const std::vector<int>& roots) {
  std::vector<DrawnCounts> per_mesh(gltf.meshes.size());
  std::vector<char> counted(gltf.meshes.size(), 0);
  std::vector<char> visited(gltf.nodes.size(), 0);
  std::vector<size_t> stack(roots.begin(), roots.end());
  DrawnCounts total;
  while (!stack.empty()) {
    const size_t index = stack.back();
    stack.pop_back();
    if (index >= gltf.nodes.size() || visited[index]) continue;
    visited[index] = 1;
    const tinygltf::Node& node = gltf.nodes[index];
    if (node.mesh >= 0 && static_cast<size_t>(node.mesh) < gltf.meshes.size()) {
      const auto mesh = static_cast<size_t>(node.mesh);
      if (!counted[mesh]) {
        per_mesh[mesh] = meshCounts(gltf, gltf.meshes[mesh]);
        counted[mesh] = 1;
      }
      total.triangles = addCapped(total.triangles, per_mesh[mesh].triangles);
      total.vertices = addCapped(total.vertices, per_mesh[mesh].vertices);
      total.points = addCapped(total.points, per_mesh[mesh].points);
    }
    for (int child : node.children)
      if (child >= 0) stack.push_back(static_cast<size_t>(child));
  }
  return total;
}

}  // namespace tessera::io::gltf
