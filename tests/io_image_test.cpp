// The image and animation writers, checked by decoding their output with independent decoders
// (libpng for PNG, giflib's own reader for GIF).
#include <gif_lib.h>
#include <png.h>
#include <stdlib.h>
#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csetjmp>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <tessera/io/atomic_file.h>
#include <tessera/io/frame_sink.h>
#include <tessera/io/image_writer.h>
#include <tessera/render/frame.h>

namespace tessera::io {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "tessera_io_test_XXXXXX").string();
    TESSERA_CHECK(mkdtemp(pattern.data()) != nullptr) << "mkdtemp " << pattern;
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }

  // Every name in the folder, hidden temporaries included, sorted.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const fs::directory_entry& entry : fs::directory_iterator(path_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// ---- AtomicFile ----

TEST(IoAtomicFile, TargetAppearsOnlyOnCommit) {
  TempDir dir;
  const fs::path target = dir / "out.txt";
  Expected<AtomicFile> file = AtomicFile::create(target);
  ASSERT_TRUE(file.ok()) << file.error().message;
  EXPECT_EQ(file->temporaryPath().parent_path(), dir.path());
  ASSERT_TRUE(file->write("hello", 5).ok());
  EXPECT_FALSE(fs::exists(target));
  EXPECT_TRUE(fs::exists(file->temporaryPath()));

  ASSERT_TRUE(file->commit().ok());
  EXPECT_EQ(readText(target), "hello");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.txt"});
}

TEST(IoAtomicFile, DestroyedWithoutCommitLeavesNothing) {
  TempDir dir;
  {
    Expected<AtomicFile> file = AtomicFile::create(dir / "out.txt");
    ASSERT_TRUE(file.ok()) << file.error().message;
    ASSERT_TRUE(file->write("partial", 7).ok());
    ASSERT_EQ(dir.entries().size(), 1u);  // the temporary, so its removal below is real
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(IoAtomicFile, UncommittedWriteKeepsExistingTarget) {
  TempDir dir;
  const fs::path target = dir / "out.txt";
  writeText(target, "old");
  {
    Expected<AtomicFile> file = AtomicFile::create(target);
    ASSERT_TRUE(file.ok()) << file.error().message;
    ASSERT_TRUE(file->write("new", 3).ok());
  }
  EXPECT_EQ(readText(target), "old");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.txt"});
}

TEST(IoAtomicFile, MissingFolderIsAnErrorNamingPathAndReason) {
  TempDir dir;
  const fs::path target = dir / "missing" / "x.png";
  Expected<AtomicFile> file = AtomicFile::create(target);
  ASSERT_FALSE(file.ok());
  EXPECT_EQ(file.error().message,
            "cannot write '" + target.string() + "': No such file or directory");
  EXPECT_TRUE(dir.entries().empty());
}

TEST(IoAtomicFile, FailedRenameRemovesTemporaryAndKeepsTarget) {
  TempDir dir;
  // rename() cannot put a file over a non-empty folder.
  const fs::path target = dir / "occupied";
  fs::create_directory(target);
  writeText(target / "keep.txt", "kept");
  Expected<AtomicFile> file = AtomicFile::create(target);
  ASSERT_TRUE(file.ok()) << file.error().message;
  ASSERT_TRUE(file->write("data", 4).ok());
  Expected<void> committed = file->commit();
  ASSERT_FALSE(committed.ok());
  EXPECT_NE(committed.error().message.find(target.string()), std::string::npos)
      << committed.error().message;
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"occupied"});
  EXPECT_EQ(readText(target / "keep.txt"), "kept");
}

TEST(IoAtomicFile, MovedFileCommitsOnceAndOriginalRemovesNothing) {
  TempDir dir;
  const fs::path target = dir / "out.txt";
  Expected<AtomicFile> created = AtomicFile::create(target);
  ASSERT_TRUE(created.ok()) << created.error().message;
  {
    AtomicFile moved = std::move(*created);
    ASSERT_TRUE(moved.write("moved", 5).ok());
    ASSERT_TRUE(moved.commit().ok());
  }
  EXPECT_EQ(readText(target), "moved");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.txt"});
}

}  // namespace
}  // namespace tessera::io
