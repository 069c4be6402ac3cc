// Every format assimp reads that tessera has no loader of its own for, sandboxed (loadAssimp,
// model_loader.h): the size and path checks first, the declared counts of PLY and OFF headers
// against the budget before assimp allocates for them, then assimp through SandboxIOSystem, and
// its failures and exceptions as one line naming the file.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <new>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include <assimp/config.h>
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include "assimp_formats.h"
#include "assimp_io.h"
#include "assimp_scene.h"
#include "load_budget.h"
#include "model_paths.h"

namespace tessera::io {

namespace fs = std::filesystem;

namespace {

// Triangles only (polygons split, points and lines sorted into meshes of their own) and shared
// vertices joined. Not aiProcess_ValidateDataStructure nor FindInvalidData: they refuse or
// remove point clouds (a mesh without faces, "No meshes remaining") before they could be named;
// the scene builder checks every index it uses and replaces non-finite normals and UVs instead.
// assimp's logger is left as it is by default, the null logger: nothing reaches standard output.
constexpr unsigned kPostProcess =
    aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType;

std::string lowered(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// A library message on one line, without its trailing blanks, at most 300 characters.
std::string oneLine(std::string_view text) {
  std::string out;
  for (char c : text) {
    const bool blank = c == '\n' || c == '\r' || c == '\t' || c == ' ';
    if (blank && (out.empty() || out.back() == ' ')) continue;
    out += blank ? ' ' : c;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  if (out.empty()) out = "no reason given";
  if (out.size() > 300) out = out.substr(0, 297) + "...";
  return out;
}

// The first `max_words` blank-separated words of `text`, '#' comments skipped (OFF).
std::vector<std::string_view> headerWords(std::string_view text, size_t max_words) {
  std::vector<std::string_view> words;
  size_t at = 0;
  while (at < text.size() && words.size() < max_words) {
    const char c = text[at];
    if (c == '#') {
      while (at < text.size() && text[at] != '\n') ++at;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++at;
    } else {
      const size_t begin = at;
      while (at < text.size() && !std::isspace(static_cast<unsigned char>(text[at]))) ++at;
      words.push_back(text.substr(begin, at - begin));
    }
  }
  return words;
}

uint64_t parseCount(std::string_view word) {
  uint64_t value = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  return error == std::errc{} ? value : 0;
}

// A count a header declares, against the budget and against what the file can hold: every
// element takes at least one byte, so a count past the file's size is a lie assimp would
// allocate for.
Expected<void> checkDeclared(const std::string& name, const std::string& what, uint64_t count,
                             uint64_t budget, size_t file_bytes) {
  if (count > file_bytes)
    return makeError(name + ": the header declares " + std::to_string(count) + " " + what +
                     ", more than the file's " + std::to_string(file_bytes) + " bytes can hold");
  return checkBudget(name, what, count, budget, "--max-triangles");
}

// PLY ("element vertex N", "element face N") and OFF ("OFF V F E") headers, before assimp reads
// them: its readers size their arrays from these counts.
Expected<void> checkDeclaredCounts(const std::vector<uint8_t>& bytes, const std::string& name,
                                   const LoadBudget& budget) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()),
                              std::min<size_t>(bytes.size(), 64 << 10));
  if (text.starts_with("ply")) {
    const size_t end = text.find("end_header");
    const std::vector<std::string_view> words =
        headerWords(text.substr(0, end == std::string_view::npos ? text.size() : end), 1 << 14);
    for (size_t i = 0; i + 2 < words.size(); ++i) {
      if (words[i] != "element") continue;
      const std::string element(words[i + 1]);
      const uint64_t count = parseCount(words[i + 2]);
      const uint64_t limit = element == "face"     ? budget.triangles()
                             : element == "vertex" ? budget.vertices()
                                                   : UINT64_MAX;
      const std::string what = element == "vertex" ? "vertices"
                               : element == "face" ? "faces"
                                                   : singleQuoted(elided(element)) + " elements";
      if (Expected<void> ok = checkDeclared(name, what, count, limit, bytes.size()); !ok) return ok;
    }
  } else {
    // By content, as assimp finds the reader when the extension does not say.
    const std::vector<std::string_view> words = headerWords(text, 4);
    if (words.size() == 4 && words[0].ends_with("OFF") && words[0].size() <= 5) {
      if (Expected<void> ok = checkDeclared(name, "vertices", parseCount(words[1]),
                                            budget.vertices(), bytes.size());
          !ok)
        return ok;
      return checkDeclared(name, "faces", parseCount(words[2]), budget.triangles(), bytes.size());
    }
  }
  return {};
}

// The message for an import that failed: assimp's reason, and the files the sandbox refused.
std::string failure(const std::string& name, const char* reason, const SandboxIOSystem& files) {
  std::string message = name + ": assimp cannot read it: " + oneLine(reason ? reason : "");
  if (!files.refusals().empty()) message += " (" + files.refusals().front() + ")";
  return message;
}

// assimp on a model whose bytes are read: `key` is the name assimp is given (its extension picks
// the reader first), `name` the one messages use, `folder` where referred files may be (empty:
// none).
Expected<Model> importScene(const std::string& key, const std::string& name,
                            std::vector<uint8_t> bytes, const fs::path& folder,
                            const LoadBudget& budget) {
  if (Expected<void> ok = checkDeclaredCounts(bytes, name, budget); !ok) return ok.error();
  try {
    Assimp::Importer importer;
    // The importer owns and deletes its IO system.
    auto* files = new SandboxIOSystem(key, std::move(bytes), folder, budget.fileBytes());
    importer.SetIOHandler(files);
    // Bones without a mesh would be drawn as a made-up skeleton mesh.
    importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
    const aiScene* scene = importer.ReadFile(key, kPostProcess);
    if (!files->overBudget().empty()) return makeError(name + ": " + files->overBudget());
    if (scene == nullptr) return makeError(failure(name, importer.GetErrorString(), *files));
    Model model;
    assimp::SceneBuilder builder(*scene, name, folder, budget, model);
    if (Expected<void> ok = builder.run(); !ok) return ok.error();
    for (const std::string& refusal : files->refusals())
      model.warnings.push_back(name + ": " + refusal);
    return model;
  } catch (const std::bad_alloc&) {
    return makeError(name + ": assimp cannot read it: it ran out of memory");
  } catch (const std::exception& error) {
    return makeError(name + ": assimp cannot read it: " + oneLine(error.what()));
  } catch (...) {
    return makeError(name + ": assimp cannot read it: an unknown exception");
  }
}

// "Stanford Polygon Library (PLY) Importer" -> "Stanford Polygon Library (PLY)".
std::string formatName(const char* importer) {
  std::string name = trimmed(importer ? importer : "");
  for (std::string_view suffix : {" Importer", " importer", " Reader", " reader", " Loader"})
    if (name.ends_with(suffix)) name.resize(name.size() - suffix.size());
  return trimmed(name);
}

}  // namespace

const std::vector<ModelFormat>& assimpFormats() {
  static const std::vector<ModelFormat> formats = [] {
    std::vector<ModelFormat> out;
    std::vector<std::string> taken(std::begin(kOwnExtensions), std::end(kOwnExtensions));
    const Assimp::Importer importer;
    for (size_t i = 0; i < importer.GetImporterCount(); ++i) {
      const aiImporterDesc* desc = importer.GetImporterInfo(i);
      if (desc == nullptr || desc->mFileExtensions == nullptr) continue;
      ModelFormat format{formatName(desc->mName), {}, "assimp"};
      for (std::string_view words = desc->mFileExtensions; !words.empty();) {
        const size_t space = std::min(words.find(' '), words.size());
        std::string extension = lowered(std::string(words.substr(0, space)));
        words.remove_prefix(std::min(space + 1, words.size()));
        extension.erase(0, extension.find_first_not_of("*."));
        if (extension.empty() || std::find(taken.begin(), taken.end(), extension) != taken.end())
          continue;
        taken.push_back(extension);
        format.extensions.push_back(extension);
      }
      if (!format.extensions.empty()) out.push_back(std::move(format));
    }
    return out;
  }();
  return formats;
}

bool isAssimpExtension(const std::string& extension) {
  for (const ModelFormat& format : assimpFormats())
    if (std::find(format.extensions.begin(), format.extensions.end(), extension) !=
        format.extensions.end())
      return true;
  return false;
}

bool hasAssimp() {
  return true;
}

Expected<Model> loadAssimp(const fs::path& path, const LoadBudget& budget) {
  const std::string name = path.string();
  // The size and type first, as for every model: assimp never sees a FIFO or a huge file.
  Expected<std::vector<unsigned char>> bytes = readRegularFile(path, budget.fileBytes(), "model");
  if (!bytes) return bytes.error();
  std::error_code error;
  const fs::path absolute = fs::absolute(path, error).lexically_normal();
  if (error) return makeError(name + ": cannot resolve its folder: " + error.message());
  return importScene(absolute.string(), name, std::move(bytes).value(), absolute.parent_path(),
                     budget);
}

Expected<Model> loadAssimpFromMemory(std::span<const uint8_t> bytes, const std::string& name,
                                     const LoadBudget& budget) {
  if (bytes.empty()) return makeError(name + ": the file is empty");
  if (bytes.size() > budget.fileBytes())
    return makeError(name + ": the file is " + std::to_string(bytes.size()) +
                     " bytes, over the budget of " + std::to_string(budget.fileBytes()) +
                     "; raise it with --memory-limit");
  return importScene(name, name, std::vector<uint8_t>(bytes.begin(), bytes.end()), {}, budget);
}

}  // namespace tessera::io
