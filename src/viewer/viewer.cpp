// The SDL2 side of the viewer: window, events, presenting frames, the text overlay and
// screenshots. Camera and input logic live in orbit_camera / input_state (no SDL).
#include <tessera/viewer/viewer.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <tessera/io/image_writer.h>
#include <tessera/io/validation.h>
#include <tessera/render/frame.h>
#include <tessera/render/heatmap.h>
#include <tessera/viewer/animation_player.h>
#include <tessera/viewer/diagnostic_view.h>
#include <tessera/viewer/frame_renderer.h>
#include <tessera/viewer/input_state.h>
#include <tessera/viewer/orbit_camera.h>
#include <tessera/viewer/scene_loader.h>

#include "overlay.h"
#include "sdl_support.h"

namespace tessera::viewer {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

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
      : options_(options),
        backend_(backend),
        hooks_(hooks),
        frames_(options.projection, ViewAngles{options.fov_y_degrees, options.view_angle},
                SamplingModes(options.msaa, options.jitter, options.temporal)) {
    stats_ = options.stats;
    world_axes_ = options.world_axes;
    frames_.setPointStyle(options.points, options.line_width);
    frames_.setShadows(options.shadows);
  }

  Expected<void> open(const fs::path& font_path);
  void run(const std::optional<fs::path>& model);

 private:
  void startLoad(const fs::path& path);
  void takeLoadResult();
  void showScene(LoadedScene loaded, const std::string& name);
  void togglePlayback();
  void handleEvent(const SDL_Event& event);
  void handleAction(const Action& action);
  void drawFrame();
  void drawOverlay(int pixel_width, int pixel_height);
  void drawKeyList(int pixel_width, int pixel_height);
  void renderScene(int pixel_width, int pixel_height);
  void saveScreenshot(int pixel_width, int pixel_height);
  void checkCrc();
  void setDiagnosticView(DiagnosticView view);
  void toggleCommitPath();
  // What the window shows of the rendered frame: the frame, or the diagnostic view's picture.
  const std::vector<uint32_t>& shownPixels();
  float pixelAspect() const;
  // Frames keep coming without input: the stats measure them, a load shows its progress, the
  // jitter cycles, the temporal pass converges or the animation plays.
  bool animating() const {
    return stats_ || loader_.busy() || sampling().wantsAnotherFrame() || player_.playing();
  }
  SamplingModes& sampling() { return frames_.sampling(); }
  const SamplingModes& sampling() const { return frames_.sampling(); }

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
  TextOverlay text_;

  Scene scene_;
  std::string scene_name_;
  bool has_scene_ = false;
  bool announce_scene_ = false;  // print "showing ..." after the scene's first frame
  OrbitCamera camera_;
  AnimationPlayer player_;  // the space bar: the loaded graph's clip
  InputState input_;
  FrameRenderer frames_;
  Frame frame_;

  bool stats_ = false;
  bool world_axes_ = false;
  bool object_axes_ = false;
  bool key_list_ = false;
  bool quit_ = false;
  bool dirty_ = true;         // the window needs presenting again
  bool view_changed_ = true;  // ...and the scene rendering again (camera, scene or axes changed)
  bool screenshot_requested_ = false;
  // F5 / F6, done on the next frame drawn: the frame the window is about to show.
  enum class CrcRequest { kNone, kStore, kCompare };
  CrcRequest crc_request_ = CrcRequest::kNone;
  std::optional<uint32_t> stored_crc_;
  std::string crc_message_;  // the overlay line, until an action changes the picture
  SDL_Color crc_color_{255, 255, 255, 255};
  // Shift+F1 / F11: the picture shown instead of the frame, and its overlay line.
  DiagnosticView diagnostic_view_ = DiagnosticView::kOff;
  DiagnosticPicture diagnostic_picture_;
  std::string commit_message_;  // Shift+F2's line: the commit path, or that it does not apply
  std::string notice_;          // space without an animation: says so, as crc_message_ lasts
  std::string error_;           // the last load error, shown until the next load
  fs::path loading_path_;
  Clock::time_point load_started_;

  double fps_ = 0.0;
  int frames_in_window_ = 0;
  Clock::time_point fps_window_start_ = Clock::now();
};

Expected<void> Viewer::open(const fs::path& font_path) {
  if (Expected<void> shown =
          openWindow(options_.width, options_.height, options_.fullscreen, window_, renderer_);
      !shown)
    return shown;
  SDL_EventState(SDL_DROPFILE, SDL_ENABLE);
  if (!text_.open(font_path))
    return makeError("cannot open the font " + font_path.string() + ": " + TTF_GetError());
  return {};
}

float Viewer::pixelAspect() const {
  int w = 0, h = 0;
  SDL_GetRendererOutputSize(renderer_.get(), &w, &h);
  return w > 0 && h > 0 ? static_cast<float>(w) / static_cast<float>(h) : 4.0f / 3.0f;
}

void Viewer::startLoad(const fs::path& path) {
  const std::string name = path.filename().string();
  loading_path_ = path;
  load_started_ = Clock::now();
  error_.clear();
  std::function<Expected<LoadedScene>(const fs::path&)> load_file = hooks_.load_file;
  loader_.start(name, [load_file, path] { return load_file(path); });
  dirty_ = true;
}

void Viewer::showScene(LoadedScene loaded, const std::string& name) {
  scene_ = std::move(loaded.scene);
  scene_name_ = name;
  has_scene_ = true;
  announce_scene_ = true;
  const Bounds bounds = loaded.bounds.empty() ? scene_.bounds() : loaded.bounds;
  const std::optional<Camera> start =
      hooks_.start_camera ? hooks_.start_camera(loaded, pixelAspect()) : std::nullopt;
  if (start)
    camera_.frameCamera(*start, bounds);
  else
    camera_.frame(bounds, options_.view_direction, options_.fov_y_degrees, pixelAspect());
  player_.reset(std::move(loaded.graph), loaded.clip);
  scene_.world_axes_length = axesLength(bounds);
  for (Object& object : scene_.objects)
    if (object.mesh) object.axes_length = axesLength(object.mesh->bounds()) * 0.75f;
  SDL_SetWindowTitle(window_.get(), ("tessera view: " + name).c_str());
  sampling().reset();
  crc_message_.clear();  // it was about the previous scene
  dirty_ = view_changed_ = true;
}

void Viewer::takeLoadResult() {
  std::optional<Expected<LoadedScene>> result = loader_.takeResult();
  if (!result) return;
  dirty_ = true;
  if (result->ok()) {
    if (result->value().scene.objects.empty()) {
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
  if (!has_scene_) showScene(withoutGraph(hooks_.default_scene()), "cube");
}

// Space: stdout says what it did (for scripts and tests); without a clip, the window too.
void Viewer::togglePlayback() {
  const bool toggled = player_.togglePlaying(Clock::now());
  notice_ = toggled ? "" : "no animation to play in " + scene_name_;
  std::cout << "tessera view: " << (toggled ? player_.state() : notice_) << std::endl;
}

void Viewer::handleAction(const Action& action) {
  // A CRC result (and the notice) describes the picture it was taken of: gone once it changes.
  using T = Action::Type;
  if (action.type != T::kStoreCrc && action.type != T::kCompareCrc &&
      action.type != T::kScreenshot && action.type != T::kToggleKeyList &&
      action.type != T::kToggleStats)
    crc_message_.clear(), notice_.clear();
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
      sampling().reset();
      view_changed_ = true;
      break;
    case Action::Type::kToggleObjectAxes:
      object_axes_ = !object_axes_;
      sampling().reset();
      view_changed_ = true;
      break;
    case Action::Type::kCycleProjection:
      frames_.cycleProjection();
      view_changed_ = true;
      break;
    case Action::Type::kScreenshot:
      screenshot_requested_ = true;
      break;
    case Action::Type::kStoreCrc:
      crc_request_ = CrcRequest::kStore;
      break;
    case Action::Type::kCompareCrc:
      crc_request_ = CrcRequest::kCompare;
      break;
    case Action::Type::kToggleTileHeatmap:
      setDiagnosticView(toggleTileHeatmap(diagnostic_view_));
      break;
    case Action::Type::kCycleAnalysisView:
      setDiagnosticView(nextAnalysisView(diagnostic_view_));
      break;
    case Action::Type::kToggleCommitPath:
      toggleCommitPath();
      break;
    case Action::Type::kCycleMsaa:
      sampling().cycleMsaa();
      view_changed_ = true;
      break;
    case Action::Type::kToggleJitter:
      sampling().toggleJitter();
      view_changed_ = true;
      break;
    case Action::Type::kToggleTemporal:
      sampling().toggleTemporal();
      view_changed_ = true;
      break;
    case Action::Type::kToggleShadows:
      frames_.setShadows(!frames_.shadows());
      sampling().reset();
      view_changed_ = true;
      break;
    case Action::Type::kToggleKeyList:
      key_list_ = !key_list_;
      break;
    case Action::Type::kTogglePlayback:
      togglePlayback();
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

void Viewer::drawKeyList(int pixel_width, int pixel_height) {
  std::vector<std::pair<std::string, std::string>> rows;
  for (const KeyHelp& help : keyList()) rows.emplace_back(help.keys, help.action);
  rows.emplace_back("", "");
  rows.emplace_back("now", frames_.describeProjection() + ", " + sampling().describe() +
                               (frames_.shadows() ? ", shadows" : ""));
  text_.drawTable(renderer_.get(), rows, pixel_width, pixel_height);
}

void Viewer::drawOverlay(int pixel_width, int pixel_height) {
  const int margin = std::max(6, text_.fontSize() / 2);
  const int wrap = pixel_width - 4 * margin;
  if (stats_) {
    // fps: frames presented per second of wall-clock time (0 until the first half second is
    // measured); render: the backend's own time for the last frame, whatever the pacing.
    char fps[32] = "-- fps";
    if (fps_ > 0.0) std::snprintf(fps, sizeof fps, "%.1f fps", fps_);
    char text[256];
    std::snprintf(text, sizeof text, "%s\nrender %.2f ms", fps, frames_.renderMs());
    std::string lines = text;
    if (sampling().blending()) {
      std::snprintf(text, sizeof text, " + TAA %.2f ms", frames_.temporalMs());
      lines += text;
    }
    std::snprintf(text, sizeof text, "\n%d x %d, %zu triangles, %s\n", pixel_width, pixel_height,
                  scene_.triangleCount(), backend_.name());
    lines += text + frames_.describeProjection() + "\n" + sampling().describe();
    if (player_.hasClip()) lines += "\n" + player_.describe();
    if (hooks_.commit_path) {
      if (const std::string path = hooks_.commit_path(backend_, false); !path.empty())
        lines += "\n" + path;
    }
    text_.drawTextBox(renderer_.get(), lines, margin, margin, false, SDL_Color{255, 255, 255, 255},
                      wrap);
  }
  std::string status;
  SDL_Color color{255, 255, 255, 255};
  if (loader_.busy()) {
    const double seconds = std::chrono::duration<double>(Clock::now() - load_started_).count();
    char elapsed[32];
    std::snprintf(elapsed, sizeof elapsed, " (%.1f s)", seconds);
    status = "loading " + loader_.name() + "..." + elapsed;
  } else if (!error_.empty() || !frames_.error().empty()) {
    const char* between = error_.empty() || frames_.error().empty() ? "" : "\n";
    status = "error: " + error_ + between + frames_.error();
    color = SDL_Color{255, 120, 110, 255};
  }
  // Lines stack up from the bottom, above a diagnostic picture's legend.
  int bottom = pixel_height - margin;
  if (!diagnostic_picture_.pixels.empty()) bottom -= heatmapLegendHeight(pixel_width, pixel_height);
  auto stack = [&](const std::string& text, SDL_Color line_color) {
    const int height =
        text_.drawTextBox(renderer_.get(), text, margin, bottom, true, line_color, wrap);
    if (height > 0) bottom -= height + margin / 2;
  };
  const SDL_Color white{255, 255, 255, 255};
  stack(status, color);
  stack(crc_message_, crc_color_);
  stack(notice_, white);
  stack(commit_message_, white);
  stack(diagnostic_picture_.caption, white);
  if (key_list_) drawKeyList(pixel_width, pixel_height);
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

// The CRC-32 of the rendered frame's RGBA8 pixels (as `tessera render --crc`), without the
// overlay; printed on stdout too, for scripts and tests.
void Viewer::checkCrc() {
  const CrcRequest request = std::exchange(crc_request_, CrcRequest::kNone);
  const uint32_t crc = io::crc32Rgba8(frame_.color.data(), frame_.width, frame_.height);
  const std::string hex = io::crc32Hex(crc);
  if (request == CrcRequest::kStore) {
    stored_crc_ = crc;
    crc_message_ = "CRC " + hex + " stored (F6 compares)";
    crc_color_ = SDL_Color{255, 255, 255, 255};
    std::cout << "tessera view: crc32 stored " << hex << std::endl;
  } else if (!stored_crc_) {
    crc_message_ = "no CRC stored: press F5 first";
    crc_color_ = SDL_Color{255, 255, 255, 255};
    std::cout << "tessera view: crc32 nothing stored" << std::endl;
  } else if (*stored_crc_ == crc) {
    crc_message_ = "MATCH " + hex;
    crc_color_ = SDL_Color{90, 230, 90, 255};
    std::cout << "tessera view: crc32 MATCH " << hex << std::endl;
  } else {
    const std::string stored = io::crc32Hex(*stored_crc_);
    crc_message_ = "MISMATCH: stored " + stored + ", now " + hex;
    crc_color_ = SDL_Color{255, 90, 80, 255};
    std::cout << "tessera view: crc32 MISMATCH stored " << stored << " current " << hex
              << std::endl;
  }
}

void Viewer::renderScene(int pixel_width, int pixel_height) {
  scene_.camera = frames_.camera(camera_, pixel_width, pixel_height);
  scene_.show_world_axes = world_axes_;
  for (Object& object : scene_.objects) object.show_axes = object_axes_;
  if (hooks_.place_lights) hooks_.place_lights(scene_);
  // A backend that could not draw the frame (a Vulkan device lost, a fence timeout, a projection
  // it does not draw) says why in the window, once on stderr, rather than showing an empty frame
  // silently; the window stays usable, and the message goes with the next frame it draws.
  const std::string previous_error = frames_.error();
  if (!frames_.render(backend_, scene_, pixel_width, pixel_height, frame_) &&
      frames_.error() != previous_error)
    std::cerr << "tessera view: error: " << frames_.error() << std::endl;
  if (texture_) SDL_UpdateTexture(texture_.get(), nullptr, shownPixels().data(), pixel_width * 4);
}

const std::vector<uint32_t>& Viewer::shownPixels() {
  // A frame that did not draw says why in red; the view's line would only repeat it.
  diagnostic_picture_ = frames_.error().empty()
                            ? diagnosticPicture(frame_, diagnostic_view_, backend_.name())
                            : DiagnosticPicture{};
  return diagnostic_picture_.pixels.empty() ? frame_.color : diagnostic_picture_.pixels;
}

// Shift+F1 / F11. Frames measure their diagnostics only while a view is shown.
void Viewer::setDiagnosticView(DiagnosticView view) {
  diagnostic_view_ = view;
  frames_.setDiagnostics(needsDiagnostics(view));
  if (!needsDiagnostics(view)) diagnostic_picture_ = {};
  view_changed_ = true;
}

// Shift+F2: the line goes to the overlay and to stdout (for scripts and tests).
void Viewer::toggleCommitPath() {
  commit_message_ = hooks_.commit_path ? hooks_.commit_path(backend_, true) : "";
  if (commit_message_.empty())
    commit_message_ = std::string("32-bit commit path: does not apply to the ") + backend_.name() +
                      " backend (vulkan only)";
  std::cout << "tessera view: " << commit_message_ << std::endl;
  sampling().reset();
  view_changed_ = true;
}

void Viewer::drawFrame() {
  int pixel_w = 0, pixel_h = 0, window_w = 0, window_h = 0;
  SDL_GetRendererOutputSize(renderer_.get(), &pixel_w, &pixel_h);
  SDL_GetWindowSize(window_.get(), &window_w, &window_h);
  if (pixel_w <= 0 || pixel_h <= 0) return;  // minimized
  text_.setScale(window_h > 0 ? static_cast<float>(pixel_h) / static_cast<float>(window_h) : 1.0f);

  if (!texture_ || texture_width_ != pixel_w || texture_height_ != pixel_h) {
    texture_.reset(SDL_CreateTexture(renderer_.get(), SDL_PIXELFORMAT_ABGR8888,
                                     SDL_TEXTUREACCESS_STREAMING, pixel_w, pixel_h));
    texture_width_ = pixel_w, texture_height_ = pixel_h;
    if (texture_) SDL_SetTextureBlendMode(texture_.get(), SDL_BLENDMODE_NONE);
  }

  // The scene is rendered again only when it would look different, or continuously while the
  // stats are shown (they measure it) or the jittered samples change it; an overlay-only update
  // reuses the last frame. A new pose moves geometry: the temporal history no longer matches.
  if (player_.update(Clock::now(), scene_)) sampling().reset(), view_changed_ = true;
  if (view_changed_ || stats_ || sampling().wantsAnotherFrame() || frame_.width != pixel_w ||
      frame_.height != pixel_h) {
    view_changed_ = false;
    renderScene(pixel_w, pixel_h);
  }
  if (crc_request_ != CrcRequest::kNone) checkCrc();

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
    showScene(withoutGraph(hooks_.default_scene()), "cube");
  }
  const auto frame_interval = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / options_.fps));
  // While only the "loading..." line changes, ten updates a second are plenty and leave the
  // CPU to the loading thread.
  const auto loading_interval =
      std::max<Clock::duration>(frame_interval, std::chrono::milliseconds(100));
  auto nextDraw = [&](Clock::time_point last_draw) {
    const bool moving = dirty_ || stats_ || sampling().wantsAnotherFrame() || player_.playing();
    return last_draw + (moving ? frame_interval : loading_interval);
  };
  Clock::time_point last_draw = Clock::now() - loading_interval;
  while (!quit_) {
    // Draw when something changed, and keep drawing while something changes by itself (the
    // stats, a load in progress); otherwise sleep until an event arrives.
    int timeout_ms = -1;
    if (dirty_ || animating()) {
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
    if ((dirty_ || animating()) && now >= nextDraw(last_draw)) {
      dirty_ = false;
      last_draw = now;
      drawFrame();
    }
  }
}

}  // namespace

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
