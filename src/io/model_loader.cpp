#include <tessera/io/model_loader.h>

#include <cctype>
#include <string>

namespace tessera::io {

Expected<Model> loadModel(const std::filesystem::path& path, const LoadBudget& budget) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".obj") return loadObj(path, budget);
  if (extension == ".gltf" || extension == ".glb") return loadGltf(path, budget);
  if (extension == ".stl") return loadStl(path, budget);
  const std::string what =
      extension.empty() ? "has no file extension" : "has an unknown extension '" + extension + "'";
  return makeError(path.string() + ": " + what +
                   "; supported model formats: .obj, .gltf, .glb, .stl");
}

}  // namespace tessera::io
