// The GIF writer and its frame timing, checked by decoding its output with giflib's own reader.
#include <gif_lib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <tessera/io/frame_sink.h>
#include <tessera/io/image_writer.h>

#include "io_test_support.h"

namespace tessera::io {
namespace {

using namespace tessera::test;

// ---- GIF decoding with giflib's reader ----

struct GifCloser {
  void operator()(GifFileType* gif) const { DGifCloseFile(gif, nullptr); }
};
using DecodedGif = std::unique_ptr<GifFileType, GifCloser>;

DecodedGif decodeGif(const fs::path& path) {
  int error = 0;
  DecodedGif gif(DGifOpenFileName(path.c_str(), &error));
  if (!gif) return nullptr;
  if (DGifSlurp(gif.get()) != GIF_OK) return nullptr;
  return gif;
}

std::array<int, 3> gifPixel(const GifFileType* gif, int frame, int x, int y) {
  const SavedImage& image = gif->SavedImages[frame];
  const ColorMapObject* map =
      image.ImageDesc.ColorMap != nullptr ? image.ImageDesc.ColorMap : gif->SColorMap;
  const int index = image.RasterBits[static_cast<size_t>(y) * image.ImageDesc.Width + x];
  const GifColorType colour = map->Colors[index];
  return {colour.Red, colour.Green, colour.Blue};
}

int gifDelayCs(GifFileType* gif, int frame) {
  GraphicsControlBlock control{};
  if (DGifSavedExtensionToGCB(gif, frame, &control) != GIF_OK) return -1;
  return control.DelayTime;
}

// The NETSCAPE2.0 loop count, wherever giflib filed the extension (before the first image, or
// after the last).
std::optional<int> gifLoopCount(const GifFileType* gif) {
  auto search = [](const ExtensionBlock* blocks, int count) -> std::optional<int> {
    for (int i = 0; i + 1 < count; ++i) {
      const ExtensionBlock& application = blocks[i];
      const ExtensionBlock& data = blocks[i + 1];
      if (application.Function == APPLICATION_EXT_FUNC_CODE && application.ByteCount == 11 &&
          std::memcmp(application.Bytes, "NETSCAPE2.0", 11) == 0 &&
          data.Function == CONTINUE_EXT_FUNC_CODE && data.ByteCount == 3 && data.Bytes[0] == 1) {
        return data.Bytes[1] | (data.Bytes[2] << 8);
      }
    }
    return std::nullopt;
  };
  if (gif->ImageCount > 0) {
    const SavedImage& first = gif->SavedImages[0];
    if (auto count = search(first.ExtensionBlocks, first.ExtensionBlockCount)) return count;
  }
  return search(gif->ExtensionBlocks, gif->ExtensionBlockCount);
}

// A GIF sink at `path` that has taken `frames` (each of settings' size) and is not finished;
// null, with `error` saying why, where it could not be opened or did not take a frame.
std::unique_ptr<FrameSink> sinkWithFrames(const fs::path& path, const AnimationSettings& settings,
                                          const std::vector<std::vector<uint32_t>>& frames,
                                          std::string& error) {
  Expected<std::unique_ptr<FrameSink>> sink = openGifSink(path, settings);
  if (!sink) {
    error = sink.error().message;
    return nullptr;
  }
  for (const std::vector<uint32_t>& pixels : frames) {
    if (Expected<void> added = (*sink)->addFrame(pixels.data()); !added) {
      error = added.error().message;
      return nullptr;
    }
  }
  return std::move(*sink);
}

// sinkWithFrames of one solid 3x3 frame.
std::unique_ptr<FrameSink> sinkWithOneFrame(const fs::path& path, std::string& error) {
  return sinkWithFrames(path, settingsOf(3, 3), {solidFrame(3, 3, packRgba(1, 1, 1))}, error);
}

// The GIF of sinkWithFrames, finished and read back by giflib; null, with `error` saying why,
// where a step failed.
DecodedGif writeGif(const fs::path& path, const AnimationSettings& settings,
                    const std::vector<std::vector<uint32_t>>& frames, std::string& error) {
  const std::unique_ptr<FrameSink> sink = sinkWithFrames(path, settings, frames, error);
  if (!sink) return nullptr;
  if (Expected<void> finished = sink->finish(); !finished) {
    error = finished.error().message;
    return nullptr;
  }
  DecodedGif gif = decodeGif(path);
  if (!gif) error = "giflib cannot read " + path.string();
  return gif;
}

int maxChannelDifference(const std::array<int, 3>& a, const std::array<int, 3>& b) {
  return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
}

// ---- frame timing and naming ----

TEST(IoGifFrameDelay, ThirtyFpsRepeatsThreeThreeFour) {
  const std::array<int, 9> expected = {3, 3, 4, 3, 3, 4, 3, 3, 4};
  for (int i = 0; i < 9; ++i) EXPECT_EQ(gifFrameDelayCs(i, 30), expected[i]) << "frame " << i;
}

TEST(IoGifFrameDelay, DelaysAddUpToTheExactDuration) {
  for (int fps : {1, 7, 24, 25, 30, 60, 144, 1000}) {
    int total = 0;
    for (int i = 0; i < 3 * fps; ++i) total += gifFrameDelayCs(i, fps);
    EXPECT_EQ(total, 300) << fps << " fps over 3 seconds";
  }
}

TEST(IoFramePath, ReplacesFrameWithZeroPaddedIndex) {
  EXPECT_EQ(formatFramePath("out_{frame}.png", 7), fs::path("out_0007.png"));
  EXPECT_EQ(formatFramePath("dir/{frame}.png", 0), fs::path("dir/0000.png"));
  EXPECT_EQ(formatFramePath("f{frame}.png", 12345), fs::path("f12345.png"));
  EXPECT_EQ(formatFramePath("{frame}/{frame}.png", 42), fs::path("0042/0042.png"));
}

// ---- GIF sink ----

TEST(IoGifSink, DecodesWithFrameCountSizeAndDelays) {
  TempDir dir;
  const fs::path path = dir / "anim.gif";
  const int width = 7;
  const int height = 5;  // not square, so a swapped width and height shows
  const int frames = 7;
  std::vector<std::vector<uint32_t>> pixels;
  for (int i = 0; i < frames; ++i)
    pixels.push_back(solidFrame(width, height, packRgba(i * 30, 0, 0)));
  std::string error;
  DecodedGif gif = writeGif(path, settingsOf(width, height, 30), pixels, error);
  ASSERT_TRUE(gif) << error;
  EXPECT_EQ(gif->SWidth, width);
  EXPECT_EQ(gif->SHeight, height);
  ASSERT_EQ(gif->ImageCount, frames);
  const std::array<int, frames> expected_delays = {3, 3, 4, 3, 3, 4, 3};
  int total = 0;
  for (int i = 0; i < frames; ++i) {
    EXPECT_EQ(gif->SavedImages[i].ImageDesc.Width, width);
    EXPECT_EQ(gif->SavedImages[i].ImageDesc.Height, height);
    EXPECT_EQ(gifDelayCs(gif.get(), i), expected_delays[i]) << "frame " << i;
    total += gifDelayCs(gif.get(), i);
  }
  EXPECT_EQ(total, frames * 100 / 30);  // 7 frames at 30 fps: 0.23 s
}

TEST(IoGifSink, SolidFramesKeepTheirColours) {
  TempDir dir;
  const fs::path path = dir / "solid.gif";
  const std::array<uint32_t, 5> colours = {packRgba(255, 0, 0), packRgba(0, 255, 0),
                                           packRgba(0, 0, 255), packRgba(12, 200, 99),
                                           packRgba(128, 128, 128, 0)};
  std::vector<std::vector<uint32_t>> pixels;
  for (uint32_t colour : colours) pixels.push_back(solidFrame(6, 4, colour));
  std::string error;
  DecodedGif gif = writeGif(path, settingsOf(6, 4), pixels, error);
  ASSERT_TRUE(gif) << error;
  ASSERT_EQ(gif->ImageCount, static_cast<int>(colours.size()));
  constexpr int kTolerance = 2;
  for (size_t i = 0; i < colours.size(); ++i) {
    const std::array<int, 3> expected = {static_cast<int>(colours[i] & 255),
                                         static_cast<int>((colours[i] >> 8) & 255),
                                         static_cast<int>((colours[i] >> 16) & 255)};
    for (int y = 0; y < 4; ++y) {
      for (int x = 0; x < 6; ++x) {
        EXPECT_LE(maxChannelDifference(gifPixel(gif.get(), static_cast<int>(i), x, y), expected),
                  kTolerance)
            << "frame " << i << " pixel " << x << "," << y;
      }
    }
  }
}

// A frame of at most 256 colours keeps every pixel exactly (its own colours are the palette, no
// dithering); one colour more goes through the quantizer, which cannot keep them all.
TEST(IoGifSink, FrameOfAtMost256ColoursIsExact) {
  TempDir dir;
  const fs::path path = dir / "exact.gif";
  const int width = 17;
  const int height = 16;  // 272 pixels: 256 distinct colours, then 16 repeats
  auto colourOf = [](int i) {
    return packRgba((i * 37) & 255, (i * 11 + 5) & 255, (i >> 3) * 31 & 255);
  };
  std::vector<uint32_t> exact(static_cast<size_t>(width) * height);
  std::vector<uint32_t> over(exact.size());
  for (size_t i = 0; i < exact.size(); ++i) {
    exact[i] = colourOf(static_cast<int>(i % 256));
    over[i] = colourOf(static_cast<int>(i % 257));
  }
  ASSERT_EQ(std::set<uint32_t>(exact.begin(), exact.end()).size(), 256u);
  ASSERT_EQ(std::set<uint32_t>(over.begin(), over.end()).size(), 257u);
  std::string error;
  DecodedGif gif = writeGif(path, settingsOf(width, height), {exact, over}, error);
  ASSERT_TRUE(gif) << error;
  ASSERT_EQ(gif->ImageCount, 2);
  int inexact_over = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t i = static_cast<size_t>(y) * width + x;
      auto channels = [](uint32_t c) {
        return std::array<int, 3>{static_cast<int>(c & 255), static_cast<int>((c >> 8) & 255),
                                  static_cast<int>((c >> 16) & 255)};
      };
      EXPECT_EQ(maxChannelDifference(gifPixel(gif.get(), 0, x, y), channels(exact[i])), 0)
          << "pixel " << x << "," << y;
      if (maxChannelDifference(gifPixel(gif.get(), 1, x, y), channels(over[i])) != 0)
        ++inexact_over;
    }
  }
  EXPECT_GT(inexact_over, 0);  // 257 colours cannot all be in a 256-entry palette
}

TEST(IoGifSink, ManyColouredFrameKeepsLocalAverages) {
  TempDir dir;
  const fs::path path = dir / "gradient.gif";
  // 4096 distinct colours: more than a palette holds, so quantization and dithering both work.
  const int size = 64;
  std::vector<uint32_t> pixels(static_cast<size_t>(size) * size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) pixels[y * size + x] = packRgba(x * 4, y * 4, 255 - x * 2);
  }
  std::string error;
  DecodedGif gif = writeGif(path, settingsOf(size, size), {pixels}, error);
  ASSERT_TRUE(gif) << error;
  ASSERT_EQ(gif->ImageCount, 1);
  // Dithering trades per-pixel error for local averages: compare 8x8 block means.
  constexpr int kBlock = 8;
  constexpr double kMaxBlockMeanError = 3.0;
  for (int by = 0; by < size; by += kBlock) {
    for (int bx = 0; bx < size; bx += kBlock) {
      std::array<double, 3> input{};
      std::array<double, 3> output{};
      for (int y = by; y < by + kBlock; ++y) {
        for (int x = bx; x < bx + kBlock; ++x) {
          const uint32_t p = pixels[y * size + x];
          const std::array<int, 3> decoded = gifPixel(gif.get(), 0, x, y);
          for (int c = 0; c < 3; ++c) {
            input[c] += (p >> (8 * c)) & 255;
            output[c] += decoded[c];
          }
        }
      }
      for (int c = 0; c < 3; ++c) {
        EXPECT_LE(std::abs(input[c] - output[c]) / (kBlock * kBlock), kMaxBlockMeanError)
            << "block " << bx << "," << by << " channel " << c;
      }
    }
  }
}

TEST(IoGifSink, DithersAGradientThePaletteCannotCover) {
  TempDir dir;
  const fs::path path = dir / "dither.gif";
  // Noise fills most of the frame and so claims most of the palette; the grey ramp below it is
  // left with a few entries. Undithered, each ramp row is a staircase (it changes index about
  // as often as it has distinct indices); dithered, neighbouring pixels alternate between them.
  const int size = 256;
  const int ramp_top = 240;
  std::vector<uint32_t> pixels(static_cast<size_t>(size) * size);
  uint32_t state = 12345;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      uint32_t& p = pixels[static_cast<size_t>(y) * size + x];
      if (y < ramp_top) {
        state = state * 1664525u + 1013904223u;  // Numerical Recipes LCG
        p = (state >> 8) | 0xFF000000u;
      } else {
        p = packRgba(x, x, x);
      }
    }
  }
  std::string error;
  DecodedGif gif = writeGif(path, settingsOf(size, size), {pixels}, error);
  ASSERT_TRUE(gif) << error;
  ASSERT_EQ(gif->ImageCount, 1);
  const GifByteType* raster = gif->SavedImages[0].RasterBits;
  int index_changes = 0;
  int staircase_steps = 0;
  for (int y = ramp_top; y < size; ++y) {
    const GifByteType* row = raster + static_cast<size_t>(y) * size;
    std::vector<bool> seen(256, false);
    int distinct = 0;
    for (int x = 0; x < size; ++x) {
      if (!seen[row[x]]) ++distinct;
      seen[row[x]] = true;
      if (x > 0 && row[x] != row[x - 1]) ++index_changes;
    }
    staircase_steps += distinct - 1;
  }
  EXPECT_GT(index_changes, 2 * staircase_steps)
      << index_changes << " index changes in " << staircase_steps << " staircase steps";
}

TEST(IoGifSink, LoopingGifHasInfiniteLoopExtension) {
  TempDir dir;
  const fs::path path = dir / "loop.gif";
  const std::vector<uint32_t> pixels = solidFrame(2, 2, packRgba(5, 6, 7));
  std::string error;
  DecodedGif gif = writeGif(path, settingsOf(2, 2, 30, true), {pixels, pixels}, error);
  ASSERT_TRUE(gif) << error;
  std::optional<int> loop_count = gifLoopCount(gif.get());
  ASSERT_TRUE(loop_count.has_value());
  EXPECT_EQ(*loop_count, 0);  // 0 = forever
}

TEST(IoGifSink, NonLoopingGifHasNoLoopExtension) {
  TempDir dir;
  const fs::path path = dir / "once.gif";
  std::string error;
  DecodedGif gif =
      writeGif(path, settingsOf(2, 2, 30, false), {solidFrame(2, 2, packRgba(5, 6, 7))}, error);
  ASSERT_TRUE(gif) << error;
  EXPECT_EQ(gif->ImageCount, 1);
  EXPECT_FALSE(gifLoopCount(gif.get()).has_value());
}

TEST(IoGifSink, AppearsOnlyWhenFinished) {
  TempDir dir;
  const fs::path path = dir / "anim.gif";
  std::string error;
  std::unique_ptr<FrameSink> sink = sinkWithOneFrame(path, error);
  ASSERT_TRUE(sink) << error;
  EXPECT_FALSE(fs::exists(path));
  ASSERT_TRUE(sink->finish().ok());
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"anim.gif"});
}

TEST(IoGifSink, DestroyedWithoutFinishLeavesNoFile) {
  TempDir dir;
  {
    std::string error;
    const std::unique_ptr<FrameSink> sink = sinkWithOneFrame(dir / "anim.gif", error);
    ASSERT_TRUE(sink) << error;
    ASSERT_FALSE(dir.entries().empty());  // the temporary exists while the sink does
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(IoGifSink, UnfinishedSinkKeepsExistingTarget) {
  TempDir dir;
  const fs::path path = dir / "anim.gif";
  writeFile(path, "previous animation");
  {
    std::string error;
    const std::unique_ptr<FrameSink> sink = sinkWithOneFrame(path, error);
    ASSERT_TRUE(sink) << error;
  }
  EXPECT_EQ(readText(path), "previous animation");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"anim.gif"});
}

TEST(IoGifSink, FinishedSinkReplacesExistingTarget) {
  TempDir dir;
  const fs::path path = dir / "anim.gif";
  writeFile(path, "previous animation");
  std::string error;
  std::unique_ptr<FrameSink> sink = sinkWithOneFrame(path, error);
  ASSERT_TRUE(sink) << error;
  ASSERT_TRUE(sink->finish().ok());
  DecodedGif gif = decodeGif(path);
  ASSERT_TRUE(gif);
  EXPECT_EQ(gif->ImageCount, 1);
}

TEST(IoGifSink, FinishWithoutFramesIsAnErrorAndKeepsExistingTarget) {
  TempDir dir;
  const fs::path path = dir / "anim.gif";
  writeFile(path, "previous animation");
  {
    Expected<std::unique_ptr<FrameSink>> sink = openGifSink(path, settingsOf(3, 3));
    ASSERT_TRUE(sink.ok()) << sink.error().message;
    Expected<void> finished = (*sink)->finish();
    ASSERT_FALSE(finished.ok());
    EXPECT_NE(finished.error().message.find("no frames"), std::string::npos)
        << finished.error().message;
  }
  EXPECT_EQ(readText(path), "previous animation");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"anim.gif"});
}

TEST(IoGifSink, WriteFailureIsAnErrorAndLeavesNoFile) {
  TempDir dir;
  const fs::path path = dir / "noise.gif";
  const std::vector<uint32_t> pixels = noiseFrame(64, 64);
  Expected<std::unique_ptr<FrameSink>> sink = openGifSink(path, settingsOf(64, 64));
  ASSERT_TRUE(sink.ok()) << sink.error().message;
  std::string error;
  {
    FileSizeLimit limit(1024);
    // The failure may surface at a frame or, for bytes still buffered, at finish().
    for (int i = 0; i < 4 && error.empty(); ++i) {
      if (Expected<void> added = (*sink)->addFrame(pixels.data()); !added) {
        error = added.error().message;
      }
    }
    if (error.empty()) {
      if (Expected<void> finished = (*sink)->finish(); !finished) error = finished.error().message;
    }
  }
  EXPECT_EQ(error, "cannot write '" + path.string() + "': File too large");
  sink->reset();
  EXPECT_TRUE(dir.entries().empty());
}

TEST(IoGifSink, MissingFolderIsAnErrorAndLeavesNoFile) {
  TempDir dir;
  const fs::path path = dir / "missing" / "anim.gif";
  Expected<std::unique_ptr<FrameSink>> sink = openGifSink(path, settingsOf(3, 3));
  ASSERT_FALSE(sink.ok());
  EXPECT_EQ(sink.error().message,
            "cannot write '" + path.string() + "': No such file or directory");
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace tessera::io
