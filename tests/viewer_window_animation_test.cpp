// The space bar and the start camera in the real `tessera view` window under Xvfb: an animated
// glTF written here moves while it plays and holds still while paused, a model without one says
// so, --camera-index starts from the file's camera (and Enter returns to it); and the index flags'
// checks, which fail before any window opens. Each picture is a screenshot the viewer saved on
// F12.
#include <gtest/gtest.h>

#include <unistd.h>

#include <string>
#include <vector>

#include "animated_cube_file.h"
#include "viewer_window.h"

namespace {

using namespace tessera::test;

constexpr int kWidth = 320, kHeight = 240;

class ViewerAnimation : public ViewerWindow {
 protected:
  // Starts the viewer on the animated cube (written into the test's folder) with `args`.
  bool openAnimatedCube(const std::vector<std::string>& args, bool camera = false,
                        int width = kWidth) {
    AnimatedCubeFile file;
    file.camera = camera;
    file.write(dir_);
    if (xserver_ == nullptr && !startX(skip_reason_)) return false;
    std::vector<std::string> all{
        "-w", std::to_string(width), "-h", std::to_string(kHeight), "-workers", "2", "cube.gltf"};
    all.insert(all.end(), args.begin(), args.end());
    startViewer(all);
    EXPECT_TRUE(viewer_->waitForLine("tessera view: showing cube.gltf"))
        << viewer_->output() << slurp(dir_ / "viewer.err");
    window_ = findWindow();
    EXPECT_FALSE(window_.empty()) << "no visible 'tessera view' window";
    xdotool(
        {"mousemove", "--window", window_, std::to_string(width / 2), std::to_string(kHeight / 2)});
    return !window_.empty() && !HasFailure();
  }

  // Presses space and returns the line the viewer printed about it.
  std::string space(const std::string& expected_prefix) {
    xdotool({"key", "space"});
    std::optional<std::string> line = viewer_->waitForLine(expected_prefix);
    EXPECT_TRUE(line) << "no '" << expected_prefix << "'; output:\n" << viewer_->output();
    return line.value_or("");
  }
};

TEST_F(ViewerAnimation, SpacePlaysTheClipAndPausedFramesStayTheSame) {
  if (!openAnimatedCube({})) GTEST_SKIP() << skip_reason_;
  const DecodedPng start = screenshot();
  ASSERT_EQ(start.width, kWidth);
  const DecodedPng start_again = screenshot();
  EXPECT_EQ(countDifferent(start, start_again, 0, 0, kWidth, kHeight), 0);  // not playing yet

  space("tessera view: animation playing from 0.000 s");
  ::usleep(600 * 1000);
  const std::string paused_prefix = "tessera view: animation paused at ";
  const std::string paused = space(paused_prefix);
  ASSERT_FALSE(paused.empty());
  // The clip ran by the wall clock: somewhere past 0.3 s of its 2 s (a slow machine draws few
  // frames, but each one poses the time it is drawn at).
  const std::string when = paused.substr(paused_prefix.size());  // "0.612 s"
  const double t = std::stod(when);
  EXPECT_GT(t, 0.3) << paused;
  EXPECT_LT(t, 2.0) << paused;
  const DecodedPng held = screenshot();
  ::usleep(400 * 1000);
  const DecodedPng held_later = screenshot();
  ASSERT_EQ(held.width, kWidth);
  ASSERT_EQ(held_later.width, kWidth);
  // The cube moved (0.3 s moves it 0.6 of its size and turns it 27 degrees)...
  EXPECT_GT(countDifferent(start, held, 0, 0, kWidth, kHeight), 500);
  // ...and paused, it holds its pose exactly.
  EXPECT_EQ(countDifferent(held, held_later, 0, 0, kWidth, kHeight), 0);

  // Playing again goes on from there, and moves the picture again.
  space("tessera view: animation playing from " + when);
  ::usleep(300 * 1000);
  space("tessera view: animation paused at ");
  const DecodedPng moved_on = screenshot();
  EXPECT_GT(countDifferent(held, moved_on, 0, 0, kWidth, kHeight), 100);
  quit();
}

TEST_F(ViewerAnimation, SpaceWithoutAnAnimationSaysSoAndKeepsRunning) {
  if (!openCube({}, kWidth, kHeight)) GTEST_SKIP() << skip_reason_;
  const DecodedPng before = screenshot();
  space("tessera view: no animation to play in cube");
  const DecodedPng after = screenshot();
  ASSERT_EQ(after.width, kWidth);
  // The notice is drawn in the window's bottom-left corner; the cube above it has not moved.
  EXPECT_GT(countDifferent(before, after, 0, kHeight - 40, kWidth, kHeight), 0);
  EXPECT_EQ(countDifferent(before, after, 0, 0, kWidth, kHeight - 60), 0);
  quit();
}

TEST_F(ViewerAnimation, CameraIndexStartsFromTheFilesCameraAndEnterReturnsToIt) {
  if (!openAnimatedCube({}, /*camera=*/true)) GTEST_SKIP() << skip_reason_;
  const DecodedPng framed = screenshot();
  quit();
  ASSERT_TRUE(openAnimatedCube({"--camera-index", "0"}, /*camera=*/true));
  const DecodedPng from_camera = screenshot();
  ASSERT_EQ(framed.width, kWidth);
  ASSERT_EQ(from_camera.width, kWidth);
  EXPECT_GT(countDifferent(framed, from_camera, 0, 0, kWidth, kHeight), 500);
  // The file's camera looks straight at the cube's front face (z = 0.5) from (0, 0, 6): a square
  // in the middle of the window, 1 / (2 * 5.5 * tan(0.15)) = 0.60 of its height.
  const Rgb background = pixel(from_camera, 2, 2);
  const Coverage seen = coverage(from_camera, background);
  EXPECT_NEAR(seen.centre_x, kWidth / 2, 4.0);
  EXPECT_NEAR(seen.centre_y, kHeight / 2, 4.0);
  const double side = 0.6015 * kHeight;
  EXPECT_NEAR(seen.share, side * side / (kWidth * kHeight), 0.03);
  // A drag turns the view away from it; Enter comes back to the very same picture.
  xdotool({"mousemove", "--window", window_, "160", "120", "mousedown", "1", "mousemove",
           "--window", window_, "200", "130", "mousemove", "--window", window_, "220", "140",
           "mouseup", "1"});
  const DecodedPng turned = screenshot();
  EXPECT_GT(countDifferent(from_camera, turned, 0, 0, kWidth, kHeight), 500);
  xdotool({"key", "Return"});
  const DecodedPng back = screenshot();
  EXPECT_EQ(countDifferent(from_camera, back, 0, 0, kWidth, kHeight), 0);
  quit();
}

TEST_F(ViewerAnimation, TheStatsOverlayShowsTheClipItsTimeAndWhetherItPlays) {
  // Wide enough for the clip's line on one line.
  constexpr int kWide = 480;
  if (!openAnimatedCube({"-stats"}, false, kWide)) GTEST_SKIP() << skip_reason_;
  const DecodedPng start = screenshot();
  ASSERT_EQ(start.width, kWide);
  // Lines: fps, render time, size and backend, projection, sampling, then the clip's; counted
  // left of the cube (from x = 160), whose lit top is as bright as text.
  const std::vector<std::pair<int, int>> lines = textLines(start, 0, 0, 150, 140);
  ASSERT_EQ(lines.size(), 6u);
  space("tessera view: animation playing from 0.000 s");
  ::usleep(400 * 1000);
  space("tessera view: animation paused at ");
  const DecodedPng paused = screenshot();
  ASSERT_EQ(paused.width, kWide);
  // The clip's line changed (its time; paused, not playing) where the projection's did not.
  EXPECT_FALSE(sameText(start, paused, lines[5]));
  EXPECT_TRUE(sameText(start, paused, lines[3]));
  quit();
}

TEST_F(ViewerAnimation, CameraOrthographicStartsOrthographicAndEnterReturnsToIt) {
  if (!openAnimatedCube({})) GTEST_SKIP() << skip_reason_;
  const DecodedPng perspective = screenshot();
  quit();
  ASSERT_TRUE(openAnimatedCube({"--camera-orthographic"}));
  const DecodedPng orthographic = screenshot();
  ASSERT_EQ(perspective.width, kWidth);
  ASSERT_EQ(orthographic.width, kWidth);
  // The same three-quarter view of the same bounds, drawn without perspective: another picture
  // of about the same size.
  EXPECT_GT(countDifferent(perspective, orthographic, 0, 0, kWidth, kHeight), 200);
  const Rgb background = pixel(perspective, 2, 2);
  const double share = coverage(perspective, background).share;
  EXPECT_NEAR(coverage(orthographic, background).share, share, share * 0.35);
  xdotool({"mousemove", "--window", window_, "160", "120", "mousedown", "1", "mousemove",
           "--window", window_, "190", "150", "mouseup", "1"});
  xdotool({"click", "4"});  // wheel: zoom in
  const DecodedPng moved = screenshot();
  EXPECT_GT(countDifferent(orthographic, moved, 0, 0, kWidth, kHeight), 200);
  xdotool({"key", "Return"});
  const DecodedPng back = screenshot();
  EXPECT_EQ(countDifferent(orthographic, back, 0, 0, kWidth, kHeight), 0);
  quit();
}

// The index flags are checked against the model before the window opens: no display needed.
TEST_F(ViewerAnimation, AnIndexPastTheEndFailsBeforeAnyWindowAsRenderDoes) {
  AnimatedCubeFile().write(dir_);
  struct Case {
    std::vector<std::string> args;
    int status;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"cube.gltf", "--animation-index", "5"},
       1,
       "cube.gltf has 1 animation (--animation-index 0 to 0); --animation-index 5 is past the end"},
      {{"cube.gltf", "--camera-index", "0"},
       1,
       "cube.gltf: --camera-index 0: the model has 0 cameras"},
      {{"--animation-index", "0"}, 2, "--animation-index picks an animation of a MODEL"},
      {{"cube.gltf", "--camera-orthographic", "--projection", "fisheye"},
       2,
       "--camera-orthographic and --projection fisheye do not go together"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> argv{TESSERA_EXE, "view"};
    argv.insert(argv.end(), c.args.begin(), c.args.end());
    Process view;
    // No display at all: these must fail before SDL is asked for a window.
    ASSERT_TRUE(
        view.start(argv, dir_, {{"DISPLAY", ""}, {"WAYLAND_DISPLAY", ""}}, dir_ / "view.err"));
    EXPECT_EQ(view.waitExit(), c.status) << c.args[0];
    const std::string err = slurp(dir_ / "view.err");
    EXPECT_NE(err.find(c.message), std::string::npos) << err;
  }
}

}  // namespace
