// KHR_draco_mesh_compression: primitives whose geometry is a Draco stream in a buffer view.
// Private to tessera_io. Two halves:
// - gltf_draco_json.cpp (every build): tinygltf 2.7 refuses a primitive whose indices accessor
//   has no bufferView ("accessor[0] invalid bufferView"), which is how a Draco primitive without
//   an uncompressed fallback is written. Such indices are hidden from tinygltf and put back into
//   its model after the parse, so the builder sees the file as written.
// - gltf_draco.cpp (TESSERA_HAS_DRACO, Debian's libdraco-dev) decodes a primitive with
//   draco::Decoder; gltf_draco_missing.cpp refuses it. tinygltf's own Draco path
//   (TINYGLTF_ENABLE_DRACO) is not used: it indexes buffer views and attributes unchecked,
//   ignores decode failures and allocates whatever the stream claims.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/io/model_loader.h>

namespace tinygltf {
class Model;
struct Primitive;
}  // namespace tinygltf

namespace tessera::io::gltf {

inline constexpr std::string_view kDracoExtension = "KHR_draco_mesh_compression";

// Whether this build decodes Draco streams.
bool dracoDecoderBuilt();

// "WHAT needs KHR_draco_mesh_compression (this build has no Draco decoder)".
std::string noDracoDecoder(const std::string& what);

// ---- Before tinygltf (gltf_draco_json.cpp) ----

// The indices accessor of meshes[mesh].primitives[primitive], hidden from tinygltf.
struct HiddenIndices {
  size_t mesh = 0;
  size_t primitive = 0;
  int accessor = -1;
};

// The file as tinygltf is given it: the JSON rewritten without the hidden indices (for a GLB, a
// new container around it with the same binary chunk).
struct DracoReadyFile {
  std::vector<uint8_t> bytes;
  std::vector<HiddenIndices> hidden;
};

// Nothing when no Draco primitive's indices need hiding (the file is parsed as it is).
// `json_text` is the file's JSON (the whole file, or a GLB's JSON chunk, checked by
// checkGlbContainer and checkJsonShape).
Expected<std::optional<DracoReadyFile>> hideDracoIndices(std::span<const uint8_t> file,
                                                         std::string_view json_text, bool binary,
                                                         const std::string& name);

// Puts the hidden indices back into tinygltf's model.
void restoreDracoIndices(tinygltf::Model& gltf, const std::vector<HiddenIndices>& hidden);

// ---- Decoding (gltf_draco.cpp, or gltf_draco_missing.cpp) ----

// One accessor's values as the Draco stream gives them, converted to `component_type` and packed
// (stride = components * component bytes), `count` elements.
struct DecodedAccessor {
  std::vector<uint8_t> bytes;
  size_t count = 0;
  int component_type = 0;
};

struct DracoPrimitive {
  // Three per triangle, in the order the decoder gives the faces: that order is the file's
  // triangle order (the id AOV's), whatever order the mesh had before it was encoded.
  std::vector<uint32_t> indices;
  size_t points = 0;
  std::map<int, DecodedAccessor> accessors;  // by accessor index: the attributes it decoded
  std::vector<std::string> warnings;         // without the file's name
};

// What has been stored before this primitive, for the budget check of the decoded counts.
struct DracoBudget {
  LoadBudget budget;
  uint64_t stored_triangles = 0;
  uint64_t stored_vertices = 0;
};

// Decodes `primitive`'s Draco stream from its buffer view (a buffer tinygltf has already read
// through the loader's file callbacks). The decoded counts are checked against the budget before
// anything is converted, and against the accessors' declared counts: more than declared is
// refused (the budget after instancing was checked with the declared counts), fewer is a
// warning. `where` is "mesh 0 primitive 1"; every error names `name` and `where`.
Expected<DracoPrimitive> decodeDracoPrimitive(const tinygltf::Model& gltf,
                                              const tinygltf::Primitive& primitive,
                                              const std::string& name, const std::string& where,
                                              const DracoBudget& budget);

}  // namespace tessera::io::gltf
