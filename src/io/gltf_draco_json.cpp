// KHR_draco_mesh_compression before tinygltf: the indices accessors tinygltf 2.7 cannot take
// (no bufferView) hidden from it and put back after the parse (gltf_draco.h). Every build
// compiles this: a build without Draco needs the file parsed to refuse it in words of its own.
#include <cstring>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "gltf_container.h"
#include "gltf_draco.h"
#include "tinygltf_include.h"

namespace tessera::io::gltf {

namespace {

using Json = nlohmann::json;

// Whether accessors[index] exists and lacks a usable bufferView: tinygltf would refuse it as a
// primitive's indices. Anything else (an index out of range) is left for tinygltf to refuse.
bool lacksBufferView(const Json& accessors, const Json& index) {
  if (!index.is_number_integer() || !accessors.is_array()) return false;
  const int64_t i = index.get<int64_t>();
  if (i < 0 || static_cast<uint64_t>(i) >= accessors.size()) return false;
  const Json& accessor = accessors[static_cast<size_t>(i)];
  if (!accessor.is_object()) return false;
  auto view = accessor.find("bufferView");
  return view == accessor.end() || !view->is_number_integer() || view->get<int64_t>() < 0;
}

// Hides the indices of Draco primitives that tinygltf would refuse; returns what it hid.
std::vector<HiddenIndices> hideIndices(Json& root) {
  std::vector<HiddenIndices> hidden;
  auto meshes = root.find("meshes");
  auto accessors = root.find("accessors");
  if (meshes == root.end() || !meshes->is_array() || accessors == root.end()) return hidden;
  for (size_t m = 0; m < meshes->size(); ++m) {
    Json& mesh = (*meshes)[m];
    if (!mesh.is_object()) continue;
    auto primitives = mesh.find("primitives");
    if (primitives == mesh.end() || !primitives->is_array()) continue;
    for (size_t p = 0; p < primitives->size(); ++p) {
      Json& primitive = (*primitives)[p];
      if (!primitive.is_object()) continue;
      auto extensions = primitive.find("extensions");
      if (extensions == primitive.end() || !extensions->is_object() ||
          !extensions->contains(kDracoExtension))
        continue;
      auto indices = primitive.find("indices");
      if (indices == primitive.end() || !lacksBufferView(*accessors, *indices)) continue;
      // In range of an int: checkJsonShape refuses larger indices.
      hidden.push_back({m, p, static_cast<int>(indices->get<int64_t>())});
      primitive.erase(indices);
    }
  }
  return hidden;
}

void appendU32(std::vector<uint8_t>& out, uint32_t value) {
  const size_t at = out.size();
  out.resize(at + 4);
  std::memcpy(out.data() + at, &value, 4);
}

// A GLB around `json` with the original file's binary chunk (everything after its JSON chunk).
std::vector<uint8_t> rebuiltGlb(std::span<const uint8_t> file, std::string json) {
  while (json.size() % 4 != 0) json += ' ';  // chunks are 4-byte aligned
  const size_t old_json_end = 20 + size_t{readU32(file.data() + 12)};
  const size_t old_length = readU32(file.data() + 8);
  const size_t rest = old_length - old_json_end;  // checkGlbContainer: json_end <= length
  std::vector<uint8_t> out;
  out.reserve(20 + json.size() + rest);
  appendU32(out, kGlbMagic);
  appendU32(out, 2);
  appendU32(out, static_cast<uint32_t>(20 + json.size() + rest));
  appendU32(out, static_cast<uint32_t>(json.size()));
  appendU32(out, 0x4E4F534A);  // "JSON"
  out.insert(out.end(), json.begin(), json.end());
  out.insert(out.end(), file.begin() + static_cast<std::ptrdiff_t>(old_json_end),
             file.begin() + static_cast<std::ptrdiff_t>(old_length));
  return out;
}

}  // namespace

std::string noDracoDecoder(const std::string& what) {
  return what + " needs " + std::string(kDracoExtension) + " (this build has no Draco decoder)";
}

Expected<std::optional<DracoReadyFile>> hideDracoIndices(std::span<const uint8_t> file,
                                                         std::string_view json_text, bool binary,
                                                         const std::string& name) {
  using Result = std::optional<DracoReadyFile>;
  // Most files never name the extension: they are not parsed a second time.
  if (json_text.find(kDracoExtension) == std::string_view::npos) return Result();
  Json root = Json::parse(json_text.begin(), json_text.end(), nullptr,
                          /*allow_exceptions=*/false);
  if (!root.is_object()) return Result();  // checkJsonShape has accepted it: not reached
  DracoReadyFile ready;
  ready.hidden = hideIndices(root);
  if (ready.hidden.empty()) return Result();
  std::string text;
  try {
    text = root.dump();
  } catch (const Json::type_error&) {
    // dump() throws on a string that is not UTF-8, which the parser let through.
    return makeError(name + ": the JSON has a string that is not UTF-8");
  }
  // tinygltf takes the length as an unsigned int.
  const uint64_t rest =
      binary ? uint64_t{readU32(file.data() + 8)} - 20 - readU32(file.data() + 12) : 0;
  if (text.size() + 24 + rest > UINT32_MAX)
    return makeError(name + ": the file is too large to rewrite for its Draco primitives");
  ready.bytes =
      binary ? rebuiltGlb(file, std::move(text)) : std::vector<uint8_t>(text.begin(), text.end());
  return Result(std::move(ready));
}

void restoreDracoIndices(tinygltf::Model& gltf, const std::vector<HiddenIndices>& hidden) {
  for (const HiddenIndices& h : hidden) {
    if (h.mesh >= gltf.meshes.size()) continue;
    std::vector<tinygltf::Primitive>& primitives = gltf.meshes[h.mesh].primitives;
    // tinygltf drops a primitive without attributes, which moves the ones after it: only a
    // Draco primitive without indices takes them back.
    if (h.primitive >= primitives.size()) continue;
    tinygltf::Primitive& primitive = primitives[h.primitive];
    if (primitive.indices < 0 && primitive.extensions.count(std::string(kDracoExtension)) > 0)
      primitive.indices = h.accessor;
  }
}

}  // namespace tessera::io::gltf
