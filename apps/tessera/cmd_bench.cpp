// tessera bench [SCENE|MODEL...]: the median frame time of built-in scenes or model files at one
// or more resolutions, optionally beside Mesa's llvmpipe drawing the same frames through OpenGL.
// The timed loop covers rendering only: scenes are built and loaded, shaders compiled and buffers
// uploaded before it, and nothing is encoded or written.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <thread>

#include <tessera/io/validation.h>
#include <tessera/model/model_scene.h>
#include <tessera/render/sampling.h>

#include "backends.h"
#include "bench/llvmpipe_reference.h"
#include "bench/scenes.h"
#include "budget_flags.h"
#include "commands.h"
#include "flags.h"
#include "light_flags.h"
#include "point_flags.h"
#include "surface_flags.h"
#include "view_setup.h"

namespace tessera::cli {

using namespace tessera::model;

namespace {

struct Resolution {
  int width = 0, height = 0;
};

const std::vector<Resolution> kStandardResolutions = {{640, 480}, {1920, 1080}, {3840, 2160}};

struct BenchSettings {
  std::vector<Resolution> resolutions;
  int frames = 20;
  int warmup = 2;
  std::string shading = "gouraud";
  std::string backface = "hidden";
  CameraSettings camera;
  int workers = 0;
  std::string backend = "cpu";
  std::string simd = "auto";
  int msaa = 1;
  int device = -1;
  bool json = false;
  bool all = false;
  bool crc = false;
  std::string versus;  // "" or "llvmpipe"
  io::LoadBudget budget;
  LightSettings lights;  // --light, --ambient: in place of every scene's own lights
  PointSettings points;  // --point-size, --point-sprites, --line-width
  ToneSettings tone;     // --tone-mapping, --exposure: on every scene, for tessera and llvmpipe
  std::string hdri;      // --hdri: the environment light of every scene (tessera only)
};

struct Timing {
  double median_ms = 0, mean_ms = 0, min_ms = 0, max_ms = 0;
};

Timing summarize(std::vector<double> ms) {
  Timing t;
  std::sort(ms.begin(), ms.end());
  const size_t n = ms.size();
  t.median_ms = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
  for (double v : ms) t.mean_ms += v / static_cast<double>(n);
  t.min_ms = ms.front();
  t.max_ms = ms.back();
  return t;
}

// "W,H" or "WxH" items; several in one value separated by ';' or spaces, or by ',' between WxH
// items ("640x480,1920x1080"); "640,480,1920,1080" pairs the numbers up.
std::string parseResolutions(const std::string& text, std::vector<Resolution>& out) {
  std::string items = text;
  std::replace(items.begin(), items.end(), ';', ' ');
  std::istringstream in(items);
  std::string item;
  std::vector<Resolution> parsed;
  while (in >> item) {
    std::vector<std::string> numbers;
    std::string part;
    std::istringstream parts(item);
    while (std::getline(parts, part, ',')) {
      if (size_t x = part.find('x'); x != std::string::npos) {
        numbers.push_back(part.substr(0, x));
        numbers.push_back(part.substr(x + 1));
      } else {
        numbers.push_back(part);
      }
    }
    if (numbers.empty() || numbers.size() % 2 != 0)
      return "expected W,H or WxH (several separated by ';'), got '" + text + "'";
    for (size_t i = 0; i < numbers.size(); i += 2) {
      long long w, h;
      if (!parseIntStrict(numbers[i], w) || !parseIntStrict(numbers[i + 1], h))
        return "expected W,H or WxH (several separated by ';'), got '" + text + "'";
      if (w < 1 || h < 1 || w > 16384 || h > 16384) return "each side must be between 1 and 16384";
      parsed.push_back({static_cast<int>(w), static_cast<int>(h)});
    }
  }
  if (parsed.empty()) return "expected W,H or WxH, got '" + text + "'";
  out.insert(out.end(), parsed.begin(), parsed.end());
  return "";
}

std::string jsonString(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

// A built-in scene by name, or else a model file; an error names the argument.
Expected<bench::BenchScene> openScene(const std::string& arg, Shading shading,
                                      const io::LoadBudget& budget) {
  const std::vector<std::string> extra = bench::extraSceneNames();
  if (bench::isBuiltinScene(arg) || std::find(extra.begin(), extra.end(), arg) != extra.end())
    return bench::makeBuiltinScene(arg, shading);
  std::error_code error;
  if (!std::filesystem::exists(arg, error)) {
    std::string known;
    for (const std::string& n : bench::builtinSceneNames())
      known += (known.empty() ? "" : ", ") + n;
    for (const std::string& n : extra) known += ", " + n;
    return makeError("'" + arg + "' is neither a built-in scene (" + known + ") nor a model file");
  }
  Expected<bench::BenchScene> scene = bench::loadModelScene(arg, shading, budget);
  if (scene) scene->name = arg;  // the argument as given names the scene in the output
  return scene;
}

// Places the camera and lights for one image size: the scene's own view, or a camera that frames
// the model as `tessera render` does (or the one the camera flags give) with the view's lights.
Expected<void> placeView(bench::BenchScene& b, const CameraSettings& camera_settings,
                         Resolution resolution) {
  const float aspect = static_cast<float>(resolution.width) / static_cast<float>(resolution.height);
  if (b.fixed_view && !camera_settings.explicitCamera()) {
    // The scene's own camera and view angle, drawn in the mode asked for.
    if (std::string range =
            checkViewAngle(camera_settings.projectionMode(), b.scene.camera.fov_y_degrees, aspect);
        !range.empty())
      return makeError(b.name + ": " + range);
    if (camera_settings.projectionMode() != Projection::kPerspective)
      fitDistanceRange(b.scene.camera, b.bounds);
    return {};
  }
  Expected<Camera> camera = makeCamera(camera_settings, b.bounds, aspect);
  if (!camera) return camera.error();
  b.scene.camera = *camera;
  addViewLights(b.scene);
  if (!b.fixed_view) b.spin_axis = camera_settings.upAxis();
  return {};
}

// Renders `warmup` untimed frames, then timed frames [first, first + count), posing the scene
// before each; the clock runs around draw() alone. Appends the times to `ms`.
template <typename Draw>
void timeFrames(bench::BenchScene& b, int warmup, int first, int count, Draw&& draw,
                std::vector<double>& ms) {
  for (int i = 0; i < warmup; ++i) {
    bench::poseForFrame(b, first);
    draw();
  }
  for (int i = first; i < first + count; ++i) {
    bench::poseForFrame(b, i);
    const auto start = std::chrono::steady_clock::now();
    draw();
    const auto stop = std::chrono::steady_clock::now();
    ms.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
  }
}

// With a reference, the two renderers take turns in rounds of this many timed frames (after one
// untimed frame each, to bring their own data back into the caches): a shared machine's slow and
// fast spells then fall on both alike, which a whole run of one then the other does not give.
constexpr int kFramesPerRound = 5;

void addBenchFlags(FlagSet& flags, BenchSettings& s, bool& resolution_given) {
  flags.addCustom("resolution", "W,H",
                  "image size; repeatable, or a list such as 640x480,1920x1080 "
                  "(default 640x480, 1920x1080 and 3840x2160)",
                  [&s, &resolution_given](const std::string& v) {
                    resolution_given = true;
                    return parseResolutions(v, s.resolutions);
                  });
  flags.addInt("frames", &s.frames, "timed frames per scene and resolution (default 20)", 1,
               100000);
  flags.addInt("warmup", &s.warmup, "untimed frames before them (default 2)", 0, 1000);
  flags.addChoice("shading", &s.shading, {"flat", "smooth", "gouraud", "unlit", "pbr"},
                  "flat, smooth (per-pixel), gouraud (per-vertex), unlit or pbr (default gouraud)");
  flags.addChoice("backface-type", &s.backface, {"visible", "hidden"},
                  "draw or cull back faces (default hidden)");
  addCameraFlags(flags, s.camera);
  flags.addInt("workers", &s.workers,
               "render threads, and llvmpipe's LP_NUM_THREADS; 0 = all cores (default 0)", 0, 1024);
  flags.addChoice("backend", &s.backend, backendNames(), "renderer (default cpu)");
  addSimdFlag(flags, &s.simd);
  flags.addCustom("msaa", "N",
                  "samples per pixel: 1, 2, 4 or 8 (default 1); with --vs llvmpipe, llvmpipe "
                  "draws as many through a multisampled framebuffer object",
                  [&s](const std::string& v) -> std::string {
                    long long n = 0;
                    if (!parseIntStrict(v, n) || n < 1 || n > kMaxSamples ||
                        !isSampleCount(static_cast<int>(n)))
                      return "samples per pixel must be 1, 2, 4 or 8, not '" + v + "'";
                    s.msaa = static_cast<int>(n);
                    return "";
                  });
  flags.addInt("device", &s.device, "Vulkan device index (default: the first suitable)", 0, 64);
  flags.addChoice("vs", &s.versus, {"llvmpipe"},
                  "time the same frames on Mesa's llvmpipe too (needs a build with OSMesa)");
  flags.addSwitch("json", &s.json,
                  "print one JSON object per line: scene, resolution, width, height, triangles, "
                  "lights, frames, msaa, median_ms... and llvmpipe_median_ms, ratio with --vs");
  flags.addSwitch("crc", &s.crc,
                  "print the CRC-32 of the last timed frame's RGBA8 pixels for each scene and "
                  "resolution (crc32 SCENE WxH HEX; a crc32 field with --json)");
  flags.addSwitch("all", &s.all, "every built-in scene at every standard resolution (the default)");
  addBudgetFlags(flags, s.budget);
  addLightFlags(flags, s.lights);
  addPointFlags(flags, s.points, "the width in pixels of the scenes' lines, up to 64 (default 1)");
  addToneFlags(flags, s.tone);
  flags.addString("hdri", &s.hdri,
                  "an equirectangular Radiance .hdr or OpenEXR .exr image lighting every scene "
                  "(image-based light in --shading pbr; not with --vs llvmpipe)");
}

// Every scene is built or loaded before anything is timed, so a bad argument fails at once.
Expected<std::vector<bench::BenchScene>> openScenes(const std::vector<std::string>& args,
                                                    Shading shading, CullMode cull,
                                                    const BenchSettings& s) {
  // --hdri's image, read and prepared once for every scene (their up is +Y).
  Scene lit;
  SurfaceSettings surface;
  surface.hdri = s.hdri;
  if (Expected<void> read = applyEnvironment(surface, s.budget.texturePixels(), {0, 1, 0}, lit);
      !read)
    return read.error();
  const ToneSettings& tone = s.tone;
  const io::LoadBudget& budget = s.budget;
  std::vector<bench::BenchScene> scenes;
  for (const std::string& arg : args) {
    Expected<bench::BenchScene> scene = openScene(arg, shading, budget);
    if (!scene) return scene.error();
    for (const std::string& warning : scene->warnings)
      std::cerr << "tessera bench: warning: " << warning << "\n";
    for (Object& object : scene->scene.objects) object.cull = cull;
    applyTone(tone, scene->scene);
    scene->scene.environment = lit.environment;
    scene->scene.world_to_environment = lit.world_to_environment;
    scenes.push_back(std::move(*scene));
  }
  return scenes;
}

// The OSMesa reference on `workers` threads, drawing `msaa` samples per pixel. An llvmpipe that
// cannot draw exactly as many fails here, before anything is timed: timing it at another count
// would not be the same work.
Expected<std::unique_ptr<bench::LlvmpipeReference>> makeReference(int workers, int msaa) {
  // create() sets LP_NUM_THREADS to the worker count before llvmpipe starts its threads.
  Expected<std::unique_ptr<bench::LlvmpipeReference>> reference =
      bench::LlvmpipeReference::create(workers);
  if (!reference) return reference;
  if (Expected<void> sampled = (*reference)->setSamples(msaa); !sampled) return sampled.error();
  if (!(*reference)->isLlvmpipe())
    std::cerr << "tessera bench: warning: OSMesa renders with '" << (*reference)->renderer()
              << "', not llvmpipe\n";
  return reference;
}

// What one run of the benchmark draws with, for every scene and resolution.
struct BenchRun {
  const BenchSettings& settings;
  CullMode cull;
  int workers;  // the count in use (settings.workers, or the cores for 0)
  Backend& renderer;
  bench::LlvmpipeReference* reference;  // null without --vs
  RenderOptions options;
  Frame frame;
};

struct Measured {
  Timing tessera, llvmpipe;  // llvmpipe: zero without a reference
  uint32_t crc32 = 0;        // of tessera's last timed frame, with --crc
};

// Times tessera, and the reference in turns with it, on one scene at one resolution.
// `reference_loaded`: whether the reference holds this scene already.
Expected<Measured> measure(BenchRun& run, bench::BenchScene& b, Resolution resolution,
                           bool& reference_loaded) {
  const BenchSettings& s = run.settings;
  if (Expected<void> placed = placeView(b, s.camera, resolution); !placed) return placed.error();
  applyLights(b.scene, s.lights.lights, s.lights);
  run.options.width = resolution.width;
  run.options.height = resolution.height;
  auto drawTessera = [&] { run.renderer.render(b.scene, run.options, run.frame); };
  std::vector<double> tessera_ms, llvmpipe_ms;
  Measured measured;
  if (!run.reference) {
    timeFrames(b, s.warmup, 0, s.frames, drawTessera, tessera_ms);
  } else {
    if (!reference_loaded) {
      if (Expected<void> loaded = run.reference->setScene(b.scene); !loaded) return loaded.error();
      reference_loaded = true;
    }
    if (Expected<void> sized = run.reference->setResolution(resolution.width, resolution.height);
        !sized)
      return sized.error();
    auto drawLlvmpipe = [&] { run.reference->render(b.scene); };
    for (int first = 0; first < s.frames; first += kFramesPerRound) {
      const int count = std::min(kFramesPerRound, s.frames - first);
      const int warmup = first == 0 ? s.warmup : 1;
      timeFrames(b, warmup, first, count, drawTessera, tessera_ms);
      timeFrames(b, warmup, first, count, drawLlvmpipe, llvmpipe_ms);
    }
    measured.llvmpipe = summarize(llvmpipe_ms);
  }
  // A backend that failed (e.g. a device without the sample count) says why.
  if (Expected<void> rendered = run.renderer.lastResult(); !rendered) return rendered.error();
  measured.tessera = summarize(tessera_ms);
  // The last frame drawn by tessera is the last timed one (frame FRAMES-1), in either order.
  if (s.crc)
    measured.crc32 = io::crc32Rgba8(run.frame.color.data(), run.frame.width, run.frame.height);
  return measured;
}

// The camera flags given, as they are typed ("" for the bench's own view): --camera-position,
// --camera-focal-point and --camera-view-up, each x,y,z.
std::string cameraFlags(const CameraSettings& c) {
  std::ostringstream out;
  auto add = [&out](bool given, const char* name, float3 v) {
    if (!given) return;
    if (out.tellp() > 0) out << ' ';
    out << "--camera-" << name << ' ' << v.x << ',' << v.y << ',' << v.z;
  };
  add(c.has_position, "position", c.position);
  add(c.has_focal_point, "focal-point", c.focal_point);
  add(c.has_view_up, "view-up", c.view_up);
  return out.str();
}

// One line of output: a JSON object with --json, else a line of text.
void printMeasured(const BenchRun& run, const bench::BenchScene& b, Resolution resolution,
                   const Measured& m) {
  const BenchSettings& s = run.settings;
  const std::string size =
      std::to_string(resolution.width) + "x" + std::to_string(resolution.height);
  const size_t triangles = b.scene.triangleCount();
  const double ratio = m.llvmpipe.median_ms / m.tessera.median_ms;
  if (s.json) {
    std::cout << "{\"scene\": " << jsonString(b.name) << ", \"resolution\": \"" << size
              << "\", \"width\": " << resolution.width << ", \"height\": " << resolution.height
              << ", \"triangles\": " << triangles << ", \"lights\": " << b.scene.lights.size()
              << ", \"frames\": " << s.frames << ", \"warmup_frames\": " << s.warmup
              << ", \"msaa\": " << s.msaa << ", \"shading\": \"" << s.shading
              << "\", \"tone_mapping\": \"" << s.tone.tone_mapping
              << "\", \"exposure\": " << fixed(s.tone.exposure, 2)
              << ", \"hdri\": " << jsonString(s.hdri)
              << ", \"camera\": " << jsonString(cameraFlags(s.camera)) << ", \"back_faces\": \""
              << (run.cull == CullMode::kBack ? "culled" : "drawn")
              << "\", \"backend\": " << jsonString(run.renderer.name())
              << ", \"simd\": " << jsonString(simdName(run.renderer))
              << ", \"workers\": " << run.workers
              << ", \"median_ms\": " << fixed(m.tessera.median_ms, 4)
              << ", \"mean_ms\": " << fixed(m.tessera.mean_ms, 4)
              << ", \"min_ms\": " << fixed(m.tessera.min_ms, 4)
              << ", \"max_ms\": " << fixed(m.tessera.max_ms, 4);
    if (run.reference)
      std::cout << ", \"llvmpipe_median_ms\": " << fixed(m.llvmpipe.median_ms, 4)
                << ", \"llvmpipe_mean_ms\": " << fixed(m.llvmpipe.mean_ms, 4)
                << ", \"llvmpipe_min_ms\": " << fixed(m.llvmpipe.min_ms, 4)
                << ", \"llvmpipe_max_ms\": " << fixed(m.llvmpipe.max_ms, 4)
                << ", \"ratio\": " << fixed(ratio, 4)
                << ", \"reference\": " << jsonString(run.reference->renderer())
                << ", \"reference_version\": " << jsonString(run.reference->version());
    if (s.crc) std::cout << ", \"crc32\": \"" << io::crc32Hex(m.crc32) << "\"";
    std::cout << "}\n";
  } else {
    char line[512];
    std::snprintf(line, sizeof line,
                  "%-10s %10s %9zu triangles %5d frames %dx MSAA  tessera %9.3f ms", b.name.c_str(),
                  size.c_str(), triangles, s.frames, s.msaa, m.tessera.median_ms);
    std::cout << line;
    if (run.reference) {
      std::snprintf(line, sizeof line, "  llvmpipe %9.3f ms  ratio %6.2f", m.llvmpipe.median_ms,
                    ratio);
      std::cout << line;
    }
    std::cout << "\n";
    if (s.crc)
      std::cout << "crc32 " << b.name << " " << size << " " << io::crc32Hex(m.crc32) << "\n";
  }
  std::cout << std::flush;
}

void printHeader(const BenchRun& run) {
  const BenchSettings& s = run.settings;
  const std::string simd = simdName(run.renderer);
  std::cout << "# tessera bench: backend " << run.renderer.name()
            << (simd.empty() ? "" : " (" + simd + " kernels)") << ", " << run.workers
            << (run.workers == 1 ? " worker" : " workers") << ", " << s.shading << " shading, "
            << "tone mapping " << s.tone.tone_mapping << ", exposure " << fixed(s.tone.exposure, 2)
            << (s.hdri.empty() ? "" : ", environment " + s.hdri) << ", "
            << (run.cull == CullMode::kBack ? "back faces culled" : "back faces drawn") << ", "
            << s.msaa << (s.msaa == 1 ? " sample" : " samples") << " per pixel, " << s.warmup
            << " warm-up + " << s.frames << " timed frames, median\n";
  if (run.reference)
    std::cout << "# reference: " << run.reference->renderer() << ", " << run.reference->version()
              << ", LP_NUM_THREADS=" << run.reference->threads() << "\n";
  std::cout << std::flush;
}

// The flags against each other, before any work: "" or the usage error. `scenes_given`: scenes or
// models were named.
std::string checkBenchFlags(const BenchSettings& s, bool scenes_given, bool resolution_given) {
  if (std::string refused = refuseSimd(s.simd, s.backend); !refused.empty()) return refused;
  if (s.all && (scenes_given || resolution_given))
    return "--all runs the full matrix: give no scene and no --resolution with it";
  if (s.camera.projectionMode() != Projection::kPerspective && s.versus == "llvmpipe")
    return "--vs llvmpipe draws the perspective projection only; leave it out for --projection " +
           s.camera.projection;
  if (!s.hdri.empty() && s.versus == "llvmpipe")
    return "--vs llvmpipe draws no environment light: leave out --hdri";
  if (s.camera.explicitCamera()) {
    // The camera flags fail alike for every model.
    const Bounds unit{{-1, -1, -1}, {1, 1, 1}};
    if (Expected<Camera> camera = makeCamera(s.camera, unit, 1.0f); !camera)
      return camera.error().message;
  }
  return "";
}

}  // namespace

int runBench(const std::vector<std::string>& args) {
  BenchSettings s;
  bool resolution_given = false;
  FlagSet flags(
      "tessera bench [SCENE|MODEL...] [flags]\n\n"
      "Times frames of the built-in scenes (cube, bunny, dense, fill, textured) or of model files\n"
      "and prints the median frame time, one line per scene and resolution. With no scene and no\n"
      "--resolution it runs every built-in scene at 640x480, 1920x1080 and 3840x2160. With --vs\n"
      "llvmpipe the same frames are drawn by Mesa's llvmpipe (OpenGL through OSMesa) on as many\n"
      "threads, the two taking turns in rounds of 5 frames, and ratio = llvmpipe median / tessera\n"
      "median (above 1: tessera is faster).");
  addBenchFlags(flags, s, resolution_given);
  Expected<std::vector<std::string>> positional = flags.parse(args);
  if (flags.helpRequested()) {
    std::cout << flags.usage();
    return kExitOk;
  }
  auto usageError = [&](const std::string& message) {
    printError("bench", message);
    std::cerr << flags.hint();
    return kExitUsage;
  };
  if (!positional) return usageError(positional.error().message);
  if (std::string wrong = checkBenchFlags(s, !positional->empty(), resolution_given);
      !wrong.empty())
    return usageError(wrong);
  auto failure = [](const Error& error) {
    printError("bench", error.message);
    return kExitFailure;
  };
  if (s.resolutions.empty()) s.resolutions = kStandardResolutions;
  // The view angle against the projection's range, at every size: a usage error before any work.
  for (const Resolution& r : s.resolutions)
    if (Expected<float> angle =
            viewAngle(s.camera, static_cast<float>(r.width) / static_cast<float>(r.height));
        !angle)
      return usageError(angle.error().message);
  const CullMode cull = s.backface == "visible" ? CullMode::kNone : CullMode::kBack;
  const int workers = s.workers > 0
                          ? s.workers
                          : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  Expected<std::vector<bench::BenchScene>> scenes =
      openScenes(positional->empty() ? bench::builtinSceneNames() : *positional,
                 shadingFromName(s.shading), cull, s);
  if (!scenes) return failure(scenes.error());
  std::unique_ptr<bench::LlvmpipeReference> reference;
  if (s.versus == "llvmpipe") {
    Expected<std::unique_ptr<bench::LlvmpipeReference>> created = makeReference(workers, s.msaa);
    if (!created) return failure(created.error());
    reference = std::move(*created);
  }
  Expected<std::unique_ptr<Backend>> backend = makeBackend(s.backend, s.workers, s.device, s.simd);
  if (!backend) return failure(backend.error());

  BenchRun run{s, cull, workers, **backend, reference.get(), {}, {}};
  run.options.depth = false;
  run.options.ids = false;
  run.options.normals = false;
  run.options.lines = false;
  run.options.msaa = s.msaa;
  run.options.projection = s.camera.projectionMode();
  run.options.shadows.enabled = s.lights.shadows;
  // The frames follow one another in one Frame, only read between them (as a turntable's).
  run.options.frame_kept = true;
  applyPointSettings(s.points, run.options);
  if (!s.json) printHeader(run);
  for (bench::BenchScene& b : *scenes) {
    bool reference_loaded = false;
    for (const Resolution& resolution : s.resolutions) {
      Expected<Measured> measured = measure(run, b, resolution, reference_loaded);
      if (!measured) return failure(measured.error());
      printMeasured(run, b, resolution, *measured);
    }
  }
  return kExitOk;
}

}  // namespace tessera::cli
