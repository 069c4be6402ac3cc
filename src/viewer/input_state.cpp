#include <tessera/viewer/input_state.h>

#include <algorithm>

namespace tessera::viewer {

std::optional<Action> keyAction(Key key) {
  Action action;
  switch (key) {
    case Key::kOne:
      action.type = Action::Type::kSetView, action.view = ViewPreset::kFront;
      return action;
    case Key::kThree:
      action.type = Action::Type::kSetView, action.view = ViewPreset::kRight;
      return action;
    case Key::kSeven:
      action.type = Action::Type::kSetView, action.view = ViewPreset::kTop;
      return action;
    case Key::kNine:
      action.type = Action::Type::kSetView, action.view = ViewPreset::kIsometric;
      return action;
    case Key::kEnter:
      action.type = Action::Type::kResetCamera;
      return action;
    case Key::kEscape:
      action.type = Action::Type::kQuit;
      return action;
    case Key::kF1:
      action.type = Action::Type::kToggleStats;
      return action;
    case Key::kF2:
      action.type = Action::Type::kToggleWorldAxes;
      return action;
    case Key::kF3:
      action.type = Action::Type::kToggleObjectAxes;
      return action;
    case Key::kF12:
      action.type = Action::Type::kScreenshot;
      return action;
    case Key::kOther:
      break;
  }
  return std::nullopt;
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
      return keyAction(event.key);
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
