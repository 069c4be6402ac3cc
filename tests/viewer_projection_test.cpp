// The viewer's projections without a window (F4, the view angles, the orbit camera in the
// nonlinear modes, the frames a backend draws or cannot draw). Apart from viewer_test.cpp to keep
// each file to one concern.
#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <optional>

#include <tessera/render/projection.h>
#include <tessera/viewer/frame_renderer.h>
#include <tessera/viewer/input_state.h>
#include <tessera/viewer/orbit_camera.h>
#include <tessera/viewer/projection_mode.h>

using namespace tessera;
using namespace tessera::viewer;

namespace {

// The box from -1 to 1 on each axis: a bounding sphere of radius sqrt(3) about the origin.
const Bounds kBox{{-1, -1, -1}, {1, 1, 1}};

TEST(ViewerProjectionMode, F4CyclesEveryModeInTheMapsOrderAndTheListSaysSo) {
  std::optional<Action> a = keyAction(Key::kF4);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->type, Action::Type::kCycleProjection);
  EXPECT_FALSE(keyAction(Key::kF4, /*shift=*/true));
  const Projection order[] = {Projection::kPerspective, Projection::kCylindrical,
                              Projection::kSpherical,   Projection::kStereographic,
                              Projection::kFisheye,     Projection::kPerspective};
  for (size_t i = 0; i + 1 < std::size(order); ++i)
    EXPECT_EQ(nextProjection(order[i]), order[i + 1]) << projectionName(order[i]);
  int f4_lines = 0;
  for (const KeyHelp& help : keyList())
    for (const KeyChord& chord : help.chords)
      if (chord.key == Key::kF4) {
        ++f4_lines;
        EXPECT_EQ(help.keys, "F4");
        EXPECT_NE(help.action.find("projection"), std::string::npos) << help.action;
      }
  EXPECT_EQ(f4_lines, 1);
}

TEST(ViewerProjectionMode, EachModeTakesTheRequestedAngleWhereItFitsAndItsDefaultElsewhere) {
  ViewAngles given{35.0f, std::nullopt};
  EXPECT_EQ(viewAngleFor(Projection::kPerspective, 2.0f, given), 35.0f);
  // Nothing requested: each nonlinear mode's own default for the aspect.
  for (Projection p : kProjections) {
    if (p == Projection::kPerspective) continue;
    EXPECT_EQ(viewAngleFor(p, 4.0f / 3.0f, given), defaultViewAngle(p, 4.0f / 3.0f))
        << projectionName(p);
  }
  EXPECT_EQ(viewAngleFor(Projection::kSpherical, 2.0f, given), 180.0f);
  EXPECT_EQ(viewAngleFor(Projection::kCylindrical, 4.0f, given), 90.0f);  // 360 across
  // 270 fits a fisheye, not a sphere (at most 180 high), nor perspective's own angle.
  ViewAngles wide{50.0f, 270.0f};
  EXPECT_EQ(viewAngleFor(Projection::kFisheye, 1.0f, wide), 270.0f);
  EXPECT_EQ(viewAngleFor(Projection::kStereographic, 1.0f, wide), 270.0f);
  EXPECT_EQ(viewAngleFor(Projection::kSpherical, 1.0f, wide), 180.0f);
  EXPECT_EQ(viewAngleFor(Projection::kPerspective, 1.0f, wide), 50.0f);
  // 120 fits a cylinder on a square window, not on one 4 wide (480 degrees across).
  ViewAngles narrow{50.0f, 120.0f};
  EXPECT_EQ(viewAngleFor(Projection::kCylindrical, 1.0f, narrow), 120.0f);
  EXPECT_EQ(viewAngleFor(Projection::kCylindrical, 4.0f, narrow), 90.0f);
  EXPECT_EQ(describeProjection(Projection::kSpherical, 180.0f), "spherical 180\u00b0");
  EXPECT_EQ(describeProjection(Projection::kCylindrical, 112.5f), "cylindrical 112.5\u00b0");
}

TEST(OrbitCamera, NonlinearModesTakeTheirAngleAndNearAndFarAsDistances) {
  OrbitCamera orbit;
  orbit.frame(kBox, {0, 0, 1}, 50.0f, 1.0f);
  orbit.pan(1.5f, 0.0f);  // the model far to the side: its corners are farther than its depth
  const float3 eye = orbit.position();
  float nearest = 1e9f, farthest = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const float3 corner{i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f};
    nearest = std::min(nearest, length(corner - eye));
    farthest = std::max(farthest, length(corner - eye));
  }
  const Camera along_axis = orbit.camera();
  EXPECT_EQ(along_axis.fov_y_degrees, 50.0f);
  EXPECT_LT(along_axis.far_z, farthest);  // depth along the axis would cut the far corners
  orbit.setProjection(Projection::kSpherical, 180.0f);
  const Camera spherical = orbit.camera();
  EXPECT_EQ(spherical.fov_y_degrees, 180.0f);
  EXPECT_LE(spherical.near_z, nearest);
  EXPECT_GE(spherical.far_z, farthest);
  EXPECT_GT(spherical.near_z, 0.0f);
  // Within the bounding sphere's slack (1%), not a blanket range.
  const float centre = length(eye);
  EXPECT_NEAR(spherical.far_z, centre + std::sqrt(3.0f), 0.05f);
  EXPECT_NEAR(spherical.near_z, centre - std::sqrt(3.0f), 0.05f);
  // Back in perspective: frame()'s angle and the bracket along the axis again.
  orbit.setProjection(Projection::kPerspective, 180.0f);
  EXPECT_EQ(orbit.camera().fov_y_degrees, 50.0f);
  EXPECT_EQ(orbit.camera().far_z, along_axis.far_z);
}

TEST(OrbitCamera, PanFollowsThePointerAtTheMiddleInEveryMode) {
  constexpr int kSize = 200;
  for (Projection p : kProjections) {
    if (p == Projection::kPerspective) continue;  // PanMovesTheTargetWithThePointer
    for (float angle : {90.0f, 160.0f}) {         // cylindrical: below 180
      OrbitCamera orbit;
      orbit.frame(kBox, {0, 0, 1}, 50.0f, 1.0f);
      orbit.setProjection(p, angle);
      // A drag of a fiftieth of the height right and down: the old target moves 4 pixels each way.
      orbit.pan(0.02f, 0.02f);
      const Camera camera = orbit.camera();
      const float4 eye_space = camera.view() * float4{0, 0, 0, 1};
      const double d[3] = {eye_space.x, eye_space.y, eye_space.z};
      double sx = 0, sy = 0;
      ASSERT_TRUE(projectDirection(p, d, kSize, kSize, radians(angle), sx, sy));
      EXPECT_NEAR(sx, kSize / 2 + 4.0, 0.05) << projectionName(p) << " " << angle;
      EXPECT_NEAR(sy, kSize / 2 + 4.0, 0.05) << projectionName(p) << " " << angle;
    }
  }
}

// Records what it was asked to draw; in `perspective_only` mode it fails the other projections,
// as vulkan-raster does, and leaves a cleared frame.
class RecordingBackend : public Backend {
 public:
  static constexpr uint32_t kDrawn = 0xff336699u;
  bool perspective_only = false;
  RenderOptions options;
  Camera camera;
  bool failed = false;

  const char* name() const override { return "recording"; }
  void render(const Scene& scene, const RenderOptions& o, Frame& frame) override {
    options = o;
    camera = scene.camera;
    failed = perspective_only && o.projection != Projection::kPerspective;
    frame.resize(o.width, o.height, o.depth, false, false);
    std::fill(frame.color.begin(), frame.color.end(), failed ? 0u : kDrawn);
    std::fill(frame.depth.begin(), frame.depth.end(), 0.5f);
  }
  Expected<void> lastResult() const override {
    if (failed) return makeError("recording draws the perspective projection only");
    return {};
  }
};

TEST(FrameRenderer, EachModeDrawsWithItsProjectionViewAngleAndDistances) {
  FrameRenderer frames(Projection::kPerspective, ViewAngles{40.0f, std::nullopt},
                       SamplingModes(4, false, true));
  OrbitCamera orbit;
  orbit.frame(kBox, {0, 0, 1}, 40.0f, 2.0f);
  RecordingBackend backend;
  Scene scene;
  Frame frame;
  auto draw = [&](int width, int height) {
    scene.camera = frames.camera(orbit, width, height);
    EXPECT_TRUE(frames.render(backend, scene, width, height, frame));
    EXPECT_EQ(backend.options.width, width);
    EXPECT_EQ(backend.options.msaa, 4);
    EXPECT_EQ(backend.options.projection, frames.projection());
    EXPECT_EQ(backend.camera.fov_y_degrees, scene.camera.fov_y_degrees);
  };
  draw(200, 100);
  EXPECT_EQ(backend.options.projection, Projection::kPerspective);
  EXPECT_EQ(backend.camera.fov_y_degrees, 40.0f);
  EXPECT_EQ(frames.describeProjection(), "perspective 40\u00b0");
  frames.cycleProjection();
  frames.cycleProjection();
  draw(200, 100);
  // Spherical on a 2:1 window: the whole 360 x 180 panorama; near and far around the bounding
  // sphere as distances from the eye.
  EXPECT_EQ(backend.options.projection, Projection::kSpherical);
  EXPECT_EQ(backend.camera.fov_y_degrees, 180.0f);
  EXPECT_EQ(frames.describeProjection(), "spherical 180\u00b0");
  const float centre = length(orbit.position());
  EXPECT_NEAR(backend.camera.far_z, centre + std::sqrt(3.0f), 0.05f);
  EXPECT_NEAR(backend.camera.near_z, centre - std::sqrt(3.0f), 0.05f);
  // A window 4 wide: 90 degrees high is the whole way round.
  draw(400, 100);
  EXPECT_EQ(backend.camera.fov_y_degrees, 90.0f);
  EXPECT_EQ(frames.describeProjection(), "spherical 90\u00b0");
}

TEST(FrameRenderer, AModeTheBackendCannotDrawSaysWhyAndTheNextItDrawsClearsIt) {
  FrameRenderer frames(Projection::kPerspective, ViewAngles{}, SamplingModes(1, true, true));
  OrbitCamera orbit;
  orbit.frame(kBox, {0, 0, 1}, 50.0f, 1.0f);
  RecordingBackend backend;
  backend.perspective_only = true;
  Scene scene;
  Frame frame;
  auto draw = [&] {
    scene.camera = frames.camera(orbit, 16, 16);
    return frames.render(backend, scene, 16, 16, frame);
  };
  EXPECT_TRUE(draw());
  EXPECT_TRUE(draw());
  EXPECT_EQ(frames.error(), "");
  EXPECT_EQ(frames.sampling().describe(), "MSAA 1x, jitter, TAA 2/16");
  frames.cycleProjection();  // cylindrical: the backend refuses, every frame
  for (int i = 0; i < 3; ++i) {
    EXPECT_FALSE(draw());
    EXPECT_EQ(frames.error(), "recording draws the perspective projection only");
  }
  for (int i = 0; i < 4; ++i) frames.cycleProjection();  // ... fisheye, perspective
  EXPECT_TRUE(draw());
  EXPECT_EQ(frames.error(), "");
  EXPECT_EQ(frame.color[0], RecordingBackend::kDrawn);
  // The history started again with the mode: one frame in it.
  EXPECT_EQ(frames.sampling().describe(), "MSAA 1x, jitter, TAA 1/16");
}

}  // namespace
