// tessera view [MODEL]: the interactive viewer (an SDL2 window). Built only with TESSERA_VIEWER;
// otherwise the command says so.
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include <tessera/io/image_loader.h>
#include <tessera/io/model_loader.h>
#include <tessera/model/camera_setup.h>
#include <tessera/model/ground_grid.h>
#include <tessera/model/model_scene.h>
#include <tessera/render/projection.h>
#include <tessera/render/sampling.h>
#include <tessera/scene/color.h>
#include <tessera/scene/primitives.h>

#include "animation_frames.h"
#include "backends.h"
#include "budget_flags.h"
#include "commands.h"
#include "flags.h"
#include "light_flags.h"
#include "point_flags.h"
#include "surface_flags.h"

#ifdef TESSERA_HAS_VIEWER
#include <tessera/viewer/animation_player.h>
#include <tessera/viewer/viewer.h>
#endif

namespace tessera::cli {

using namespace tessera::model;

namespace {

struct ViewSettings {
  int width = 800;
  int height = 600;
  int fps = 60;
  float fov = 50.0f;
  bool has_fov = false;
  std::string projection = "perspective";
  bool stats = false;
  bool axes = false;
  bool grid = false;
  bool fullscreen = false;
  int workers = 0;
  std::string texture;
  std::string shading;  // empty: defaultShading of each model loaded
  std::string backend = "cpu";
  int device = -1;
  int msaa = 4;  // what `tessera render` makes by default
  io::LoadBudget budget;
  LightSettings lights;      // --light, --ambient
  PointSettings points;      // --point-size, --point-sprites, --line-width
  int animation_index = -1;  // --animation-index: the clip space plays; -1: the first, if any
  CameraSettings camera;     // --camera-index, --camera-orthographic (the rest unused)
  ToneSettings tone;         // --tone-mapping, --exposure
  std::string hdri;          // --hdri: the environment light of every model shown
  bool hdri_background = false;
};

bool isPerspectiveFov(float fov) {
  return fov >= 1.0f && fov <= 170.0f;
}

// -fov's check for the start mode on a window of this aspect: "" or the valid range.
std::string checkFov(const ViewSettings& s, Projection mode, float aspect) {
  if (!s.has_fov) return "";
  if (mode != Projection::kPerspective) return checkViewAngle(mode, s.fov, aspect);
  if (isPerspectiveFov(s.fov)) return "";
  return "must be between 1 and 170 in perspective (other projections take wider angles)";
}

#ifdef TESSERA_HAS_VIEWER
// The built-in model: the demo's orange cube, flat-shaded.
io::Model cubeModel() {
  io::Model model;
  model.mesh = makeCube();
  Material material;
  material.base_color = demoCubeColor();
  model.materials.push_back(material);
  return model;
}
#endif

// --camera-index, --camera-orthographic and --animation-index against the other flags: "" or the
// usage error.
std::string checkViewCameraFlags(const ViewSettings& s, Projection projection, bool no_model) {
  const CameraSettings& c = s.camera;
  if ((c.orthographic || c.camera_index >= 0) && projection != Projection::kPerspective)
    return std::string(c.orthographic ? "--camera-orthographic" : "--camera-index") +
           " and --projection " + projectionName(projection) + " do not go together";
  if (no_model && c.camera_index >= 0) return "--camera-index picks a camera of a MODEL: give one";
  if (no_model && s.animation_index >= 0)
    return "--animation-index picks an animation of a MODEL: give one";
  return "";
}

#ifdef TESSERA_HAS_VIEWER

// What every load of the viewer shares; the loading thread owns its copy.
struct ViewLoad {
  ModelSceneSettings scene_settings;
  std::string shading;  // --shading; empty: defaultShading of the file
  io::LoadBudget budget;
  LightSettings lights;
  int animation_index = -1;
  // Whether the model last loaded brings its own lights (its file's or --light's): the default
  // rig, fixed to the view, is placed only when it does not.
  std::shared_ptr<std::atomic<bool>> own_lights;
  bool grid = false;  // --grid: a ground grid under each model loaded, across +Y
  ToneSettings tone;  // --tone-mapping, --exposure
  // --hdri, read once before the window opens and shared by every model loaded (the viewer's
  // up is +Y); null without it.
  std::shared_ptr<const Environment> environment;
  bool environment_background = false;
  float3x3 world_to_environment;
};

// --hdri's light (and --hdri-background) on a scene the viewer shows.
void applyViewEnvironment(const ViewLoad& load, Scene& scene) {
  scene.environment = load.environment;
  scene.environment_background = load.environment_background;
  scene.world_to_environment = load.world_to_environment;
}

// The start model loaded before the window opened, taken (once) by the viewer's first load.
struct PreloadedScene {
  std::mutex mutex;  // loads run on their own threads
  std::optional<viewer::LoadedScene> scene;

  std::optional<viewer::LoadedScene> take() {
    std::lock_guard<std::mutex> lock(mutex);
    return std::exchange(scene, std::nullopt);
  }
};

// A model as the viewer shows it: framed (any scale is drawn), with its graph and the clip the
// space bar plays: --animation-index where the model has it, else its first.
Expected<viewer::LoadedScene> loadViewScene(const ViewLoad& load,
                                            const std::filesystem::path& path) {
  Expected<io::Model> model = io::loadModel(path, load.budget);
  if (!model) return model.error();
  model->lights.insert(model->lights.end(), load.lights.lights.begin(), load.lights.lights.end());
  fitModelScale(*model, path, /*keep_coordinates=*/false);
  for (const std::string& warning : model->warnings)
    std::cerr << "tessera view: warning: " << warning << "\n";
  const std::vector<Light> lights = model->lights;
  viewer::LoadedScene loaded;
  ModelSceneSettings settings = load.scene_settings;
  settings.shading = load.shading.empty() ? defaultShading(path) : shadingFromName(load.shading);
  Expected<Scene> scene = makeModelScene(std::move(*model), path, settings, &loaded.graph);
  if (!scene) return scene.error();
  loaded.scene = std::move(*scene);
  if (load.grid) model::appendGroundGrid(loaded.scene.bounds(), {0, 1, 0}, loaded.scene.lines);
  addViewLights(loaded.scene);
  applyLights(loaded.scene, lights, load.lights);
  applyTone(load.tone, loaded.scene);
  applyViewEnvironment(load, loaded.scene);
  load.own_lights->store(!lights.empty());
  const size_t clips = loaded.graph.animations.size();
  const int wanted = std::max(load.animation_index, 0);
  viewer::prepareClip(loaded, clips == 0 ? -1 : static_cast<size_t>(wanted) < clips ? wanted : 0);
  return loaded;
}

// The start model, loaded before the window opens when --animation-index or --camera-index name
// something in it, so that an index past the end fails as in `render` (exit 1). kExitOk or the
// status (printed).
int preloadViewScene(const ViewSettings& s, const ViewLoad& load, const std::filesystem::path& path,
                     viewer::LoadedScene& loaded) {
  Expected<viewer::LoadedScene> made = loadViewScene(load, path);
  if (!made) {
    printError("view", made.error().message);
    return kExitFailure;
  }
  const size_t clips = made->graph.animations.size();
  if (s.animation_index >= 0 && static_cast<size_t>(s.animation_index) >= clips) {
    printError("view", animationIndexError(path.string(), clips, s.animation_index));
    return kExitFailure;
  }
  if (s.camera.camera_index >= 0) {
    const float aspect = static_cast<float>(s.width) / static_cast<float>(s.height);
    if (Expected<Camera> camera = makeCamera(s.camera, made->bounds, aspect, &made->graph);
        !camera) {
      printError("view", path.string() + ": " + camera.error().message);
      return kExitFailure;
    }
  }
  loaded = std::move(*made);
  return kExitOk;
}

// The start camera of a loaded scene: --camera-index's where the scene has that camera (a model
// dropped later may not: it is framed), or the orthographic framing; nullopt: the orbit camera
// frames it. `fov`: the viewer's perspective angle, which the orthographic framing matches.
std::optional<Camera> viewStartCamera(CameraSettings settings, float fov,
                                      const viewer::LoadedScene& loaded, float aspect) {
  if (settings.camera_index >= 0 &&
      static_cast<size_t>(settings.camera_index) >= loaded.graph.cameras.size())
    settings.camera_index = -1;
  if (settings.camera_index < 0 && !settings.orthographic) return std::nullopt;
  settings.view_angle = fov, settings.has_view_angle = true;
  Expected<Camera> camera = makeCamera(settings, loaded.bounds, aspect, &loaded.graph);
  if (!camera) {
    std::cerr << "tessera view: warning: " << camera.error().message << "; framing the model\n";
    return std::nullopt;
  }
  return *camera;
}

// The viewer's hooks: loads (on the loading thread; the first may take the preloaded scene), the
// default cube, the lights, Shift+F2 and the start camera. `fov`: the perspective view angle.
viewer::ViewerHooks viewHooks(const ViewSettings& s, const ViewLoad& load,
                              std::shared_ptr<PreloadedScene> preloaded, float fov) {
  viewer::ViewerHooks hooks;
  // For tests only: while the file named by TESSERA_VIEW_TEST_HOLD_LOADS exists (at most a
  // minute), loads wait, so that a test can see the window during a load that takes long.
  std::string hold_file;
  if (const char* hold = std::getenv("TESSERA_VIEW_TEST_HOLD_LOADS")) hold_file = hold;
  // Runs on the loading thread. Between a load and the scene's swap a frame may place (or keep)
  // the previous model's lights: the next frame is right.
  hooks.load_file = [load, hold_file, preloaded](
                        const std::filesystem::path& path) -> Expected<viewer::LoadedScene> {
    if (std::optional<viewer::LoadedScene> loaded = preloaded->take()) return std::move(*loaded);
    if (!hold_file.empty()) {
      const auto until = std::chrono::steady_clock::now() + std::chrono::minutes(1);
      std::error_code ec;
      while (std::filesystem::exists(hold_file, ec) && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return loadViewScene(load, path);
  };
  hooks.default_scene = [load] {
    ModelSceneSettings cube_settings = load.scene_settings;
    cube_settings.shading = Shading::kFlat;
    cube_settings.cull = CullMode::kBack;
    Scene scene = makeModelScene(cubeModel(), "cube", cube_settings).value();
    applyViewEnvironment(load, scene);
    return scene;
  };
  hooks.place_lights = [own_lights = load.own_lights, light_settings = s.lights](Scene& scene) {
    if (own_lights->load()) return;
    addViewLights(scene);
    if (light_settings.ambient_given) scene.ambient = light_settings.ambient;
  };
  hooks.commit_path = vulkanCommitPath;
  hooks.start_camera = [camera = s.camera, fov](const viewer::LoadedScene& loaded, float aspect) {
    return viewStartCamera(camera, fov, loaded, aspect);
  };
  return hooks;
}

#endif

// The flags of `tessera view`, into `s`.
void addViewFlags(FlagSet& flags, ViewSettings& s) {
  flags.addInt("w|width", &s.width, "window width (default 800)", 1, 16384);
  flags.addInt("h|height", &s.height, "window height (default 600)", 1, 16384);
  flags.addInt("fps", &s.fps, "most frames a second while anything moves (default 60)", 1, 1000);
  flags.addCustom("fov", "DEG",
                  "vertical view angle in degrees (default 50; 1 to 170 in perspective; another "
                  "projection takes it where it fits, else its default: docs/rendering.md)",
                  [&s](const std::string& v) -> std::string {
                    if (!parseFloatStrict(v, s.fov) || !(s.fov > 0.0f))
                      return "needs a number of degrees above 0, got '" + v + "'";
                    s.has_fov = true;
                    return "";
                  });
  std::vector<std::string> modes;
  for (Projection p : kProjections) modes.push_back(projectionName(p));
  flags.addChoice("projection", &s.projection, modes,
                  "projection at start (default perspective; F4 cycles them)");
  flags.addSwitch("stats", &s.stats, "show the stats overlay at start (F1 toggles it)");
  flags.addSwitch("axes", &s.axes, "show the world axes at start (F2 toggles them)");
  flags.addSwitch("grid|g", &s.grid, "draw a ground grid under the model, across +Y (f3d's -g)");
  addToneFlags(flags, s.tone);
  flags.addString("hdri", &s.hdri,
                  "an equirectangular Radiance .hdr or OpenEXR .exr image as the light around "
                  "the model (image-based lighting in --shading pbr)");
  flags.addSwitch("hdri-background|hdri-skybox", &s.hdri_background,
                  "show the --hdri image behind the model");
  flags.addSwitch("fullscreen", &s.fullscreen, "fill the screen");
  flags.addInt("workers", &s.workers, "render threads; 0 = all cores (default 0)", 0, 1024);
  flags.addString("texture", &s.texture, "an image used as the albedo of every material");
  flags.addChoice("shading", &s.shading, {"flat", "smooth", "gouraud", "unlit", "pbr"},
                  "flat, smooth (per-pixel), gouraud (per-vertex), unlit or pbr (default pbr for "
                  "glTF, smooth for other formats)");
  addBudgetFlags(flags, s.budget);
  addLightFlags(flags, s.lights);
  addPointFlags(flags, s.points, "the width in pixels of the model's lines, up to 64 (default 1)");
  flags.addInt("animation-index", &s.animation_index,
               "the model's animation the space bar plays (glTF, from 0; default 0)", 0, 1000000);
  flags.addInt("camera-index", &s.camera.camera_index,
               "start from the file's camera N (glTF cameras, from 0; Enter returns to it)", 0,
               1 << 30);
  flags.addSwitch("camera-orthographic", &s.camera.orthographic,
                  "orthographic projection for the start camera");
  flags.addChoice("backend", &s.backend, backendNames(), "renderer (default cpu)");
  flags.addInt("device", &s.device, "Vulkan device index (default: the first suitable)", 0, 64);
  flags.addCustom(
      "msaa", "N", "samples per pixel: 1, 2, 4 or 8 (default 4; Shift+F3 cycles)",
      [&s](const std::string& v) -> std::string {
        long long n = 0;
        if (!parseIntStrict(v, n) || n < 1 || n > 8 || !isSampleCount(static_cast<int>(n)))
          return "must be 1, 2, 4 or 8, got '" + v + "'";
        s.msaa = static_cast<int>(n);
        return "";
      });
}

// `tessera view --help`: the flags, then the mouse and the keys.
void printViewHelp(const FlagSet& flags) {
  std::cout << flags.usage()
            << "\nMouse: left drag orbits, wheel zooms, middle or shift + left drag pans.\n"
               "Keys: 1 front, 3 right, 7 top, 9 isometric, Enter resets the camera,\n"
               "F1 stats, F2 world axes, F3 object axes, F4 cycles the projection\n"
               "(perspective, cylindrical, spherical, stereographic, fisheye),\n"
               "F5 / F6 store / compare the frame's CRC, F10 sub-pixel jitter,\n"
               "F11 cycles the analysis view (off, tile field, density), F12 screenshot,\n"
               "Shift+F1 tile heatmap, Shift+F2 32-bit commit path (vulkan),\n"
               "Shift+F3 cycles MSAA 1/2/4/8, Shift+F12 temporal reprojection (on with\n"
               "jitter), space plays or pauses the animation, S toggles shadows,\n"
               "H lists the keys in the window, Escape quits.\n"
               "Drop a model file on the window to load it.\n";
}

#ifdef TESSERA_HAS_VIEWER
// The viewer's options from the flags; `fov`: the perspective view angle.
viewer::ViewerOptions viewerOptions(const ViewSettings& s, Projection projection, float fov) {
  viewer::ViewerOptions options;
  options.width = s.width;
  options.height = s.height;
  options.fps = s.fps;
  // Perspective takes -fov when it is a perspective angle; every mode takes it where it fits.
  options.fov_y_degrees = fov;
  if (s.has_fov) options.view_angle = s.fov;
  options.projection = projection;
  options.stats = s.stats;
  options.world_axes = s.axes;
  options.fullscreen = s.fullscreen;
  options.msaa = s.msaa;
  options.points.size = s.points.points.size;
  options.points.sprites = s.points.points.sprites;
  options.line_width = s.points.line_width;
  options.shadows = s.lights.shadows;
  options.view_direction = threeQuarterDirection({0, 1, 0});
  return options;
}
// What every model the viewer loads takes from the flags: --texture's albedo (read here), the
// shading, budgets, lights, grid and tone, and --hdri's environment (read once here).
Expected<ViewLoad> makeViewLoad(const ViewSettings& s) {
  ModelSceneSettings scene_settings;
  if (!s.texture.empty()) {
    Expected<Texture> texture = io::loadTexture(s.texture, /*srgb=*/true, s.budget.texturePixels());
    if (!texture) return texture.error();
    scene_settings.albedo = std::make_shared<const Texture>(std::move(*texture));
  }
  ViewLoad load{scene_settings,
                s.shading,
                s.budget,
                s.lights,
                s.animation_index,
                std::make_shared<std::atomic<bool>>(false),
                s.grid,
                s.tone,
                nullptr,
                false,
                float3x3{}};
  if (!s.hdri.empty()) {
    Scene lit;  // applyEnvironment's image, prepared once for every load
    SurfaceSettings surface;
    surface.hdri = s.hdri;
    surface.hdri_background = s.hdri_background;
    if (Expected<void> read = applyEnvironment(surface, s.budget.texturePixels(), {0, 1, 0}, lit);
        !read)
      return read.error();
    load.environment = lit.environment;
    load.environment_background = lit.environment_background;
    load.world_to_environment = lit.world_to_environment;
  }
  return load;
}
#endif

}  // namespace

int runView(const std::vector<std::string>& args) {
  ViewSettings s;
  FlagSet flags("tessera view [MODEL] [--width 800] [--height 600] [--fps 60] [--fov 50] [flags]",
                /*single_dash=*/true);
  addViewFlags(flags, s);
  Expected<std::vector<std::string>> positional = flags.parse(args);
  if (flags.helpRequested()) {
    printViewHelp(flags);
    return kExitOk;
  }
  auto usageError = [&](const std::string& message) {
    printError("view", message);
    std::cerr << flags.hint();
    return kExitUsage;
  };
  if (!positional) return usageError(positional.error().message);
  if (positional->size() > 1) return usageError("more than one model given");
  const Projection projection = parseProjection(s.projection).value_or(Projection::kPerspective);
  if (std::string range = checkFov(s, projection, static_cast<float>(s.width) / s.height);
      !range.empty())
    return usageError("-fov: " + range);
  if (std::string wrong = checkViewCameraFlags(s, projection, positional->empty()); !wrong.empty())
    return usageError(wrong);
  if (s.hdri_background && s.hdri.empty())
    return usageError("--hdri-background needs an image: --hdri PATH");
#ifndef TESSERA_HAS_VIEWER
  printError("view",
             "this tessera was built without the viewer (it needs SDL2 and SDL2_ttf: install "
             "libsdl2-dev and libsdl2-ttf-dev, then configure with -DTESSERA_VIEWER=ON)");
  return kExitFailure;
#else
  std::optional<std::filesystem::path> model_path;
  if (!positional->empty()) {
    model_path = positional->front();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(*model_path, ec)) {
      printError("view", model_path->string() + ": no such file");
      return kExitFailure;
    }
  }

  Expected<ViewLoad> made = makeViewLoad(s);
  if (!made) {
    printError("view", made.error().message);
    return kExitFailure;
  }
  ViewLoad& load = *made;
  // --animation-index and --camera-index are checked against the model before the window opens;
  // the viewer's first load then takes this scene.
  auto preloaded = std::make_shared<PreloadedScene>();
  if (model_path && (s.animation_index >= 0 || s.camera.camera_index >= 0)) {
    if (int status = preloadViewScene(s, load, *model_path, preloaded->scene.emplace());
        status != kExitOk)
      return status;
  }

  Expected<std::unique_ptr<Backend>> backend = makeBackend(s.backend, s.workers, s.device);
  if (!backend) {
    printError("view", backend.error().message);
    return kExitFailure;
  }

  const float fov = s.has_fov && isPerspectiveFov(s.fov) ? s.fov : 50.0f;
  const viewer::ViewerHooks hooks = viewHooks(s, load, preloaded, fov);
  const viewer::ViewerOptions options = viewerOptions(s, projection, fov);
  if (Expected<void> ran = viewer::runViewer(options, **backend, hooks, model_path); !ran) {
    printError("view", ran.error().message);
    return kExitFailure;
  }
  return kExitOk;
#endif
}

}  // namespace tessera::cli
