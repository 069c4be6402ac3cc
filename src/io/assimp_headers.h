// What tessera checks in a file before assimp reads it (assimp_loader.cpp): assimp's PLY and
// OFF readers trust their headers and bodies, and loop forever, crash or fail an assertion on
// broken ones (fuzz/assimp_fuzz.cpp found each). Private to tessera_io.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tessera/io/model_loader.h>

namespace tessera::io {

// A PLY file's header (its grammar, and the counts it declares against the budget and the
// file's size) and a whole OFF file (counts, vertex lines, faces with indices in range), by
// content, and also by `extension` ("off": an OFF file must look like one). Other formats pass.
// The face count a PLY header declares (0 without a face element); 0 for other files. A PLY that
// declares faces is not a point cloud, even when assimp reads none of them (a truncated file).
uint64_t plyDeclaredFaces(const std::vector<uint8_t>& bytes);

Expected<void> checkHeaders(const std::vector<uint8_t>& bytes, const std::string& name,
                            const std::string& extension, const LoadBudget& budget);

}  // namespace tessera::io
