// The SDL2 side of the viewer: window, events, presenting frames, the text overlay and
// screenshots. Camera and input logic live in orbit_camera / input_state (no SDL).
#include <tessera/viewer/viewer.h>

#include <SDL.h>
#include <SDL_ttf.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include <tessera/io/image_writer.h>
#include <tessera/render/frame.h>
#include <tessera/viewer/input_state.h>
#include <tessera/viewer/orbit_camera.h>
#include <tessera/viewer/scene_loader.h>

namespace tessera::viewer {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

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
  ~SdlSession() {
    if (ttf_) TTF_Quit();
    if (video_) SDL_Quit();
  }
  Expected<void> start() {
    // A desktop citizen: let the screen saver run, and let the first click on the window start
    // a drag rather than only focus it.
    SDL_SetHint(SDL_HINT_VIDEO_ALLOW_SCREENSAVER, "1");
    SDL_SetHint(SDL_HINT_MOUSE_FOCUS_CLICKTHROUGH, "1");
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

 private:
  bool video_ = false;
  bool ttf_ = false;
};

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
    case SDLK_F1:
      return Key::kF1;
    case SDLK_F2:
      return Key::kF2;
    case SDLK_F3:
      return Key::kF3;
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

// The SDL event as the input mapping sees it; nullopt for events it does not take.
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
      return in;
    case SDL_WINDOWEVENT:
      if (e.window.event != SDL_WINDOWEVENT_FOCUS_LOST) return std::nullopt;
      in.type = InputEvent::Type::kFocusLost;
      return in;
    default:
      return std::nullopt;
  }
}

fs::path nextScreenshotPath() {
  for (int n = 1; n < 100000; ++n) {
    char name[32];
    std::snprintf(name, sizeof name, "screenshot-%04d.png", n);
    std::error_code ec;
    if (!fs::exists(name, ec) && !ec) return fs::absolute(name, ec);
  }
  return fs::absolute("screenshot-overflow.png");
}

// The length of the axes that show a scene's extent.
float axesLength(const Bounds& bounds) {
  if (bounds.empty()) return 1.0f;
  return std::max(bounds.radius(), 1e-6f);
}

class Viewer {
 public:
  Viewer(const ViewerOptions& options, Backend& backend, const ViewerHooks& hooks)
      : options_(options), backend_(backend), hooks_(hooks) {
    stats_ = options.stats;
    world_axes_ = options.world_axes;
    render_options_.depth = false;
    render_options_.ids = false;
    render_options_.lines = true;
  }

  Expected<void> open(const fs::path& font_path);
  void run(const std::optional<fs::path>& model);

 private:
  void startLoad(const fs::path& path);
  void takeLoadResult();
  void showScene(Scene scene, const std::string& name);
  void handleEvent(const SDL_Event& event);
  void handleAction(const Action& action);
  void drawFrame();
  void drawOverlay(int pixel_width, int pixel_height);
  void drawTextBox(const std::string& text, int x, int y, bool from_bottom, SDL_Color color,
                   int wrap_width);
  void saveScreenshot(int pixel_width, int pixel_height);
  float pixelAspect() const;
  void ensureFont(float pixel_scale);

  ViewerOptions options_;
  Backend& backend_;
  const ViewerHooks& hooks_;
  // Declared before the SDL objects: destroyed after the window is gone, so a quit during a
  // long load closes the window at once and only then waits for the loading thread.
  SceneLoader loader_;
  SdlPtr<SDL_Window> window_;
  SdlPtr<SDL_Renderer> renderer_;
  SdlPtr<SDL_Texture> texture_;
  int texture_width_ = 0, texture_height_ = 0;
  SdlPtr<TTF_Font> font_;
  int font_size_ = 0;
  fs::path font_path_;

  Scene scene_;
  std::string scene_name_;
  bool has_scene_ = false;
  bool announce_scene_ = false;  // print "showing ..." after the scene's first frame
  OrbitCamera camera_;
  InputState input_;
  RenderOptions render_options_;
  Frame frame_;

  bool stats_ = false;
  bool world_axes_ = false;
  bool object_axes_ = false;
  bool quit_ = false;
  bool dirty_ = true;         // the window needs presenting again
  bool view_changed_ = true;  // ...and the scene rendering again (camera, scene or axes changed)
  bool screenshot_requested_ = false;
  std::string error_;  // the last load error, shown until the next load
  fs::path loading_path_;
  Clock::time_point load_started_;

  double render_ms_ = 0.0;
  double fps_ = 0.0;
  int frames_in_window_ = 0;
  Clock::time_point fps_window_start_ = Clock::now();
};

Expected<void> Viewer::open(const fs::path& font_path) {
  font_path_ = font_path;
  Uint32 flags = SDL_WINDOW_RESIZABLE | SDL_WINDOW_ALLOW_HIGHDPI;
  if (options_.fullscreen) flags |= SDL_WINDOW_FULLSCREEN_DESKTOP;
  window_.reset(SDL_CreateWindow("tessera view", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED,
                                 options_.width, options_.height, flags));
  if (!window_) return makeError(std::string("cannot create a window: ") + SDL_GetError());
  // No vsync: the loop paces itself to -fps and the render time stays measurable.
  renderer_.reset(SDL_CreateRenderer(window_.get(), -1, 0));
  if (!renderer_) renderer_.reset(SDL_CreateRenderer(window_.get(), -1, SDL_RENDERER_SOFTWARE));
  if (!renderer_) return makeError(std::string("cannot create a renderer: ") + SDL_GetError());
  SDL_EventState(SDL_DROPFILE, SDL_ENABLE);
  ensureFont(1.0f);
  if (!font_)
    return makeError("cannot open the font " + font_path.string() + ": " + TTF_GetError());
  return {};
}

float Viewer::pixelAspect() const {
  int w = 0, h = 0;
  SDL_GetRendererOutputSize(renderer_.get(), &w, &h);
  return w > 0 && h > 0 ? static_cast<float>(w) / static_cast<float>(h) : 4.0f / 3.0f;
}

void Viewer::ensureFont(float pixel_scale) {
  // 15 points, in pixels on a HiDPI display so that text is as sharp as the model.
  const int size = std::max(8, static_cast<int>(15.0f * pixel_scale + 0.5f));
  if (font_ && size == font_size_) return;
  SdlPtr<TTF_Font> font(TTF_OpenFont(font_path_.c_str(), size));
  if (!font) return;  // keep the previous size
  font_ = std::move(font);
  font_size_ = size;
}

void Viewer::startLoad(const fs::path& path) {
  const std::string name = path.filename().string();
  loading_path_ = path;
  load_started_ = Clock::now();
  error_.clear();
  std::function<Expected<Scene>(const fs::path&)> load_file = hooks_.load_file;
  loader_.start(name, [load_file, path] { return load_file(path); });
  dirty_ = true;
}

void Viewer::showScene(Scene scene, const std::string& name) {
  scene_ = std::move(scene);
  scene_name_ = name;
  has_scene_ = true;
  announce_scene_ = true;
  const Bounds bounds = scene_.bounds();
  camera_.frame(bounds, options_.view_direction, options_.fov_y_degrees, pixelAspect());
  scene_.world_axes_length = axesLength(bounds);
  for (Object& object : scene_.objects)
    if (object.mesh) object.axes_length = axesLength(object.mesh->bounds()) * 0.75f;
  SDL_SetWindowTitle(window_.get(), ("tessera view: " + name).c_str());
  dirty_ = view_changed_ = true;
}

void Viewer::takeLoadResult() {
  std::optional<Expected<Scene>> result = loader_.takeResult();
  if (!result) return;
  dirty_ = true;
  if (result->ok()) {
    if (result->value().objects.empty()) {
      error_ = loader_.name() + ": nothing to show";
    } else {
      showScene(std::move(result->value()), loader_.name());
      return;
    }
  } else {
    error_ = result->error().message;
  }
  std::cerr << "tessera view: error: " << error_ << std::endl;
  // In the window the file's folder is noise that pushes the message over the model.
  const std::string folder = loading_path_.parent_path().string();
  if (!folder.empty()) {
    for (size_t at; (at = error_.find(folder + "/")) != std::string::npos;)
      error_.erase(at, folder.size() + 1);
  }
  // The model given at start failed: show the default scene under the message.
  if (!has_scene_) showScene(hooks_.default_scene(), "cube");
}

void Viewer::handleAction(const Action& action) {
  if (applyCameraAction(action, camera_)) {
    dirty_ = view_changed_ = true;
    return;
  }
  switch (action.type) {
    case Action::Type::kToggleStats:
      stats_ = !stats_;
      fps_window_start_ = Clock::now(), frames_in_window_ = 0, fps_ = 0.0;
      break;
    case Action::Type::kToggleWorldAxes:
      world_axes_ = !world_axes_;
      view_changed_ = true;
      break;
    case Action::Type::kToggleObjectAxes:
      object_axes_ = !object_axes_;
      view_changed_ = true;
      break;
    case Action::Type::kScreenshot:
      screenshot_requested_ = true;
      break;
    case Action::Type::kQuit:
      quit_ = true;
      break;
    default:
      break;
  }
  dirty_ = true;
}

void Viewer::handleEvent(const SDL_Event& event) {
  switch (event.type) {
    case SDL_QUIT:
      quit_ = true;
      return;
    case SDL_DROPFILE: {
      std::unique_ptr<char, decltype(&SDL_free)> file(event.drop.file, &SDL_free);
      if (file) startLoad(fs::path(file.get()));
      return;
    }
    case SDL_WINDOWEVENT:
      dirty_ = true;  // resized, exposed, shown: draw again at the current size
      break;
    default:
      break;
  }
  std::optional<InputEvent> in = toInputEvent(event);
  if (!in) return;
  int window_w = 0, window_h = 0;
  SDL_GetWindowSize(window_.get(), &window_w, &window_h);
  if (std::optional<Action> action = input_.handle(*in, static_cast<float>(window_h)))
    handleAction(*action);
}

void Viewer::drawTextBox(const std::string& text, int x, int y, bool from_bottom, SDL_Color color,
                         int wrap_width) {
  if (text.empty() || !font_) return;
  SdlPtr<SDL_Surface> surface(TTF_RenderUTF8_Blended_Wrapped(
      font_.get(), text.c_str(), color, static_cast<Uint32>(std::max(wrap_width, 16))));
  if (!surface) return;
  SdlPtr<SDL_Texture> texture(SDL_CreateTextureFromSurface(renderer_.get(), surface.get()));
  if (!texture) return;
  const int pad = std::max(4, font_size_ / 3);
  SDL_Rect box{x, from_bottom ? y - surface->h - 2 * pad : y, surface->w + 2 * pad,
               surface->h + 2 * pad};
  SDL_SetRenderDrawBlendMode(renderer_.get(), SDL_BLENDMODE_BLEND);
  SDL_SetRenderDrawColor(renderer_.get(), 0, 0, 0, 170);
  SDL_RenderFillRect(renderer_.get(), &box);
  SDL_Rect dst{box.x + pad, box.y + pad, surface->w, surface->h};
  SDL_RenderCopy(renderer_.get(), texture.get(), nullptr, &dst);
}

void Viewer::drawOverlay(int pixel_width, int pixel_height) {
  const int margin = std::max(6, font_size_ / 2);
  const int wrap = pixel_width - 4 * margin;
  if (stats_) {
    // fps: frames presented per second of wall-clock time (0 until the first half second is
    // measured); render: the backend's own time for the last frame, whatever the pacing.
    char fps[32] = "-- fps";
    if (fps_ > 0.0) std::snprintf(fps, sizeof fps, "%.1f fps", fps_);
    char text[256];
    std::snprintf(text, sizeof text, "%s\nrender %.2f ms\n%d x %d, %zu triangles, %s", fps,
                  render_ms_, pixel_width, pixel_height, scene_.triangleCount(), backend_.name());
    drawTextBox(text, margin, margin, false, SDL_Color{255, 255, 255, 255}, wrap);
  }
  std::string status;
  SDL_Color color{255, 255, 255, 255};
  if (loader_.busy()) {
    const double seconds = std::chrono::duration<double>(Clock::now() - load_started_).count();
    char elapsed[32];
    std::snprintf(elapsed, sizeof elapsed, " (%.1f s)", seconds);
    status = "loading " + loader_.name() + "..." + elapsed;
  } else if (!error_.empty()) {
    status = "error: " + error_;
    color = SDL_Color{255, 120, 110, 255};
  }
  drawTextBox(status, margin, pixel_height - margin, true, color, wrap);
}

void Viewer::saveScreenshot(int pixel_width, int pixel_height) {
  // What is about to be presented, read back from the renderer: the window's own pixels.
  std::vector<uint32_t> pixels(static_cast<size_t>(pixel_width) * pixel_height);
  if (SDL_RenderReadPixels(renderer_.get(), nullptr, SDL_PIXELFORMAT_ABGR8888, pixels.data(),
                           pixel_width * 4) != 0) {
    error_ = std::string("screenshot failed: ") + SDL_GetError();
    std::cerr << "tessera view: error: " << error_ << std::endl;
    return;
  }
  const fs::path path = nextScreenshotPath();
  if (Expected<void> written = io::writePngRgba8(path, pixel_width, pixel_height, pixels.data());
      !written) {
    error_ = written.error().message;
    std::cerr << "tessera view: error: " << error_ << std::endl;
    return;
  }
  std::cout << "saved " << path.string() << std::endl;
}

void Viewer::drawFrame() {
  int pixel_w = 0, pixel_h = 0, window_w = 0, window_h = 0;
  SDL_GetRendererOutputSize(renderer_.get(), &pixel_w, &pixel_h);
  SDL_GetWindowSize(window_.get(), &window_w, &window_h);
  if (pixel_w <= 0 || pixel_h <= 0) return;  // minimized
  ensureFont(window_h > 0 ? static_cast<float>(pixel_h) / static_cast<float>(window_h) : 1.0f);

  if (!texture_ || texture_width_ != pixel_w || texture_height_ != pixel_h) {
    texture_.reset(SDL_CreateTexture(renderer_.get(), SDL_PIXELFORMAT_ABGR8888,
                                     SDL_TEXTUREACCESS_STREAMING, pixel_w, pixel_h));
    texture_width_ = pixel_w, texture_height_ = pixel_h;
    if (texture_) SDL_SetTextureBlendMode(texture_.get(), SDL_BLENDMODE_NONE);
  }

  // The scene is rendered again only when it would look different, or continuously while the
  // stats are shown (they measure it); an overlay-only update reuses the last frame.
  if (view_changed_ || stats_ || frame_.width != pixel_w || frame_.height != pixel_h) {
    view_changed_ = false;
    scene_.camera = camera_.camera();
    scene_.show_world_axes = world_axes_;
    for (Object& object : scene_.objects) object.show_axes = object_axes_;
    if (hooks_.place_lights) hooks_.place_lights(scene_);
    render_options_.width = pixel_w;
    render_options_.height = pixel_h;
    const Clock::time_point start = Clock::now();
    backend_.render(scene_, render_options_, frame_);
    render_ms_ = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    // A backend that could not draw the frame (a Vulkan device lost, a fence timeout) says why
    // in the window rather than showing an empty frame silently.
    if (Expected<void> rendered = backend_.lastResult(); !rendered)
      error_ = rendered.error().message;
    if (texture_) SDL_UpdateTexture(texture_.get(), nullptr, frame_.color.data(), pixel_w * 4);
  }

  SDL_SetRenderDrawColor(renderer_.get(), 0, 0, 0, 255);
  SDL_RenderClear(renderer_.get());
  if (texture_) SDL_RenderCopy(renderer_.get(), texture_.get(), nullptr, nullptr);
  drawOverlay(pixel_w, pixel_h);
  if (screenshot_requested_) {
    screenshot_requested_ = false;
    saveScreenshot(pixel_w, pixel_h);
  }
  SDL_RenderPresent(renderer_.get());

  ++frames_in_window_;
  const double seconds = std::chrono::duration<double>(Clock::now() - fps_window_start_).count();
  if (seconds >= 0.5) {
    fps_ = frames_in_window_ / seconds;
    frames_in_window_ = 0;
    fps_window_start_ = Clock::now();
  }
  if (announce_scene_ && has_scene_) {
    announce_scene_ = false;
    std::cout << "tessera view: showing " << scene_name_ << " (" << scene_.triangleCount()
              << " triangles, " << pixel_w << "x" << pixel_h << ")" << std::endl;
  }
}

void Viewer::run(const std::optional<fs::path>& model) {
  if (model) {
    scene_ = hooks_.default_scene();
    scene_.objects.clear();  // only its background, until the model arrives
    startLoad(*model);
  } else {
    showScene(hooks_.default_scene(), "cube");
  }
  const auto frame_interval = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / options_.fps));
  // While only the "loading..." line changes, ten updates a second are plenty and leave the
  // CPU to the loading thread.
  const auto loading_interval =
      std::max<Clock::duration>(frame_interval, std::chrono::milliseconds(100));
  auto nextDraw = [&](Clock::time_point last_draw) {
    return last_draw + (dirty_ || stats_ ? frame_interval : loading_interval);
  };
  Clock::time_point last_draw = Clock::now() - loading_interval;
  while (!quit_) {
    // Draw when something changed, and keep drawing while something changes by itself (the
    // stats, a load in progress); otherwise sleep until an event arrives.
    int timeout_ms = -1;
    if (dirty_ || stats_ || loader_.busy()) {
      const auto wait =
          std::chrono::duration_cast<std::chrono::milliseconds>(nextDraw(last_draw) - Clock::now());
      timeout_ms = static_cast<int>(std::max<long long>(0, wait.count()));
    }
    SDL_Event event;
    if (timeout_ms < 0 ? SDL_WaitEvent(&event) : SDL_WaitEventTimeout(&event, timeout_ms)) {
      handleEvent(event);
      while (!quit_ && SDL_PollEvent(&event)) handleEvent(event);
    }
    if (quit_) break;
    takeLoadResult();
    const Clock::time_point now = Clock::now();
    if ((dirty_ || stats_ || loader_.busy()) && now >= nextDraw(last_draw)) {
      dirty_ = false;
      last_draw = now;
      drawFrame();
    }
  }
}

}  // namespace

Expected<fs::path> findOverlayFont() {
  if (const char* forced = std::getenv("TESSERA_FONT"); forced != nullptr && *forced != '\0') {
    std::error_code ec;
    if (fs::is_regular_file(forced, ec)) return fs::path(forced);
    return makeError(std::string("TESSERA_FONT names no font file: ") + forced);
  }
  const char* folders[] = {"/usr/share/fonts/truetype/dejavu", "/usr/share/fonts/dejavu",
                           "/usr/share/fonts/TTF", "/usr/local/share/fonts",
                           "/usr/share/fonts/truetype"};
  const char* names[] = {"DejaVuSansMono.ttf", "DejaVuSans.ttf"};
  std::string looked;
  for (const char* name : names) {
    for (const char* folder : folders) {
      const fs::path candidate = fs::path(folder) / name;
      std::error_code ec;
      if (fs::is_regular_file(candidate, ec)) return candidate;
    }
  }
  for (const char* folder : folders) looked += std::string(looked.empty() ? "" : ", ") + folder;
  return makeError(
      "no DejaVu font for the overlay (looked for DejaVuSansMono.ttf and DejaVuSans.ttf in " +
      looked + "); install fonts-dejavu-core or set TESSERA_FONT to a .ttf file");
}

Expected<void> runViewer(const ViewerOptions& options, Backend& backend, const ViewerHooks& hooks,
                         const std::optional<fs::path>& model) {
  TESSERA_CHECK(hooks.load_file && hooks.default_scene) << "runViewer needs its hooks";
  TESSERA_CHECK(options.fps > 0 && options.width > 0 && options.height > 0);
  Expected<fs::path> font = findOverlayFont();
  if (!font) return font.error();
  SdlSession session;
  if (Expected<void> started = session.start(); !started) return started;
  // The viewer is destroyed before the session quits SDL.
  Viewer viewer(options, backend, hooks);
  if (Expected<void> opened = viewer.open(*font); !opened) return opened;
  viewer.run(model);
  return {};
}

}  // namespace tessera::viewer
