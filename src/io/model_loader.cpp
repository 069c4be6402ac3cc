#include <tessera/io/model_loader.h>

#include <cctype>
#include <string>

namespace tessera::io {

Expected<Model> loadModel(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".obj") return loadObj(path);
  if (extension == ".gltf" || extension == ".glb") return loadGltf(path);
  if (extension == ".stl") return loadStl(path);
  const std::string what =
      extension.empty() ? "has no file extension" : "has an unknown extension '" + extension + "'";
  return makeError(path.string() + ": " + what +
                   "; supported model formats: .obj, .gltf, .glb, .stl");
}

}  // namespace tessera::io
