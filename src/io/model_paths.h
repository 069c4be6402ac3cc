// What every model loader shares about files: reading the model file itself within a size limit,
// and resolving the files a model refers to (MTL libraries, textures, glTF buffers) to paths
// beneath the model's own folder. Private to tessera_io.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <tessera/base/expected.h>

namespace tessera::io {

// `text` without leading and trailing blanks and line ends.
std::string trimmed(std::string_view text);

bool equalsIgnoreCase(std::string_view a, std::string_view b);

// The digits after the last `marker` in a library's message ("... line 12.)" -> "12"), or empty.
std::string numberAfter(std::string_view text, std::string_view marker);

// A value from a file, short enough for a message: a data: URI as "data:image/png;base64,iVBO..."
// and any other text over 80 characters cut with "...".
std::string elided(std::string_view text);

// `text` in single quotes, for messages.
inline std::string singleQuoted(std::string_view text) {
  std::string out;
  out.reserve(text.size() + 2);
  out += '\'';
  out += text;
  out += '\'';
  return out;
}

// Encoded image files a model names (or --texture): far past any real texture, and read whole
// into memory before decoding.
constexpr uintmax_t kMaxImageFileBytes = uintmax_t{512} << 20;

// A file opened for reading that is known to be a regular file: open(2) with O_NONBLOCK, so
// that a FIFO cannot block, and the type checked with fstat(2) on the descriptor, never by name.
class RegularFile {
 public:
  RegularFile() = default;
  RegularFile(RegularFile&& other) noexcept;
  RegularFile& operator=(RegularFile&&) = delete;
  ~RegularFile();

  int fd() const { return fd_; }
  uintmax_t size() const { return size_; }
  // Hands the descriptor to the caller, who closes it.
  int release();

 private:
  friend Expected<RegularFile> openRegularFile(const std::filesystem::path&, uintmax_t,
                                               const std::string&);
  int fd_ = -1;
  uintmax_t size_ = 0;
};

// Opens `path` if it is a regular, non-empty file of at most `max_bytes`; otherwise says what it
// is ("no such file", "is a FIFO", "is a directory"). `format` names the kind of file in the
// message ("OBJ", "STL", "image").
Expected<RegularFile> openRegularFile(const std::filesystem::path& path, uintmax_t max_bytes,
                                      const std::string& format);

// The whole file, after openRegularFile's checks.
Expected<std::vector<unsigned char>> readRegularFile(const std::filesystem::path& path,
                                                     uintmax_t max_bytes,
                                                     const std::string& format);

// Resolves a file named inside a model (an MTL library, a texture, a buffer) to a path beneath
// `folder`, or says why it is refused: URIs, absolute paths, `..` that climbs out of the folder
// (after normalizing) and symbolic links that lead outside. '\' is taken as a separator, since
// Windows exporters write `.\tex\a.png`.
Expected<std::filesystem::path> resolveReferencedFile(const std::filesystem::path& folder,
                                                      std::string_view reference);

}  // namespace tessera::io
