// A build without assimp (TESSERA_ASSIMP=OFF, or libassimp-dev not found): the formats it would
// read are refused with a message that says so.
#include <algorithm>
#include <string>

#include "assimp_formats.h"

namespace tessera::io {

namespace {

// The formats users reach for most that assimp reads, so that the message says what is missing
// rather than "unknown extension".
constexpr const char* kCommonAssimpExtensions[] = {
    "ply",  "off", "dae", "fbx",     "3ds", "3mf", "blend", "x3d", "dxf", "lwo", "ase", "ac", "x",
    "ms3d", "md2", "md3", "md5mesh", "b3d", "irr", "q3o",   "smd", "cob", "amf", "ifc", "ter"};

Error noAssimp(const std::filesystem::path& path) {
  return makeError(path.string() +
                   ": this build of tessera has no assimp, which reads this format (build with "
                   "libassimp-dev installed and -DTESSERA_ASSIMP=ON)");
}

}  // namespace

const std::vector<ModelFormat>& assimpFormats() {
  static const std::vector<ModelFormat> kNone;
  return kNone;
}

bool isAssimpExtension(const std::string& extension) {
  return std::find(std::begin(kCommonAssimpExtensions), std::end(kCommonAssimpExtensions),
                   extension) != std::end(kCommonAssimpExtensions);
}

bool hasAssimp() {
  return false;
}

Expected<Model> loadAssimp(const std::filesystem::path& path, const LoadBudget&) {
  return noAssimp(path);
}

Expected<Model> loadAssimpFromMemory(std::span<const uint8_t>, const std::string& name,
                                     const LoadBudget&) {
  return noAssimp(name);
}

}  // namespace tessera::io
