// The image writers and the frame sinks other than GIF's (io_gif_test.cpp): the atomic file, PNG
// (checked by decoding with libpng), the AOV encodings, PNG sequences, MP4 through ffmpeg, and
// the choice of sink by path.
#include <png.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
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

#include "decode.h"
#include "io_test_support.h"

namespace tessera::io {
namespace {

using namespace tessera::test;

// ---- PNG and GIF decoding with libpng and giflib (decode.h) ----

using test::DecodedGif;
using test::DecodedPng;
using test::decodeGif;
using test::decodePng;

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
  writeFile(target, "old");
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
  writeFile(target / "keep.txt", "kept");
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

// ---- PNG writer ----

TEST(IoPngWriter, RgbRoundTripIsExactAndDropsAlpha) {
  TempDir dir;
  const int width = 3;
  const int height = 2;
  const std::vector<uint32_t> pixels = {packRgba(255, 0, 0, 10),   packRgba(0, 255, 0, 0),
                                        packRgba(0, 0, 255),       packRgba(1, 2, 3, 128),
                                        packRgba(250, 128, 7, 77), packRgba(0, 0, 0)};
  const fs::path path = dir / "rgb.png";
  ASSERT_TRUE(writePngRgba8(path, width, height, pixels.data()).ok());

  std::optional<DecodedPng> png = decodePng(path);
  ASSERT_TRUE(png.has_value());
  EXPECT_EQ(png->width, width);
  EXPECT_EQ(png->height, height);
  EXPECT_EQ(png->bit_depth, 8);
  EXPECT_EQ(png->color_type, PNG_COLOR_TYPE_RGB);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const uint32_t p = pixels[static_cast<size_t>(y) * width + x];
      const std::array<int, 3> expected = {static_cast<int>(p & 255),
                                           static_cast<int>((p >> 8) & 255),
                                           static_cast<int>((p >> 16) & 255)};
      EXPECT_EQ(png->rgb(x, y), expected) << "pixel " << x << "," << y;
    }
  }
}

TEST(IoPngWriter, RgbaRoundTripKeepsAlpha) {
  TempDir dir;
  const std::vector<uint32_t> pixels = {packRgba(10, 20, 30, 0), packRgba(40, 50, 60, 128),
                                        packRgba(70, 80, 90, 255), packRgba(255, 254, 253, 1)};
  const fs::path path = dir / "rgba.png";
  ASSERT_TRUE(writePngRgba8(path, 2, 2, pixels.data(), /*keep_alpha=*/true).ok());

  std::optional<DecodedPng> png = decodePng(path);
  ASSERT_TRUE(png.has_value());
  EXPECT_EQ(png->color_type, PNG_COLOR_TYPE_RGB_ALPHA);
  EXPECT_EQ(png->bit_depth, 8);
  EXPECT_EQ(png->rgba(0, 0), (std::array<int, 4>{10, 20, 30, 0}));
  EXPECT_EQ(png->rgba(1, 0), (std::array<int, 4>{40, 50, 60, 128}));
  EXPECT_EQ(png->rgba(0, 1), (std::array<int, 4>{70, 80, 90, 255}));
  EXPECT_EQ(png->rgba(1, 1), (std::array<int, 4>{255, 254, 253, 1}));
}

TEST(IoPngWriter, Gray16RoundTripIsExact) {
  TempDir dir;
  // Values whose two bytes differ, so a byte-order mistake shows.
  const std::vector<uint16_t> pixels = {0, 1, 255, 256, 0x1234, 0xABCD, 65534, 65535};
  const fs::path path = dir / "gray.png";
  ASSERT_TRUE(writePngGray16(path, 4, 2, pixels.data()).ok());

  std::optional<DecodedPng> png = decodePng(path);
  ASSERT_TRUE(png.has_value());
  EXPECT_EQ(png->color_type, PNG_COLOR_TYPE_GRAY);
  EXPECT_EQ(png->bit_depth, 16);
  EXPECT_EQ(png->width, 4);
  EXPECT_EQ(png->height, 2);
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(png->gray16(i % 4, i / 4), pixels[i]) << "pixel " << i;
  }
}

TEST(IoPngWriter, MissingFolderIsAnErrorAndLeavesNoFile) {
  TempDir dir;
  const fs::path path = dir / "missing" / "x.png";
  const std::vector<uint32_t> pixels(4, packRgba(1, 2, 3));
  Expected<void> written = writePngRgba8(path, 2, 2, pixels.data());
  ASSERT_FALSE(written.ok());
  EXPECT_NE(written.error().message.find(path.string()), std::string::npos);
  EXPECT_NE(written.error().message.find("No such file or directory"), std::string::npos);
  EXPECT_TRUE(dir.entries().empty());
}

TEST(IoPngWriter, ExistingTargetIsReplaced) {
  TempDir dir;
  const fs::path path = dir / "out.png";
  writeFile(path, "not a png");
  const std::vector<uint32_t> pixels(1, packRgba(9, 8, 7));
  ASSERT_TRUE(writePngRgba8(path, 1, 1, pixels.data()).ok());
  std::optional<DecodedPng> png = decodePng(path);
  ASSERT_TRUE(png.has_value());
  EXPECT_EQ(png->rgb(0, 0), (std::array<int, 3>{9, 8, 7}));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.png"});
}

TEST(IoPngWriter, WriteFailureIsAnErrorAndKeepsExistingTarget) {
  TempDir dir;
  const fs::path path = dir / "noise.png";
  writeFile(path, "old");
  const std::vector<uint32_t> pixels = noiseFrame(64, 64);  // ~12 KB that do not compress
  Expected<void> written = [&] {
    FileSizeLimit limit(1024);
    return writePngRgba8(path, 64, 64, pixels.data());
  }();
  ASSERT_FALSE(written.ok());
  EXPECT_EQ(written.error().message, "cannot write '" + path.string() + "': File too large");
  EXPECT_EQ(readText(path), "old");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"noise.png"});
}

// ---- AOV encodings ----

Frame aovFrame(int width, int height, bool with_normals) {
  Frame frame;
  frame.width = width;
  frame.height = height;
  const size_t count = frame.pixelCount();
  frame.color.assign(count, 0);
  frame.depth.assign(count, std::numeric_limits<float>::infinity());
  frame.triangle_id.assign(count, kNoTriangle);
  if (with_normals) frame.normal.assign(count, float3(0.0f));
  return frame;
}

TEST(IoAovPng, IdSplitsIntoRgbBytesLowFirst) {
  TempDir dir;
  Frame frame = aovFrame(5, 1, false);
  frame.triangle_id = {kNoTriangle, 1, 70000, 0x00FFFFFF, 0x00010203};
  const fs::path path = dir / "id.png";
  ASSERT_TRUE(writeIdPng(path, frame).ok());

  std::optional<DecodedPng> png = decodePng(path);
  ASSERT_TRUE(png.has_value());
  EXPECT_EQ(png->color_type, PNG_COLOR_TYPE_RGB);
  EXPECT_EQ(png->bit_depth, 8);
  EXPECT_EQ(png->rgb(0, 0), (std::array<int, 3>{0, 0, 0}));
  EXPECT_EQ(png->rgb(1, 0), (std::array<int, 3>{1, 0, 0}));
  EXPECT_EQ(png->rgb(2, 0), (std::array<int, 3>{112, 17, 1}));  // 70000 = 112 + 17*256 + 65536
  EXPECT_EQ(png->rgb(3, 0), (std::array<int, 3>{255, 255, 255}));
  EXPECT_EQ(png->rgb(4, 0), (std::array<int, 3>{3, 2, 1}));
}

TEST(IoAovPng, IdAboveTwentyFourBitsIsAnError) {
  TempDir dir;
  Frame frame = aovFrame(2, 1, false);
  frame.triangle_id = {1, 0x01000000};
  Expected<void> written = writeIdPng(dir / "id.png", frame);
  ASSERT_FALSE(written.ok());
  EXPECT_NE(written.error().message.find("16777216"), std::string::npos) << written.error().message;
  EXPECT_TRUE(dir.entries().empty());
}

TEST(IoAovPng, DepthMapsUnitRangeToSixteenBits) {
  TempDir dir;
  Frame frame = aovFrame(8, 1, false);
  const float inf = std::numeric_limits<float>::infinity();
  frame.depth = {0.0f, 1.0f, 0.5f, 0.25f, inf, -0.5f, 1.5f, 1.0f / 65535.0f};
  const fs::path path = dir / "depth.png";
  ASSERT_TRUE(writeDepthPng(path, frame).ok());

  std::optional<DecodedPng> png = decodePng(path);
  ASSERT_TRUE(png.has_value());
  EXPECT_EQ(png->color_type, PNG_COLOR_TYPE_GRAY);
  EXPECT_EQ(png->bit_depth, 16);
  const std::array<int, 8> expected = {0, 65535, 32768, 16384, 65535, 0, 65535, 1};
  for (int x = 0; x < 8; ++x) {
    EXPECT_EQ(png->gray16(x, 0), expected[x]) << "depth " << frame.depth[x];
  }
}

TEST(IoAovPng, NormalMapsToHalfOffsetRgbAndBlackWhereNothingWasDrawn) {
  TempDir dir;
  Frame frame = aovFrame(4, 1, true);
  frame.triangle_id = {1, 2, 3, kNoTriangle};
  frame.normal = {float3(1.0f, 0.0f, 0.0f), float3(0.0f, -1.0f, 0.0f), float3(0.28f, 0.96f, 0.0f),
                  float3(0.0f, 0.0f, 1.0f)};
  const fs::path path = dir / "normal.png";
  ASSERT_TRUE(writeNormalPng(path, frame).ok());

  std::optional<DecodedPng> png = decodePng(path);
  ASSERT_TRUE(png.has_value());
  EXPECT_EQ(png->color_type, PNG_COLOR_TYPE_RGB);
  EXPECT_EQ(png->rgb(0, 0), (std::array<int, 3>{255, 128, 128}));
  EXPECT_EQ(png->rgb(1, 0), (std::array<int, 3>{128, 0, 128}));
  EXPECT_EQ(png->rgb(2, 0), (std::array<int, 3>{163, 250, 128}));  // 163.2, 249.9, 127.5
  EXPECT_EQ(png->rgb(3, 0), (std::array<int, 3>{0, 0, 0}));
}

TEST(IoAovPng, NormalWithoutRenderedNormalsIsAnError) {
  TempDir dir;
  Frame frame = aovFrame(2, 2, false);
  Expected<void> written = writeNormalPng(dir / "normal.png", frame);
  ASSERT_FALSE(written.ok());
  EXPECT_NE(written.error().message.find("normals were not rendered"), std::string::npos)
      << written.error().message;
  EXPECT_TRUE(dir.entries().empty());
}
// ---- PNG sequence and single PNG sinks ----

TEST(IoPngSequenceSink, WritesEachFrameToItsNumberedPathOnFinish) {
  TempDir dir;
  const std::string path_template = (dir / "out_{frame}.png").string();
  Expected<std::unique_ptr<FrameSink>> sink = openPngSequenceSink(path_template, settingsOf(2, 1));
  ASSERT_TRUE(sink.ok()) << sink.error().message;
  const std::array<uint32_t, 3> colours = {packRgba(10, 0, 0), packRgba(0, 20, 0),
                                           packRgba(0, 0, 30)};
  for (uint32_t colour : colours) {
    const std::vector<uint32_t> pixels = solidFrame(2, 1, colour);
    ASSERT_TRUE((*sink)->addFrame(pixels.data()).ok());
  }
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(fs::exists(formatFramePath(path_template, i)));
  ASSERT_TRUE((*sink)->finish().ok());

  EXPECT_EQ(dir.entries(),
            (std::vector<std::string>{"out_0000.png", "out_0001.png", "out_0002.png"}));
  for (int i = 0; i < 3; ++i) {
    std::optional<DecodedPng> png = decodePng(formatFramePath(path_template, i));
    ASSERT_TRUE(png.has_value()) << "frame " << i;
    EXPECT_EQ(png->rgb(1, 0), (std::array<int, 3>{static_cast<int>(colours[i] & 255),
                                                  static_cast<int>((colours[i] >> 8) & 255),
                                                  static_cast<int>((colours[i] >> 16) & 255)}));
  }
}

TEST(IoPngSequenceSink, DestroyedWithoutFinishLeavesNoFiles) {
  TempDir dir;
  {
    Expected<std::unique_ptr<FrameSink>> sink =
        openPngSequenceSink((dir / "out_{frame}.png").string(), settingsOf(2, 2));
    ASSERT_TRUE(sink.ok()) << sink.error().message;
    const std::vector<uint32_t> pixels = solidFrame(2, 2, packRgba(1, 2, 3));
    ASSERT_TRUE((*sink)->addFrame(pixels.data()).ok());
    ASSERT_TRUE((*sink)->addFrame(pixels.data()).ok());
    ASSERT_EQ(dir.entries().size(), 2u);  // the two temporaries
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(IoPngSequenceSink, TemplateWithoutFrameIsAnError) {
  TempDir dir;
  Expected<std::unique_ptr<FrameSink>> sink =
      openPngSequenceSink((dir / "out.png").string(), settingsOf(2, 2));
  ASSERT_FALSE(sink.ok());
  EXPECT_NE(sink.error().message.find("{frame}"), std::string::npos) << sink.error().message;
  EXPECT_TRUE(dir.entries().empty());
}

TEST(IoSinglePngSink, WritesOneFrameAndRejectsASecond) {
  TempDir dir;
  const fs::path path = dir / "still.png";
  Expected<std::unique_ptr<FrameSink>> sink = openFrameSink(path.string(), settingsOf(2, 2));
  ASSERT_TRUE(sink.ok()) << sink.error().message;
  const std::vector<uint32_t> pixels = solidFrame(2, 2, packRgba(40, 50, 60));
  ASSERT_TRUE((*sink)->addFrame(pixels.data()).ok());
  Expected<void> second = (*sink)->addFrame(pixels.data());
  ASSERT_FALSE(second.ok());
  EXPECT_NE(second.error().message.find(".gif"), std::string::npos) << second.error().message;
  ASSERT_TRUE((*sink)->finish().ok());

  std::optional<DecodedPng> png = decodePng(path);
  ASSERT_TRUE(png.has_value());
  EXPECT_EQ(png->rgb(0, 0), (std::array<int, 3>{40, 50, 60}));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"still.png"});
}

// ---- choosing and validating ----

TEST(IoFrameSink, PicksTheSinkByPath) {
  TempDir dir;
  const std::vector<uint32_t> pixels = solidFrame(2, 2, packRgba(200, 100, 50));
  for (const std::string name : {"a.gif", "b.GIF", "c_{frame}.png", "d.png"}) {
    Expected<std::unique_ptr<FrameSink>> sink =
        openFrameSink((dir / name).string(), settingsOf(2, 2));
    ASSERT_TRUE(sink.ok()) << name << ": " << sink.error().message;
    ASSERT_TRUE((*sink)->addFrame(pixels.data()).ok()) << name;
    ASSERT_TRUE((*sink)->finish().ok()) << name;
  }
  DecodedGif gif;
  EXPECT_TRUE(decodeGif((dir / "a.gif").string(), gif));
  EXPECT_TRUE(decodeGif((dir / "b.GIF").string(), gif));
  EXPECT_TRUE(decodePng(dir / "c_0000.png").has_value());
  EXPECT_TRUE(decodePng(dir / "d.png").has_value());
  EXPECT_FALSE(decodeGif((dir / "d.png").string(), gif));  // a PNG, not a GIF named .png
}

TEST(IoFrameSink, UnsupportedPathIsAnErrorNamingTheSupportedForms) {
  TempDir dir;
  for (const std::string name : {"movie.avi", "noextension", "frames_{frame}.gif"}) {
    Expected<std::unique_ptr<FrameSink>> sink =
        openFrameSink((dir / name).string(), settingsOf(2, 2));
    ASSERT_FALSE(sink.ok()) << name;
    EXPECT_NE(sink.error().message.find(".png"), std::string::npos) << sink.error().message;
    EXPECT_NE(sink.error().message.find(name), std::string::npos) << sink.error().message;
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(IoFrameSink, OutOfRangeSettingsAreErrors) {
  TempDir dir;
  const std::array<AnimationSettings, 6> bad = {settingsOf(0, 10),     settingsOf(10, -1),
                                                settingsOf(16385, 10), settingsOf(10, 16385),
                                                settingsOf(10, 10, 0), settingsOf(10, 10, 1001)};
  for (const AnimationSettings& settings : bad) {
    for (const std::string name : {"a.gif", "b_{frame}.png", "c.png"}) {
      Expected<std::unique_ptr<FrameSink>> sink = openFrameSink((dir / name).string(), settings);
      ASSERT_FALSE(sink.ok()) << name << " " << settings.width << "x" << settings.height << "@"
                              << settings.fps;
      EXPECT_NE(sink.error().message.find("must be between"), std::string::npos)
          << sink.error().message;
    }
  }
  EXPECT_TRUE(dir.entries().empty());
  // The limits themselves are accepted.
  Expected<std::unique_ptr<FrameSink>> edge =
      openFrameSink((dir / "edge.gif").string(), settingsOf(16384, 1, 1000));
  EXPECT_TRUE(edge.ok()) << edge.error().message;
}

}  // namespace
}  // namespace tessera::io

namespace {

// Runs a shell command and returns what it printed on stdout.
std::string captureOutput(const std::string& command) {
  std::string out;
  if (FILE* pipe = ::popen(command.c_str(), "r")) {
    char buffer[256];
    while (size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
    ::pclose(pipe);
  }
  return out;
}

}  // namespace

TEST(IoMp4Sink, FfmpegWritesTheFramesAndTheFileAppearsOnFinish) {
  if (captureOutput("command -v ffmpeg ffprobe").empty())
    GTEST_SKIP() << "ffmpeg/ffprobe are not installed (scripts/setup.sh installs them)";
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("tessera_mp4_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / "clip.mp4";
  tessera::io::AnimationSettings settings{34, 24, 10, true};
  auto sink = tessera::io::openFrameSink(path.string(), settings);
  ASSERT_TRUE(sink.ok()) << sink.error().message;
  std::vector<uint32_t> pixels(34 * 24);
  for (int frame = 0; frame < 7; ++frame) {
    std::fill(pixels.begin(), pixels.end(), 0xff000000u | (frame * 30u));
    ASSERT_TRUE((*sink)->addFrame(pixels.data()).ok());
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  auto finished = (*sink)->finish();
  ASSERT_TRUE(finished.ok()) << finished.error().message;
  ASSERT_TRUE(std::filesystem::exists(path));
  const std::string probe = captureOutput(
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=width,height,nb_read_frames,codec_name -of csv=p=0 '" +
      path.string() + "'");
  EXPECT_EQ(probe, "h264,34,24,7\n");
  // Nothing but the MP4 is left in the folder.
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) files += entry.exists();
  EXPECT_EQ(files, 1);
  std::filesystem::remove_all(dir);
}

// yuv420p needs even sides: an odd size is refused up front (ffmpeg or not), never padded to a
// file a pixel larger than asked.
TEST(IoMp4Sink, OddSizesAreRefusedWithTheNearestEvenOnes) {
  EXPECT_EQ(tessera::io::mp4SizeProblem(34, 24), "");
  EXPECT_NE(tessera::io::mp4SizeProblem(33, 24).find("32x24 or 34x24"), std::string::npos);
  EXPECT_NE(tessera::io::mp4SizeProblem(1, 1).find("use 2x2 ("), std::string::npos);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("tessera_mp4_odd_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  auto sink = tessera::io::openFrameSink((dir / "odd.mp4").string(), {33, 24, 10, true});
  ASSERT_FALSE(sink.ok());
  EXPECT_NE(sink.error().message.find("odd.mp4"), std::string::npos) << sink.error().message;
  EXPECT_NE(sink.error().message.find("even"), std::string::npos) << sink.error().message;
  EXPECT_TRUE(std::filesystem::is_empty(dir));
  std::filesystem::remove_all(dir);
}

TEST(IoMp4Sink, MissingFfmpegIsAClearErrorAndLeavesNothing) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("tessera_noffmpeg_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string saved = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::setenv("PATH", dir.c_str(), 1);  // a folder with no ffmpeg in it
  auto sink = tessera::io::openFrameSink((dir / "x.mp4").string(), {16, 16, 30, true});
  ::setenv("PATH", saved.c_str(), 1);
  ASSERT_FALSE(sink.ok());
  EXPECT_NE(sink.error().message.find("ffmpeg"), std::string::npos) << sink.error().message;
  EXPECT_TRUE(std::filesystem::is_empty(dir));
  std::filesystem::remove_all(dir);
}

TEST(IoMp4Sink, AbandonedSinkLeavesNoFile) {
  if (captureOutput("command -v ffmpeg").empty())
    GTEST_SKIP() << "ffmpeg is not installed (scripts/setup.sh installs it)";
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("tessera_mp4_abandon_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    auto sink = tessera::io::openFrameSink((dir / "x.mp4").string(), {16, 16, 30, true});
    ASSERT_TRUE(sink.ok());
    std::vector<uint32_t> pixels(16 * 16, 0xff808080u);
    ASSERT_TRUE((*sink)->addFrame(pixels.data()).ok());
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir));
  std::filesystem::remove_all(dir);
}
