#include "assimp_io.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <system_error>
#include <utility>

#include <assimp/IOStream.hpp>

#include "model_paths.h"

namespace tessera::io {

namespace fs = std::filesystem;

namespace {

// Refusals listed in a message; the rest are counted only by their absence.
constexpr size_t kMaxRefusals = 8;

// A read-only stream over a file's bytes, shared with the IO system's cache.
class BytesStream : public Assimp::IOStream {
 public:
  explicit BytesStream(std::shared_ptr<const std::vector<uint8_t>> bytes)
      : bytes_(std::move(bytes)) {}

  size_t Read(void* buffer, size_t size, size_t count) override {
    if (size == 0 || count == 0 || buffer == nullptr) return 0;
    const size_t left = bytes_->size() - at_;
    // Whole elements only, as fread; size * count may overflow, left / size cannot.
    const size_t elements = std::min(count, left / size);
    std::memcpy(buffer, bytes_->data() + at_, elements * size);
    at_ += elements * size;
    return elements;
  }
  size_t Write(const void*, size_t, size_t) override { return 0; }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    size_t base = 0;
    if (origin == aiOrigin_CUR)
      base = at_;
    else if (origin == aiOrigin_END)
      base = bytes_->size();
    else if (origin != aiOrigin_SET)
      return aiReturn_FAILURE;
    // assimp passes negative offsets from the end or the current place as huge size_t values:
    // unsigned arithmetic wraps them back.
    const size_t target = base + offset;
    if (target > bytes_->size()) return aiReturn_FAILURE;
    at_ = target;
    return aiReturn_SUCCESS;
  }
  size_t Tell() const override { return at_; }
  size_t FileSize() const override { return bytes_->size(); }
  void Flush() override {}

 private:
  std::shared_ptr<const std::vector<uint8_t>> bytes_;
  size_t at_ = 0;
};

}  // namespace

SandboxIOSystem::SandboxIOSystem(std::string model, std::vector<uint8_t> bytes, fs::path folder,
                                 uint64_t max_bytes)
    : model_name_(std::move(model)), folder_(std::move(folder)), max_bytes_(max_bytes) {
  bytes_read_ = bytes.size();
  files_[model_name_] = std::make_shared<const std::vector<uint8_t>>(std::move(bytes));
}

void SandboxIOSystem::refuse(const std::string& file, const std::string& why) {
  const std::string line = singleQuoted(elided(file)) + " " + why;
  if (refusals_.size() < kMaxRefusals &&
      std::find(refusals_.begin(), refusals_.end(), line) == refusals_.end())
    refusals_.push_back(line);
}

fs::path SandboxIOSystem::resolve(const std::string& file, std::string& why) const {
  if (file == model_name_) return file;
  if (folder_.empty()) {
    why = "refused: the model was given in memory, and no other file can be opened";
    return {};
  }
  // assimp names the files a model refers to by joining the model's folder and the name the
  // file gives; what lies beneath the folder goes through the rules every loader follows.
  std::string reference = file;
  std::replace(reference.begin(), reference.end(), '\\', '/');
  const fs::path normal = fs::path(reference).lexically_normal();
  const fs::path inside = normal.lexically_relative(folder_.lexically_normal());
  if (normal.is_absolute() && !inside.empty() && *inside.begin() != "..")
    reference = inside.generic_string();
  Expected<fs::path> path = resolveReferencedFile(folder_, reference);
  if (!path) {
    why = "refused: " + path.error().message;
    return {};
  }
  return *path;
}

SandboxIOSystem::Bytes SandboxIOSystem::load(const std::string& file) {
  std::string why;
  const fs::path path = resolve(file, why);
  if (path.empty()) {
    refuse(file, why);
    return nullptr;
  }
  const std::string key = path.string();
  if (auto cached = files_.find(key); cached != files_.end()) return cached->second;
  const uint64_t left = max_bytes_ > bytes_read_ ? max_bytes_ - bytes_read_ : 0;
  uintmax_t size = 0;
  if (Expected<RegularFile> opened =
          openRegularFile(path, std::numeric_limits<uintmax_t>::max(), "model");
      opened)
    size = opened->size();
  if (size > left) {
    why = "is " + std::to_string(size) + " bytes, past what is left of the budget of " +
          std::to_string(max_bytes_) + " bytes for the model's files; raise it with " +
          "--memory-limit";
    if (over_budget_.empty()) over_budget_ = key + " " + why;
    refuse(file, why);
    return nullptr;
  }
  Expected<std::vector<unsigned char>> bytes = readRegularFile(path, left, "model");
  if (!bytes) {
    refuse(file, "cannot be read: " + bytes.error().message);
    return nullptr;
  }
  bytes_read_ += bytes->size();
  auto shared = std::make_shared<const std::vector<uint8_t>>(std::move(bytes).value());
  files_.emplace(key, shared);
  return shared;
}

bool SandboxIOSystem::Exists(const char* file) const {
  if (file == nullptr) return false;
  std::string why;
  const fs::path path = resolve(file, why);
  if (path.empty()) return false;
  if (files_.count(path.string())) return true;
  std::error_code error;
  return fs::is_regular_file(path, error);
}

Assimp::IOStream* SandboxIOSystem::Open(const char* file, const char* mode) {
  if (file == nullptr) return nullptr;
  if (mode != nullptr &&
      (std::strchr(mode, 'w') || std::strchr(mode, 'a') || std::strchr(mode, '+'))) {
    refuse(file, "refused: assimp asked to write it");
    return nullptr;
  }
  Bytes bytes = load(file);
  if (!bytes) return nullptr;
  return new BytesStream(std::move(bytes));
}

void SandboxIOSystem::Close(Assimp::IOStream* stream) {
  delete stream;
}

bool SandboxIOSystem::ComparePaths(const char* one, const char* second) const {
  if (one == nullptr || second == nullptr) return false;
  std::string why;
  const fs::path a = resolve(one, why), b = resolve(second, why);
  return !a.empty() && a == b;
}

}  // namespace tessera::io
