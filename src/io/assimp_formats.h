// The formats read through assimp, for loadModel's dispatch and modelFormats(). Private to
// tessera_io; assimp_loader.cpp with assimp, assimp_missing.cpp without.
#pragma once

#include <string>
#include <vector>

#include <tessera/io/model_loader.h>

namespace tessera::io {

// Extensions tessera's own loaders keep, though assimp reads them too.
inline constexpr const char* kOwnExtensions[] = {"obj", "gltf", "glb", "stl"};

// assimp's formats without tessera's own extensions; empty without assimp.
const std::vector<ModelFormat>& assimpFormats();

// Whether `extension` (lower case, no dot) is one of assimpFormats()'s, or, in a build without
// assimp, one of the common ones assimp would read (so that the error says what is missing).
bool isAssimpExtension(const std::string& extension);

}  // namespace tessera::io
