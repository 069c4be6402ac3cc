#include <tessera/viewer/input_state.h>

#include <algorithm>

namespace tessera::viewer {

namespace {

std::optional<Action> act(Action::Type type) {
  Action action;
  action.type = type;
  return action;
}

std::optional<Action> view(ViewPreset preset) {
  Action action;
  action.type = Action::Type::kSetView, action.view = preset;
  return action;
}

// Shift + a function key: the second row of the map.
std::optional<Action> shiftedFunctionKey(Key key) {
  switch (key) {
    case Key::kF1:
      return act(Action::Type::kToggleTileHeatmap);
    case Key::kF2:
      return act(Action::Type::kToggleCommitPath);
    case Key::kF3:
      return act(Action::Type::kCycleMsaa);
    case Key::kF12:
      return act(Action::Type::kToggleTemporal);
    default:
      return std::nullopt;  // Shift+F4, F5, F6, F10, F11: not in this viewer
  }
}

}  // namespace

std::optional<Action> keyAction(Key key, bool shift) {
  const bool function_key = key == Key::kF1 || key == Key::kF2 || key == Key::kF3 ||
                            key == Key::kF4 || key == Key::kF5 || key == Key::kF6 ||
                            key == Key::kF10 || key == Key::kF11 || key == Key::kF12;
  if (shift && function_key) return shiftedFunctionKey(key);
  switch (key) {
    case Key::kOne:
      return view(ViewPreset::kFront);
    case Key::kThree:
      return view(ViewPreset::kRight);
    case Key::kSeven:
      return view(ViewPreset::kTop);
    case Key::kNine:
      return view(ViewPreset::kIsometric);
    case Key::kEnter:
      return act(Action::Type::kResetCamera);
    case Key::kEscape:
      return act(Action::Type::kQuit);
    case Key::kH:
      return act(Action::Type::kToggleKeyList);
    case Key::kSpace:
      return act(Action::Type::kTogglePlayback);
    case Key::kS:
      return act(Action::Type::kToggleShadows);
    case Key::kF1:
      return act(Action::Type::kToggleStats);
    case Key::kF2:
      return act(Action::Type::kToggleWorldAxes);
    case Key::kF3:
      return act(Action::Type::kToggleObjectAxes);
    case Key::kF4:
      return act(Action::Type::kCycleProjection);
    case Key::kF5:
      return act(Action::Type::kStoreCrc);
    case Key::kF6:
      return act(Action::Type::kCompareCrc);
    case Key::kF10:
      return act(Action::Type::kToggleJitter);
    case Key::kF11:
      return act(Action::Type::kCycleAnalysisView);
    case Key::kF12:
      return act(Action::Type::kScreenshot);
    case Key::kOther:
      break;
  }
  return std::nullopt;
}

int nextMsaa(int msaa) {
  return msaa >= 8 ? 1 : msaa * 2;
}

const std::vector<KeyHelp>& keyList() {
  static const std::vector<KeyHelp> list = {
      {"left drag", "orbit", {}},
      {"middle or Shift+left drag", "pan", {}},
      {"wheel", "zoom", {}},
      {"1 / 3 / 7 / 9",
       "front / right / top / isometric view",
       {{Key::kOne}, {Key::kThree}, {Key::kSeven}, {Key::kNine}}},
      {"Enter", "reset the camera", {{Key::kEnter}}},
      {"F1", "stats overlay", {{Key::kF1}}},
      {"F2 / F3", "world axes / object axes", {{Key::kF2}, {Key::kF3}}},
      {"F4", "cycle the projection", {{Key::kF4}}},
      {"F5 / F6", "store / compare the frame's CRC", {{Key::kF5}, {Key::kF6}}},
      {"F10", "sub-pixel jitter", {{Key::kF10}}},
      {"F11", "analysis view: off, tile field, density", {{Key::kF11}}},
      {"F12", "screenshot", {{Key::kF12}}},
      {"Shift+F1", "tile heatmap", {{Key::kF1, true}}},
      {"Shift+F2", "32-bit commit path (vulkan)", {{Key::kF2, true}}},
      {"Shift+F3", "MSAA 1, 2, 4, 8 samples", {{Key::kF3, true}}},
      {"Shift+F12", "temporal reprojection", {{Key::kF12, true}}},
      {"space", "play / pause the animation", {{Key::kSpace}}},
      {"S", "shadows", {{Key::kS}}},
      {"H", "this list", {{Key::kH}}},
      {"Escape", "quit", {{Key::kEscape}}},
  };
  return list;
}

std::optional<Action> InputState::handle(const InputEvent& event, float viewport_height) {
  switch (event.type) {
    case InputEvent::Type::kButtonDown: {
      if (drag_ != Drag::kNone) return std::nullopt;  // a second button joins nothing
      if (event.button == MouseButton::kLeft)
        drag_ = event.shift ? Drag::kPan : Drag::kOrbit;
      else if (event.button == MouseButton::kMiddle)
        drag_ = Drag::kPan;
      else
        return std::nullopt;
      drag_button_ = event.button;
      last_x_ = event.x, last_y_ = event.y;
      return std::nullopt;
    }
    case InputEvent::Type::kButtonUp:
      if (drag_ != Drag::kNone && event.button == drag_button_) drag_ = Drag::kNone;
      return std::nullopt;
    case InputEvent::Type::kFocusLost:
      // The release may never arrive (it goes to another window): end the drag now.
      drag_ = Drag::kNone;
      return std::nullopt;
    case InputEvent::Type::kMotion: {
      if (drag_ == Drag::kNone) return std::nullopt;
      const float scale = 1.0f / std::max(viewport_height, 1.0f);
      Action action;
      action.type = drag_ == Drag::kOrbit ? Action::Type::kOrbit : Action::Type::kPan;
      action.dx = (event.x - last_x_) * scale;
      action.dy = (event.y - last_y_) * scale;
      last_x_ = event.x, last_y_ = event.y;
      if (action.dx == 0.0f && action.dy == 0.0f) return std::nullopt;
      return action;
    }
    case InputEvent::Type::kWheel: {
      if (event.wheel == 0.0f) return std::nullopt;
      Action action;
      action.type = Action::Type::kZoom;
      action.steps = event.wheel;
      return action;
    }
    case InputEvent::Type::kKeyDown:
      return keyAction(event.key, event.shift);
  }
  return std::nullopt;
}

bool applyCameraAction(const Action& action, OrbitCamera& camera) {
  switch (action.type) {
    case Action::Type::kOrbit:
      camera.orbit(action.dx, action.dy);
      return true;
    case Action::Type::kPan:
      camera.pan(action.dx, action.dy);
      return true;
    case Action::Type::kZoom:
      camera.zoom(action.steps);
      return true;
    case Action::Type::kSetView:
      camera.setView(action.view);
      return true;
    case Action::Type::kResetCamera:
      camera.reset();
      return true;
    default:
      return false;
  }
}

}  // namespace tessera::viewer
