// The resolve (render/resolve.h): a shaded tile and the background written into the frame, past
// the caches (streaming stores) or through them, with the same pixels either way; and which
// frames take which.
#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <vector>

#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/color.h>

#include "render/resolve.h"

#include "render_test_scenes.h"

using namespace tessera;
using namespace tessera::render;
using tessera::test::clipSpaceScene;
using tessera::test::unlitObject;
using tessera::test::windowTriangle;

// Both ways of writing give every pixel of the region its value and leave the rest alone, at
// unaligned starts and widths that are not a multiple of four (the streamed rows' scalar ends).
TEST(Resolve, StreamedAndCachedWritesGiveTheSamePixels) {
  constexpr int kWidth = 131, kHeight = 70;
  constexpr uint32_t kBackground = 0x11223344u, kUntouched = 0xdeadbeefu;
  auto tile = std::make_unique<TileVisibility>();
  auto shaded = std::make_unique<ShadedTile>();
  for (int i = 0; i < ShadedTile::kSize; ++i) shaded->rgba[i] = 0x01000000u * (i % 97) + i;
  for (bool stream : {false, true}) {
    Frame frame;
    frame.resize(kWidth, kHeight, false, false, false, false);
    std::fill(frame.color.begin(), frame.color.end(), kUntouched);
    // A run of empty tiles from column 1 to 120 on rows 2 to 9, then a shaded tile at (5, 13)
    // of 61 x 50 pixels.
    resolveEmptyTile(1, 2, 119, 8, kBackground, stream, frame);
    tile->clear(5, 13, 61, 50);
    resolveTile(*tile, *shaded, {}, stream, frame);
    size_t wrong = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        uint32_t want = kUntouched;
        if (x >= 1 && x < 120 && y >= 2 && y < 10) want = kBackground;
        if (x >= 5 && x < 66 && y >= 13 && y < 63)
          want = shaded->rgba[(y - 13) * kTileSize + (x - 5)];
        wrong += frame.color[static_cast<size_t>(y) * kWidth + x] != want;
      }
    EXPECT_EQ(wrong, 0u) << (stream ? "streamed" : "cached");
  }
}

// The streamed writes go to whole cache lines only, the ends of a run through the cache: runs
// shorter than a line, runs within one line and runs that end on a line's boundary, at every
// start within a line, give the background to exactly their pixels.
TEST(Resolve, StreamedRunsOfEveryLengthAndStartGiveTheirPixels) {
  constexpr int kWidth = 64;
  constexpr uint32_t kBackground = 0x55667788u, kUntouched = 0xdeadbeefu;
  Frame frame;
  frame.resize(kWidth, 1, false, false, false, false);
  size_t wrong = 0;
  for (int x0 = 0; x0 < 17; ++x0) {
    for (int n = 1; x0 + n <= kWidth; ++n) {
      std::fill(frame.color.begin(), frame.color.end(), kUntouched);
      resolveEmptyTile(x0, 0, n, 1, kBackground, true, frame);
      for (int x = 0; x < kWidth; ++x)
        wrong += frame.color[x] != (x >= x0 && x < x0 + n ? kBackground : kUntouched);
    }
  }
  EXPECT_EQ(wrong, 0u);
}

// Every empty tile of a grid 3.3 tiles wide and 2.5 tall, called once each in any order, as the
// workers do: the tiles of each run along a row get the background (depth +inf, no id) once, the
// last column's narrow tiles included, and the tiles that hold triangles are left alone.
TEST(Resolve, EmptyRunsFillEveryEmptyTileAndNoOther) {
  const TileGrid grid = TileGrid::forViewport(3 * kTileSize + 21, 2 * kTileSize + 33);
  ASSERT_EQ(grid.columns, 4);
  ASSERT_EQ(grid.rows, 3);
  // Row 0: empty, full, empty, empty; row 1: all empty; row 2: full, empty, full, empty.
  const std::vector<uint8_t> empty = {1, 0, 1, 1, 1, 1, 1, 1, 0, 1, 0, 1};
  constexpr uint32_t kBackground = 0x0a0b0c0du, kUntouched = 0xdeadbeefu;
  for (bool stream : {false, true}) {
    Frame frame;
    frame.resize(grid.width, grid.height, true, true, false, false);
    std::fill(frame.color.begin(), frame.color.end(), kUntouched);
    std::fill(frame.depth.begin(), frame.depth.end(), 1.0f);
    std::fill(frame.triangle_id.begin(), frame.triangle_id.end(), 7u);
    for (int tile = grid.tileCount() - 1; tile >= 0; --tile)
      if (empty[static_cast<size_t>(tile)])
        resolveEmptyRun(grid, empty, tile, kBackground, stream, frame);
    size_t wrong = 0;
    for (int y = 0; y < grid.height; ++y)
      for (int x = 0; x < grid.width; ++x) {
        const size_t i = static_cast<size_t>(y) * grid.width + x;
        const bool background =
            empty[static_cast<size_t>(y / kTileSize * grid.columns + x / kTileSize)] != 0;
        wrong += frame.color[i] != (background ? kBackground : kUntouched);
        wrong += frame.depth[i] != (background ? std::numeric_limits<float>::infinity() : 1.0f);
        wrong += frame.triangle_id[i] != (background ? kNoTriangle : 7u);
      }
    EXPECT_EQ(wrong, 0u) << (stream ? "streamed" : "cached");
  }
}

// A frame streams when its colour and its triangles' records would take more than half the
// last-level cache, whatever that cache's size (up to a gigabyte): a small frame of a few
// triangles never does, a frame of a gigabyte of colour or of records always does.
TEST(Resolve, OnlyFramesBeyondTheCacheAreStreamed) {
  EXPECT_FALSE(streamsFrame(640 * 480, 12));
  EXPECT_FALSE(streamsFrame(256 * 256, 1000));
  EXPECT_TRUE(streamsFrame(size_t{16384} * 16384, 12));
  EXPECT_TRUE(streamsFrame(640 * 480, 10'000'000));
  EXPECT_FALSE(streamsFrame(0, 0));
}

// The empty tiles' background streams past kStreamedBackgroundBytes of colour whatever the cache,
// and wherever the frame itself streams; a small frame's stays in the cache.
TEST(Resolve, BackgroundsOfLargeFramesAreStreamed) {
  EXPECT_FALSE(streamsBackground(640 * 480, 12));
  EXPECT_TRUE(streamsBackground(1920 * 1080, 12));
  EXPECT_TRUE(streamsBackground(3840 * 2160, 12));
  EXPECT_EQ(streamsBackground(kStreamedBackgroundBytes / 4, 12),
            streamsFrame(kStreamedBackgroundBytes / 4, 12));
  EXPECT_TRUE(streamsBackground(kStreamedBackgroundBytes / 4 + 1, 12));
  EXPECT_TRUE(streamsBackground(640 * 480, 10'000'000));
}

// The whole renderer at a size that streams where the last-level cache is unknown or below 8 MB
// (1101 x 1000: 4.4 MB) and at one that never does: every pixel gets the triangle's colour where
// the id AOV (written apart from the colour) names it, the background elsewhere, odd widths' row
// ends and empty tiles' runs included. Where the frame does not stream, its whole tiles take the
// colour straight from the shading's encode (ShadedTile::direct) and the last column's narrow
// tiles through resolveTile's copy: both in one frame.
TEST(Resolve, LargeAndSmallFramesGetEveryPixelWritten) {
  for (const auto& [width, height] : {std::pair{1101, 1000}, std::pair{301, 203}}) {
    Scene scene = clipSpaceScene();
    scene.background = {0.2f, 0.4f, 0.6f, 1.0f};
    const float w = static_cast<float>(width), h = static_cast<float>(height);
    scene.objects.push_back(
        unlitObject(windowTriangle({0.3f * w, 0.1f * h, 0.5f}, {0.9f * w, 0.5f * h, 0.5f},
                                   {0.45f * w, 0.8f * h, 0.5f}, width, height)));
    RenderOptions options;
    options.width = width;
    options.height = height;
    options.ids = true;
    Frame frame;
    CpuRenderer(2).render(scene, options, frame);
    const uint32_t background = packSrgba8(scene.background), white = packSrgba8({1, 1, 1, 1});
    size_t covered = 0, wrong = 0;
    for (size_t i = 0; i < frame.color.size(); ++i) {
      const bool on = frame.triangle_id[i] != kNoTriangle;
      covered += on;
      wrong += frame.color[i] != (on ? white : background);
    }
    EXPECT_EQ(wrong, 0u) << width << "x" << height;
    EXPECT_GT(covered, frame.color.size() / 10) << width << "x" << height;
  }
}
