// Output files appear whole or not at all: data goes to a temporary file beside the target,
// which is renamed over the target on commit() and removed if the AtomicFile is destroyed first.
#pragma once

#include <cstddef>
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

  // The open temporary file; null once close() or commit() has run.
  std::FILE* file() const { return file_; }
  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temporaryPath() const { return temporary_; }

  // Appends bytes to the temporary file. The first failure is remembered (with the OS reason)
  // and returned again by close() and commit().
  Expected<void> write(const void* data, size_t size);

  // Flushes, syncs and closes the temporary file but does not rename it yet, so a caller can
  // hold many finished files (a PNG sequence) without holding a descriptor for each.
  Expected<void> close();

  // Closes (if still open) and renames over the target. Fails on any write error seen so far;
  // on failure the temporary file is removed and the target is left as it was.
  Expected<void> commit();

 private:
  AtomicFile() = default;
  void discard();
  Error failWith(const std::string& reason);

  std::FILE* file_ = nullptr;
  bool temporary_exists_ = false;  // ours to remove: created, not yet renamed or removed
  std::string first_error_;        // first write failure, reported by close() and commit()
  std::filesystem::path target_;
  std::filesystem::path temporary_;
};

// Creates the folders above `target` that do not exist yet (an output's folder, for the CLI:
// `-o renders/a.png` makes renders/). An error naming the folder that could not be made, and
// why (a file in the way, no permission).
Expected<void> createParentFolders(const std::filesystem::path& target);

}  // namespace tessera::io
