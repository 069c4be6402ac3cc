// Test helpers: a fresh folder per test under the system temp folder, and writing files into it.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace tessera::test {

// An empty folder named for the running test, `<temp>/<prefix>_<test>_<pid>_<random>`: the pid
// and the random part keep test processes run side by side (ctest -j) out of each other's way.
// The caller removes it.
inline std::filesystem::path makeTestFolder(const std::string& prefix) {
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const std::filesystem::path folder = std::filesystem::temp_directory_path() /
                                       (prefix + "_" + test + "_" + std::to_string(::getpid()) +
                                        "_" + std::to_string(std::random_device{}()));
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

// Writes `bytes` to `path`, creating the folders above it; returns `path`.
inline std::filesystem::path writeFile(const std::filesystem::path& path,
                                       const std::string& bytes) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

}  // namespace tessera::test
