// tessera view [MODEL]: the interactive viewer (an SDL2 window). Built only with TESSERA_VIEWER;
// otherwise the command says so.
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

#include <tessera/io/image_loader.h>
#include <tessera/io/model_loader.h>
#include <tessera/model/model_scene.h>
#include <tessera/render/projection.h>
#include <tessera/render/sampling.h>
#include <tessera/scene/color.h>
#include <tessera/scene/primitives.h>

#include "backends.h"
#include "budget_flags.h"
#include "commands.h"
#include "flags.h"
#include "light_flags.h"

#ifdef TESSERA_HAS_VIEWER
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
  bool fullscreen = false;
  int workers = 0;
  std::string texture;
  std::string backend = "cpu";
  int device = -1;
  int msaa = 4;  // what `tessera render` makes by default
  io::LoadBudget budget;
  LightSettings lights;  // --light, --ambient
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

// The built-in model: the demo's orange cube, flat-shaded.
io::Model cubeModel() {
  io::Model model;
  model.mesh = makeCube();
  Material material;
  material.base_color = demoCubeColor();
  model.materials.push_back(material);
  return model;
}

}  // namespace

int runView(const std::vector<std::string>& args) {
  ViewSettings s;
  FlagSet flags("tessera view [MODEL] [--width 800] [--height 600] [--fps 60] [--fov 50] [flags]",
                /*single_dash=*/true);
  flags.addInt("w|width", &s.width, "window width (default 800)", 1, 16384);
  flags.addInt("h|height", &s.height, "window height (default 600)", 1, 16384);
  flags.addInt("fps", &s.fps, "most frames a second while anything moves (default 60)", 1, 1000);
  flags.addCustom("fov", "DEG",
                  "vertical view angle in degrees (default 50; 1 to 170 in perspective; another "
                  "projection takes it where it fits, else its default: docs/usage.md)",
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
  flags.addSwitch("fullscreen", &s.fullscreen, "fill the screen");
  flags.addInt("workers", &s.workers, "render threads; 0 = all cores (default 0)", 0, 1024);
  flags.addString("texture", &s.texture, "an image used as the albedo of every material");
  addBudgetFlags(flags, s.budget);
  addLightFlags(flags, s.lights);
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

  Expected<std::vector<std::string>> positional = flags.parse(args);
  if (flags.helpRequested()) {
    std::cout << flags.usage()
              << "\nMouse: left drag orbits, wheel zooms, middle or shift + left drag pans.\n"
                 "Keys: 1 front, 3 right, 7 top, 9 isometric, Enter resets the camera,\n"
                 "F1 stats, F2 world axes, F3 object axes, F4 cycles the projection\n"
                 "(perspective, cylindrical, spherical, stereographic, fisheye),\n"
                 "F5 / F6 store / compare the frame's CRC, F10 sub-pixel jitter,\n"
                 "F11 cycles the analysis view (off, tile field, density), F12 screenshot,\n"
                 "Shift+F1 tile heatmap, Shift+F2 32-bit commit path (vulkan),\n"
                 "Shift+F3 cycles MSAA 1/2/4/8, Shift+F12 temporal reprojection (on with\n"
                 "jitter), H lists the keys in the window, Escape quits.\n"
                 "Drop a model file on the window to load it.\n";
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

  ModelSceneSettings scene_settings;
  if (!s.texture.empty()) {
    Expected<Texture> texture = io::loadTexture(s.texture, /*srgb=*/true, s.budget.texturePixels());
    if (!texture) {
      printError("view", texture.error().message);
      return kExitFailure;
    }
    scene_settings.albedo = std::make_shared<const Texture>(std::move(*texture));
  }

  Expected<std::unique_ptr<Backend>> backend = makeBackend(s.backend, s.workers, s.device);
  if (!backend) {
    printError("view", backend.error().message);
    return kExitFailure;
  }

  viewer::ViewerHooks hooks;
  // For tests only: while the file named by TESSERA_VIEW_TEST_HOLD_LOADS exists (at most a
  // minute), loads wait, so that a test can see the window during a load that takes long.
  std::string hold_file;
  if (const char* hold = std::getenv("TESSERA_VIEW_TEST_HOLD_LOADS")) hold_file = hold;
  // Runs on the loading thread: it owns its copy of the settings.
  // Whether the model last loaded brings its own lights (its file's or --light's): the default
  // rig, fixed to the view, is placed only when it does not. Between a load and the scene's swap a
  // frame may place (or keep) the previous model's lights: the next frame is right.
  auto own_lights = std::make_shared<std::atomic<bool>>(false);
  hooks.load_file = [scene_settings, hold_file, budget = s.budget, light_settings = s.lights,
                     own_lights](const std::filesystem::path& path) -> Expected<Scene> {
    if (!hold_file.empty()) {
      const auto until = std::chrono::steady_clock::now() + std::chrono::minutes(1);
      std::error_code ec;
      while (std::filesystem::exists(hold_file, ec) && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    Expected<io::Model> model = io::loadModel(path, budget);
    if (!model) return model.error();
    model->lights.insert(model->lights.end(), light_settings.lights.begin(),
                         light_settings.lights.end());
    // The viewer frames every model: any scale is drawn.
    fitModelScale(*model, path, /*keep_coordinates=*/false);
    for (const std::string& warning : model->warnings)
      std::cerr << "tessera view: warning: " << warning << "\n";
    const std::vector<Light> lights = model->lights;
    Expected<Scene> scene = makeModelScene(std::move(*model), path, scene_settings);
    if (scene) {
      addViewLights(*scene);
      applyLights(*scene, lights, light_settings);
      own_lights->store(!lights.empty());
    }
    return scene;
  };
  hooks.default_scene = [scene_settings] {
    ModelSceneSettings cube_settings = scene_settings;
    cube_settings.shading = Shading::kFlat;
    cube_settings.cull = CullMode::kBack;
    return makeModelScene(cubeModel(), "cube", cube_settings).value();
  };
  hooks.place_lights = [own_lights, light_settings = s.lights](Scene& scene) {
    if (own_lights->load()) return;
    addViewLights(scene);
    if (light_settings.ambient_given) scene.ambient = light_settings.ambient;
  };
  hooks.commit_path = vulkanCommitPath;

  viewer::ViewerOptions options;
  options.width = s.width;
  options.height = s.height;
  options.fps = s.fps;
  // Perspective takes -fov when it is a perspective angle; every mode takes it where it fits.
  if (s.has_fov && isPerspectiveFov(s.fov)) options.fov_y_degrees = s.fov;
  if (s.has_fov) options.view_angle = s.fov;
  options.projection = projection;
  options.stats = s.stats;
  options.world_axes = s.axes;
  options.fullscreen = s.fullscreen;
  options.msaa = s.msaa;
  options.view_direction = threeQuarterDirection({0, 1, 0});
  if (Expected<void> ran = viewer::runViewer(options, **backend, hooks, model_path); !ran) {
    printError("view", ran.error().message);
    return kExitFailure;
  }
  return kExitOk;
#endif
}

}  // namespace tessera::cli
