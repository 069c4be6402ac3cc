// tessera info MODEL (and render --info): what a model holds, without rendering it.
#include <iostream>
#include <set>

#include <tessera/io/model_loader.h>

#include "budget_flags.h"
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
      << "colours:    " << (model.mesh.colors.empty() ? "none" : "per vertex") << "\n"
      << "lights:     " << model.lights.size() << "\n";
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

int runInfo(const std::vector<std::string>& args) {
  FlagSet flags("tessera info MODEL");
  io::LoadBudget budget;
  addBudgetFlags(flags, budget);
  Expected<std::vector<std::string>> positional = flags.parse(args);
  if (flags.helpRequested()) {
    std::cout << flags.usage();
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
