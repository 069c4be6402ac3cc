// PLY point clouds read directly, without assimp. assimp's PLY reader builds a DOM with an
// allocation per vertex property and then runs JoinIdenticalVertices, and tessera runs it twice
// (the sandboxed child first, assimp_process.h): a 10-million-point binary PLY took 18.6 s to
// load through it (docs/perf.md). A PLY whose only element is `vertex`, of scalar properties with
// x, y and z, is simple enough to read here in one bounded pass. Private to tessera_io.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include <tessera/io/model_loader.h>

namespace tessera::io {

// The point cloud, when `bytes` is such a PLY (its header already passed checkHeaders, so its
// grammar is sound and its vertex count within LoadBudget::points() and the file's size):
// Model::points, coloured when the vertices have red, green and blue (8-bit or 16-bit integers,
// or floats in 0..1, taken as sRGB as for assimp's formats, and decoded). An error for a body that
// does not hold what the header declares. std::nullopt for any other PLY (faces, lists, other
// elements, no x, y or z): assimp reads those.
std::optional<Expected<Model>> readPlyPointCloud(std::span<const uint8_t> bytes,
                                                 const std::string& name);

}  // namespace tessera::io
