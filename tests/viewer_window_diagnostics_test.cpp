// The diagnostic keys in the real `tessera view` window under Xvfb: Shift+F1 (tile heatmap), F11
// (analysis view: tile field, density) and Shift+F2 (the vulkan backend's 32-bit commit path).
// Each picture is a screenshot the viewer saved on F12.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "viewer_window.h"

namespace {

using namespace tessera::test;

constexpr Rgb kBackground{51, 51, 51};
constexpr Rgb kRampBottom{0, 0, 4};     // inferno(0): nothing in the tile or pixel
constexpr Rgb kRampTop{252, 255, 164};  // inferno(1): the top of the legend
constexpr int kTile = 64;               // the CPU renderer's tiles
// The bottom rows hold the legend and the overlay's lines: left out of the checks.
constexpr int kBottomRows = 90;

// Whether (x, y) and its 8 neighbours are all `inside` (the cube) or all background in `plain`.
bool uniformAround(const DecodedPng& plain, int x, int y, bool inside) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if (near(pixel(plain, x + dx, y + dy), kBackground, 8) == inside) return false;
  return true;
}

// Whether any pixel of the tile shows the cube in `plain`.
bool tileShowsCube(const DecodedPng& plain, int tx, int ty) {
  for (int y = ty * kTile; y < std::min(plain.height, (ty + 1) * kTile); ++y)
    for (int x = tx * kTile; x < std::min(plain.width, (tx + 1) * kTile); ++x)
      if (!near(pixel(plain, x, y), kBackground, 8)) return true;
  return false;
}

}  // namespace

TEST_F(ViewerWindow, ShiftF1ShowsTheTileHeatmapWhereTheCubeIsAndAgainTheFrame) {
  const int w = 512, h = 384;  // 8 x 6 tiles
  if (!openCube({}, w, h)) GTEST_SKIP() << skip_reason_;
  const DecodedPng plain = screenshot();
  xdotool({"key", "shift+F1"});
  const DecodedPng heat = screenshot();
  ASSERT_EQ(heat.width, w);
  int cube_tiles = 0, empty_tiles = 0;
  for (int ty = 0; ty * kTile < h - kBottomRows; ++ty)
    for (int tx = 0; tx * kTile < w; ++tx) {
      // The centre of the tile: the whole tile has the tile's colour.
      const int cx = tx * kTile + kTile / 2, cy = ty * kTile + kTile / 2;
      const Rgb c = pixel(heat, cx, cy);
      EXPECT_TRUE(near(pixel(heat, tx * kTile + 1, ty * kTile + 1), c, 0)) << tx << "," << ty;
      if (tileShowsCube(plain, tx, ty)) {
        ++cube_tiles;
        // Triangles were binned there: a colour of the ramp above black.
        EXPECT_FALSE(near(c, kRampBottom, 0)) << "tile " << tx << "," << ty;
      } else if (tx == 0 || ty == 0 || tx == w / kTile - 1) {
        ++empty_tiles;  // the border tiles, far from the cube, have no triangle
        EXPECT_TRUE(near(c, kRampBottom, 0)) << "tile " << tx << "," << ty << ": " << c.r;
      }
    }
  EXPECT_GE(cube_tiles, 4);
  EXPECT_GE(empty_tiles, 10);
  // The legend strip: black, with the ramp's top colour at its right end, on the bottom rows.
  EXPECT_TRUE(near(pixel(heat, w / 2, h - 1), {0, 0, 0}, 0));
  EXPECT_GT(countDifferent(plain, heat, 0, 0, w, h), w * h / 2);
  // Again: the frame as before, to the byte.
  xdotool({"key", "shift+F1"});
  const DecodedPng back = screenshot();
  EXPECT_EQ(countDifferent(plain, back, 0, 0, w, h), 0);
  // Shift+F2 on the cpu backend says it does not apply.
  xdotool({"key", "shift+F2"});
  std::optional<std::string> line = viewer_->waitForLine("tessera view: 32-bit commit path");
  ASSERT_TRUE(line) << viewer_->output();
  EXPECT_NE(line->find("does not apply to the cpu backend"), std::string::npos) << *line;
  quit();
}

TEST_F(ViewerWindow, F11CyclesTheTileFieldTheDensityAndOff) {
  const int w = 512, h = 384;
  if (!openCube({}, w, h)) GTEST_SKIP() << skip_reason_;
  const DecodedPng plain = screenshot();
  xdotool({"key", "F11"});
  const DecodedPng field = screenshot();
  xdotool({"key", "F11"});
  const DecodedPng density = screenshot();
  xdotool({"key", "F11"});
  const DecodedPng back = screenshot();
  ASSERT_EQ(density.width, w);
  const int area = w * (h - kBottomRows);
  EXPECT_GT(countDifferent(plain, field, 0, 0, w, h - kBottomRows), area / 2);
  EXPECT_GT(countDifferent(field, density, 0, 0, w, h - kBottomRows), area / 20);
  EXPECT_EQ(countDifferent(plain, back, 0, 0, w, h), 0);
  // Tile field: a tile without the cube is uncovered (black); one inside it fully covered (top).
  EXPECT_TRUE(near(pixel(field, kTile / 2, kTile / 2), kRampBottom, 0));
  int full_tiles = 0;
  for (int ty = 0; (ty + 1) * kTile <= h - kBottomRows; ++ty)
    for (int tx = 0; (tx + 1) * kTile <= w; ++tx) {
      bool all_cube = true;
      for (int y = ty * kTile; y < (ty + 1) * kTile && all_cube; y += 4)
        for (int x = tx * kTile; x < (tx + 1) * kTile && all_cube; x += 4)
          all_cube = !near(pixel(plain, x, y), kBackground, 8);
      if (!all_cube) continue;
      ++full_tiles;
      EXPECT_TRUE(near(pixel(field, tx * kTile + 32, ty * kTile + 32), kRampTop, 0));
    }
  EXPECT_GE(full_tiles, 1);
  // Density: the cube's material has the default density 1, the frame's largest: the ramp's
  // top on the cube, black around it.
  int on_cube = 0, off_cube = 0;
  for (int y = 1; y < h - kBottomRows; y += 3)
    for (int x = 1; x + 1 < w; x += 3) {
      if (uniformAround(plain, x, y, true)) {
        ++on_cube;
        EXPECT_TRUE(near(pixel(density, x, y), kRampTop, 0)) << x << "," << y;
      } else if (uniformAround(plain, x, y, false)) {
        ++off_cube;
        EXPECT_TRUE(near(pixel(density, x, y), kRampBottom, 0)) << x << "," << y;
      }
      if (HasFailure()) return;
    }
  EXPECT_GT(on_cube, 500);
  EXPECT_GT(off_cube, 500);
  quit();
}

#ifdef TESSERA_TEST_VULKAN
TEST_F(ViewerWindow, ShiftF2SwitchesTheVulkanCommitPathAndTheFrameStaysTheSame) {
  const int w = 320, h = 240;
  if (!openCube({"-backend", "vulkan"}, w, h)) GTEST_SKIP() << skip_reason_;
  xdotool({"key", "F5"});
  std::optional<std::string> stored = viewer_->waitForLine("tessera view: crc32 stored ");
  ASSERT_TRUE(stored) << viewer_->output() << slurp(dir_ / "viewer.err");
  const std::string crc = stored->substr(std::string("tessera view: crc32 stored ").size());
  const DecodedPng before = screenshot();
  std::string paths[2];
  DecodedPng after[2];
  for (int i = 0; i < 2; ++i) {
    xdotool({"key", "shift+F2"});
    std::optional<std::string> line = viewer_->waitForLine("tessera view: commit path: ");
    ASSERT_TRUE(line) << viewer_->output() << slurp(dir_ / "viewer.err");
    paths[i] = line->substr(std::string("tessera view: commit path: ").size());
    // Both commit paths draw the same image: the CRC of the rendered frame matches.
    xdotool({"key", "F6"});
    EXPECT_TRUE(viewer_->waitForLine("tessera view: crc32 MATCH " + crc)) << viewer_->output();
    after[i] = screenshot();
  }
  if (paths[0].find("no 64-bit atomics") != std::string::npos) {
    EXPECT_EQ(paths[0], paths[1]);  // nothing to switch to: it says so each time
  } else {
    EXPECT_EQ(paths[0], "32-bit, two passes");  // the device starts on the 64-bit path
    EXPECT_EQ(paths[1], "64-bit atomics");
  }
  // The picture above the overlay's lines is the same; the line itself changed.
  for (const DecodedPng& shot : after)
    EXPECT_EQ(countDifferent(before, shot, 0, 0, w, h - kBottomRows), 0);
  if (paths[0] != paths[1]) {
    EXPECT_GT(countDifferent(after[0], after[1], 0, 0, w, h), 0);
  }
  quit();
}
#endif
