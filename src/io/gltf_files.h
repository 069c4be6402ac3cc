// The files a glTF file names, opened through tinygltf's file callbacks only from beneath the
// model's folder. Private to tessera_io.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <tessera/base/expected.h>

namespace tinygltf {
struct Image;
}

namespace tessera::io::gltf {

// tinygltf joins a buffer's URI to the base folder it is given, then also tries ".". The base
// passed to it is this marker, so the callbacks can tell the URI from the attempt in "." (which
// they refuse) and resolve it themselves beneath the model's folder.
constexpr std::string_view kFolderMarker = "<tessera-model-folder>/";

// The callbacks' state (their `user` pointer).
struct ExternalFiles {
  std::filesystem::path folder;  // empty: nothing may be opened
  std::string model_name;
  std::vector<std::string> refusals;  // why a URI was refused, for the error message
  uintmax_t bytes_read = 0;
  uintmax_t bytes_left = 0;  // what the budget leaves for more files

  Expected<std::filesystem::path> resolve(const std::string& joined);
};

// tinygltf::FsCallbacks.
bool fileExists(const std::string& joined, void* user);
std::string expandFilePath(const std::string& path, void* user);
bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& joined,
                   void* user);
bool refuseWrite(std::string* err, const std::string& path, const std::vector<unsigned char>& bytes,
                 void* user);

// tinygltf's image loader: keeps the encoded bytes of images given as data: URIs; images in
// buffer views are read from the buffer later, and only images a material uses are decoded.
bool keepEncodedImage(tinygltf::Image* image, const int index, std::string* err,
                      std::string* warn, int width, int height, const unsigned char* bytes,
                      int size, void* user);

}  // namespace tessera::io::gltf
