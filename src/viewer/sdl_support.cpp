#include "sdl_support.h"

#include <cstdlib>
#include <string>

#if defined(TESSERA_HAS_X11)
#include <X11/Xlib.h>
#endif

namespace tessera::viewer {
namespace {

#if defined(TESSERA_HAS_X11)
// Xlib's handler before ours: every error but the one below goes to it (its default prints the
// error and exits).
XErrorHandler previous_x_error_handler = nullptr;

// A request on a window that no longer exists (BadWindow) is not fatal. A viewer once ended with
// status 1 as it quit, on Xlib's default handler, for an X_SendEvent to its own window after
// that was gone: most likely SDL 2.26 sending a wake-up to a destroyed window (SDL 2.28's
// SDL_DestroyWindow clears a pending one).
int ignoreStaleWindowErrors(Display* display, XErrorEvent* error) {
  if (error->error_code == BadWindow) return 0;
  return previous_x_error_handler ? previous_x_error_handler(display, error) : 0;
}
#endif

}  // namespace

SdlSession::~SdlSession() {
  if (ttf_) TTF_Quit();
  if (video_) SDL_Quit();
}

Expected<void> SdlSession::start() {
  // A desktop citizen: let the screen saver run, and let the first click on the window start
  // a drag rather than only focus it.
  SDL_SetHint(SDL_HINT_VIDEO_ALLOW_SCREENSAVER, "1");
  SDL_SetHint(SDL_HINT_MOUSE_FOCUS_CLICKTHROUGH, "1");
#if defined(TESSERA_HAS_X11)
  // Before SDL_Init: SDL's x11 driver keeps the handler it finds as the one to forward to, and
  // puts it back when it closes the display at SDL_Quit, where a late BadWindow still arrives.
  // Installed after SDL_Init, ours was replaced by Xlib's default at quit. Harmless with any other
  // driver.
  if (previous_x_error_handler == nullptr)
    previous_x_error_handler = XSetErrorHandler(ignoreStaleWindowErrors);
#endif
  if (SDL_Init(SDL_INIT_VIDEO) != 0) {
    const char* driver = std::getenv("SDL_VIDEODRIVER");
    std::string message = std::string("cannot open a window: ") + SDL_GetError();
    if (driver != nullptr && *driver != '\0')
      message += " (SDL_VIDEODRIVER=" + std::string(driver) + ")";
    else if (std::getenv("DISPLAY") == nullptr && std::getenv("WAYLAND_DISPLAY") == nullptr)
      message += " (neither DISPLAY nor WAYLAND_DISPLAY is set: is there a display?)";
    return makeError(message);
  }
  video_ = true;
  // Debian's SDL falls back to an invisible driver when there is no display; a viewer that
  // shows nothing is no viewer, unless that driver was asked for by name.
  const std::string current = SDL_GetCurrentVideoDriver() ? SDL_GetCurrentVideoDriver() : "";
  const char* requested = std::getenv("SDL_VIDEODRIVER");
  if ((current == "offscreen" || current == "dummy" || current == "evdev") &&
      (requested == nullptr || current != requested))
    return makeError("cannot open a window: no display (SDL found none and fell back to its '" +
                     current +
                     "' driver); set DISPLAY (X11) or WAYLAND_DISPLAY, or run under xvfb-run");
  if (TTF_Init() != 0) return makeError(std::string("cannot start SDL2_ttf: ") + TTF_GetError());
  ttf_ = true;
  return {};
}

Expected<void> openWindow(int width, int height, bool fullscreen, SdlPtr<SDL_Window>& window,
                          SdlPtr<SDL_Renderer>& renderer) {
  // Hidden until the renderer exists: an OpenGL renderer makes SDL destroy the window and create
  // it again, and a window shown before that would appear, vanish and come back under a new id
  // (a flicker, and a stale id for anything that found the first one).
  Uint32 flags = SDL_WINDOW_RESIZABLE | SDL_WINDOW_ALLOW_HIGHDPI | SDL_WINDOW_HIDDEN;
  if (fullscreen) flags |= SDL_WINDOW_FULLSCREEN_DESKTOP;
  window.reset(SDL_CreateWindow("tessera view", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED,
                                width, height, flags));
  if (!window) return makeError(std::string("cannot create a window: ") + SDL_GetError());
  // No vsync: the loop paces itself to -fps and the render time stays measurable.
  renderer.reset(SDL_CreateRenderer(window.get(), -1, 0));
  if (!renderer) renderer.reset(SDL_CreateRenderer(window.get(), -1, SDL_RENDERER_SOFTWARE));
  if (!renderer) return makeError(std::string("cannot create a renderer: ") + SDL_GetError());
  SDL_ShowWindow(window.get());
  return {};
}

namespace {

Key toKey(SDL_Keycode code) {
  switch (code) {
    case SDLK_1:
    case SDLK_KP_1:
      return Key::kOne;
    case SDLK_3:
    case SDLK_KP_3:
      return Key::kThree;
    case SDLK_7:
    case SDLK_KP_7:
      return Key::kSeven;
    case SDLK_9:
    case SDLK_KP_9:
      return Key::kNine;
    case SDLK_RETURN:
    case SDLK_KP_ENTER:
      return Key::kEnter;
    case SDLK_ESCAPE:
      return Key::kEscape;
    case SDLK_h:
      return Key::kH;
    case SDLK_s:
      return Key::kS;
    case SDLK_SPACE:
      return Key::kSpace;
    case SDLK_F1:
      return Key::kF1;
    case SDLK_F2:
      return Key::kF2;
    case SDLK_F3:
      return Key::kF3;
    case SDLK_F4:
      return Key::kF4;
    case SDLK_F5:
      return Key::kF5;
    case SDLK_F6:
      return Key::kF6;
    case SDLK_F10:
      return Key::kF10;
    case SDLK_F11:
      return Key::kF11;
    case SDLK_F12:
      return Key::kF12;
    default:
      return Key::kOther;
  }
}

std::optional<MouseButton> toButton(Uint8 button) {
  switch (button) {
    case SDL_BUTTON_LEFT:
      return MouseButton::kLeft;
    case SDL_BUTTON_MIDDLE:
      return MouseButton::kMiddle;
    case SDL_BUTTON_RIGHT:
      return MouseButton::kRight;
    default:
      return std::nullopt;
  }
}

}  // namespace

std::optional<InputEvent> toInputEvent(const SDL_Event& e) {
  InputEvent in;
  in.shift = (SDL_GetModState() & KMOD_SHIFT) != 0;
  switch (e.type) {
    case SDL_MOUSEBUTTONDOWN:
    case SDL_MOUSEBUTTONUP: {
      std::optional<MouseButton> button = toButton(e.button.button);
      if (!button) return std::nullopt;
      in.type = e.type == SDL_MOUSEBUTTONDOWN ? InputEvent::Type::kButtonDown
                                              : InputEvent::Type::kButtonUp;
      in.button = *button;
      in.x = static_cast<float>(e.button.x), in.y = static_cast<float>(e.button.y);
      return in;
    }
    case SDL_MOUSEMOTION:
      in.type = InputEvent::Type::kMotion;
      in.x = static_cast<float>(e.motion.x), in.y = static_cast<float>(e.motion.y);
      return in;
    case SDL_MOUSEWHEEL:
      in.type = InputEvent::Type::kWheel;
      in.wheel = e.wheel.preciseY;
      if (e.wheel.direction == SDL_MOUSEWHEEL_FLIPPED) in.wheel = -in.wheel;
      return in;
    case SDL_KEYDOWN:
      if (e.key.repeat != 0) return std::nullopt;  // toggles must not flicker while held
      in.type = InputEvent::Type::kKeyDown;
      in.key = toKey(e.key.keysym.sym);
      // The event's own modifiers: the state when the key went down, not when it is read.
      in.shift = (e.key.keysym.mod & KMOD_SHIFT) != 0;
      return in;
    case SDL_WINDOWEVENT:
      if (e.window.event != SDL_WINDOWEVENT_FOCUS_LOST) return std::nullopt;
      in.type = InputEvent::Type::kFocusLost;
      return in;
    default:
      return std::nullopt;
  }
}

}  // namespace tessera::viewer
