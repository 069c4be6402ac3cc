// The interactive viewer: an SDL2 window that renders a scene with any Backend, an orbit camera,
// a stats overlay (SDL2_ttf, DejaVu) and models loaded in the background. This header shows no
// SDL type; only tessera_viewer links SDL.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include <tessera/base/expected.h>
#include <tessera/render/backend.h>
#include <tessera/render/options.h>
#include <tessera/render/projection.h>
#include <tessera/scene/scene.h>
#include <tessera/viewer/scene_loader.h>

namespace tessera::viewer {

struct ViewerOptions {
  int width = 800;  // window size in points (the framebuffer follows its size in pixels)
  int height = 600;
  int fps = 60;                 // the most frames a second drawn while anything moves
  float fov_y_degrees = 50.0f;  // perspective's vertical field of view (it frames the model)
  Projection projection = Projection::kPerspective;  // at start (F4 cycles)
  // The view angle asked for (-fov), in degrees: a nonlinear mode takes it where checkViewAngle
  // accepts it for that mode and the window's aspect, and its own default otherwise.
  std::optional<float> view_angle;
  bool stats = false;       // the stats overlay (F1) at start
  bool world_axes = false;  // the world axes (F2) at start
  bool fullscreen = false;
  int msaa = 4;          // samples per pixel at start (Shift+F3 cycles 1, 2, 4, 8)
  bool jitter = false;   // sub-pixel jitter at start (F10)
  bool temporal = true;  // temporal reprojection of the jittered frames (Shift+F12)
  bool shadows = false;  // shadow maps at start (S; the cpu backend draws them)
  float3 view_direction{0.6f, 0.45f, 1.0f};  // from the model towards the camera at start/reset
  PointOptions points;                       // Scene::points (--point-size, --point-sprites)
  float line_width = 1.0f;                   // Scene::lines, in pixels (--line-width)
};

struct ViewerHooks {
  // Makes the scene of a model file (given at start or dropped on the window), with its graph and
  // the clip the space bar plays (prepareClip). Runs on a background thread: it must not touch
  // anything the caller keeps.
  std::function<Expected<LoadedScene>(const std::filesystem::path&)> load_file;
  // The scene shown without a model, or when the model given at start fails to load.
  std::function<Scene()> default_scene;
  // The camera a loaded scene starts from (and Enter returns to) for a window of `aspect`: a
  // camera of its graph or an orthographic one; nullopt (or unset): the orbit camera frames it.
  std::function<std::optional<Camera>(const LoadedScene&, float aspect)> start_camera;
  // Places the lights for the scene's current camera (called whenever the camera moves).
  std::function<void(Scene&)> place_lights;
  // Shift+F2: with `toggle`, switches the backend's 32-bit visibility commit path; returns the
  // overlay's line naming the path now active, or "" where the key does not apply (a backend
  // other than `vulkan`; unset: on every backend).
  std::function<std::string(Backend&, bool toggle)> commit_path;
};

// Opens the window and runs until Escape or the close button. `model`: loaded in the background
// at start; without one the default scene is shown. Fails (without opening anything, or after
// closing what it opened) when there is no display, no usable SDL video driver or no font.
Expected<void> runViewer(const ViewerOptions& options, Backend& backend, const ViewerHooks& hooks,
                         const std::optional<std::filesystem::path>& model);

// The overlay font: $TESSERA_FONT if set, else the first DejaVu Sans Mono or DejaVu Sans found in
// the usual font folders.
Expected<std::filesystem::path> findOverlayFont();

}  // namespace tessera::viewer
