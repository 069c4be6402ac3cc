// The SDL plumbing of the viewer: owning pointers, SDL_Init and its quit, and SDL events as the
// input mapping (input_state.h) sees them.
#pragma once

#include <SDL.h>
#include <SDL_ttf.h>

#include <memory>
#include <optional>

#include <tessera/base/expected.h>
#include <tessera/viewer/input_state.h>

namespace tessera::viewer {

struct SdlDeleter {
  void operator()(SDL_Window* w) const { SDL_DestroyWindow(w); }
  void operator()(SDL_Renderer* r) const { SDL_DestroyRenderer(r); }
  void operator()(SDL_Texture* t) const { SDL_DestroyTexture(t); }
  void operator()(SDL_Surface* s) const { SDL_FreeSurface(s); }
  void operator()(TTF_Font* f) const { TTF_CloseFont(f); }
};
template <typename T>
using SdlPtr = std::unique_ptr<T, SdlDeleter>;

// SDL_Init / TTF_Init and their matching quits.
class SdlSession {
 public:
  SdlSession() = default;
  SdlSession(const SdlSession&) = delete;
  SdlSession& operator=(const SdlSession&) = delete;
  ~SdlSession();
  // Fails on no display, a video driver that shows nothing, or no SDL2_ttf.
  Expected<void> start();

 private:
  bool video_ = false;
  bool ttf_ = false;
};

// The viewer's window ("tessera view", resizable, fullscreen if asked) and its renderer (SDL's
// first choice, else software; no vsync), shown once both exist.
Expected<void> openWindow(int width, int height, bool fullscreen, SdlPtr<SDL_Window>& window,
                          SdlPtr<SDL_Renderer>& renderer);

// The SDL event as the input mapping sees it; nullopt for events it does not take.
std::optional<InputEvent> toInputEvent(const SDL_Event& e);

}  // namespace tessera::viewer
