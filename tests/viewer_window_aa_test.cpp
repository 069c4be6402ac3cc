// The anti-aliasing keys in the real `tessera view` window under Xvfb: Shift+F3 (MSAA), F10
// (jitter), Shift+F12 (temporal reprojection), H (the key list), and -msaa. Each picture is a
// screenshot the viewer saved on F12.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include <tessera/viewer/input_state.h>

#include "viewer_window.h"

namespace {

using namespace tessera::test;

// The pixels that differ between `a` and `b`, and how many of them are away from an edge of `a`
// (a pixel whose 3x3 neighbourhood is all one colour in `a`).
struct Differences {
  int pixels = 0;
  int away_from_edges = 0;
};

Differences differencesOnEdges(const DecodedPng& a, const DecodedPng& b) {
  Differences d;
  for (int y = 1; y + 1 < a.height; ++y)
    for (int x = 1; x + 1 < a.width; ++x) {
      if (near(pixel(a, x, y), pixel(b, x, y), 0)) continue;
      ++d.pixels;
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) edge |= !near(pixel(a, x + dx, y + dy), pixel(a, x, y), 2);
      if (!edge) ++d.away_from_edges;
    }
  return d;
}

size_t distinctColours(const DecodedPng& png) {
  std::set<int> colours;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) {
      const Rgb p = pixel(png, x, y);
      colours.insert(p.r << 16 | p.g << 8 | p.b);
    }
  return colours.size();
}

class ViewerAntiAliasing : public ViewerWindow {
 protected:
  // Screenshots until two in a row are the same: the image has stopped changing.
  DecodedPng steadyScreenshot() {
    DecodedPng last = screenshot();
    for (int i = 0; i < 40; ++i) {
      DecodedPng next = screenshot();
      if (next.width == last.width &&
          countDifferent(last, next, 0, 0, last.width, last.height) == 0)
        return next;
      last = std::move(next);
    }
    ADD_FAILURE() << "the image kept changing";
    return last;
  }
};

TEST_F(ViewerAntiAliasing, ShiftF3CyclesMsaaOnTheEdgesAndThroughTheOverlay) {
  if (!openCube({"-msaa", "1"}, 320, 240)) GTEST_SKIP() << skip_reason_;
  // -msaa 1: the flat-shaded cube in its face colours and the background, nothing between.
  const DecodedPng one = screenshot();
  ASSERT_EQ(one.width, 320);
  EXPECT_LT(distinctColours(one), 12u);
  // 1 -> 2 -> 4 -> 8: the edges take the colours between, and only the edges change.
  for (int i = 0; i < 3; ++i) xdotool({"key", "shift+F3"});
  const DecodedPng eight = screenshot();
  ASSERT_EQ(eight.width, 320);
  EXPECT_GT(distinctColours(eight), distinctColours(one) + 20);
  const Differences d = differencesOnEdges(one, eight);
  EXPECT_GT(d.pixels, 100);
  EXPECT_EQ(d.away_from_edges, 0);
  // ...and 8 -> 1 is the first picture again, exactly.
  xdotool({"key", "shift+F3"});
  const DecodedPng again = screenshot();
  ASSERT_EQ(again.width, 320);
  EXPECT_EQ(countDifferent(one, again, 0, 0, 320, 240), 0);

  // The stats overlay's last line names the mode: the same twice at 1x, another at 2x.
  xdotool({"key", "F1"});
  const DecodedPng stats = screenshot();
  const DecodedPng stats_again = screenshot();
  xdotool({"key", "shift+F3"});
  const DecodedPng stats_two = screenshot();
  ASSERT_EQ(stats_two.width, 320);
  const std::vector<std::pair<int, int>> lines = textLines(stats, 0, 0, 320, 120);
  ASSERT_GE(lines.size(), 4u);
  EXPECT_TRUE(sameText(stats, stats_again, lines.back()));
  EXPECT_FALSE(sameText(stats, stats_two, lines.back()));
  quit();
}

TEST_F(ViewerAntiAliasing, HListsEveryKeyAndHidesAgain) {
  if (!openCube({}, 480, 400)) GTEST_SKIP() << skip_reason_;
  const DecodedPng plain = screenshot();
  xdotool({"key", "h"});
  const DecodedPng listed = screenshot();
  ASSERT_EQ(listed.width, 480);
  // A line for each entry of the key list, the mode line below them, in a box in the middle.
  const std::vector<std::pair<int, int>> lines = textLines(listed, 0, 0, 480, 400);
  EXPECT_EQ(lines.size(), tessera::viewer::keyList().size() + 1);
  EXPECT_GT(countDifferent(plain, listed, 40, 40, 440, 360), 400 * 320 / 2);
  xdotool({"key", "h"});
  const DecodedPng hidden = screenshot();
  ASSERT_EQ(hidden.width, 480);
  EXPECT_EQ(countDifferent(plain, hidden, 0, 0, 480, 400), 0);
  quit();
}

TEST_F(ViewerAntiAliasing, JitterWithTemporalReprojectionSmoothsAStillImageOnTheEdgesOnly) {
  if (!openCube({"-msaa", "1"}, 240, 180)) GTEST_SKIP() << skip_reason_;
  const DecodedPng plain = screenshot();
  ASSERT_EQ(plain.width, 240);
  // F10 (temporal reprojection is on by default): the still camera converges to the average of
  // the jitter cycle, which differs from the plain image where the edges are.
  xdotool({"key", "F10"});
  const DecodedPng converged = steadyScreenshot();
  ASSERT_EQ(converged.width, 240);
  const Differences d = differencesOnEdges(plain, converged);
  EXPECT_GT(d.pixels, 50);
  EXPECT_EQ(d.away_from_edges, 0);
  EXPECT_GT(distinctColours(converged), distinctColours(plain) + 20);
  // Shift+F12 and F10 turn both off: the plain image again, exactly.
  xdotool({"key", "shift+F12", "F10"});
  const DecodedPng off = screenshot();
  ASSERT_EQ(off.width, 240);
  EXPECT_EQ(countDifferent(plain, off, 0, 0, 240, 180), 0);
  quit();
}

}  // namespace
