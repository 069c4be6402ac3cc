// The glTF builder's walk over the node graph: the scene's nodes depth-first into
// Model::graph (parents first, so world transforms take one pass), each glTF mesh read once on
// first use, cameras checked; warnings and the end of the load.
#include <cmath>
#include <string>
#include <utility>

#include "gltf_builder.h"
#include "gltf_draco.h"
#include "gltf_lights.h"
#include "graph_model.h"
#include "load_budget.h"
#include "tinygltf_include.h"

namespace tessera::io::gltf {

Expected<void> GraphBuilder::run() {
  if (Expected<void> ok = checkExtensions(); !ok) return ok;
  Expected<std::vector<int>> roots = sceneRoots(gltf_, name_, warner());
  if (!roots) return roots.error();
  if (Expected<void> ok = checkNodeTree(gltf_, name_); !ok) return ok;
  if (Expected<void> ok = checkDrawnCounts(*roots); !ok) return ok;
  readCameras();

  // Depth-first, a node before its children, without recursion (a hierarchy may be as deep as
  // the file is long): the path from the root is the only state, one entry per level with the
  // node, its next child and its index in the graph.
  struct Level {
    size_t node;
    size_t next_child;
    int32_t graph_node;
  };
  std::vector<Level> path;
  std::vector<char> added(gltf_.nodes.size(), 0);
  auto enter = [&](size_t index, int32_t parent) -> Expected<void> {
    if (added[index]) {
      warn("node " + std::to_string(index) +
           " is reached more than once from the scene's roots; it is drawn once");
      return {};
    }
    added[index] = 1;
    if (Expected<void> ok = addNode(index, parent); !ok) return ok;
    path.push_back({index, 0, static_cast<int32_t>(model_.graph.nodes.size() - 1)});
    return {};
  };
  for (int root : *roots) {
    if (Expected<void> ok = enter(static_cast<size_t>(root), kNoIndex); !ok) return ok;
    while (!path.empty()) {
      Level& level = path.back();
      const std::vector<int>& children = gltf_.nodes[level.node].children;
      if (level.next_child == children.size()) {
        path.pop_back();
        continue;
      }
      const auto child = static_cast<size_t>(children[level.next_child++]);
      // `level` is not used past this point: entering a child may move the path.
      const int32_t parent = level.graph_node;
      if (Expected<void> ok = enter(child, parent); !ok) return ok;
    }
  }
  placeLights();
  if (Expected<void> ok = placePointsAndLines(); !ok) return ok;
  readAnimations();
  return finish();
}

Expected<void> GraphBuilder::addNode(size_t index, int32_t parent) {
  const tinygltf::Node& node = gltf_.nodes[index];
  GraphNode out;
  out.name = node.name;
  out.parent = parent;
  out.source = static_cast<int32_t>(index);
  out.local = localTransform(node, index, warner());
  if (node.mesh >= 0) {
    if (static_cast<size_t>(node.mesh) >= gltf_.meshes.size())
      return makeError(name_ + ": node " + std::to_string(index) + " refers to mesh " +
                       std::to_string(node.mesh) + ", but the file has " +
                       std::to_string(gltf_.meshes.size()) + " meshes");
    if (node.skin >= 0) warn("skins are not applied: skinned meshes are drawn in their bind pose");
    Expected<int32_t> mesh = meshFor(static_cast<size_t>(node.mesh));
    if (!mesh) return mesh.error();
    out.mesh = *mesh;
    model_.nonfinite_triangles += mesh_nonfinite_[static_cast<size_t>(*mesh)];
  }
  if (node.camera >= 0) {
    if (static_cast<size_t>(node.camera) >= gltf_.cameras.size())
      warn("node " + std::to_string(index) + " refers to camera " + std::to_string(node.camera) +
           ", but the file has " + std::to_string(gltf_.cameras.size()) + "; it is ignored");
    else
      out.camera = graph_camera_[static_cast<size_t>(node.camera)];
  }
  model_.graph.nodes.push_back(std::move(out));
  return {};
}

// The lights the drawn nodes carry (KHR_lights_punctual), at their nodes' world matrices, into
// Model::lights.
void GraphBuilder::placeLights() {
  SceneGraph& graph = model_.graph;
  graph.updateWorld();
  for (size_t i = 0; i < graph.nodes.size(); ++i) {
    const auto source = static_cast<size_t>(graph.nodes[i].source);
    Matrix global;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) global.at(r, c) = graph.world[i].col[c][r];
    addNodeLight(gltf_, gltf_.nodes[source], source, global, warner(), model_.lights);
  }
}

// Every camera of the file, in order; one with a field that is zero, negative or not finite
// where glTF asks for a positive number is skipped with a warning naming it (the rest of the
// file is sound), and keeps its index (GraphCamera::skipped).
void GraphBuilder::readCameras() {
  graph_camera_.assign(gltf_.cameras.size(), kNoIndex);
  const auto positive = [](double v) { return v > 0 && std::isfinite(v); };
  for (size_t i = 0; i < gltf_.cameras.size(); ++i) {
    const tinygltf::Camera& c = gltf_.cameras[i];
    const std::string what =
        "camera " + std::to_string(i) + (c.name.empty() ? "" : " ('" + c.name + "')");
    GraphCamera out;
    out.name = c.name;
    std::string bad;
    if (c.type == "perspective") {
      const tinygltf::PerspectiveCamera& p = c.perspective;
      if (!positive(p.yfov) || p.yfov >= 3.14159265358979)
        bad = "yfov " + std::to_string(p.yfov);
      else if (!positive(p.znear))
        bad = "znear " + std::to_string(p.znear);
      else if (p.zfar != 0 && !(p.zfar > p.znear && std::isfinite(p.zfar)))
        bad = "zfar " + std::to_string(p.zfar) + " (not past znear)";
      else if (p.aspectRatio < 0 || !std::isfinite(p.aspectRatio))
        bad = "aspectRatio " + std::to_string(p.aspectRatio);
      out.yfov_radians = static_cast<float>(p.yfov);
      out.aspect_ratio = static_cast<float>(p.aspectRatio);
      out.znear = static_cast<float>(p.znear);
      out.zfar = static_cast<float>(p.zfar);
    } else if (c.type == "orthographic") {
      const tinygltf::OrthographicCamera& o = c.orthographic;
      out.orthographic = true;
      if (!positive(o.xmag))
        bad = "xmag " + std::to_string(o.xmag);
      else if (!positive(o.ymag))
        bad = "ymag " + std::to_string(o.ymag);
      else if (!(o.znear >= 0) || !std::isfinite(o.znear))
        bad = "znear " + std::to_string(o.znear);
      else if (!(o.zfar > o.znear) || !std::isfinite(o.zfar))
        bad = "zfar " + std::to_string(o.zfar) + " (not past znear)";
      out.xmag = static_cast<float>(o.xmag);
      out.ymag = static_cast<float>(o.ymag);
      out.znear = static_cast<float>(o.znear);
      out.zfar = static_cast<float>(o.zfar);
    } else {
      bad = "type '" + c.type + "'";
    }
    if (!bad.empty()) warn(what + " has " + bad + ": the camera is skipped");
    out.skipped = bad;
    graph_camera_[i] = static_cast<int32_t>(model_.graph.cameras.size());
    model_.graph.cameras.push_back(std::move(out));
  }
}

// ---- Warnings ----

// A warning about the model file; at most kMaxWarnings distinct ones are listed.
void GraphBuilder::warn(const std::string& text) {
  warnAbout(name_ + ": " + text);
}
Warn GraphBuilder::warner() {
  return [this](const std::string& text) { warn(text); };
}
// A warning that names its own file (a texture's).
void GraphBuilder::warnAbout(const std::string& text) {
  if (!warned_.insert(text).second) return;
  if (warned_.size() > kMaxWarnings) {
    ++unlisted_warnings_;
    return;
  }
  model_.warnings.push_back(text);
}

// ---- Extensions, scene, node tree ----

// The budget, before anything is flattened: instancing can multiply a small file into a huge
// mesh.
Expected<void> GraphBuilder::checkDrawnCounts(const std::vector<int>& roots) {
  const DrawnCounts counts = countDrawn(gltf_, roots);
  if (Expected<void> ok = checkBudget(name_, "triangles (after instancing)", counts.triangles,
                                      budget_.triangles(), "--max-triangles");
      !ok)
    return ok;
  if (Expected<void> ok = checkBudget(name_, "vertices (after instancing)", counts.vertices,
                                      budget_.vertices(), "--max-triangles");
      !ok)
    return ok;
  return checkBudget(name_, "points and line end points (after instancing)", counts.points,
                     budget_.points(), "");
}

Expected<void> GraphBuilder::checkExtensions() {
  for (const std::string& extension : gltf_.extensionsRequired) {
    if (extension == "KHR_mesh_quantization") continue;  // read like any other accessor
    if (extension == "KHR_lights_punctual") continue;    // gltf_lights.cpp
    if (extension == kDracoExtension) {                  // gltf_draco.h
      if (dracoDecoderBuilt()) continue;
      return makeError(noDracoDecoder(name_ + ": the file"));
    }
    if (extension == "KHR_texture_transform") continue;  // gltf_materials.cpp
    if (extension.starts_with("KHR_materials_")) {
      warn("extension " + extension + " is not applied");
      continue;
    }
    return makeError(name_ + ": the file requires the extension " + extension +
                     ", which tessera does not support");
  }
  return {};
}

Expected<void> GraphBuilder::finish() {
  SceneGraph& graph = model_.graph;
  if (graph.drawnTriangleCount() == 0 && model_.points.empty() && model_.lines.points.empty())
    return makeError(name_ + ": nothing to draw: no faces, points or lines in the scene");
  for (auto [mode, count] : skipped_by_mode_)
    warn(std::to_string(count) + " primitive(s) of mode " + std::to_string(mode) +
         " skipped: not a glTF 2.0 mode");
  size_t double_sided = 0;
  for (const Material& material : model_.materials) double_sided += material.double_sided;
  model_.cull_back_faces = double_sided == 0;
  if (double_sided > 0 && double_sided < model_.materials.size())
    warn("some materials are double-sided and some are not; back faces are drawn for all");
  finishGraphModel(model_, name_, unlisted_warnings_);
  return {};
}
}  // namespace tessera::io::gltf
