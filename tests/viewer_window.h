// The fixture of the window tests: the real `tessera view` under its own Xvfb, driven by real X
// input (xdotool sends XTEST pointer and key events), and the helpers that read its screenshots.
// Shared by viewer_window_test.cpp, viewer_window_aa_test.cpp and
// viewer_window_projection_test.cpp.
#pragma once

#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "decode.h"

namespace tessera::test {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Generous: a loaded 2-core CI machine may be slow to start an X server or a process.
constexpr auto kTimeout = std::chrono::seconds(60);

inline std::optional<fs::path> findProgram(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const fs::path candidate = fs::path(dir) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return std::nullopt;
}

// A child process with its own environment, stdout on a pipe (or a file), stderr in a file.
class Process {
 public:
  Process() = default;
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;
  ~Process() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (out_fd_ >= 0) ::close(out_fd_);
  }

  // Runs `argv` in `dir` with `env` changes (an empty value unsets). Extra: an fd of the child
  // to connect to a pipe whose read end is returned by extraFd() (for Xvfb's -displayfd).
  bool start(const std::vector<std::string>& argv, const fs::path& dir,
             const std::map<std::string, std::string>& env, const fs::path& stderr_path,
             int extra_child_fd = -1) {
    int out[2], extra[2] = {-1, -1};
    if (::pipe(out) != 0) return false;
    if (extra_child_fd >= 0 && ::pipe(extra) != 0) return false;
    pid_ = ::fork();
    if (pid_ < 0) return false;
    if (pid_ == 0) {
      ::dup2(out[1], STDOUT_FILENO);
      int err = ::open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (err >= 0) ::dup2(err, STDERR_FILENO);
      int in = ::open("/dev/null", O_RDONLY);
      if (in >= 0) ::dup2(in, STDIN_FILENO);
      if (extra_child_fd >= 0) ::dup2(extra[1], extra_child_fd);
      if (::chdir(dir.c_str()) != 0) ::_exit(126);
      for (const auto& [name, value] : env) {
        if (value.empty())
          ::unsetenv(name.c_str());
        else
          ::setenv(name.c_str(), value.c_str(), 1);
      }
      std::vector<char*> args;
      for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
      args.push_back(nullptr);
      ::execvp(args[0], args.data());
      ::_exit(127);
    }
    ::close(out[1]);
    out_fd_ = out[0];
    if (extra_child_fd >= 0) {
      ::close(extra[1]);
      extra_fd_ = extra[0];
    }
    return true;
  }

  // Reads lines from `fd` until one starts with `prefix`; returns it, or nullopt once `timeout`
  // has passed or at end of file.
  static std::optional<std::string> readLine(int fd, std::string& buffer,
                                             std::vector<std::string>& seen,
                                             const std::string& prefix,
                                             Clock::duration timeout = kTimeout) {
    const Clock::time_point deadline = Clock::now() + timeout;
    while (true) {
      size_t newline;
      while ((newline = buffer.find('\n')) != std::string::npos) {
        std::string line = buffer.substr(0, newline);
        buffer.erase(0, newline + 1);
        seen.push_back(line);
        if (line.rfind(prefix, 0) == 0) return line;
      }
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
      pollfd p{fd, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(std::max<long long>(left, 0))) <= 0) {
        if (left <= 0) return std::nullopt;
        continue;
      }
      char chunk[4096];
      ssize_t n = ::read(fd, chunk, sizeof chunk);
      if (n <= 0) return std::nullopt;
      buffer.append(chunk, static_cast<size_t>(n));
    }
  }

  std::optional<std::string> waitForLine(const std::string& prefix) {
    return readLine(out_fd_, buffer_, lines_, prefix);
  }
  // Only what the process has printed so far.
  std::optional<std::string> waitForLineNow(const std::string& prefix) {
    return readLine(out_fd_, buffer_, lines_, prefix, Clock::duration::zero());
  }
  int extraFd() const { return extra_fd_; }

  // The exit status, or -1 if it did not exit before the deadline (or died of a signal).
  int waitExit() {
    const Clock::time_point deadline = Clock::now() + kTimeout;
    while (Clock::now() < deadline) {
      int status = 0;
      pid_t r = ::waitpid(pid_, &status, WNOHANG);
      if (r == pid_) {
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      }
      // Drain stdout so the child never blocks on a full pipe.
      pollfd p{out_fd_, POLLIN, 0};
      if (::poll(&p, 1, 50) > 0) {
        char chunk[4096];
        ssize_t n = ::read(out_fd_, chunk, sizeof chunk);
        if (n > 0) buffer_.append(chunk, static_cast<size_t>(n));
      }
    }
    return -1;
  }

  std::string output() const {
    std::string all;
    for (const std::string& l : lines_) all += l + "\n";
    return all + buffer_;
  }

 private:
  pid_t pid_ = -1;
  int out_fd_ = -1;
  int extra_fd_ = -1;
  std::string buffer_;
  std::vector<std::string> lines_;
};

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Rgb {
  int r = 0, g = 0, b = 0;
};

inline Rgb pixel(const DecodedPng& png, int x, int y) {
  return {png.at(x, y, 0), png.at(x, y, 1), png.at(x, y, 2)};
}

inline bool near(Rgb a, Rgb b, int tolerance) {
  return std::abs(a.r - b.r) <= tolerance && std::abs(a.g - b.g) <= tolerance &&
         std::abs(a.b - b.b) <= tolerance;
}

// Pixels of the rectangle [x0, x1) x [y0, y1) that differ between two same-sized pictures.
inline int countDifferent(const DecodedPng& a, const DecodedPng& b, int x0, int y0, int x1,
                          int y1) {
  int count = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      if (!near(pixel(a, x, y), pixel(b, x, y), 0)) ++count;
  return count;
}

// The share of the picture that is not background, and the centre of that part.
struct Coverage {
  double share = 0;
  double centre_x = 0, centre_y = 0;
};

inline Coverage coverage(const DecodedPng& png, Rgb background) {
  Coverage c;
  long long count = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x)
      if (!near(pixel(png, x, y), background, 8)) {
        ++count;
        c.centre_x += x;
        c.centre_y += y;
      }
  if (count == 0) return c;
  c.share = static_cast<double>(count) / (static_cast<double>(png.width) * png.height);
  c.centre_x /= static_cast<double>(count);
  c.centre_y /= static_cast<double>(count);
  return c;
}

inline bool isText(Rgb p) {
  return p.r > 160 && p.g > 160 && p.b > 160;
}

// The rows [first, last] of each line of white text inside the rectangle, top to bottom.
inline std::vector<std::pair<int, int>> textLines(const DecodedPng& png, int x0, int y0, int x1,
                                                  int y1) {
  std::vector<std::pair<int, int>> lines;
  bool in_line = false;
  for (int y = y0; y < y1; ++y) {
    int text = 0;
    for (int x = x0; x < x1; ++x) text += isText(pixel(png, x, y)) ? 1 : 0;
    if (text > 0 && !in_line) lines.push_back({y, y});
    if (text > 0) lines.back().second = y;
    in_line = text > 0;
  }
  return lines;
}

// Whether the white text of rows [first, last] is the same in both pictures, in columns
// [0, x_end) (all of them by default). Anti-aliased text takes the colour of what is under its
// box: compare where that is the same in both.
inline bool sameText(const DecodedPng& a, const DecodedPng& b, std::pair<int, int> rows,
                     int x_end = -1) {
  for (int y = rows.first; y <= rows.second; ++y)
    for (int x = 0; x < (x_end < 0 ? a.width : x_end); ++x)
      if (isText(pixel(a, x, y)) != isText(pixel(b, x, y))) return false;
  return true;
}

class ViewerWindow : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("tessera_view_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    viewer_.reset();
    xserver_.reset();
    if (!HasFailure()) fs::remove_all(dir_);
  }

  // Starts Xvfb on a free display (it picks one and reports it through -displayfd).
  // Returns false and sets `why` when the tools are missing.
  bool startX(std::string& why) {
    std::optional<fs::path> xvfb = findProgram("Xvfb");
    std::optional<fs::path> xdotool = findProgram("xdotool");
    if (!xvfb || !xdotool) {
      why = std::string("skipped: ") + (!xvfb ? "Xvfb" : "xdotool") +
            " is not installed (scripts/setup.sh installs xvfb and xdotool)";
      return false;
    }
    xserver_ = std::make_unique<Process>();
    constexpr int kDisplayFd = 9;
    if (!xserver_->start({xvfb->string(), "-displayfd", std::to_string(kDisplayFd), "-screen", "0",
                          "1024x768x24", "-nolisten", "tcp"},
                         dir_, {}, dir_ / "xvfb.log", kDisplayFd)) {
      why = "cannot start Xvfb";
      return false;
    }
    std::string buffer;
    std::vector<std::string> seen;
    std::optional<std::string> number = Process::readLine(xserver_->extraFd(), buffer, seen, "");
    if (!number || number->empty()) {
      why = "Xvfb reported no display: " + slurp(dir_ / "xvfb.log");
      return false;
    }
    display_ = ":" + *number;
    return true;
  }

  std::map<std::string, std::string> viewerEnv() const {
    return {{"DISPLAY", display_}, {"SDL_VIDEODRIVER", "x11"}, {"WAYLAND_DISPLAY", ""}};
  }

  void startViewer(const std::vector<std::string>& args) {
    std::vector<std::string> argv{TESSERA_EXE, "view"};
    argv.insert(argv.end(), args.begin(), args.end());
    viewer_ = std::make_unique<Process>();
    ASSERT_TRUE(viewer_->start(argv, dir_, viewerEnv(), dir_ / "viewer.err"));
  }

  // Runs xdotool with `args`; returns its standard output.
  std::string xdotool(const std::vector<std::string>& args) {
    std::vector<std::string> argv{"xdotool"};
    argv.insert(argv.end(), args.begin(), args.end());
    Process tool;
    EXPECT_TRUE(tool.start(argv, dir_, {{"DISPLAY", display_}}, dir_ / "xdotool.err"));
    std::string out;
    while (std::optional<std::string> line = tool.waitForLine("")) out += *line + "\n";
    EXPECT_EQ(tool.waitExit(), 0) << "xdotool " << argv[1] << ": " << slurp(dir_ / "xdotool.err");
    return out;
  }

  // The viewer's window id, once it is mapped.
  std::string findWindow() {
    const Clock::time_point deadline = Clock::now() + kTimeout;
    while (Clock::now() < deadline) {
      std::vector<std::string> argv{"xdotool", "search", "--onlyvisible", "--name",
                                    "^tessera view"};
      Process tool;
      if (!tool.start(argv, dir_, {{"DISPLAY", display_}}, dir_ / "xdotool.err")) break;
      std::optional<std::string> line = tool.waitForLine("");
      tool.waitExit();
      if (line && !line->empty()) return *line;
      ::usleep(100 * 1000);
    }
    return "";
  }

  // Starts the viewer on the cube in a width x height window with `args` and points at its window
  // (window_); the X server starts at the first call. False, with the reason in skip_reason_, when
  // no X server can start.
  bool openCube(const std::vector<std::string>& args, int width, int height) {
    if (xserver_ == nullptr && !startX(skip_reason_)) return false;
    std::vector<std::string> all{
        "-w", std::to_string(width), "-h", std::to_string(height), "-workers", "2"};
    all.insert(all.end(), args.begin(), args.end());
    startViewer(all);
    EXPECT_TRUE(viewer_->waitForLine("tessera view: showing cube"))
        << viewer_->output() << slurp(dir_ / "viewer.err");
    window_ = findWindow();
    EXPECT_FALSE(window_.empty()) << "no visible 'tessera view' window";
    // Keys go to the window under the pointer (there is no window manager to give focus).
    xdotool(
        {"mousemove", "--window", window_, std::to_string(width / 2), std::to_string(height / 2)});
    return !window_.empty();
  }

  // Escape quits with status 0.
  void quit() {
    xdotool({"key", "Escape"});
    EXPECT_EQ(viewer_->waitExit(), 0) << viewer_->output() << slurp(dir_ / "viewer.err");
  }

  // Presses F12 and decodes the screenshot the viewer reports.
  DecodedPng screenshot() {
    xdotool({"key", "F12"});
    DecodedPng png;
    std::optional<std::string> line = viewer_->waitForLine("saved ");
    EXPECT_TRUE(line.has_value()) << "no screenshot reported; output:\n"
                                  << viewer_->output() << slurp(dir_ / "viewer.err");
    if (!line) return png;
    const std::string path = line->substr(6);
    EXPECT_EQ(fs::path(path).parent_path(), dir_) << "not in the working folder: " << path;
    EXPECT_TRUE(tessera::test::decodePng(path, png)) << path;
    return png;
  }

  // One screenshot of `tessera view MODEL ARGS...` (a model in the working folder), the pointer
  // in the middle of the window, then Escape.
  DecodedPng shotOfModel(const std::string& model, const std::vector<std::string>& args) {
    std::vector<std::string> argv{model};
    argv.insert(argv.end(), args.begin(), args.end());
    startViewer(argv);
    EXPECT_TRUE(viewer_->waitForLine("tessera view: showing " + model))
        << viewer_->output() << slurp(dir_ / "viewer.err");
    const std::string window = findWindow();
    EXPECT_FALSE(window.empty());
    xdotool({"mousemove", "--window", window, "100", "100"});
    DecodedPng shot = screenshot();
    xdotool({"key", "Escape"});
    EXPECT_EQ(viewer_->waitExit(), 0);
    return shot;
  }

  fs::path dir_;
  std::string display_;
  std::unique_ptr<Process> xserver_;
  std::unique_ptr<Process> viewer_;
  std::string window_;       // the viewer's window id (openCube)
  std::string skip_reason_;  // why openCube could not start an X server
};

}  // namespace tessera::test
