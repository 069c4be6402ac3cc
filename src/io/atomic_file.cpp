#include <tessera/io/atomic_file.h>

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <random>
#include <system_error>
#include <utility>

namespace tessera::io {
namespace {

std::string osReason(int error_number) {
  return std::generic_category().message(error_number);
}

std::string cannotWrite(const std::filesystem::path& target, const std::string& reason) {
  return "cannot write '" + target.string() + "': " + reason;
}

// ".name.tmp-XXXXXX": hidden, and beside the target so that rename() never crosses filesystems.
std::filesystem::path temporaryName(const std::filesystem::path& target, std::mt19937& random) {
  static constexpr char kAlphabet[] =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::uniform_int_distribution<size_t> pick(0, sizeof(kAlphabet) - 2);
  std::string name(1, '.');
  name += target.filename().string();
  name += ".tmp-";
  for (int i = 0; i < 6; ++i) name += kAlphabet[pick(random)];
  return target.parent_path() / name;
}

}  // namespace

Expected<void> createParentFolders(const std::filesystem::path& target) {
  const std::filesystem::path folder = target.parent_path();
  if (folder.empty()) return {};
  std::error_code error;
  if (std::filesystem::is_directory(folder, error)) return {};
  std::filesystem::create_directories(folder, error);
  if (error || !std::filesystem::is_directory(folder))
    return makeError("cannot create the folder '" + folder.string() + "' for '" +
                     target.string() + "': " +
                     (error ? error.message() : std::string("a file is in the way")));
  return {};
}

Expected<AtomicFile> AtomicFile::create(const std::filesystem::path& target) {
  if (!target.has_filename()) return makeError(cannotWrite(target, "not a file name"));

  // open(O_EXCL) rather than mkstemp(): mkstemp makes the file 0600, and the output should get
  // the permissions the user's umask gives any new file.
  std::random_device seed;
  std::mt19937 random(seed());
  constexpr int kAttempts = 64;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    std::filesystem::path temporary = temporaryName(target, random);
    int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) {
      if (errno == EEXIST) continue;
      return makeError(cannotWrite(target, osReason(errno)));
    }
    std::FILE* file = ::fdopen(fd, "wb");
    if (file == nullptr) {
      int fdopen_error = errno;
      ::close(fd);
      ::unlink(temporary.c_str());
      return makeError(cannotWrite(target, osReason(fdopen_error)));
    }
    AtomicFile result;
    result.file_ = file;
    result.temporary_exists_ = true;
    result.target_ = target;
    result.temporary_ = std::move(temporary);
    return result;
  }
  return makeError(cannotWrite(target, "no unused temporary file name in its folder"));
}

AtomicFile::AtomicFile(AtomicFile&& other) noexcept
    : file_(std::exchange(other.file_, nullptr)),
      temporary_exists_(std::exchange(other.temporary_exists_, false)),
      first_error_(std::move(other.first_error_)),
      target_(std::move(other.target_)),
      temporary_(std::move(other.temporary_)) {}

AtomicFile& AtomicFile::operator=(AtomicFile&& other) noexcept {
  if (this != &other) {
    discard();
    file_ = std::exchange(other.file_, nullptr);
    temporary_exists_ = std::exchange(other.temporary_exists_, false);
    first_error_ = std::move(other.first_error_);
    target_ = std::move(other.target_);
    temporary_ = std::move(other.temporary_);
  }
  return *this;
}

AtomicFile::~AtomicFile() {
  discard();
}

void AtomicFile::discard() {
  if (file_ != nullptr) {
    std::fclose(file_);
    file_ = nullptr;
  }
  if (temporary_exists_) {
    ::unlink(temporary_.c_str());
    temporary_exists_ = false;
  }
}

Error AtomicFile::failWith(const std::string& reason) {
  if (first_error_.empty()) first_error_ = cannotWrite(target_, reason);
  // Removed at once: a full disk gets its space back before the caller unwinds.
  discard();
  return makeError(first_error_);
}

Expected<void> AtomicFile::write(const void* data, size_t size) {
  if (!first_error_.empty()) return makeError(first_error_);
  TESSERA_CHECK(file_ != nullptr) << "write() to a closed AtomicFile for " << target_;
  if (size == 0) return {};
  if (std::fwrite(data, 1, size, file_) != size) return failWith(osReason(errno));
  return {};
}

Expected<void> AtomicFile::close() {
  if (!first_error_.empty()) return makeError(first_error_);
  TESSERA_CHECK(temporary_exists_) << "close() of an AtomicFile already committed or moved from";
  if (file_ == nullptr) return {};  // closed before
  if (std::fflush(file_) != 0) return failWith(osReason(errno));
  // Bytes written through file() directly never reached write(), so look at the stream too.
  if (std::ferror(file_)) return failWith("write error");
  // Synced before the rename, so that after a crash the target is the old file or the new one.
  if (::fsync(::fileno(file_)) != 0) return failWith(osReason(errno));
  std::FILE* file = std::exchange(file_, nullptr);
  if (std::fclose(file) != 0) return failWith(osReason(errno));
  return {};
}

Expected<void> AtomicFile::commit() {
  if (auto closed = close(); !closed) return closed;
  if (::rename(temporary_.c_str(), target_.c_str()) != 0) return failWith(osReason(errno));
  temporary_exists_ = false;
  return {};
}

}  // namespace tessera::io
