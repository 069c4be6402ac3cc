// The glTF builder's points and lines: primitives of mode POINTS, LINES, LINE_LOOP and LINE_STRIP,
// read once per glTF mesh in its own space and placed, for every node that draws the mesh, at the
// node's world matrix into Model::points and Model::lines. Colour: the material's baseColorFactor
// (glTF's default material is white) times COLOR_0 (linear); a segment takes the mean of its two
// ends' colours.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <tessera/scene/color.h>

#include "gltf_builder.h"
#include "tinygltf_include.h"

namespace tessera::io::gltf {

namespace {

bool isPointOrLineMode(int mode) {
  return mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE ||
         mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP;
}

// The corners (into the primitive's index list) of segment `s` of `count` corners.
std::pair<size_t, size_t> segmentCorners(int mode, size_t s, size_t count) {
  if (mode == TINYGLTF_MODE_LINE) return {2 * s, 2 * s + 1};
  if (mode == TINYGLTF_MODE_LINE_LOOP && s + 1 == count) return {s, 0};  // the closing segment
  return {s, s + 1};
}

size_t segmentCount(int mode, size_t corners) {
  if (mode == TINYGLTF_MODE_LINE) return corners / 2;
  if (mode == TINYGLTF_MODE_LINE_LOOP) return corners >= 2 ? corners : 0;
  return corners >= 2 ? corners - 1 : 0;  // LINE_STRIP
}

float3 worldPoint(const float4x4& world, float3 p) {
  return (world * float4{p, 1.0f}).xyz();
}

}  // namespace

// The material's baseColorFactor, clamped to 0..1; white without a material (glTF 3.9.6).
float3 GraphBuilder::baseColorOf(int material) const {
  float3 color{1, 1, 1};
  if (material < 0 || static_cast<size_t>(material) >= gltf_.materials.size()) return color;
  const std::vector<double>& factor =
      gltf_.materials[static_cast<size_t>(material)].pbrMetallicRoughness.baseColorFactor;
  for (int c = 0; c < 3 && static_cast<size_t>(c) < factor.size(); ++c)
    color[c] = std::isfinite(factor[static_cast<size_t>(c)])
                   ? std::clamp(static_cast<float>(factor[static_cast<size_t>(c)]), 0.0f, 1.0f)
                   : 1.0f;
  return color;
}

// One point or line primitive, in the mesh's space, appended to `out`.
Expected<void> GraphBuilder::readPointsOrLines(const tinygltf::Primitive& primitive, int mode,
                                               const std::string& where, PointsAndLines& out) {
  auto position_it = primitive.attributes.find("POSITION");
  if (position_it == primitive.attributes.end()) {
    warn(where + " has no POSITION and is skipped");
    return {};
  }
  Expected<ElementReader> positions = reader(position_it->second, "POSITION of " + where, {3}, {});
  if (!positions) return positions.error();
  const size_t vertex_count = positions->count;
  Expected<std::optional<ElementReader>> read_indices = indexReader(primitive, where);
  if (!read_indices) return read_indices.error();
  const std::optional<ElementReader> indices = *read_indices;
  const size_t corners = indices ? indices->count : vertex_count;
  Expected<void> fatal;
  const std::optional<ElementReader> colors = colorAttribute(primitive, where, vertex_count, fatal);
  if (!fatal) return fatal;
  const float3 base = baseColorOf(primitive.material);

  // The vertex at `corner`, checked against the positions.
  auto vertexAt = [&](size_t corner) -> Expected<size_t> {
    const size_t local = indices ? indices->index(corner) : corner;
    if (local >= vertex_count)
      return makeError(name_ + ": " + where + ": index " + std::to_string(local) + " is past the " +
                       std::to_string(vertex_count) + " vertices");
    return local;
  };
  auto position = [&](size_t v) {
    return float3{positions->component(v, 0), positions->component(v, 1),
                  positions->component(v, 2)};
  };
  auto color = [&](size_t v) {
    if (!colors) return base;
    return base * float3{colors->component(v, 0), colors->component(v, 1), colors->component(v, 2)};
  };
  if (mode == TINYGLTF_MODE_POINTS) {
    for (size_t c = 0; c < corners; ++c) {
      Expected<size_t> v = vertexAt(c);
      if (!v) return v.error();
      out.points.positions.push_back(position(*v));
      out.points.colors.push_back(packSrgba8(float4{color(*v), 1.0f}));
    }
    return {};
  }
  if (mode == TINYGLTF_MODE_LINE && corners % 2 != 0)
    warn(where + ": 1 vertex after the last whole line segment is ignored");
  const size_t segments = segmentCount(mode, corners);
  for (size_t s = 0; s < segments; ++s) {
    const auto [first, second] = segmentCorners(mode, s, corners);
    Expected<size_t> a = vertexAt(first);
    if (!a) return a.error();
    Expected<size_t> b = vertexAt(second);
    if (!b) return b.error();
    out.lines.add(position(*a), position(*b), (color(*a) + color(*b)) * 0.5f);
  }
  return {};
}

// Every point and line primitive of glTF mesh `mesh_index`, read on first use.
Expected<const GraphBuilder::PointsAndLines*> GraphBuilder::pointsAndLinesOf(size_t mesh_index) {
  if (auto known = mesh_points_.find(mesh_index); known != mesh_points_.end())
    return &known->second;
  PointsAndLines read;
  const tinygltf::Mesh& mesh = gltf_.meshes[mesh_index];
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& primitive = mesh.primitives[p];
    if (!isPointOrLineMode(primitive.mode)) continue;
    const std::string where =
        "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(p);
    if (Expected<void> ok = readPointsOrLines(primitive, primitive.mode, where, read); !ok)
      return ok.error();
  }
  return &mesh_points_.emplace(mesh_index, std::move(read)).first->second;
}

// Each node's points and lines at its world matrix (world matrices up to date), in node order.
Expected<void> GraphBuilder::placePointsAndLines() {
  SceneGraph& graph = model_.graph;
  size_t dropped = 0;
  for (size_t i = 0; i < graph.nodes.size(); ++i) {
    const tinygltf::Node& node = gltf_.nodes[static_cast<size_t>(graph.nodes[i].source)];
    if (node.mesh < 0 || static_cast<size_t>(node.mesh) >= gltf_.meshes.size()) continue;
    Expected<const PointsAndLines*> local = pointsAndLinesOf(static_cast<size_t>(node.mesh));
    if (!local) return local.error();
    const float4x4& world = graph.world[i];
    const PointsAndLines& from = **local;
    for (size_t p = 0; p < from.points.size(); ++p) {
      const float3 w = worldPoint(world, from.points.positions[p]);
      if (!isFinite(w)) {
        ++dropped;
        continue;
      }
      model_.points.positions.push_back(w);
      model_.points.colors.push_back(from.points.colors[p]);
    }
    for (size_t s = 0; s < from.lines.colors.size(); ++s) {
      const float3 a = worldPoint(world, from.lines.points[2 * s]);
      const float3 b = worldPoint(world, from.lines.points[2 * s + 1]);
      if (isFinite(a) && isFinite(b))
        model_.lines.add(a, b, from.lines.colors[s]);
      else
        ++dropped;
    }
  }
  mesh_points_.clear();
  if (dropped > 0)
    warn(std::to_string(dropped) +
         " points or line segments at a NaN or infinite position are not drawn");
  return {};
}

}  // namespace tessera::io::gltf
