// Helpers of the image and animation writers' tests (io_image_test.cpp, io_gif_test.cpp): a fresh
// folder per test, a file read whole, a file-size limit that stands for a full disk,
// and frames to write.
#pragma once

#include <sys/resource.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

#include <tessera/base/check.h>
#include <tessera/io/frame_sink.h>

#include "temp_folder.h"

namespace tessera::test {

namespace fs = std::filesystem;

// A fresh folder per test (makeTestFolder's), removed with everything in it.
class TempDir {
 public:
  TempDir() : path_(makeTestFolder("tessera_io_test")) {}
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

inline std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

constexpr uint32_t packRgba(uint32_t r, uint32_t g, uint32_t b, uint32_t a = 255) {
  return r | (g << 8) | (b << 16) | (a << 24);
}

// Makes writes past `bytes` fail with EFBIG (instead of raising SIGXFSZ) while it lives: a
// full disk, without needing one.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    TESSERA_CHECK(getrlimit(RLIMIT_FSIZE, &saved_) == 0) << "getrlimit";
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limited = saved_;
    limited.rlim_cur = std::min(bytes, saved_.rlim_max);
    TESSERA_CHECK(setrlimit(RLIMIT_FSIZE, &limited) == 0) << "setrlimit";
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_handler_);
  }

 private:
  rlimit saved_{};
  void (*previous_handler_)(int) = SIG_DFL;
};

inline std::vector<uint32_t> noiseFrame(int width, int height) {
  std::vector<uint32_t> pixels(static_cast<size_t>(width) * height);
  uint32_t state = 1;
  for (uint32_t& p : pixels) {
    state = state * 1664525u + 1013904223u;  // Numerical Recipes LCG
    p = (state >> 8) | 0xFF000000u;
  }
  return pixels;
}

inline std::vector<uint32_t> solidFrame(int width, int height, uint32_t colour) {
  return std::vector<uint32_t>(static_cast<size_t>(width) * height, colour);
}

inline io::AnimationSettings settingsOf(int width, int height, int fps = 30, bool loop = true) {
  io::AnimationSettings settings;
  settings.width = width;
  settings.height = height;
  settings.fps = fps;
  settings.loop = loop;
  return settings;
}

}  // namespace tessera::test
