// Every format assimp reads that tessera has no loader of its own for, sandboxed (loadAssimp,
// model_loader.h): the size and path checks first, PLY headers and OFF files (assimp_headers.h),
// then assimp through SandboxIOSystem, first in a child process (assimp_process.h), and its
// failures and exceptions as one line naming the file.
#include <algorithm>
#include <cctype>
#include <new>
#include <optional>
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
#include "assimp_headers.h"
#include "assimp_io.h"
#include "assimp_process.h"
#include "assimp_scene.h"
#include "load_budget.h"
#include "model_paths.h"
#include "ply_points.h"

// Debian's libassimp is built with its assertions on, and a failed one calls this function,
// whose library definition aborts the process: a hostile file could end tessera (the fuzz target
// found one in TriangulateProcess). This definition takes the library's place (an executable's
// symbol comes first in ELF's lookup, and assimp calls it through its PLT) and throws instead:
// the child process that reads a file first (assimp_process.h) then says which check failed
// rather than only that it crashed.
namespace Assimp {
void aiAssertViolation(const char* expression, const char* file, int line);
void aiAssertViolation(const char* expression, const char* file, int line) {
  throw std::runtime_error(std::string("assimp's internal check failed (") +
                           (expression ? expression : "?") + " at " + (file ? file : "?") + ":" +
                           std::to_string(line) + ")");
}
}  // namespace Assimp

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

// The message for an import that failed: assimp's reason, and the files the sandbox refused.
std::string failure(const std::string& name, const char* reason, const SandboxIOSystem& files) {
  std::string message = name + ": assimp cannot read it: " + oneLine(reason ? reason : "");
  if (!files.refusals().empty()) message += " (" + files.refusals().front() + ")";
  return message;
}

// assimp's reader, tessera's check of what it read, then assimp's post-processing (which indexes
// without checking): the scene `importer` holds, or one line saying why there is none. The files
// the sandbox refused go to `refusals`.
Expected<const aiScene*> readScene(Assimp::Importer& importer, const std::string& key,
                                   const std::string& name, const std::vector<uint8_t>& bytes,
                                   const fs::path& folder, const LoadBudget& budget,
                                   std::vector<std::string>& refusals) {
  // The importer owns and deletes its IO system.
  auto* files = new SandboxIOSystem(key, bytes, folder, budget.fileBytes());
  importer.SetIOHandler(files);
  // Bones without a mesh would be drawn as a made-up skeleton mesh.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  const aiScene* scene = importer.ReadFile(key, 0);
  refusals = files->refusals();
  if (!files->overBudget().empty()) return makeError(name + ": " + files->overBudget());
  if (scene == nullptr) return makeError(failure(name, importer.GetErrorString(), *files));
  if (Expected<void> ok = assimp::checkImportedScene(*scene, name); !ok) return ok.error();
  scene = importer.ApplyPostProcessing(kPostProcess);
  if (scene == nullptr) return makeError(failure(name, importer.GetErrorString(), *files));
  return scene;
}

// assimp on a model whose bytes are read: `key` is the name assimp is given (its extension picks
// the reader first), `name` the one messages use, `folder` where referred files may be (empty:
// none). The checks tessera can make come first; then assimp reads the file in a child process
// (assimp_process.h), and only when that went well, here.
Expected<Model> importScene(const std::string& key, const std::string& name,
                            const std::vector<uint8_t>& bytes, const fs::path& folder,
                            const LoadBudget& budget) {
  std::string extension = lowered(fs::path(key).extension().string());
  if (!extension.empty()) extension.erase(0, 1);
  if (Expected<void> ok = checkHeaders(bytes, name, extension, budget); !ok) return ok.error();
  // A PLY of vertices only is read directly, neither by assimp nor in its child process
  // (ply_points.h: twenty times faster, and its header is checked above).
  try {
    if (std::optional<Expected<Model>> cloud = readPlyPointCloud(bytes, name))
      return std::move(*cloud);
  } catch (const std::bad_alloc&) {
    return makeError(name + ": out of memory while loading");
  }
  // Half a minute, and a second more for every 10 MiB: far past any sound file's read.
  const int seconds = 30 + static_cast<int>(bytes.size() / (10 << 20));
  const auto probe = [&]() -> Expected<void> {
    Assimp::Importer importer;
    std::vector<std::string> refusals;
    Expected<const aiScene*> scene =
        readScene(importer, key, name, bytes, folder, budget, refusals);
    if (!scene) return scene.error();
    return {};
  };
  // Twice the memory limit: assimp's own structures beside the file's bytes.
  if (Expected<void> ok = runIsolated(probe, name, 2 * budget.memory_bytes, seconds); !ok)
    return ok.error();
  try {
    Assimp::Importer importer;
    std::vector<std::string> refusals;
    Expected<const aiScene*> scene =
        readScene(importer, key, name, bytes, folder, budget, refusals);
    if (!scene) return scene.error();
    Model model;
    assimp::SceneBuilder builder(**scene, name, folder, budget, model);
    builder.setDeclaredFaces(plyDeclaredFaces(bytes));
    if (Expected<void> ok = builder.run(); !ok) return ok.error();
    for (const std::string& refusal : refusals) model.warnings.push_back(name + ": " + refusal);
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
  return importScene(absolute.string(), name, *bytes, absolute.parent_path(), budget);
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
