#include <tessera/io/model_loader.h>

#include <cctype>
#include <memory>
#include <string>
#include <utility>

#include "assimp_formats.h"

namespace tessera::io {

Expected<Model> loadModel(const std::filesystem::path& path, const LoadBudget& budget) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".obj") return loadObj(path, budget);
  if (extension == ".gltf" || extension == ".glb") return loadGltf(path, budget);
  if (extension == ".stl") return loadStl(path, budget);
  if (extension.size() > 1 && isAssimpExtension(extension.substr(1)))
    return loadAssimp(path, budget);
  const std::string what =
      extension.empty() ? "has no file extension" : "has an unknown extension '" + extension + "'";
  return makeError(path.string() + ": " + what + "; supported model formats: .obj, .gltf, .glb, " +
                   ".stl" +
                   (hasAssimp() ? " and assimp's (tessera info --readers-list)"
                                : " (this build has no assimp for the others)"));
}

std::vector<ModelFormat> modelFormats() {
  std::vector<ModelFormat> formats = {
      {"Wavefront OBJ (with MTL)", {"obj"}, "tessera"},
      {TESSERA_HAS_DRACO ? "glTF 2.0 (JSON and binary, Draco)" : "glTF 2.0 (JSON and binary)",
       {"gltf", "glb"},
       "tessera"},
      {"STL (binary and ASCII)", {"stl"}, "tessera"},
  };
  for (const ModelFormat& format : assimpFormats()) formats.push_back(format);
  return formats;
}

SceneGraph takeGraph(Model&& model) {
  SceneGraph graph = std::move(model.graph);
  if (graph.nodes.empty()) {
    GraphMesh mesh;
    mesh.mesh = std::make_shared<const Mesh>(std::move(model.mesh));
    if (model.materials.empty()) model.materials.push_back(Material{});
    mesh.materials = std::move(model.materials);
    graph.meshes.push_back(std::move(mesh));
    GraphNode node;
    node.mesh = 0;
    graph.nodes.push_back(std::move(node));
  }
  graph.updateWorld();
  return graph;
}

Mesh flattenedMesh(const Model& model) {
  if (model.graph.nodes.empty()) return model.mesh;
  SceneGraph graph = model.graph;
  graph.updateWorld();
  return graph.flatten();
}

}  // namespace tessera::io
