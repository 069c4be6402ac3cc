// The viewer's input mapping: window-system-neutral events in, viewer actions out. The SDL
// layer translates its events into InputEvent; everything here is plain data and unit-tested.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <tessera/viewer/orbit_camera.h>

namespace tessera::viewer {

enum class MouseButton { kLeft, kMiddle, kRight };

// The keys the viewer reacts to; every other key is kOther.
enum class Key {
  kOne,
  kThree,
  kSeven,
  kNine,
  kEnter,
  kEscape,
  kH,
  kS,
  kSpace,
  kF1,
  kF2,
  kF3,
  kF4,
  kF5,
  kF6,
  kF10,
  kF11,
  kF12,
  kOther
};

struct InputEvent {
  enum class Type { kButtonDown, kButtonUp, kMotion, kWheel, kKeyDown, kFocusLost };
  Type type = Type::kMotion;
  MouseButton button = MouseButton::kLeft;  // kButtonDown, kButtonUp
  float x = 0, y = 0;                       // pointer position in window coordinates (points)
  float wheel = 0;                          // kWheel: steps, positive away from the user
  Key key = Key::kOther;                    // kKeyDown
  bool shift = false;  // shift held (kButtonDown picks pan with it; kKeyDown: Shift+F3...)
};

struct Action {
  enum class Type {
    kOrbit,    // dx, dy: fractions of the viewport height
    kPan,      // dx, dy: fractions of the viewport height
    kZoom,     // steps
    kSetView,  // view
    kResetCamera,
    kToggleStats,
    kToggleWorldAxes,
    kToggleObjectAxes,
    kCycleProjection,  // perspective, cylindrical, spherical, stereographic, fisheye
    kScreenshot,
    kStoreCrc,           // remember the CRC-32 of the frame shown
    kCompareCrc,         // compare the frame shown with it: MATCH / MISMATCH
    kToggleTileHeatmap,  // the per-tile occupancy heatmap instead of the frame
    kCycleAnalysisView,  // off, tile field (covered fraction), per-pixel density
    kToggleCommitPath,   // the vulkan compute backend's 32-bit visibility commit path
    kCycleMsaa,          // 1, 2, 4, 8 samples per pixel
    kToggleJitter,       // sub-pixel jitter, a new offset each frame
    kToggleTemporal,     // temporal reprojection of the jittered frames
    kToggleKeyList,      // the in-window list of keys
    kTogglePlayback,     // play or pause the model's animation
    kToggleShadows,      // shadow maps (RenderOptions::shadows; the cpu backend draws them)
    kQuit,
  };
  Type type = Type::kOrbit;
  float dx = 0, dy = 0;
  float steps = 0;
  ViewPreset view = ViewPreset::kFront;
};

// The keyboard map (ARCHITECTURE.md, "The viewer's keys"): f3d's keys, and the function keys
// with Shift for the second row. A shifted function key the viewer has no action for does
// nothing (it never falls back to the unshifted key's action); the other keys ignore Shift.
std::optional<Action> keyAction(Key key, bool shift = false);

// The next sample count of Shift+F3's cycle: 1 -> 2 -> 4 -> 8 -> 1.
int nextMsaa(int msaa);

// One line of the in-window key list: the keys as printed, what they do, and the keys it names
// (so that a test can hold the list and keyAction to each other).
struct KeyChord {
  Key key = Key::kOther;
  bool shift = false;
};
struct KeyHelp {
  std::string keys;
  std::string action;
  std::vector<KeyChord> chords;  // empty for the mouse lines
};
// Every key the viewer implements, and the mouse, in the order the list shows them.
const std::vector<KeyHelp>& keyList();

// Which drag a button press starts and where the pointer was; turns pointer motion into orbit
// and pan actions. The kind of drag is chosen at the press (left: orbit, shift + left or middle:
// pan) and holds until that button is released.
class InputState {
 public:
  // `viewport_height`: the window's height in the same units as the event coordinates.
  std::optional<Action> handle(const InputEvent& event, float viewport_height);

  bool dragging() const { return drag_ != Drag::kNone; }

 private:
  enum class Drag { kNone, kOrbit, kPan };
  Drag drag_ = Drag::kNone;
  MouseButton drag_button_ = MouseButton::kLeft;
  float last_x_ = 0, last_y_ = 0;
};

// Applies a camera action (orbit, pan, zoom, view, reset) to `camera`; returns false for the
// other actions, which the caller handles.
bool applyCameraAction(const Action& action, OrbitCamera& camera);

}  // namespace tessera::viewer
