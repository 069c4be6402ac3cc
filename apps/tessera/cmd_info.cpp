// tessera info MODEL (and render --info): what a model holds, without rendering it.
#include <iostream>
#include <set>
#include <string>

#include <tessera/io/model_loader.h>

#include "budget_flags.h"
#include "commands.h"
#include "flags.h"

namespace tessera::cli {

void printModelInfo(const std::string& path, const io::Model& model, std::ostream& out) {
  // A scene graph's meshes are stored once: counts are of the instances drawn.
  SceneGraph graph = model.graph;
  graph.updateWorld();
  const bool has_graph = !graph.nodes.empty();
  std::set<const Texture*> textures;
  size_t vertices = model.mesh.vertexCount(), triangles = model.mesh.triangleCount();
  bool normals = !model.mesh.normals.empty(), uvs = !model.mesh.uvs.empty(),
       colors = !model.mesh.colors.empty();
  size_t materials = model.materials.size();
  for (const Material& m : model.materials)
    if (m.albedo) textures.insert(m.albedo.get());
  if (has_graph) {
    vertices = 0;
    triangles = graph.drawnTriangleCount();
    for (const GraphNode& node : graph.nodes)
      if (node.mesh != kNoIndex)
        vertices += graph.meshes[static_cast<size_t>(node.mesh)].mesh->vertexCount();
    for (const GraphMesh& m : graph.meshes) {
      normals |= !m.mesh->normals.empty();
      uvs |= !m.mesh->uvs.empty();
      colors |= !m.mesh->colors.empty();
      materials = m.materials.size();  // one list, shared by every mesh
      for (const Material& material : m.materials)
        if (material.albedo) textures.insert(material.albedo.get());
    }
  }
  Bounds bounds = has_graph ? graph.bounds() : model.mesh.bounds();
  for (const float3& p : model.points.positions)
    if (isFinite(p)) bounds.add(p);
  for (const float3& p : model.lines.points)
    if (isFinite(p)) bounds.add(p);
  out << "model:      " << path << "\n"
      << "vertices:   " << vertices << "\n"
      << "triangles:  " << triangles << "\n"
      << "points:     " << model.points.size()
      << (model.points.colors.empty() ? "" : " (coloured per point)") << "\n"
      << "lines:      " << model.lines.colors.size() << " segments\n"
      << "materials:  " << materials << "\n"
      << "textures:   " << textures.size() << "\n"
      << "normals:    " << (normals ? "per vertex" : "none") << "\n"
      << "uvs:        " << (uvs ? "per vertex" : "none") << "\n"
      << "colours:    " << (colors ? "per vertex" : "none") << "\n"
      << "lights:     " << model.lights.size() << "\n";
  if (has_graph)
    out << "nodes:      " << graph.nodes.size() << " (" << graph.instanceCount()
        << " drawing a mesh, " << graph.meshes.size() << " meshes stored)\n"
        << "cameras:    " << graph.cameras.size() << "\n";
  if (bounds.empty()) {
    out << "bounds:     empty\n";
  } else {
    // The size in double: a model from -3e38 to 3e38 is 6e38 across, past float.
    const double e[3] = {double(bounds.max.x) - bounds.min.x, double(bounds.max.y) - bounds.min.y,
                         double(bounds.max.z) - bounds.min.z};
    out << "bounds:     min " << bounds.min.x << "," << bounds.min.y << "," << bounds.min.z
        << "  max " << bounds.max.x << "," << bounds.max.y << "," << bounds.max.z << "  size "
        << e[0] << "," << e[1] << "," << e[2] << "\n";
  }
  out << "warnings:   " << model.warnings.size() << "\n";
  for (const std::string& w : model.warnings) out << "  " << w << "\n";
}

// f3d's --readers-list: one line per format, its reader and its extensions.
void printReaders(std::ostream& out) {
  out << "format                                          reader   extensions\n";
  for (const io::ModelFormat& format : io::modelFormats()) {
    std::string name = format.name;
    if (name.size() < 48) name.resize(48, ' ');
    std::string reader = format.reader;
    if (reader.size() < 9) reader.resize(9, ' ');
    out << name << reader;
    for (size_t i = 0; i < format.extensions.size(); ++i)
      out << (i ? " ." : ".") << format.extensions[i];
    out << "\n";
  }
  if (!io::hasAssimp())
    out << "(this build has no assimp: PLY, OFF, COLLADA, FBX, 3DS, 3MF... are not read)\n";
}

int runInfo(const std::vector<std::string>& args) {
  FlagSet flags("tessera info MODEL | tessera info --readers-list");
  io::LoadBudget budget;
  addBudgetFlags(flags, budget);
  bool readers_list = false;
  flags.addSwitch("readers-list", &readers_list,
                  "list the model formats tessera reads, with their reader and extensions");
  Expected<std::vector<std::string>> positional = flags.parse(args);
  if (flags.helpRequested()) {
    std::cout << flags.usage();
    return kExitOk;
  }
  if (positional && readers_list && positional->empty()) {
    printReaders(std::cout);
    return kExitOk;
  }
  if (!positional || positional->size() != 1) {
    printError("info", !positional ? positional.error().message : "expected one model");
    std::cerr << flags.hint();
    return kExitUsage;
  }
  Expected<io::Model> model = io::loadModel(positional->front(), budget);
  if (!model) {
    printError("info", model.error().message);
    return kExitFailure;
  }
  printModelInfo(positional->front(), *model, std::cout);
  return kExitOk;
}

}  // namespace tessera::cli
