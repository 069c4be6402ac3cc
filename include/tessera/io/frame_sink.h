// Destinations for a sequence of frames: an animated GIF, a PNG sequence, or a single PNG.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include <tessera/base/expected.h>

namespace tessera::io {

class FrameSink {
 public:
  virtual ~FrameSink() = default;  // a sink destroyed before finish() leaves no output file
  // RGBA8 pixels, R in the low byte, row 0 at the top, width*height of them.
  virtual Expected<void> addFrame(const uint32_t* pixels) = 0;
  // Completes the output: every file appears whole, or none does.
  virtual Expected<void> finish() = 0;
};

struct AnimationSettings {
  int width = 0;
  int height = 0;
  int fps = 30;
  bool loop = true;
};

// GIF frame delays in centiseconds that add up to the exact duration: frame i lasts
// floor((i+1)*100/fps) - floor(i*100/fps) (at 30 fps: 3, 3, 4, 3, 3, 4, ...).
int gifFrameDelayCs(int frame_index, int fps);

// The path of frame `index` for a template containing "{frame}" (replaced by the index, zero
// padded to 4 digits).
std::filesystem::path formatFramePath(const std::string& path_template, int index);

// An animated GIF (giflib, one libimagequant palette per frame with dithering).
Expected<std::unique_ptr<FrameSink>> openGifSink(const std::filesystem::path& path,
                                                 const AnimationSettings& settings);
// A PNG per frame, named by formatFramePath. Each frame is encoded when added; the files are
// renamed into place together by finish().
Expected<std::unique_ptr<FrameSink>> openPngSequenceSink(const std::string& path_template,
                                                         const AnimationSettings& settings);
// An MP4 (H.264) made by the `ffmpeg` program, found on PATH, with the frames piped to it; an
// error naming the missing program when there is none, and for an odd width or height
// (mp4SizeProblem: the file is never silently a pixel larger than asked). Ignores SIGPIPE for the
// process, so that an ffmpeg that dies shows up as a write error.
Expected<std::unique_ptr<FrameSink>> openMp4Sink(const std::filesystem::path& path,
                                                 const AnimationSettings& settings);
// "" when an MP4 can be made at width x height; else why not (yuv420p halves both sides for
// colour, so both must be even) with the nearest even sizes to use instead.
std::string mp4SizeProblem(int width, int height);
// Picks by the path: a "{frame}" template ending in .png -> PNG sequence, ".gif" -> GIF, ".mp4"
// -> MP4 through ffmpeg, ".png" -> a single PNG (a second frame is an error). Extensions are
// case-insensitive. Anything else is an error naming the supported forms. Every opener validates
// the settings (1..16384 pixels a side, 1..1000 fps) and checks that the output folder can be
// written.
Expected<std::unique_ptr<FrameSink>> openFrameSink(const std::string& path,
                                                   const AnimationSettings& settings);

}  // namespace tessera::io
