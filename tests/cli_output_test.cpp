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

}  // namespace
