#include "model_paths.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <string>
#include <system_error>

namespace tessera::io {

namespace fs = std::filesystem;

std::string trimmed(std::string_view text) {
  const char* kSpace = " \t\r\n";
  size_t begin = text.find_first_not_of(kSpace);
  if (begin == std::string_view::npos) return {};
  size_t end = text.find_last_not_of(kSpace);
  return std::string(text.substr(begin, end - begin + 1));
}

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

std::string numberAfter(std::string_view text, std::string_view marker) {
  std::string number;
  const size_t at = text.rfind(marker);
  if (at == std::string_view::npos) return number;
  for (size_t i = at + marker.size(); i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i)
    number += text[i];
  return number;
}

std::string elided(std::string_view text) {
  constexpr size_t kMaxShown = 80;
  if (text.starts_with("data:")) {
    // The media type and the first bytes say what it is; the rest says nothing a user can use.
    const size_t comma = text.find(',');
    const size_t keep = comma == std::string_view::npos ? 24 : std::min(comma + 5, kMaxShown);
    return text.size() <= keep ? std::string(text) : std::string(text.substr(0, keep)) + "...";
  }
  if (text.size() <= kMaxShown) return std::string(text);
  return std::string(text.substr(0, kMaxShown - 3)) + "...";
}

namespace {

// "2 GiB", "64 MiB" or a byte count.
std::string sizeText(uintmax_t bytes) {
  if (bytes >= (uintmax_t{1} << 30) && bytes % (uintmax_t{1} << 30) == 0)
    return std::to_string(bytes >> 30) + " GiB";
  if (bytes >= (uintmax_t{1} << 20) && bytes % (uintmax_t{1} << 20) == 0)
    return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

}  // namespace

namespace {

// What a non-regular file is, for messages.
std::string fileKind(mode_t mode) {
  if (S_ISFIFO(mode)) return "is a FIFO";
  if (S_ISDIR(mode)) return "is a directory";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "is a device";
  if (S_ISSOCK(mode)) return "is a socket";
  return "is not a regular file";
}

}  // namespace

RegularFile::~RegularFile() {
  if (fd_ >= 0) ::close(fd_);
}

RegularFile::RegularFile(RegularFile&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), size_(other.size_) {}

int RegularFile::release() {
  return std::exchange(fd_, -1);
}

Expected<RegularFile> openRegularFile(const fs::path& path, uintmax_t max_bytes,
                                      const std::string& format) {
  const std::string name = path.string();
  // O_NONBLOCK: opening a FIFO nobody writes to returns at once instead of waiting for a writer.
  // The type is then checked on the descriptor, so nothing can be swapped in after the check.
  const int fd = ::open(name.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    const int error = errno;
    if (error == ENOENT || error == ENOTDIR) return makeError(name + ": no such file");
    return makeError(name + ": cannot open: " + std::strerror(error));
  }
  RegularFile file;
  file.fd_ = fd;
  struct stat info {};
  if (::fstat(fd, &info) != 0)
    return makeError(name + ": cannot read the file's status: " + std::strerror(errno));
  if (!S_ISREG(info.st_mode))
    return makeError(name + ": " + fileKind(info.st_mode) + ", not a regular file");
  // Reads from here on may wait for the disk, as any read does.
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags < 0 || ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0)
    return makeError(name + ": cannot open: " + std::strerror(errno));
  file.size_ = static_cast<uintmax_t>(info.st_size);
  if (file.size_ > max_bytes)
    return makeError(name + ": the file is " + std::to_string(file.size_) + " bytes; " + format +
                     " files over " + sizeText(max_bytes) + " are refused");
  if (file.size_ == 0) return makeError(name + ": the file is empty");
  return file;
}

Expected<std::vector<unsigned char>> readRegularFile(const fs::path& path, uintmax_t max_bytes,
                                                     const std::string& format) {
  Expected<RegularFile> file = openRegularFile(path, max_bytes, format);
  if (!file) return file.error();
  std::vector<unsigned char> bytes(static_cast<size_t>(file->size()));
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t got = ::read(file->fd(), bytes.data() + done, bytes.size() - done);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) return makeError(path.string() + ": read error: " + std::strerror(errno));
    if (got == 0) break;  // a file that shrank while being read is read as far as it goes
    done += static_cast<size_t>(got);
  }
  bytes.resize(done);
  if (bytes.empty()) return makeError(path.string() + ": the file is empty");
  return bytes;
}

Expected<fs::path> resolveReferencedFile(const fs::path& folder, std::string_view reference) {
  std::string name = trimmed(reference);
  if (name.empty()) return makeError("the file name is empty");
  // A scheme (http:, file:, data:) or a drive letter (C:) ahead of any separator.
  size_t scheme_end = 0;
  while (scheme_end < name.size()) {
    unsigned char c = static_cast<unsigned char>(name[scheme_end]);
    if (!std::isalnum(c) && c != '+' && c != '-' && c != '.') break;
    ++scheme_end;
  }
  if (scheme_end > 0 && scheme_end < name.size() && name[scheme_end] == ':' &&
      std::isalpha(static_cast<unsigned char>(name[0]))) {
    if (scheme_end == 1) return makeError("it is an absolute path");
    return makeError("it is a URI; only files beneath the model's folder are read");
  }
  std::replace(name.begin(), name.end(), '\\', '/');
  if (name.front() == '/') return makeError("it is an absolute path");

  std::vector<std::string> parts;
  size_t begin = 0;
  while (begin <= name.size()) {
    size_t end = std::min(name.find('/', begin), name.size());
    std::string part = name.substr(begin, end - begin);
    begin = end + 1;
    if (part.empty() || part == ".") continue;
    if (part == "..") {
      if (parts.empty()) return makeError("it leads out of the model's folder");
      parts.pop_back();
      continue;
    }
    parts.push_back(std::move(part));
  }
  if (parts.empty()) return makeError("it names the model's folder, not a file");
  fs::path full = folder;
  for (const std::string& part : parts) full /= part;

  // The lexical check cannot see a symbolic link beneath the folder that points outside it.
  std::error_code error;
  if (fs::exists(full, error)) {
    std::error_code folder_error;
    fs::path real = fs::canonical(full, error);
    fs::path real_folder = fs::canonical(folder, folder_error);
    if (error || folder_error) return makeError("its location cannot be resolved");
    fs::path inside = real.lexically_relative(real_folder);
    if (inside.empty() || *inside.begin() == "..")
      return makeError("it leads out of the model's folder through a symbolic link");
  }
  return full;
}

}  // namespace tessera::io
