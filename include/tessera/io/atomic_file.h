// Output files appear whole or not at all: data goes to a temporary file beside the target,
// which is renamed over the target on commit() and removed if the AtomicFile is destroyed first.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

#include <tessera/base/expected.h>

namespace tessera::io {

class AtomicFile {
 public:
  // Opens a temporary file in the target's folder. Fails (with a message naming the path) when
  // the folder does not exist or cannot be written.
  static Expected<AtomicFile> create(const std::filesystem::path& target);

  AtomicFile(AtomicFile&& other) noexcept;
  AtomicFile& operator=(AtomicFile&& other) noexcept;
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();  // removes the temporary file unless committed

  std::FILE* file() const { return file_; }
  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temporaryPath() const { return temporary_; }

  // Flushes, closes and renames over the target. Fails on any write error seen so far.
  Expected<void> commit();

 private:
  AtomicFile() = default;
  void discard();

  std::FILE* file_ = nullptr;
  std::filesystem::path target_;
  std::filesystem::path temporary_;
};

}  // namespace tessera::io
