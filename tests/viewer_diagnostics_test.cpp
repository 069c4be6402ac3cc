// The viewer's diagnostic views without a window: the keys' view cycle, the pictures made from
// Frame::diagnostics (heatmap.h's ramp and legend), and FrameRenderer measuring them only while a
// view is shown.
#include <gtest/gtest.h>

#include <algorithm>

#include <tessera/render/cpu_renderer.h>
#include <tessera/render/heatmap.h>
#include <tessera/scene/scene.h>
#include <tessera/viewer/diagnostic_view.h>
#include <tessera/viewer/frame_renderer.h>

using namespace tessera;
using namespace tessera::viewer;

namespace {

constexpr uint32_t kBlack = 0xff040000u;  // inferno(0): (0, 0, 4)
constexpr uint32_t kTop = 0xffa4fffcu;    // inferno(1): (252, 255, 164)

// A frame of `width` x `height` whose diagnostics say what the tests put in them: tiles of
// `tile` pixels.
Frame diagnosedFrame(int width, int height, int tile) {
  Frame frame;
  frame.resize(width, height, true, true, false);
  FrameDiagnostics& d = frame.diagnostics;
  d.valid = true;
  d.tile_size = tile;
  d.tile_columns = (width + tile - 1) / tile;
  d.tile_rows = (height + tile - 1) / tile;
  d.tile_triangles.assign(d.tileCount(), 0);
  d.tile_covered.assign(d.tileCount(), 0.0f);
  d.density.assign(frame.pixelCount(), 0.0f);
  return frame;
}

// A camera that maps object coordinates straight to clip space.
Scene clipSpaceScene() {
  Scene scene;
  scene.camera.view_override = float4x4::identity();
  scene.camera.projection_override = float4x4::identity();
  return scene;
}

// The left half of the viewport (x < 0 in NDC) as two triangles with `density`.
Object leftHalf(float density) {
  auto mesh = std::make_shared<Mesh>();
  mesh->positions = {{-1, -1, 0}, {0, -1, 0}, {0, 1, 0}, {-1, 1, 0}};
  mesh->indices = {0, 1, 2, 0, 2, 3};
  mesh->triangle_materials = {0, 0};
  Object o;
  o.mesh = mesh;
  o.cull = CullMode::kNone;
  o.materials[0].density = density;
  return o;
}

// Fills the frame and says whether it filled the diagnostics too (as a backend may not).
class FakeBackend : public Backend {
 public:
  bool fills_diagnostics = false;
  bool asked_for_diagnostics = false;
  const char* name() const override { return "fake"; }
  void render(const Scene&, const RenderOptions& o, Frame& frame) override {
    asked_for_diagnostics = o.diagnostics;
    frame.resize(o.width, o.height, true, true, false);
    std::fill(frame.color.begin(), frame.color.end(), 0xff808080u);
    if (fills_diagnostics) frame.diagnostics.valid = true;
  }
};

}  // namespace

TEST(DiagnosticView, ShiftF1TogglesTheHeatmapAndF11CyclesTheAnalysisViews) {
  EXPECT_EQ(toggleTileHeatmap(DiagnosticView::kOff), DiagnosticView::kTileHeatmap);
  EXPECT_EQ(toggleTileHeatmap(DiagnosticView::kTileHeatmap), DiagnosticView::kOff);
  EXPECT_EQ(toggleTileHeatmap(DiagnosticView::kDensity), DiagnosticView::kTileHeatmap);
  EXPECT_EQ(nextAnalysisView(DiagnosticView::kOff), DiagnosticView::kTileField);
  EXPECT_EQ(nextAnalysisView(DiagnosticView::kTileField), DiagnosticView::kDensity);
  EXPECT_EQ(nextAnalysisView(DiagnosticView::kDensity), DiagnosticView::kOff);
  EXPECT_EQ(nextAnalysisView(DiagnosticView::kTileHeatmap), DiagnosticView::kTileField);
  EXPECT_FALSE(needsDiagnostics(DiagnosticView::kOff));
  EXPECT_TRUE(needsDiagnostics(DiagnosticView::kDensity));
}

TEST(Heatmap, SpreadTilesGivesEveryPixelItsTilesValue) {
  Frame frame = diagnosedFrame(5, 3, 2);  // 3 x 2 tiles, the last column and row partial
  const std::vector<int> tiles = {1, 2, 3, 4, 5, 6};
  const std::vector<int> pixels = spreadTiles(frame.diagnostics, tiles, 5, 3);
  const std::vector<int> expected = {1, 1, 2, 2, 3,  //
                                     1, 1, 2, 2, 3,  //
                                     4, 4, 5, 5, 6};
  EXPECT_EQ(pixels, expected);
}

TEST(Heatmap, AFixedTopScalesTheRampAndLabelsTheLegend) {
  // Too small for a legend: every pixel is its count's colour.
  EXPECT_EQ(heatmapLegendHeight(8, 1), 0);
  const std::vector<uint32_t> ramp = heatmapImage(4, 1, {0, 50, 100, 200}, 100);
  EXPECT_EQ(ramp[0], kBlack);
  EXPECT_EQ(ramp[1], infernoColor(0.5f));
  EXPECT_EQ(ramp[2], kTop);
  EXPECT_EQ(ramp[3], kTop);  // above the top: clamped
  // Without a top the largest count is the top.
  EXPECT_EQ(heatmapImage(2, 1, {1, 2})[0], infernoColor(0.5f));
  // A picture big enough has a black strip along the bottom with the white labels in it.
  const int w = 200, h = 160;
  const int strip = heatmapLegendHeight(w, h);
  ASSERT_GT(strip, 0);
  const std::vector<uint32_t> image = heatmapImage(w, h, std::vector<uint32_t>(w * h, 100), 100);
  EXPECT_EQ(image[static_cast<size_t>(h - strip - 1) * w], kTop);
  EXPECT_EQ(image[static_cast<size_t>(h - strip) * w], 0xff000000u);
  EXPECT_TRUE(std::count(image.end() - strip * w, image.end(), 0xffffffffu) > 0);
}

TEST(DiagnosticView, WithoutDiagnosticsTheCaptionSaysSoAndTheFrameIsShown) {
  Frame frame = diagnosedFrame(8, 8, 4);
  frame.diagnostics.valid = false;
  const DiagnosticPicture picture = diagnosticPicture(frame, DiagnosticView::kTileHeatmap, "gpu");
  EXPECT_TRUE(picture.pixels.empty());
  EXPECT_EQ(picture.caption, "tile heatmap: not available on this backend (gpu)");
  // No occupancy (a nonlinear projection): that view is unavailable, the others are not.
  frame = diagnosedFrame(8, 8, 4);
  frame.diagnostics.tile_triangles.clear();
  EXPECT_TRUE(diagnosticPicture(frame, DiagnosticView::kTileHeatmap, "cpu").pixels.empty());
  EXPECT_NE(diagnosticPicture(frame, DiagnosticView::kTileHeatmap, "cpu")
                .caption.find("perspective only"),
            std::string::npos);
  EXPECT_EQ(diagnosticPicture(frame, DiagnosticView::kTileField, "cpu").pixels.size(), 64u);
  EXPECT_TRUE(diagnosticPicture(frame, DiagnosticView::kOff, "cpu").pixels.empty());
  EXPECT_TRUE(diagnosticPicture(frame, DiagnosticView::kOff, "cpu").caption.empty());
}

TEST(DiagnosticView, EachViewColoursItsOwnField) {
  Frame frame = diagnosedFrame(8, 4, 4);  // two tiles side by side
  FrameDiagnostics& d = frame.diagnostics;
  d.tile_triangles = {3, 6};
  d.tile_covered = {0.5f, 0.0f};
  for (int y = 0; y < 4; ++y) d.density[static_cast<size_t>(y) * 8 + 7] = 2.5f;
  d.density[0] = 1.25f;
  const DiagnosticPicture heat = diagnosticPicture(frame, DiagnosticView::kTileHeatmap, "cpu");
  ASSERT_EQ(heat.pixels.size(), 32u);
  EXPECT_EQ(heat.pixels[0], infernoColor(0.5f));
  EXPECT_EQ(heat.pixels[7], kTop);
  EXPECT_NE(heat.caption.find("0 (black) to 6 (yellow)"), std::string::npos) << heat.caption;
  // The tile field's top is a full tile, whatever the frame's fullest.
  const DiagnosticPicture field = diagnosticPicture(frame, DiagnosticView::kTileField, "cpu");
  EXPECT_EQ(field.pixels[3 * 8 + 3], infernoColor(0.5f));
  EXPECT_EQ(field.pixels[4], kBlack);
  EXPECT_NE(field.caption.find("0 to 100 %"), std::string::npos) << field.caption;
  const DiagnosticPicture density = diagnosticPicture(frame, DiagnosticView::kDensity, "cpu");
  EXPECT_EQ(density.pixels[7], kTop);
  EXPECT_EQ(density.pixels[0], infernoColor(0.5f));
  EXPECT_EQ(density.pixels[1], kBlack);
  EXPECT_NE(density.caption.find("0 to 2.500"), std::string::npos) << density.caption;
}

TEST(DiagnosticView, TheCpuRenderersCoveredTilesAndDensityShowAsExpected) {
  // 128 x 64 at 64-pixel tiles: the left half covers the first tile; the density 2 of the
  // model is the top, the empty right half density 0 (black).
  Scene scene = clipSpaceScene();
  scene.objects.push_back(leftHalf(2.0f));
  CpuRenderer cpu(2);
  RenderOptions options;
  options.width = 128, options.height = 64, options.diagnostics = true;
  Frame frame;
  cpu.render(scene, options, frame);
  ASSERT_TRUE(frame.diagnostics.valid);
  ASSERT_EQ(frame.diagnostics.tile_size, 64);
  const DiagnosticPicture field = diagnosticPicture(frame, DiagnosticView::kTileField, "cpu");
  EXPECT_EQ(field.pixels[10], kTop);     // a covered tile
  EXPECT_EQ(field.pixels[100], kBlack);  // an empty one
  const DiagnosticPicture density = diagnosticPicture(frame, DiagnosticView::kDensity, "cpu");
  EXPECT_EQ(density.pixels[10], kTop);
  EXPECT_EQ(density.pixels[100], kBlack);
  EXPECT_NE(density.caption.find("0 to 2.000"), std::string::npos) << density.caption;
  const DiagnosticPicture heat = diagnosticPicture(frame, DiagnosticView::kTileHeatmap, "cpu");
  EXPECT_EQ(heat.pixels[10], kTop);  // both triangles binned there, none in the right tile
  EXPECT_EQ(heat.pixels[100], kBlack);
}

TEST(FrameRenderer, MeasuresDiagnosticsOnlyWhileAViewAsksAndNeverKeepsStaleOnes) {
  FrameRenderer frames(Projection::kPerspective, ViewAngles{}, SamplingModes(1, false, false));
  FakeBackend backend;
  Scene scene;
  Frame frame;
  EXPECT_FALSE(frames.diagnostics());
  ASSERT_TRUE(frames.render(backend, scene, 16, 16, frame));
  EXPECT_FALSE(backend.asked_for_diagnostics);
  frames.setDiagnostics(true);
  backend.fills_diagnostics = true;
  ASSERT_TRUE(frames.render(backend, scene, 16, 16, frame));
  EXPECT_TRUE(backend.asked_for_diagnostics);
  EXPECT_TRUE(frame.diagnostics.valid);
  // A backend that leaves them alone: the last frame's are not passed off as this one's.
  backend.fills_diagnostics = false;
  ASSERT_TRUE(frames.render(backend, scene, 16, 16, frame));
  EXPECT_FALSE(frame.diagnostics.valid);
  EXPECT_NE(diagnosticPicture(frame, DiagnosticView::kTileField, backend.name())
                .caption.find("not available on this backend (fake)"),
            std::string::npos);
}
