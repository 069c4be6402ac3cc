// tessera info MODEL (and render --info): what a model holds, without rendering it.
#include <iostream>
#include <set>

#include <tessera/io/model_loader.h>

#include "commands.h"
#include "flags.h"

namespace tessera::cli {

void printModelInfo(const std::string& path, const io::Model& model, std::ostream& out) {
  std::set<const Texture*> textures;
  for (const Material& m : model.materials)
    if (m.albedo) textures.insert(m.albedo.get());
  const Bounds bounds = model.mesh.bounds();
  out << "model:      " << path << "\n"
      << "vertices:   " << model.mesh.vertexCount() << "\n"
      << "triangles:  " << model.mesh.triangleCount() << "\n"
      << "materials:  " << model.materials.size() << "\n"
      << "textures:   " << textures.size() << "\n"
      << "normals:    " << (model.mesh.normals.empty() ? "none" : "per vertex") << "\n"
      << "uvs:        " << (model.mesh.uvs.empty() ? "none" : "per vertex") << "\n"
      << "colours:    " << (model.mesh.colors.empty() ? "none" : "per vertex") << "\n";
  if (bounds.empty()) {
    out << "bounds:     empty\n";
  } else {
    const float3 e = bounds.extent();
    out << "bounds:     min " << bounds.min.x << "," << bounds.min.y << "," << bounds.min.z
        << "  max " << bounds.max.x << "," << bounds.max.y << "," << bounds.max.z << "  size "
        << e.x << "," << e.y << "," << e.z << "\n";
  }
  out << "warnings:   " << model.warnings.size() << "\n";
  for (const std::string& w : model.warnings) out << "  " << w << "\n";
}

int runInfo(const std::vector<std::string>& args) {
  FlagSet flags("tessera info MODEL");
  Expected<std::vector<std::string>> positional = flags.parse(args);
  if (flags.helpRequested()) {
    std::cout << flags.usage();
    return kExitOk;
  }
  if (!positional || positional->size() != 1) {
    printError("info", !positional ? positional.error().message : "expected one model");
    std::cerr << flags.usage();
    return kExitUsage;
  }
  Expected<io::Model> model = io::loadModel(positional->front());
  if (!model) {
    printError("info", model.error().message);
    return kExitFailure;
  }
  printModelInfo(positional->front(), *model, std::cout);
  return kExitOk;
}

}  // namespace tessera::cli
