// glTF 2.0 (JSON and GLB) through tinygltf: the loader's entry points and tinygltf's messages in
// tessera's words. The rest is split by concern: gltf_container (checks before tinygltf sees a
// file), gltf_files (the files a glTF names), gltf_builder (the node graph into Model::graph),
// gltf_nodes (scene roots, the tree check, transforms), gltf_reader and gltf_accessors (checked
// buffer reads), gltf_primitives (meshes) and gltf_materials (materials and images). Everything
// tinygltf hands back is checked before a byte of a buffer is read.
#include <tessera/io/model_loader.h>

#include <algorithm>
#include <cstdint>
#include <fstream>  // tinygltf's implementation writes files (never called: TINYGLTF_NO_FS)
#include <new>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "gltf_builder.h"
#include "gltf_container.h"
#include "gltf_draco.h"
#include "gltf_files.h"
#include "model_paths.h"

// The one translation unit that compiles tinygltf itself.
#define TINYGLTF_IMPLEMENTATION
#include "tinygltf_include.h"

namespace tessera::io {

namespace {

namespace fs = std::filesystem;
using namespace gltf;

// tinygltf takes lengths as unsigned int; 2 GiB keeps every offset well inside that.
constexpr uintmax_t kMaxGltfBytes = uintmax_t{2} << 30;

// One of tinygltf's message lines in tessera's words: the ones a hostile file reaches say what
// is wrong without tinygltf's phrasing or its placeholders, and any value is elided.
std::string inOwnWords(std::string line) {
  for (size_t at; (at = line.find(kFolderMarker)) != std::string::npos;)
    line.erase(at, kFolderMarker.size());
  // "File size mismatch : c.bin, requestedBytes 168, but got 100"
  const std::string_view kMismatch = "File size mismatch : ";
  if (line.starts_with(kMismatch)) {
    const size_t requested = line.find(", requestedBytes ");
    const size_t got = line.find(", but got ");
    if (requested != std::string::npos && got != std::string::npos && got > requested) {
      const std::string file = line.substr(kMismatch.size(), requested - kMismatch.size());
      const std::string wanted = line.substr(requested + 17, got - requested - 17);
      return "buffer file '" + elided(file) + "' is " + trimmed(line.substr(got + 10)) +
             " bytes, but the buffer's byteLength is " + wanted;
    }
  }
  // "'buffer' property is missing in BufferView."
  if (const size_t missing = line.find("' property is missing in ");
      line.starts_with("'") && missing != std::string::npos) {
    std::string object = line.substr(missing + 25);
    while (!object.empty() && (object.back() == '.' || object.back() == ' ')) object.pop_back();
    return "a " + elided(object) + " lacks its required property '" +
           elided(line.substr(1, missing - 1)) + "'";
  }
  if (line.starts_with("Unsupported `type` for accessor object"))
    return "an accessor's type is not a glTF type (" + elided(line.substr(line.find("Got") + 3)) +
           ")";
  if (line.starts_with("Failed to decode 'uri' for image["))
    return "image " + numberAfter(line, "image[") + ": its URI cannot be decoded";
  // "Failed to decode 'uri' : data:... in Buffer": the URI can be megabytes long.
  if (line.starts_with("Failed to decode 'uri' : ")) {
    std::string uri = line.substr(25);
    if (uri.ends_with(" in Buffer")) uri.resize(uri.size() - 10);
    return "a buffer's URI cannot be decoded: '" + elided(uri) + "'";
  }
  if (line.starts_with("\"asset\" object not found"))
    return "the required \"asset\" object is missing";
  std::string out;
  size_t begin = 0;
  while (begin < line.size()) {
    size_t end = std::min(line.find(' ', begin), line.size());
    if (!out.empty()) out += ' ';
    out += elided(std::string_view(line).substr(begin, end - begin));
    begin = end + 1;
  }
  return out;
}

// tinygltf's messages are lines ending in '\n'; this joins the first few into one.
std::string joinedLines(const std::string& text) {
  constexpr size_t kMaxLines = 5;
  std::string out;
  size_t lines = 0, begin = 0;
  while (begin < text.size()) {
    size_t end = std::min(text.find('\n', begin), text.size());
    std::string line = trimmed(std::string_view(text).substr(begin, end - begin));
    begin = end + 1;
    if (line.empty()) continue;
    if (++lines > kMaxLines) continue;
    if (!out.empty()) out += "; ";
    out += inOwnWords(line);
  }
  if (lines > kMaxLines) out += "; and " + std::to_string(lines - kMaxLines) + " more";
  return out;
}

Expected<Model> parseGltf(std::span<const uint8_t> bytes, const std::string& name,
                          const fs::path& folder, const LoadBudget& budget) {
  if (bytes.empty()) return makeError(name + ": the file is empty: no triangles");
  if (bytes.size() > kMaxGltfBytes)
    return makeError(name + ": the file is " + std::to_string(bytes.size()) +
                     " bytes; glTF files over 2 GiB are refused");
  const bool binary = bytes.size() >= 4 && readU32(bytes.data()) == kGlbMagic;
  std::string_view json_text;
  if (binary) {
    if (Expected<void> ok = checkGlbContainer(bytes, name); !ok) return ok.error();
    json_text = std::string_view(reinterpret_cast<const char*>(bytes.data()) + 20,
                                 readU32(bytes.data() + 12));
  } else {
    json_text = std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  }
  if (Expected<void> ok = checkJsonShape(json_text, name); !ok) return ok.error();
  // Draco primitives' indices without a bufferView, which tinygltf refuses, hidden from it.
  Expected<std::optional<DracoReadyFile>> draco_ready =
      hideDracoIndices(bytes, json_text, binary, name);
  if (!draco_ready) return draco_ready.error();
  std::span<const uint8_t> parsed_bytes = bytes;
  if (*draco_ready) {
    parsed_bytes = (*draco_ready)->bytes;
    if (!binary)
      json_text =
          std::string_view(reinterpret_cast<const char*>(parsed_bytes.data()), parsed_bytes.size());
  }

  ExternalFiles files{folder,
                      name,
                      {},
                      0,
                      budget.fileBytes() - std::min<uint64_t>(budget.fileBytes(), bytes.size())};
  tinygltf::TinyGLTF parser;
  parser.SetFsCallbacks({&fileExists, &expandFilePath, &readWholeFile, &refuseWrite, &files});
  parser.SetImageLoader(&keepEncodedImage, nullptr);
  tinygltf::Model gltf;
  std::string errors, library_warnings;
  const std::string base(kFolderMarker.substr(0, kFolderMarker.size() - 1));
  const bool parsed =
      binary ? parser.LoadBinaryFromMemory(&gltf, &errors, &library_warnings, parsed_bytes.data(),
                                           static_cast<unsigned int>(parsed_bytes.size()), base)
             : parser.LoadASCIIFromString(&gltf, &errors, &library_warnings, json_text.data(),
                                          static_cast<unsigned int>(json_text.size()), base);
  if (!parsed) {
    if (!files.refusals.empty())
      return makeError(name + ": a buffer file cannot be read: " + files.refusals.front());
    std::string message = joinedLines(errors);
    return makeError(name + ": not a readable glTF file: " +
                     (message.empty() ? "tinygltf gave no reason" : message));
  }

  if (*draco_ready) restoreDracoIndices(gltf, (*draco_ready)->hidden);
  draco_ready->reset();  // tinygltf has copied the buffers

  Model model;
  GraphBuilder builder(gltf, name, folder, bytes.size() + files.bytes_read, budget, model);
  if (Expected<void> ok = builder.run(); !ok) return ok.error();
  std::string passed_on = joinedLines(library_warnings);
  if (!passed_on.empty()) model.warnings.insert(model.warnings.begin(), name + ": " + passed_on);
  return model;
}

template <typename Load>
Expected<Model> guarded(const std::string& name, Load load) {
  try {
    return load();
  } catch (const std::bad_alloc&) {
    return makeError(name + ": out of memory while loading");
  } catch (const std::length_error&) {
    return makeError(name + ": out of memory while loading");
  } catch (const std::exception& error) {
    // tinygltf and nlohmann::json throw on some malformed input (a zero-length GLB buffer).
    return makeError(name + ": not a readable glTF file: " + inOwnWords(error.what()));
  }
}

}  // namespace

Expected<Model> loadGltfFromMemory(std::span<const uint8_t> bytes, const std::string& name,
                                   const std::filesystem::path& folder, const LoadBudget& budget) {
  return guarded(name, [&] { return parseGltf(bytes, name, folder, budget); });
}

Expected<Model> loadGltf(const std::filesystem::path& path, const LoadBudget& budget) {
  const std::string name = path.string();
  return guarded(name, [&]() -> Expected<Model> {
    Expected<std::vector<unsigned char>> bytes =
        readRegularFile(path, std::min<uint64_t>(kMaxGltfBytes, budget.fileBytes()), "glTF");
    if (!bytes) return bytes.error();
    fs::path folder = path.parent_path();
    if (folder.empty()) folder = ".";
    return parseGltf(*bytes, name, folder, budget);
  });
}

}  // namespace tessera::io