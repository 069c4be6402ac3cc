#include "gltf_files.h"

#include <algorithm>
#include <system_error>

#include "model_paths.h"

#include "tinygltf_include.h"

namespace tessera::io::gltf {

namespace fs = std::filesystem;

namespace {

// tinygltf takes lengths as unsigned int; 2 GiB keeps every offset well inside that.
constexpr uintmax_t kMaxBufferFileBytes = uintmax_t{2} << 30;

}  // namespace

Expected<fs::path> ExternalFiles::resolve(const std::string& joined) {
  if (!std::string_view(joined).starts_with(kFolderMarker))
    return makeError("only files beneath the model's folder are read");
  const std::string reference = joined.substr(kFolderMarker.size());
  if (folder.empty())
    return makeError("'" + reference + "' is an external file, and this model was given in memory");
  Expected<fs::path> path = resolveReferencedFile(folder, reference);
  if (!path) return makeError("'" + reference + "' refused: " + path.error().message);
  return path;
}

bool fileExists(const std::string& joined, void* user) {
  auto& files = *static_cast<ExternalFiles*>(user);
  // The second attempt, in ".", is never honoured and needs no second message.
  if (!std::string_view(joined).starts_with(kFolderMarker)) return false;
  Expected<fs::path> path = files.resolve(joined);
  if (!path) {
    files.refusals.push_back(path.error().message);
    return false;
  }
  // Anything that exists goes on to readWholeFile, which opens only regular files and says what
  // anything else is (a FIFO, a folder).
  std::error_code error;
  if (!fs::exists(fs::status(*path, error))) {
    files.refusals.push_back(path->string() + ": no such file");
    return false;
  }
  return true;
}

std::string expandFilePath(const std::string& path, void*) {
  return path;
}

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& joined,
                   void* user) {
  auto& files = *static_cast<ExternalFiles*>(user);
  Expected<fs::path> path = files.resolve(joined);
  if (!path) {
    files.refusals.push_back(path.error().message);
    if (err) *err = path.error().message;
    return false;
  }
  // The model's files together stay within the budget's bytes (LoadBudget::fileBytes).
  Expected<std::vector<unsigned char>> bytes =
      readRegularFile(*path, std::min<uintmax_t>(kMaxBufferFileBytes, files.bytes_left), "buffer");
  if (!bytes) {
    files.refusals.push_back(bytes.error().message);
    if (err) *err = bytes.error().message;
    return false;
  }
  files.bytes_read += bytes->size();
  files.bytes_left -= std::min<uintmax_t>(files.bytes_left, bytes->size());
  *out = std::move(bytes).value();
  return true;
}

bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "tessera never writes glTF files";
  return false;
}

bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && bytes != nullptr && size > 0)
    image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

}  // namespace tessera::io::gltf
