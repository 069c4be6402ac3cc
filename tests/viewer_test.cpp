// The viewer's window-system-neutral parts: orbit camera, input mapping, background loading.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include <tessera/math/projection.h>
#include <tessera/scene/primitives.h>
#include <tessera/viewer/input_state.h>
#include <tessera/viewer/orbit_camera.h>
#include <tessera/viewer/scene_loader.h>

using namespace tessera;
using namespace tessera::viewer;

namespace {

Bounds unitBounds() {
  Bounds b;
  b.add({-1, -1, -1});
  b.add({1, 1, 1});
  return b;
}

void expectNear(float3 a, float3 b, float tolerance = 1e-4f) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

// Where a world point lands in NDC through the camera.
float3 project(const Camera& camera, float aspect, float3 p) {
  float4 clip = camera.projection(aspect) * (camera.view() * float4{p, 1.0f});
  return clip.xyz() / clip.w;
}

TEST(OrbitCamera, FramesTheBoundsFromTheGivenDirection) {
  OrbitCamera orbit;
  orbit.frame(unitBounds(), {0, 0, 1}, 50.0f, 1.0f);
  expectNear(orbit.target(), {0, 0, 0});
  expectNear(orbit.forward(), {0, 0, -1});
  expectNear(orbit.up(), {0, 1, 0});
  EXPECT_NEAR(orbit.yawDegrees(), 0.0f, 1e-4f);
  EXPECT_NEAR(orbit.pitchDegrees(), 0.0f, 1e-4f);
  // Every corner of the box is in view, between near and far.
  const Camera camera = orbit.camera();
  for (int i = 0; i < 8; ++i) {
    const float3 corner{i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f};
    const float3 ndc = project(camera, 1.0f, corner);
    EXPECT_LT(std::fabs(ndc.x), 1.0f);
    EXPECT_LT(std::fabs(ndc.y), 1.0f);
    EXPECT_GT(ndc.z, -1.0f);
    EXPECT_LT(ndc.z, 1.0f);
  }
}

TEST(OrbitCamera, DraggingRightTurnsTheModelRight) {
  OrbitCamera orbit;
  orbit.frame(unitBounds(), {0, 0, 1}, 50.0f, 1.0f);
  // A point on the front of the model moves right on screen when the drag goes right.
  const float before = project(orbit.camera(), 1.0f, {0, 0, 1}).x;
  orbit.orbit(0.1f, 0.0f);
  const float after = project(orbit.camera(), 1.0f, {0, 0, 1}).x;
  EXPECT_GT(after, before + 0.05f);
  // Half the viewport height is 90 degrees.
  orbit.orbit(0.4f, 0.0f);
  EXPECT_NEAR(orbit.yawDegrees(), -90.0f, 1e-3f);
  expectNear(orbit.position(), {-orbit.distance(), 0, 0}, 1e-3f);
}

TEST(OrbitCamera, DraggingDownTipsTheTopTowardTheViewerAndStopsAtThePole) {
  OrbitCamera orbit;
  orbit.frame(unitBounds(), {0, 0, 1}, 50.0f, 1.0f);
  orbit.orbit(0.0f, 0.25f);
  EXPECT_NEAR(orbit.pitchDegrees(), 45.0f, 1e-3f);
  EXPECT_GT(orbit.position().y, 0.0f);
  orbit.orbit(0.0f, 5.0f);
  EXPECT_EQ(orbit.pitchDegrees(), 90.0f);
  // Straight above, the view is still well defined: looking down, screen up is -Z.
  expectNear(orbit.forward(), {0, -1, 0});
  expectNear(orbit.up(), {0, 0, -1});
  const float4x4 view = orbit.camera().view();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_TRUE(std::isfinite(view(i, j)));
  orbit.orbit(0.0f, -10.0f);
  EXPECT_EQ(orbit.pitchDegrees(), -90.0f);
}

TEST(OrbitCamera, PanMovesTheTargetWithThePointer) {
  OrbitCamera orbit;
  orbit.frame(unitBounds(), {0, 0, 1}, 50.0f, 1.0f);
  const Camera before = orbit.camera();
  // The point at the target moves right by the drag: a tenth of the viewport height is 0.2 NDC.
  orbit.pan(0.1f, 0.0f);
  const float3 ndc = project(orbit.camera(), 1.0f, {0, 0, 0});
  EXPECT_NEAR(ndc.x, 0.2f, 1e-4f);
  EXPECT_NEAR(ndc.y, 0.0f, 1e-4f);
  // Down on screen is down in NDC (y up).
  orbit.pan(-0.1f, 0.05f);
  EXPECT_NEAR(project(orbit.camera(), 1.0f, {0, 0, 0}).y, -0.1f, 1e-4f);
  EXPECT_NEAR(orbit.distance(), length(before.position - before.target), 1e-4f);
}

TEST(OrbitCamera, ZoomStepsScaleTheDistanceAndStayBounded) {
  OrbitCamera orbit;
  orbit.frame(unitBounds(), {0, 0, 1}, 50.0f, 1.0f);
  const float start = orbit.distance();
  orbit.zoom(1.0f);
  EXPECT_NEAR(orbit.distance(), start * 0.9f, 1e-4f);
  orbit.zoom(-2.0f);
  EXPECT_NEAR(orbit.distance(), start / 0.9f, 1e-4f);
  orbit.zoom(1000.0f);
  EXPECT_GT(orbit.distance(), 0.0f);
  // Even zoomed into the model, near is positive and below far.
  const Camera inside = orbit.camera();
  EXPECT_GT(inside.near_z, 0.0f);
  EXPECT_LT(inside.near_z, inside.far_z);
  orbit.zoom(-100000.0f);
  EXPECT_TRUE(std::isfinite(orbit.distance()));
}

TEST(OrbitCamera, PresetsLookFromF3dsDirectionsAndResetReturnsHome) {
  OrbitCamera orbit;
  orbit.frame(unitBounds(), {0.6f, 0.45f, 1.0f}, 50.0f, 1.5f);
  const float3 home = orbit.position();
  orbit.setView(ViewPreset::kFront);
  expectNear(orbit.forward(), {0, 0, -1});
  orbit.setView(ViewPreset::kRight);
  expectNear(orbit.forward(), {-1, 0, 0});
  expectNear(orbit.up(), {0, 1, 0});
  orbit.setView(ViewPreset::kTop);
  expectNear(orbit.forward(), {0, -1, 0});
  orbit.setView(ViewPreset::kIsometric);
  expectNear(orbit.forward(), normalize(float3{-1, -1, -1}));
  orbit.pan(0.3f, 0.2f);
  orbit.zoom(3.0f);
  orbit.reset();
  expectNear(orbit.position(), home);
  expectNear(orbit.target(), {0, 0, 0});
}

TEST(OrbitCamera, NearAndFarBracketTheModelFromAfar) {
  OrbitCamera orbit;
  orbit.frame(unitBounds(), {0, 0, 1}, 50.0f, 1.0f);
  orbit.zoom(-5.0f);  // far away
  const Camera far_camera = orbit.camera();
  const float depth = length(far_camera.position);
  EXPECT_LT(far_camera.near_z, depth - std::sqrt(3.0f) + 1e-3f);
  EXPECT_GT(far_camera.far_z, depth + std::sqrt(3.0f) - 1e-3f);
}

InputEvent press(MouseButton button, float x, float y, bool shift = false) {
  InputEvent e;
  e.type = InputEvent::Type::kButtonDown;
  e.button = button;
  e.x = x, e.y = y;
  e.shift = shift;
  return e;
}

InputEvent release(MouseButton button) {
  InputEvent e;
  e.type = InputEvent::Type::kButtonUp;
  e.button = button;
  return e;
}

InputEvent motion(float x, float y, bool shift = false) {
  InputEvent e;
  e.type = InputEvent::Type::kMotion;
  e.x = x, e.y = y;
  e.shift = shift;
  return e;
}

InputEvent key(Key k, bool shift = false) {
  InputEvent e;
  e.type = InputEvent::Type::kKeyDown;
  e.key = k;
  e.shift = shift;
  return e;
}

TEST(InputState, LeftDragOrbitsInFractionsOfTheViewportHeight) {
  InputState input;
  EXPECT_FALSE(input.handle(motion(10, 10), 200.0f));  // no button: nothing
  EXPECT_FALSE(input.handle(press(MouseButton::kLeft, 10, 10), 200.0f));
  EXPECT_TRUE(input.dragging());
  std::optional<Action> a = input.handle(motion(30, 0), 200.0f);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->type, Action::Type::kOrbit);
  EXPECT_FLOAT_EQ(a->dx, 0.1f);
  EXPECT_FLOAT_EQ(a->dy, -0.05f);
  // Deltas are from the last position, not the press.
  a = input.handle(motion(40, 0), 200.0f);
  ASSERT_TRUE(a);
  EXPECT_FLOAT_EQ(a->dx, 0.05f);
  EXPECT_FALSE(input.handle(release(MouseButton::kLeft), 200.0f));
  EXPECT_FALSE(input.dragging());
  EXPECT_FALSE(input.handle(motion(90, 90), 200.0f));
}

TEST(InputState, MiddleOrShiftLeftDragPans) {
  InputState input;
  input.handle(press(MouseButton::kMiddle, 0, 0), 100.0f);
  std::optional<Action> a = input.handle(motion(10, 20), 100.0f);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->type, Action::Type::kPan);
  EXPECT_FLOAT_EQ(a->dx, 0.1f);
  EXPECT_FLOAT_EQ(a->dy, 0.2f);
  input.handle(release(MouseButton::kMiddle), 100.0f);

  input.handle(press(MouseButton::kLeft, 0, 0, /*shift=*/true), 100.0f);
  // Letting go of shift mid-drag does not turn the pan into an orbit.
  a = input.handle(motion(5, 0, /*shift=*/false), 100.0f);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->type, Action::Type::kPan);
}

TEST(InputState, OnlyTheButtonThatStartedADragEndsIt) {
  InputState input;
  input.handle(press(MouseButton::kLeft, 0, 0), 100.0f);
  input.handle(press(MouseButton::kMiddle, 0, 0), 100.0f);
  input.handle(release(MouseButton::kMiddle), 100.0f);
  std::optional<Action> a = input.handle(motion(10, 0), 100.0f);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->type, Action::Type::kOrbit);
  // Losing focus ends the drag (the release goes elsewhere).
  InputEvent lost;
  lost.type = InputEvent::Type::kFocusLost;
  input.handle(lost, 100.0f);
  EXPECT_FALSE(input.handle(motion(20, 0), 100.0f));
  // The right button starts nothing.
  input.handle(press(MouseButton::kRight, 0, 0), 100.0f);
  EXPECT_FALSE(input.dragging());
}

TEST(InputState, WheelZoomsAndKeysMapAsInF3d) {
  InputState input;
  InputEvent wheel;
  wheel.type = InputEvent::Type::kWheel;
  wheel.wheel = 2.0f;
  std::optional<Action> a = input.handle(wheel, 100.0f);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->type, Action::Type::kZoom);
  EXPECT_EQ(a->steps, 2.0f);

  auto viewOf = [&](Key k) {
    std::optional<Action> action = input.handle(key(k), 100.0f);
    EXPECT_TRUE(action && action->type == Action::Type::kSetView);
    return action ? action->view : ViewPreset::kFront;
  };
  EXPECT_EQ(viewOf(Key::kOne), ViewPreset::kFront);
  EXPECT_EQ(viewOf(Key::kThree), ViewPreset::kRight);
  EXPECT_EQ(viewOf(Key::kSeven), ViewPreset::kTop);
  EXPECT_EQ(viewOf(Key::kNine), ViewPreset::kIsometric);
  const std::pair<Key, Action::Type> commands[] = {
      {Key::kEnter, Action::Type::kResetCamera},    {Key::kEscape, Action::Type::kQuit},
      {Key::kF1, Action::Type::kToggleStats},       {Key::kF2, Action::Type::kToggleWorldAxes},
      {Key::kF3, Action::Type::kToggleObjectAxes},  {Key::kF12, Action::Type::kScreenshot},
      {Key::kF10, Action::Type::kToggleJitter},     {Key::kH, Action::Type::kToggleKeyList},
      {Key::kF4, Action::Type::kCycleProjection},   {Key::kF5, Action::Type::kStoreCrc},
      {Key::kF6, Action::Type::kCompareCrc},        {Key::kF11, Action::Type::kCycleAnalysisView},
      {Key::kSpace, Action::Type::kTogglePlayback}, {Key::kS, Action::Type::kToggleShadows},
  };
  for (const auto& [k, type] : commands) {
    a = input.handle(key(k), 100.0f);
    ASSERT_TRUE(a);
    EXPECT_EQ(a->type, type);
  }
  EXPECT_FALSE(input.handle(key(Key::kOther), 100.0f));
}

TEST(InputState, ShiftPicksTheSecondRowOfFunctionKeysAndNothingElse) {
  InputState input;
  std::optional<Action> a = input.handle(key(Key::kF3, true), 100.0f);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->type, Action::Type::kCycleMsaa);
  a = input.handle(key(Key::kF12, true), 100.0f);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->type, Action::Type::kToggleTemporal);
  a = input.handle(key(Key::kF1, true), 100.0f);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->type, Action::Type::kToggleTileHeatmap);
  a = input.handle(key(Key::kF2, true), 100.0f);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->type, Action::Type::kToggleCommitPath);
  // Shift+F4, F5, F6, F10 and F11 do not fall back to F4, F5, F6, F10, F11.
  for (Key k : {Key::kF4, Key::kF5, Key::kF6, Key::kF10, Key::kF11})
    EXPECT_FALSE(input.handle(key(k, true), 100.0f));
  // Keys with no second row ignore Shift.
  a = input.handle(key(Key::kSeven, true), 100.0f);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->view, ViewPreset::kTop);
  a = input.handle(key(Key::kH, true), 100.0f);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->type, Action::Type::kToggleKeyList);
}

TEST(InputState, SpacePlaysOrPausesTheAnimationAndMovesNoCamera) {
  InputState input;
  for (bool shift : {false, true}) {
    std::optional<Action> a = input.handle(key(Key::kSpace, shift), 100.0f);
    ASSERT_TRUE(a);
    EXPECT_EQ(a->type, Action::Type::kTogglePlayback);
    OrbitCamera camera;
    EXPECT_FALSE(applyCameraAction(*a, camera));
  }
}

TEST(InputState, TheKeyListNamesEveryMappedKeyAndOnlyThose) {
  auto listed = [](Key k, bool shift) {
    for (const KeyHelp& help : keyList())
      for (const KeyChord& chord : help.chords)
        if (chord.key == k && chord.shift == shift) return true;
    return false;
  };
  int mapped = 0;
  for (int i = 0; i < static_cast<int>(Key::kOther); ++i) {
    const Key k = static_cast<Key>(i);
    const bool shift_differs =
        keyAction(k, true).has_value() != keyAction(k, false).has_value() ||
        (keyAction(k, true) && keyAction(k, true)->type != keyAction(k)->type);
    for (bool shift : {false, true}) {
      if (shift && !shift_differs) continue;  // the same action: listed once, unshifted
      if (!keyAction(k, shift)) continue;
      ++mapped;
      EXPECT_TRUE(listed(k, shift))
          << "key " << i << (shift ? " with shift" : "") << " is unlisted";
    }
  }
  // 1 3 7 9 Enter Escape H S space F1-F6 F10-F12, Shift+F1, Shift+F2, Shift+F3, Shift+F12
  EXPECT_EQ(mapped, 22);
  EXPECT_TRUE(listed(Key::kS, false));
  EXPECT_TRUE(listed(Key::kSpace, false));
  EXPECT_TRUE(listed(Key::kF5, false));
  EXPECT_TRUE(listed(Key::kF6, false));
  EXPECT_TRUE(listed(Key::kF4, false));
  EXPECT_FALSE(listed(Key::kF4, true));
  EXPECT_TRUE(listed(Key::kF11, false));
  EXPECT_TRUE(listed(Key::kF1, true));
  EXPECT_TRUE(listed(Key::kF2, true));
  for (const KeyHelp& help : keyList()) {
    EXPECT_FALSE(help.keys.empty());
    EXPECT_FALSE(help.action.empty());
    for (const KeyChord& chord : help.chords)
      EXPECT_TRUE(keyAction(chord.key, chord.shift))
          << help.keys << " lists a key that does nothing";
  }
}

TEST(InputState, CameraActionsReachTheCameraAndOthersDoNot) {
  OrbitCamera orbit;
  orbit.frame(unitBounds(), {0, 0, 1}, 50.0f, 1.0f);
  Action turn;
  turn.type = Action::Type::kOrbit;
  turn.dx = 0.5f;
  EXPECT_TRUE(applyCameraAction(turn, orbit));
  EXPECT_NEAR(orbit.yawDegrees(), -90.0f, 1e-3f);
  Action stats;
  stats.type = Action::Type::kToggleStats;
  EXPECT_FALSE(applyCameraAction(stats, orbit));
  Action reset;
  reset.type = Action::Type::kResetCamera;
  EXPECT_TRUE(applyCameraAction(reset, orbit));
  EXPECT_NEAR(orbit.yawDegrees(), 0.0f, 1e-4f);
}

Scene cubeScene() {
  Scene scene;
  Object object;
  object.mesh = std::make_shared<Mesh>(makeCube());
  scene.objects.push_back(object);
  return scene;
}

// Waits (generously) for the loader's result.
std::optional<Expected<LoadedScene>> waitForResult(SceneLoader& loader) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    if (std::optional<Expected<LoadedScene>> result = loader.takeResult()) return result;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return std::nullopt;
}

TEST(SceneLoader, RunsOffTheCallingThreadAndHandsTheResultOverOnce) {
  SceneLoader loader;
  EXPECT_FALSE(loader.busy());
  std::atomic<bool> release{false};
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<bool> other_thread{false};
  std::atomic<bool> finished{false};
  loader.start("cube.obj", [&]() -> Expected<LoadedScene> {
    other_thread = std::this_thread::get_id() != caller;
    while (!release) std::this_thread::yield();
    LoadedScene loaded;
    loaded.scene = cubeScene();
    finished = true;
    return loaded;
  });
  EXPECT_EQ(loader.name(), "cube.obj");
  // While the load runs, the caller is not blocked and there is no result.
  EXPECT_TRUE(loader.busy());
  EXPECT_FALSE(loader.takeResult());
  release = true;
  while (!finished) std::this_thread::yield();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  // Finished but not taken: still busy, so a caller that polls while busy() gets the result.
  EXPECT_TRUE(loader.busy());
  std::optional<Expected<LoadedScene>> result = waitForResult(loader);
  ASSERT_TRUE(result);
  ASSERT_TRUE(result->ok());
  EXPECT_EQ(result->value().scene.triangleCount(), 12u);
  EXPECT_TRUE(other_thread);
  EXPECT_FALSE(loader.busy());
  EXPECT_FALSE(loader.takeResult());
}

TEST(SceneLoader, TheLatestLoadWinsAndErrorsComeBackAsErrors) {
  SceneLoader loader;
  std::atomic<bool> release{false};
  loader.start("slow.obj", [&]() -> Expected<LoadedScene> {
    while (!release) std::this_thread::yield();
    LoadedScene loaded;
    loaded.scene = cubeScene();
    return loaded;
  });
  loader.start("bad.obj",
               []() -> Expected<LoadedScene> { return makeError("bad.obj:3: nonsense"); });
  std::optional<Expected<LoadedScene>> result = waitForResult(loader);
  ASSERT_TRUE(result);
  ASSERT_FALSE(result->ok());
  EXPECT_EQ(result->error().message, "bad.obj:3: nonsense");
  // The superseded load finishes later and its scene is dropped.
  release = true;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(200);
  while (std::chrono::steady_clock::now() < deadline) EXPECT_FALSE(loader.takeResult());
  EXPECT_FALSE(loader.busy());
}

TEST(SceneLoader, AnExceptionBecomesAnError) {
  SceneLoader loader;
  loader.start("huge.obj", []() -> Expected<LoadedScene> { throw std::bad_alloc(); });
  std::optional<Expected<LoadedScene>> result = waitForResult(loader);
  ASSERT_TRUE(result);
  ASSERT_FALSE(result->ok());
  EXPECT_NE(result->error().message.find("out of memory"), std::string::npos);
}

}  // namespace
