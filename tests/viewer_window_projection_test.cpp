// F4 and `view --projection` in the real `tessera view` window under Xvfb: the key cycles
// perspective, cylindrical, spherical, stereographic and fisheye and comes back to the first
// picture, the stats overlay names the mode, and a start mode draws what F4 reaches. Each picture
// is a screenshot the viewer saved on F12.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "viewer_window.h"

namespace {

using namespace tessera::test;

constexpr int kWidth = 320, kHeight = 240;

// The smallest rectangle holding every pixel that is not background.
struct Box {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
  int width() const { return x1 - x0 + 1; }
  int height() const { return y1 - y0 + 1; }
};

Box modelBox(const DecodedPng& png, Rgb background) {
  Box box;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x)
      if (!near(pixel(png, x, y), background, 8)) {
        box.x0 = std::min(box.x0, x), box.x1 = std::max(box.x1, x);
        box.y0 = std::min(box.y0, y), box.y1 = std::max(box.y1, y);
      }
  return box;
}

class ViewerProjection : public ViewerWindow {
 protected:
  bool open(const std::vector<std::string>& args) { return openCube(args, kWidth, kHeight); }

  DecodedPng afterF4() {
    xdotool({"key", "F4"});
    DecodedPng png = screenshot();
    EXPECT_EQ(png.width, kWidth);
    EXPECT_EQ(png.height, kHeight);
    return png;
  }
};

TEST_F(ViewerProjection, F4CyclesTheModesBackToTheFirstPictureAndAStartModeDrawsTheSame) {
  if (!open({})) GTEST_SKIP() << skip_reason_;
  const DecodedPng perspective = screenshot();
  ASSERT_EQ(perspective.width, kWidth);
  const Rgb background = pixel(perspective, 2, 2);
  const DecodedPng cylindrical = afterF4();
  const DecodedPng spherical = afterF4();
  const DecodedPng stereographic = afterF4();
  const DecodedPng fisheye = afterF4();
  const DecodedPng again = afterF4();
  if (HasFailure()) return;
  // Every mode draws another picture than the one before it...
  const std::vector<const DecodedPng*> cycle{&perspective, &cylindrical, &spherical, &stereographic,
                                             &fisheye};
  for (size_t i = 1; i < cycle.size(); ++i)
    EXPECT_GT(countDifferent(*cycle[i - 1], *cycle[i], 0, 0, kWidth, kHeight), 500) << i;
  // ...and the fifth press is perspective again, exactly.
  EXPECT_EQ(countDifferent(perspective, again, 0, 0, kWidth, kHeight), 0);

  // The spherical picture is the 360 x 180 degree panorama of a 4:3 window at 180 degrees, 76
  // pixels a radian against perspective's 257 at 50 degrees: the same cube in the middle, about
  // 0.3 as high and wide (less off the axis, where perspective stretches) and a tenth the area.
  const Coverage flat = coverage(perspective, background);
  const Coverage round = coverage(spherical, background);
  const Box flat_box = modelBox(perspective, background);
  const Box round_box = modelBox(spherical, background);
  ASSERT_GT(flat.share, 0.15);
  EXPECT_GT(round.share, flat.share * 0.04);
  EXPECT_LT(round.share, flat.share * 0.16);
  EXPECT_GT(round_box.height(), flat_box.height() * 0.2);
  EXPECT_LT(round_box.height(), flat_box.height() * 0.4);
  EXPECT_GT(round_box.width(), flat_box.width() * 0.2);
  EXPECT_LT(round_box.width(), flat_box.width() * 0.4);
  EXPECT_NEAR(round.centre_x, kWidth / 2, 10.0);
  EXPECT_NEAR(round.centre_y, kHeight / 2, 10.0);
  quit();

  // `view --projection fisheye` (and the single-dash form) starts where four presses of F4 led.
  for (const char* flag : {"--projection", "-projection"}) {
    ASSERT_TRUE(open({flag, "fisheye"}));
    const DecodedPng started = screenshot();
    ASSERT_EQ(started.width, kWidth);
    EXPECT_EQ(countDifferent(fisheye, started, 0, 0, kWidth, kHeight), 0) << flag;
    quit();
  }
}

TEST_F(ViewerProjection, TheStatsOverlayNamesTheProjection) {
  if (!open({"-stats"})) GTEST_SKIP() << skip_reason_;
  const DecodedPng perspective = screenshot();
  const DecodedPng perspective_again = screenshot();
  xdotool({"key", "F4", "F4"});
  const DecodedPng spherical = screenshot();
  ASSERT_EQ(spherical.width, kWidth);
  // Lines: fps, render time, size and backend, projection ("perspective 50°"), sampling. The
  // projection's line is the same in two perspective frames and another in spherical, where the
  // line above and the start of the one below ("MSAA 4x, TAA") stay. Compared left of the cube
  // (which starts 65 pixels in), where the box is over the background in every picture.
  constexpr int kLeftOfTheCube = 56;
  const std::vector<std::pair<int, int>> lines = textLines(perspective, 0, 0, kWidth, 120);
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_TRUE(sameText(perspective, perspective_again, lines[3]));
  EXPECT_FALSE(sameText(perspective, spherical, lines[3], kLeftOfTheCube));
  EXPECT_TRUE(sameText(perspective, spherical, lines[2], kLeftOfTheCube));
  EXPECT_TRUE(sameText(perspective, spherical, lines[4], kLeftOfTheCube));
  quit();
}

}  // namespace
