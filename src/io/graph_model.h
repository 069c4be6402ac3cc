// The last step every scene-graph loader (glTF, assimp) takes once its graph is built.
#pragma once

#include <string>

#include <tessera/io/model_loader.h>

namespace tessera::io {

// Gives every graph mesh the one list of the file's materials (in first-use order: shared, not
// copied; a default material when the file has none), and adds the warnings that count what the
// per-element warnings left out: triangles with a non-finite vertex, and `unlisted` warnings
// beyond the listed ones. `name` names the file.
inline void finishGraphModel(Model& model, const std::string& name, size_t unlisted) {
  if (model.materials.empty()) model.materials.push_back(Material{});
  const MaterialList shared(model.materials);
  for (GraphMesh& mesh : model.graph.meshes) mesh.materials = shared;
  if (model.nonfinite_triangles > 0)
    model.warnings.push_back(
        name + ": " + std::to_string(model.nonfinite_triangles) +
        " triangles have a NaN or infinite vertex position (kept so triangle ids stay in load "
        "order; they are not drawn)");
  if (unlisted > 0)
    model.warnings.push_back(name + ": " + std::to_string(unlisted) + " more warnings like these");
}

}  // namespace tessera::io
