#include <tessera/io/frame_sink.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <string_view>
#include <utility>
#include <vector>

#include <tessera/io/atomic_file.h>

#include "writer_internal.h"

namespace tessera::io {
namespace {

constexpr std::string_view kFramePlaceholder = "{frame}";
constexpr int kMaxDimension = 16384;
constexpr int kMaxFps = 1000;

std::string lowerExtension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// Fails early, at open, when the folder is missing or read-only: creates and drops a temporary.
Expected<void> checkWritable(const std::filesystem::path& path) {
  Expected<AtomicFile> probe = AtomicFile::create(path);
  if (!probe) return probe.error();
  return {};
}

// Frames are encoded as they arrive but renamed into place only by finish(), so that a sink
// given up on (an error, an interrupted render) leaves none of its files behind.
class PngFilesSink : public FrameSink {
 public:
  PngFilesSink(std::string path_template, const AnimationSettings& settings, bool single_frame)
      : path_template_(std::move(path_template)),
        settings_(settings),
        single_frame_(single_frame) {}

  Expected<void> addFrame(const uint32_t* pixels) override {
    TESSERA_CHECK(!finished_) << "addFrame() after finish() for " << path_template_;
    if (single_frame_ && !files_.empty()) {
      return makeError("'" + path_template_ +
                       "' holds a single frame; for an animation use a .gif file or a PNG "
                       "sequence template such as out_{frame}.png");
    }
    const std::filesystem::path path =
        single_frame_ ? std::filesystem::path(path_template_)
                      : formatFramePath(path_template_, static_cast<int>(files_.size()));
    Expected<AtomicFile> file = AtomicFile::create(path);
    if (!file) return file.error();
    if (auto encoded = encodePngRgba8(*file, settings_.width, settings_.height, pixels, false);
        !encoded) {
      return encoded;
    }
    // Closed now: a long sequence must not hold a descriptor per frame.
    if (auto closed = file->close(); !closed) return closed;
    files_.push_back(std::move(*file));
    return {};
  }

  Expected<void> finish() override {
    TESSERA_CHECK(!finished_) << "finish() called twice for " << path_template_;
    if (files_.empty()) return makeError("no frames were rendered for '" + path_template_ + "'");
    // Renames within one folder fail only if the folder changes under us; should one fail, the
    // frames not yet renamed are removed with the sink.
    for (AtomicFile& file : files_) {
      if (auto committed = file.commit(); !committed) return committed;
    }
    files_.clear();
    finished_ = true;
    return {};
  }

 private:
  std::string path_template_;
  AnimationSettings settings_;
  bool single_frame_;
  bool finished_ = false;
  std::vector<AtomicFile> files_;  // closed temporaries, one per frame, awaiting finish()
};

Expected<std::unique_ptr<FrameSink>> openSinglePngSink(const std::string& path,
                                                       const AnimationSettings& settings) {
  if (auto valid = validateAnimationSettings(settings); !valid) return valid.error();
  if (auto writable = checkWritable(path); !writable) return writable.error();
  return std::unique_ptr<FrameSink>(new PngFilesSink(path, settings, true));
}

}  // namespace

Expected<void> validateAnimationSettings(const AnimationSettings& settings) {
  auto outside = [](const char* what, int value, int low, int high) {
    return makeError(std::string(what) + " must be between " + std::to_string(low) + " and " +
                     std::to_string(high) + ", not " + std::to_string(value));
  };
  if (settings.width < 1 || settings.width > kMaxDimension) {
    return outside("image width", settings.width, 1, kMaxDimension);
  }
  if (settings.height < 1 || settings.height > kMaxDimension) {
    return outside("image height", settings.height, 1, kMaxDimension);
  }
  if (settings.fps < 1 || settings.fps > kMaxFps) {
    return outside("frames per second", settings.fps, 1, kMaxFps);
  }
  return {};
}

int gifFrameDelayCs(int frame_index, int fps) {
  TESSERA_CHECK(frame_index >= 0 && fps > 0) << "frame " << frame_index << " at " << fps << " fps";
  // Each frame ends at its exact time rounded down to a centisecond, so rounding never
  // accumulates: the first n delays add up to floor(n * 100 / fps).
  const int64_t index = frame_index;
  return static_cast<int>((index + 1) * 100 / fps - index * 100 / fps);
}

std::filesystem::path formatFramePath(const std::string& path_template, int index) {
  TESSERA_CHECK(index >= 0) << "frame index " << index;
  char digits[16];
  std::snprintf(digits, sizeof(digits), "%04d", index);
  std::string path = path_template;
  for (size_t at = path.find(kFramePlaceholder); at != std::string::npos;
       at = path.find(kFramePlaceholder, at)) {
    path.replace(at, kFramePlaceholder.size(), digits);
  }
  return path;
}

Expected<std::unique_ptr<FrameSink>> openPngSequenceSink(const std::string& path_template,
                                                         const AnimationSettings& settings) {
  if (auto valid = validateAnimationSettings(settings); !valid) return valid.error();
  if (path_template.find(kFramePlaceholder) == std::string::npos) {
    return makeError("PNG sequence path '" + path_template +
                     "' has no {frame} for the frame number, as in out_{frame}.png");
  }
  if (auto writable = checkWritable(formatFramePath(path_template, 0)); !writable) {
    return writable.error();
  }
  return std::unique_ptr<FrameSink>(new PngFilesSink(path_template, settings, false));
}

Expected<std::unique_ptr<FrameSink>> openFrameSink(const std::string& path,
                                                   const AnimationSettings& settings) {
  const std::string extension = lowerExtension(path);
  if (path.find(kFramePlaceholder) != std::string::npos) {
    if (extension == ".png") return openPngSequenceSink(path, settings);
    return makeError("cannot write '" + path +
                     "': a {frame} template makes a PNG sequence and must end in .png");
  }
  if (extension == ".gif") return openGifSink(path, settings);
  if (extension == ".mp4") return openMp4Sink(path, settings);
  if (extension == ".png") return openSinglePngSink(path, settings);
  return makeError("cannot write '" + path +
                   "': the output must be a .gif or .mp4 file, a .png file (one frame) or a PNG "
                   "sequence template such as out_{frame}.png");
}

}  // namespace tessera::io
