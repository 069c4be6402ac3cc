// RenderOptions::frame_kept: the frames of a sequence rendered into one Frame, whose background
// tiles the CPU renderer leaves as they are where the last render left them background too. The
// images must be those of frames rendered afresh, and tiles may be left only under the caller's
// promise, in the same buffers, with the same background, after a render that drew nothing over
// its tiles.
#include <gtest/gtest.h>

#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/primitives.h>

#include "allocation_counter.h"  // g_count_allocations, g_allocations

using namespace tessera;

namespace {

// A lit cube in front of a grey background; `x` moves it across the frame.
Scene cubeScene(float x) {
  Scene scene;
  scene.camera.position = {0, 0.3f, 4};
  scene.background = {0.2f, 0.3f, 0.4f, 1.0f};
  scene.lights.push_back({normalize(float3{-1, -2, -1}), float3(0.9f)});
  Object cube;
  cube.mesh = std::make_shared<Mesh>(makeCube());
  cube.shading = Shading::kGouraud;
  cube.transform.translation = {x, 0, 0};
  cube.transform.rotation = quat::fromAxisAngle({0, 1, 0}, 0.4f + x);
  scene.objects.push_back(cube);
  return scene;
}

constexpr uint32_t kScribble = 0xff00ff00u;  // a pixel no render of these scenes gives

}  // namespace

// The cube crosses the frame, so tiles turn from background to cube and back, with one sample
// and with 4x MSAA, every AOV asked for: each frame of the kept Frame must equal a fresh one. After
// the warm-up frames the kept frames allocate nothing.
TEST(KeptFrame, ASequenceGivesTheImagesOfFramesRenderedAfresh) {
  for (int msaa : {1, 4}) {
    CpuRenderer kept_renderer(2), fresh_renderer(2);
    RenderOptions options;
    options.width = 200;
    options.height = 120;
    options.msaa = msaa;
    options.lines = false;
    options.normals = true;
    options.coverage = true;
    RenderOptions kept_options = options;
    kept_options.frame_kept = true;
    Frame kept;
    g_allocations = 0;
    for (int i = 0; i < 16; ++i) {
      const Scene scene = cubeScene(-2.5f + 0.35f * static_cast<float>(i));
      g_count_allocations = i >= 4;  // the kept frames after the warm-up
      kept_renderer.render(scene, kept_options, kept);
      g_count_allocations = false;
      Frame fresh;
      fresh_renderer.render(scene, options, fresh);
      ASSERT_EQ(kept.color, fresh.color) << msaa << "x, frame " << i;
      ASSERT_EQ(kept.depth, fresh.depth) << msaa << "x, frame " << i;
      ASSERT_EQ(kept.triangle_id, fresh.triangle_id) << msaa << "x, frame " << i;
      ASSERT_EQ(kept.normal, fresh.normal) << msaa << "x, frame " << i;
      ASSERT_EQ(kept.coverage, fresh.coverage) << msaa << "x, frame " << i;
    }
    EXPECT_EQ(g_allocations.load(), 0u) << msaa << "x";
  }
}

// A pixel scribbled between renders (breaking the promise on purpose) shows whether the renderer
// filled its tile: left where the caller promised and the tile was background in both renders;
// filled without the promise, with another background, after a render that drew lines over the
// frame, after a panorama (the ray renderer's frame), in another Frame and at another width and
// height of as many pixels.
TEST(KeptFrame, BackgroundTilesAreLeftOnlyUnderThePromise) {
  Scene scene = cubeScene(0);
  CpuRenderer renderer(2);
  RenderOptions options;
  options.width = 256;
  options.height = 128;
  RenderOptions kept_options = options;
  kept_options.frame_kept = true;
  Frame frame;
  const size_t corner = 2 * 256 + 2;  // pixel (2, 2): a background tile in every render below
  const auto scribbled = [&](const RenderOptions& o) {
    frame.color[corner] = kScribble;
    renderer.render(scene, o, frame);
    return frame.color[corner] == kScribble;
  };
  renderer.render(scene, kept_options, frame);  // the first render fills every tile
  const uint32_t background = frame.color[corner];
  ASSERT_NE(background, kScribble);
  EXPECT_TRUE(scribbled(kept_options)) << "a background tile of both renders was filled again";
  EXPECT_FALSE(scribbled(options)) << "filled only under the promise";
  EXPECT_TRUE(scribbled(kept_options)) << "a render without the promise still records its tiles";

  scene.background = {0.5f, 0.1f, 0.1f, 1.0f};
  EXPECT_FALSE(scribbled(kept_options)) << "another background";
  EXPECT_NE(frame.color[corner], background);

  scene.show_world_axes = true;  // the line pass draws after the tiles: nothing is recorded
  renderer.render(scene, kept_options, frame);
  scene.show_world_axes = false;
  EXPECT_FALSE(scribbled(kept_options)) << "after a frame with lines";

  RenderOptions panorama = options;
  panorama.projection = Projection::kSpherical;
  renderer.render(scene, panorama, frame);
  EXPECT_FALSE(scribbled(kept_options)) << "after a panorama";

  Frame other;
  renderer.render(scene, kept_options, other);
  EXPECT_FALSE(scribbled(kept_options)) << "after a render into another frame";
  EXPECT_TRUE(scribbled(kept_options));

  // 128x256 holds as many pixels and tiles as 256x128, so the frame keeps its buffers; tile 0 is
  // background in both, but its pixels lie elsewhere in them.
  RenderOptions turned = kept_options;
  turned.width = 128;
  turned.height = 256;
  frame.color[0] = kScribble;
  renderer.render(scene, turned, frame);
  EXPECT_NE(frame.color[0], kScribble) << "after a frame of the same pixels turned";
}
