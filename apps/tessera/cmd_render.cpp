// tessera render MODEL: a model to a PNG (colour or an AOV), a turntable GIF or a PNG sequence.
// Flags follow f3d's names where f3d has one.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>

#include <tessera/model/model_scene.h>
#include <tessera/io/atomic_file.h>
#include <tessera/io/frame_sink.h>
#include <tessera/io/image_loader.h>
#include <tessera/io/image_writer.h>
#include <tessera/io/model_loader.h>
#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/color.h>

#include "backends.h"
#include "budget_flags.h"
#include "commands.h"
#include "diagnostics_output.h"
#include "flags.h"
#include "sampling_flags.h"
#include "validation.h"
#include "view_setup.h"

namespace tessera::cli {

using namespace tessera::model;

namespace {

struct RenderSettings {
  std::string output;
  int width = 1000, height = 600;
  float3 background{0.2f, 0.2f, 0.2f};
  CameraSettings camera;
  std::string shading = "smooth";
  std::string backface;  // empty: the model says (glTF doubleSided), else visible
  std::string aov = "color";
  std::string backend = "cpu";
  int turntable = 0;
  int fps = 30;
  int workers = 0;
  int device = -1;
  bool axes = false;
  bool info = false;
  std::string texture;
  bool crc = false;
  ReferenceSettings reference;
  std::string stats;      // --stats PATH.json: the frames' diagnostics (docs/stats.md)
  io::LoadBudget budget;  // --memory-limit, --max-triangles, --max-texture-pixels
  SamplingSettings sampling{.msaa = 4};  // the image a user expects: anti-aliased
};

enum class OutputKind { kPng, kVideo, kSequence };  // kVideo: .gif or .mp4

bool endsWithIgnoringCase(const std::string& text, const std::string& suffix) {
  if (text.size() < suffix.size()) return false;
  return std::equal(suffix.rbegin(), suffix.rend(), text.rbegin(),
                    [](char a, char b) { return std::tolower(a) == std::tolower(b); });
}

Expected<void> writeStill(const std::filesystem::path& path, const Frame& frame,
                          const std::string& aov) {
  if (aov == "id") return io::writeIdPng(path, frame);
  if (aov == "depth") return io::writeDepthPng(path, frame);
  if (aov == "normal") return io::writeNormalPng(path, frame);
  if (aov == "coverage") return io::writeCoveragePng(path, frame);
  if (isDiagnosticAov(aov)) return writeDiagnosticAov(path, frame, aov);
  return io::writePngRgba8(path, frame.width, frame.height, frame.color.data());
}

void addRenderFlags(FlagSet& flags, RenderSettings& s) {
  flags.addString("o|output", &s.output,
                  "output: .png; .gif, .mp4 or a {frame} PNG template for a turntable "
                  "(default MODEL's name with .png, in the current folder)");
  flags.addCustom("resolution", "W,H", "image size in pixels (default 1000,600)",
                  [&](const std::string& v) -> std::string {
                    size_t comma = v.find(',');
                    long long w, h;
                    if (comma == std::string::npos || !parseIntStrict(v.substr(0, comma), w) ||
                        !parseIntStrict(v.substr(comma + 1), h))
                      return "expected W,H, got '" + v + "'";
                    if (w < 1 || h < 1 || w > 16384 || h > 16384)
                      return "each side must be between 1 and 16384";
                    s.width = static_cast<int>(w);
                    s.height = static_cast<int>(h);
                    return "";
                  });
  flags.addCustom("background-color", "R,G,B", "background, sRGB 0..1 (default 0.2,0.2,0.2)",
                  [&](const std::string& v) -> std::string {
                    Expected<float3> c = parseFloat3(v);
                    if (!c) return c.error().message;
                    for (int i = 0; i < 3; ++i)
                      if ((*c)[i] < 0.0f || (*c)[i] > 1.0f) return "each channel must be in 0..1";
                    s.background = *c;
                    return "";
                  });
  addCameraFlags(flags, s.camera);
  flags.addChoice("shading", &s.shading, {"flat", "smooth", "gouraud", "unlit"},
                  "flat, smooth (per-pixel), gouraud (per-vertex) or unlit (default smooth)");
  flags.addChoice("backface-type", &s.backface, {"visible", "hidden"},
                  "draw or cull back faces (default: glTF materials say, else visible)");
  std::vector<std::string> aovs = {"color", "id", "depth", "normal", "coverage"};
  aovs.insert(aovs.end(), diagnosticAovNames().begin(), diagnosticAovNames().end());
  flags.addChoice("aov", &s.aov, aovs,
                  "what to write: colour, triangle id, window depth, world normal (all three at "
                  "the pixel centre, whatever --msaa says), coverage (covered samples) or a "
                  "diagnostic (docs/usage.md: overdraw, occupancy, material, density, "
                  "tile-occlusion, tile-edges; overdraw-heatmap and occupancy-heatmap for people)");
  flags.addString("stats", &s.stats,
                  "write each frame's pipeline counters, stage times and per-tile diagnostics "
                  "to this JSON file (docs/stats.md)");
  addSamplingFlags(flags, s.sampling);
  flags.addInt("turntable", &s.turntable, "frames of one full turn about the up axis", 1, 100000);
  flags.addInt("fps", &s.fps, "frames per second of a turntable (default 30)", 1, 100);
  flags.addInt("workers", &s.workers, "render threads; 0 = all cores (default 0)", 0, 1024);
  flags.addChoice("backend", &s.backend, backendNames(), "renderer (default cpu)");
  flags.addInt("device", &s.device, "Vulkan device index (default: the first suitable)", 0, 64);
  flags.addSwitch("axes", &s.axes, "draw the world axes");
  flags.addString("texture", &s.texture,
                  "an albedo texture (PNG, JPEG, BMP, TGA) for every material");
  flags.addSwitch("info", &s.info, "print the model's counts, bounds and warnings; do not render");
  flags.addSwitch("crc", &s.crc,
                  "print the CRC-32 of each frame's RGBA8 colour pixels: crc32 frame N HEX");
  addReferenceFlags(flags, s.reference);
  addBudgetFlags(flags, s.budget);
}

// What the output path asks for, and the flags that cannot go with it: "" or a usage error.
std::string checkOutput(const RenderSettings& s, OutputKind& kind) {
  if (s.output.find("{frame}") != std::string::npos) {
    if (!endsWithIgnoringCase(s.output, ".png")) return "a {frame} output must end in .png";
    kind = OutputKind::kSequence;
  } else if (endsWithIgnoringCase(s.output, ".gif") || endsWithIgnoringCase(s.output, ".mp4")) {
    kind = OutputKind::kVideo;
  } else if (endsWithIgnoringCase(s.output, ".png")) {
    kind = OutputKind::kPng;
  } else {
    return "output '" + s.output +
           "' must end in .png, .gif or .mp4, or be a {frame} .png template";
  }
  if (kind == OutputKind::kPng && s.turntable > 1)
    return "--turntable writes several frames: use a .gif, .mp4 or {frame} .png output";
  if (kind == OutputKind::kVideo && s.aov != "color")
    return "--aov " + s.aov + " needs PNG output (a .png or a {frame} template)";
  if ((s.crc || !s.reference.path.empty()) && s.aov != "color")
    return "--crc and --reference check the colour image: leave out --aov " + s.aov;
  if (!s.reference.path.empty() && kind != OutputKind::kPng)
    return "--reference compares one image: use a .png output without --turntable";
  if (s.reference.update && s.reference.path.empty())
    return "--reference-update needs --reference PATH, the file to write";
  return "";
}

// The model as a scene with its camera, lights and axes, and the model's bounds. An exit status
// other than kExitOk when something fails (printed); kExitOk after --info's listing too.
int loadScene(const RenderSettings& s, const std::filesystem::path& model_path, Scene& scene,
              Bounds& bounds, const std::function<int(const std::string&)>& usage_error) {
  Expected<io::Model> model = io::loadModel(model_path, s.budget);
  if (!model) {
    printError("render", model.error().message);
    return kExitFailure;
  }
  if (s.info) {
    printModelInfo(model_path.string(), *model, std::cout);
    return kExitOk;
  }
  if (std::string warning = fitModelScale(*model, model_path, s.camera.explicitCamera());
      !warning.empty())
    model->warnings.push_back(warning);
  for (const std::string& warning : model->warnings)
    std::cerr << "tessera render: warning: " << warning << "\n";
  ModelSceneSettings scene_settings;
  if (!s.texture.empty()) {
    Expected<Texture> texture = io::loadTexture(s.texture, /*srgb=*/true, s.budget.texturePixels());
    if (!texture) {
      printError("render", texture.error().message);
      return kExitFailure;
    }
    if (!modelHasUvs(*model))
      std::cerr << "tessera render: warning: " << model_path.string()
                << " has no texture coordinates: --texture has no effect\n";
    scene_settings.albedo = std::make_shared<const Texture>(std::move(*texture));
  }
  bounds = modelBounds(*model);
  if (bounds.empty()) {
    printError("render", model_path.string() + ": the model has no finite vertices");
    return kExitFailure;
  }

  scene_settings.shading = shadingFromName(s.shading);
  // Without the flag a glTF model's materials decide (doubleSided); other formats draw back faces.
  const bool cull_back =
      s.backface.empty() ? model->cull_back_faces.value_or(false) : s.backface == "hidden";
  scene_settings.cull = cull_back ? CullMode::kBack : CullMode::kNone;
  scene_settings.background_srgb = s.background;
  SceneGraph graph;
  Expected<Scene> made = makeModelScene(std::move(*model), model_path, scene_settings, &graph);
  if (!made) {
    printError("render", made.error().message);
    return kExitFailure;
  }
  scene = std::move(*made);

  const float aspect = static_cast<float>(s.width) / static_cast<float>(s.height);
  Expected<Camera> camera = makeCamera(s.camera, bounds, aspect, &graph);
  if (!camera && cameraIndexError(camera.error().message)) {
    printError("render", model_path.string() + ": " + camera.error().message);
    return kExitFailure;
  }
  if (!camera) return usage_error(camera.error().message);
  scene.camera = *camera;
  addViewLights(scene);
  if (s.axes) {
    scene.show_world_axes = true;
    scene.world_axes_length = std::max(bounds.radius(), 1e-6f);
  }

  return kExitOk;
}

// The options and the sampling of every frame for these settings.
RenderOptions renderOptions(const RenderSettings& s, bool diagnostics, SamplingSettings& sampling) {
  RenderOptions options;
  options.width = s.width;
  options.height = s.height;
  options.depth = s.aov == "depth";
  options.ids = s.aov == "id" || s.aov == "normal";
  options.normals = s.aov == "normal";
  options.lines = s.aov == "color";
  options.coverage = s.aov == "coverage";
  options.diagnostics = diagnostics;
  options.projection = s.camera.projectionMode();
  // The id, depth and normal AOVs are the pixel centre's: one sample, no jitter. Coverage is
  // frame 0's (not jittered) at the --msaa count.
  sampling = s.sampling;
  if (s.aov != "color") sampling.samples = 1;
  if (s.aov == "id" || s.aov == "depth" || s.aov == "normal" || isDiagnosticAov(s.aov))
    sampling.msaa = 1;
  return options;
}

// Renders the frames of `scene` and writes them (and the stats file, when open); the exit status.
int renderFrames(const RenderSettings& s, OutputKind kind, Scene& scene, const Bounds& bounds,
                 bool diagnostics, std::optional<io::AtomicFile>& stats_file) {
  std::vector<std::string> stats_frames;
  Expected<std::unique_ptr<Backend>> backend = makeBackend(s.backend, s.workers, s.device);
  if (!backend) {
    printError("render", backend.error().message);
    return kExitFailure;
  }
  Backend& renderer = **backend;
  SamplingSettings sampling;
  const RenderOptions options = renderOptions(s, diagnostics, sampling);
  Accumulator accumulator;
  Frame frame;
  const int frame_count = std::max(s.turntable, 1);
  std::unique_ptr<io::FrameSink> sink;
  if (kind == OutputKind::kVideo) {
    Expected<std::unique_ptr<io::FrameSink>> opened =
        io::openFrameSink(s.output, {s.width, s.height, s.fps, true});
    if (!opened) {
      printError("render", opened.error().message);
      return kExitFailure;
    }
    sink = std::move(*opened);
  }
  const float3 center = bounds.center();
  const float3 up = s.camera.upAxis();
  Progress progress("render: frame", frame_count);
  for (int i = 0; i < frame_count; ++i) {
    // The turntable turns the model about the up axis through its centre.
    const quat turn = quat::fromAxisAngle(
        up, 2.0f * kPi * static_cast<float>(i) / static_cast<float>(frame_count));
    scene.objects[0].transform.rotation = turn;
    scene.objects[0].transform.translation = center - rotate(turn, center);
    if (Expected<void> rendered =
            renderSampled(renderer, accumulator, scene, options, sampling, frame);
        !rendered) {
      printError("render", rendered.error().message);
      return kExitFailure;
    }
    if (stats_file) stats_frames.push_back(statsFrameJson(frame, i, s.backend));
    Expected<void> written;
    if (sink) {
      written = sink->addFrame(frame.color.data());
    } else {
      std::filesystem::path path = kind == OutputKind::kSequence ? io::formatFramePath(s.output, i)
                                                                 : std::filesystem::path(s.output);
      written = writeStill(path, frame, s.aov);
    }
    if (!written) {
      printError("render", written.error().message);
      return kExitFailure;
    }
    if (s.crc) printFrameCrc(i, frame);
    if (frame_count > 1) progress.update(i + 1);
  }
  if (sink) {
    if (Expected<void> done = sink->finish(); !done) {
      printError("render", done.error().message);
      return kExitFailure;
    }
  }
  if (frame_count > 1) progress.finish();
  if (stats_file) {
    const std::string json = statsFileJson(stats_frames);
    Expected<void> done = stats_file->write(json.data(), json.size());
    if (done) done = stats_file->commit();
    if (!done) {
      printError("render", done.error().message);
      return kExitFailure;
    }
  }
  std::cout << "wrote " << s.output << " (" << s.width << "x" << s.height << ", "
            << scene.triangleCount() << " triangles";
  if (frame_count > 1) std::cout << ", " << frame_count << " frames";
  std::cout << ")\n";
  if (!s.reference.path.empty()) return checkReference(s.reference, s.output, frame);
  return kExitOk;
}

}  // namespace

int runRender(const std::vector<std::string>& args) {
  RenderSettings s;
  FlagSet flags("tessera render MODEL [-o OUTPUT] [flags]");
  addRenderFlags(flags, s);
  Expected<std::vector<std::string>> positional = flags.parse(args);
  if (flags.helpRequested()) {
    std::cout << flags.usage();
    return kExitOk;
  }
  auto usageError = [&](const std::string& message) {
    printError("render", message);
    std::cerr << flags.usage();
    return kExitUsage;
  };
  if (!positional) return usageError(positional.error().message);
  if (positional->size() != 1)
    return usageError(positional->empty() ? "no model given" : "more than one model given");
  const std::filesystem::path model_path = positional->front();
  if (s.output.empty()) s.output = model_path.stem().string() + ".png";

  OutputKind kind = OutputKind::kPng;
  if (std::string wrong = checkOutput(s, kind); !wrong.empty()) return usageError(wrong);
  const bool diagnostics = isDiagnosticAov(s.aov) || !s.stats.empty();
  if (diagnostics && s.backend != "cpu") {
    printError("render", (isDiagnosticAov(s.aov) ? "--aov " + s.aov : std::string("--stats")) +
                             " is not yet on the " + s.backend + " backend (use --backend cpu)");
    return kExitFailure;
  }
  if ((s.camera.orthographic || s.camera.camera_index >= 0) &&
      s.camera.projectionMode() != Projection::kPerspective)
    return usageError(std::string(s.camera.orthographic ? "--camera-orthographic"
                                                        : "--camera-index") +
                      " and --projection " + s.camera.projection + " do not go together");
  if (needsPixelTests(s.aov) && s.camera.projectionMode() != Projection::kPerspective) {
    printError("render", "--aov " + s.aov + " is measured for the perspective projection only");
    return kExitFailure;
  }
  // The stats file's temporary is made now: a path that cannot be written fails before any
  // work, and the temporary goes away with any failure below.
  std::optional<io::AtomicFile> stats_file;
  if (!s.stats.empty()) {
    Expected<io::AtomicFile> created = io::AtomicFile::create(s.stats);
    if (!created) {
      printError("render", created.error().message);
      return kExitFailure;
    }
    stats_file.emplace(std::move(*created));
  }

  Scene scene;
  Bounds bounds;
  if (int status = loadScene(s, model_path, scene, bounds, usageError); status != kExitOk)
    return status;
  if (s.info) return kExitOk;

  return renderFrames(s, kind, scene, bounds, diagnostics, stats_file);
}

}  // namespace tessera::cli
