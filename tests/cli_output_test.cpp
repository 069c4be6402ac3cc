// End-to-end tests of what `tessera render` and `cube` say while they work and what they refuse
// to write: progress on a captured stderr, --quiet, --duration and MP4 sizes.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <regex>
#include <set>
#include <string>

#include "decode.h"
#include "run_process.h"
#include "temp_folder.h"

namespace fs = std::filesystem;
using tessera::test::RunResult;

namespace {

class CliOutput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = tessera::test::makeTestFolder("tessera_cli_output");
    tessera::test::writeFile(dir_ / "quad.obj",
                             "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs tessera in the test's folder; stderr goes to a file, so it is never a terminal.
  RunResult run(const std::string& args) {
    return tessera::test::runInFolder(dir_, TESSERA_EXE, args);
  }

  std::set<std::string> filesInDir() const {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.insert(e.path().filename().string());
    return names;
  }

  fs::path dir_;
};

// "render: frame 6/6, 85.3 frames/s, 0s left, done in 0s": frames done of the total, a rate
// and a time left.
const std::regex kFinalLine(
    R"((render|cube): frame (\d+)/(\d+), [0-9.]+ frames/s, \d+(h|m|s)[0-9ms]* left, done in )");

TEST_F(CliOutput, ProgressGoesToACapturedStderrWithRateAndTimeLeft) {
  RunResult r = run("render quad.obj --resolution 24,24 --turntable 6 -o turn_{frame}.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.err, m, kFinalLine)) << r.err;
  EXPECT_EQ(m[2].str(), "6");
  EXPECT_EQ(m[3].str(), "6");
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << "a terminal's in-place line in a log";
  EXPECT_NE(r.out.find("wrote turn_{frame}.png"), std::string::npos) << r.out;

  r = run("cube -w 16 -h 16 -fps 5 -dur 1s -out c.gif");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(std::regex_search(r.err, m, kFinalLine)) << r.err;
  EXPECT_EQ(m[1].str(), "cube");
  EXPECT_EQ(m[3].str(), "5");
}

TEST_F(CliOutput, QuietSilencesProgressAndTheSummaryButNotErrors) {
  RunResult r = run("render quad.obj --resolution 24,24 --turntable 6 -o turn_{frame}.png --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(fs::exists(dir_ / "turn_0005.png"));
  // --quiet wins over --progress, as in f3d.
  r = run("cube -w 16 -h 16 -fps 5 -dur 1s -out c.gif --quiet --progress");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  r = run("render missing.obj --quiet");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("missing.obj"), std::string::npos) << r.err;
}

TEST_F(CliOutput, OneFrameShowsProgressOnlyWhenAsked) {
  RunResult r = run("render quad.obj --resolution 24,24 -o one.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("frames/s"), std::string::npos) << r.err;
  r = run("render quad.obj --resolution 24,24 -o one.png --progress");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.err, m, kFinalLine)) << r.err;
  EXPECT_EQ(m[3].str(), "1");
}

// --duration SECONDS beside --turntable N: frames = round(duration x fps).
TEST_F(CliOutput, DurationSetsTheTurntablesFrames) {
  RunResult r = run("render quad.obj --resolution 16,16 --duration 0.5 --fps 8 -o d_{frame}.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "d_0003.png"));
  EXPECT_FALSE(fs::exists(dir_ / "d_0004.png"));
  // 0.55 s at 10 fps is 5.5 frames: rounded to 6 (half away from zero).
  r = run("render quad.obj --resolution 16,16 --duration=550ms --fps 10 -o e_{frame}.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "e_0005.png"));
  EXPECT_FALSE(fs::exists(dir_ / "e_0006.png"));
  // Both, agreeing: fine.
  r =
      run("render quad.obj --resolution 16,16 --duration 1s --turntable 10 --fps 10 "
          "-o f_{frame}.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "f_0009.png"));
}

TEST_F(CliOutput, DurationThatDisagreesOrGivesNoFrameIsAUsageError) {
  const std::set<std::string> before = filesInDir();
  RunResult r =
      run("render quad.obj --resolution 16,16 --duration 1 --turntable 12 --fps 10 -o g.gif");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--duration 1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("10 frames"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--turntable 12"), std::string::npos) << r.err;
  r = run("render quad.obj --duration 0.01 --fps 10 -o g.gif");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no frame"), std::string::npos) << r.err;
  r = run("render quad.obj --duration -2 -o g.gif");
  EXPECT_EQ(r.exit_code, 2);
  r = run("render quad.obj --duration 2 -o g.png");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(".gif"), std::string::npos) << r.err;
  EXPECT_EQ(filesInDir(), before);
}

// yuv420p needs even sides: an odd size is refused with the nearest even ones, before anything
// is written (ffmpeg is not needed to see it), never padded silently.
TEST_F(CliOutput, Mp4AtAnOddSizeIsRefusedWithTheNearestEvenSizes) {
  const std::set<std::string> before = filesInDir();
  RunResult r = run("render quad.obj --resolution 33x24 --turntable 2 -o odd.mp4");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("even"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("32x24 or 34x24"), std::string::npos) << r.err;
  r = run("render quad.obj --resolution 32x25 --turntable 2 -o odd.mp4");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("32x24 or 32x26"), std::string::npos) << r.err;
  r = run("cube -w 33 -h 33 -fps 2 -dur 1 -out odd.mp4");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("32x32 or 34x34"), std::string::npos) << r.err;
  EXPECT_EQ(filesInDir(), before);
  // A GIF or PNG sequence at the same odd size is fine: only the MP4 encoder needs even sides.
  r = run("render quad.obj --resolution 33x24 --turntable 2 -o odd.gif");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(CliOutput, Mp4AtAnEvenSizeIsExactlyThatSize) {
  if (std::system("command -v ffprobe > /dev/null") != 0)
    GTEST_SKIP() << "ffmpeg is not installed (scripts/setup.sh installs it)";
  RunResult r = run("render quad.obj --resolution 34x24 --turntable 2 -o even.mp4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string probe = "ffprobe -v error -show_entries stream=width,height -of csv=p=0 '" +
                            (dir_ / "even.mp4").string() + "' > '" + (dir_ / "probe.txt").string() +
                            "'";
  ASSERT_EQ(std::system(probe.c_str()), 0);
  EXPECT_EQ(tessera::test::slurp(dir_ / "probe.txt"), "34,24\n");
}

}  // namespace
