// MP4 output: frames piped as raw RGBA into the `ffmpeg` program (H.264, yuv420p), which writes
// a temporary file beside the target; the target appears only when ffmpeg succeeded.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <tessera/io/atomic_file.h>
#include <tessera/io/frame_sink.h>

#include "writer_internal.h"

extern char** environ;

namespace tessera::io {
namespace {

// The first executable `name` on PATH, or an empty path.
std::filesystem::path findOnPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return {};
  std::stringstream folders(path);
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    if (folder.empty()) continue;
    std::filesystem::path candidate = std::filesystem::path(folder) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

class Mp4Sink : public FrameSink {
 public:
  Mp4Sink(std::filesystem::path target, const AnimationSettings& settings)
      : target_(std::move(target)), settings_(settings) {}

  ~Mp4Sink() override {
    if (pid_ > 0) {
      // Given up on: stop ffmpeg and remove what it wrote.
      if (pipe_ >= 0) ::close(pipe_);
      ::kill(pid_, SIGTERM);
      int status = 0;
      ::waitpid(pid_, &status, 0);
    }
    if (!finished_ && !temporary_.empty()) {
      std::error_code ignored;
      std::filesystem::remove(temporary_, ignored);
    }
  }

  Expected<void> start(const std::filesystem::path& ffmpeg) {
    // Fails early, naming the path, when the folder is missing or read-only.
    if (Expected<AtomicFile> probe = AtomicFile::create(target_); !probe) return probe.error();
    // ffmpeg writes a temporary in the target's folder, so the final rename is atomic.
    static int counter = 0;
    const std::filesystem::path folder =
        target_.has_parent_path() ? target_.parent_path() : std::filesystem::path(".");
    std::string name = ".";  // built piecewise: GCC 12 misreports "." + string (-Wrestrict)
    name += target_.filename().string();
    name += ".tmp-";
    name += std::to_string(::getpid());
    name += '-';
    name += std::to_string(++counter);
    temporary_ = folder / name;

    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) return makeError("cannot create a pipe for ffmpeg");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
    const std::string size =
        std::to_string(settings_.width) + "x" + std::to_string(settings_.height);
    const std::string rate = std::to_string(settings_.fps);
    // yuv420p needs even sizes: openMp4Sink refuses odd ones (mp4SizeProblem), so the file is
    // the size asked for, never a pixel larger.
    // One option and its value a line.
    // clang-format off
    std::vector<std::string> args = {
        "ffmpeg", "-nostdin", "-y",
        "-loglevel", "error",
        "-f", "rawvideo",
        "-pix_fmt", "rgba",
        "-s", size,
        "-r", rate,
        "-i", "-",
        "-c:v", "libx264",
        "-pix_fmt", "yuv420p",
        "-movflags", "+faststart",
        "-f", "mp4",
        temporary_.string()};
    // clang-format on
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int spawned =
        ::posix_spawn(&pid_, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(fds[0]);
    if (spawned != 0) {
      ::close(fds[1]);
      pid_ = -1;
      return makeError("cannot start " + ffmpeg.string() + ": " + std::strerror(spawned));
    }
    pipe_ = fds[1];
    return {};
  }

  Expected<void> addFrame(const uint32_t* pixels) override {
    const char* bytes = reinterpret_cast<const char*>(pixels);
    size_t left = static_cast<size_t>(settings_.width) * settings_.height * 4;
    while (left > 0) {
      const ssize_t n = ::write(pipe_, bytes, left);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return finishFailed("ffmpeg stopped reading frames");
      bytes += n;
      left -= static_cast<size_t>(n);
    }
    return {};
  }

  Expected<void> finish() override {
    ::close(pipe_);
    pipe_ = -1;
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
      return makeError("ffmpeg failed to write '" + target_.string() + "' (exit status " +
                       std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
    std::error_code error;
    std::filesystem::rename(temporary_, target_, error);
    if (error) return makeError("cannot write '" + target_.string() + "': " + error.message());
    finished_ = true;
    return {};
  }

 private:
  Expected<void> finishFailed(const std::string& why) {
    return makeError("cannot write '" + target_.string() + "': " + why);
  }

  std::filesystem::path target_;
  std::filesystem::path temporary_;
  AnimationSettings settings_;
  pid_t pid_ = -1;
  int pipe_ = -1;
  bool finished_ = false;
};

}  // namespace

std::string mp4SizeProblem(int width, int height) {
  if (width % 2 == 0 && height % 2 == 0) return "";
  auto size = [](int w, int h) { return std::to_string(w) + "x" + std::to_string(h); };
  // 1 pixel has no smaller even size: suggest the larger one alone.
  const bool can_shrink = width > 1 && height > 1;
  return "an MP4 (H.264, yuv420p) needs an even width and height, not " + size(width, height) +
         ": use " +
         (can_shrink ? size(width - width % 2, height - height % 2) + " or " : std::string()) +
         size(width + width % 2, height + height % 2) +
         " (the nearest even sizes), or write a .gif or a {frame} PNG sequence";
}

Expected<std::unique_ptr<FrameSink>> openMp4Sink(const std::filesystem::path& path,
                                                 const AnimationSettings& settings) {
  if (auto valid = validateAnimationSettings(settings); !valid) return valid.error();
  if (std::string odd = mp4SizeProblem(settings.width, settings.height); !odd.empty())
    return makeError("cannot write '" + path.string() + "': " + odd);
  const std::filesystem::path ffmpeg = findOnPath("ffmpeg");
  if (ffmpeg.empty())
    return makeError("cannot write '" + path.string() +
                     "': MP4 output needs the ffmpeg program (Debian package ffmpeg), and none "
                     "is on PATH; write a .gif or a {frame} PNG sequence instead");
  // A dead ffmpeg must turn into an error from write(), not kill this process.
  ::signal(SIGPIPE, SIG_IGN);
  auto sink = std::make_unique<Mp4Sink>(path, settings);
  if (auto started = sink->start(ffmpeg); !started) return started.error();
  return std::unique_ptr<FrameSink>(std::move(sink));
}

}  // namespace tessera::io
