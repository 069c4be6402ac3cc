// tessera render MODEL: a model to a PNG (colour or an AOV), a turntable GIF or a PNG sequence.
// Flags follow f3d's names where f3d has one.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include <tessera/io/atomic_file.h>
#include <tessera/io/frame_sink.h>
#include <tessera/io/image_writer.h>
#include <tessera/io/model_loader.h>
#include <tessera/model/model_scene.h>
#include <tessera/render/composite.h>
#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/color.h>

#include "animation_frames.h"
#include "backends.h"
#include "budget_flags.h"
#include "commands.h"
#include "diagnostics_output.h"
#include "flags.h"
#include "light_flags.h"
#include "point_flags.h"
#include "progress.h"
#include "render_scene.h"
#include "render_settings.h"
#include "sampling_flags.h"
#include "surface_flags.h"
#include "validation.h"
#include "view_setup.h"

namespace tessera::cli {

using namespace tessera::model;

namespace {

enum class OutputKind { kPng, kVideo, kSequence };  // kVideo: .gif or .mp4

bool endsWithIgnoringCase(const std::string& text, const std::string& suffix) {
  if (text.size() < suffix.size()) return false;
  return std::equal(suffix.rbegin(), suffix.rend(), text.rbegin(),
                    [](char a, char b) { return std::tolower(a) == std::tolower(b); });
}

Expected<void> writeStill(const std::filesystem::path& path, const Frame& frame,
                          const std::string& aov, bool alpha) {
  if (aov == "id") return io::writeIdPng(path, frame);
  if (aov == "depth") return io::writeDepthPng(path, frame);
  if (aov == "normal") return io::writeNormalPng(path, frame);
  if (aov == "coverage") return io::writeCoveragePng(path, frame);
  if (isDiagnosticAov(aov)) return writeDiagnosticAov(path, frame, aov);
  if (!alpha) return io::writePngRgba8(path, frame.width, frame.height, frame.color.data());
  // A transparent background: the frame's colours are premultiplied (composite.h).
  std::vector<uint32_t> straight = frame.color;
  straightAlpha(straight);
  return io::writePngRgba8(path, frame.width, frame.height, straight.data(), /*keep_alpha=*/true);
}

// An sRGB colour flag's value, each channel in 0..1: "" or what is wrong.
std::string parseSrgbColor(const std::string& v, float3& out) {
  Expected<float3> c = parseFloat3(v);
  if (!c) return c.error().message;
  for (int i = 0; i < 3; ++i)
    if ((*c)[i] < 0.0f || (*c)[i] > 1.0f) return "each channel must be in 0..1";
  out = *c;
  return "";
}

// --visibility, --edges, --edge-color; --point-size, --point-sprites, --line-width
// (docs/rendering.md).
void addVisibilityFlags(FlagSet& flags, RenderSettings& s) {
  flags.addChoice("visibility", &s.visibility, {"z-buffer", "painter"},
                  "z-buffer, or painter: no depth test, triangles drawn back to front by their "
                  "average depth (default z-buffer; cpu backend, perspective projection)");
  flags.addSwitch("edges|e", &s.edges,
                  "draw every polygon's outline (cpu backend, perspective projection)");
  flags.addCustom("edge-color", "R,G,B", "the edges' colour, sRGB 0..1 (default 0,0,0)",
                  [&](const std::string& v) { return parseSrgbColor(v, s.edge_color); });
  addPointFlags(flags, s.points,
                "the width in pixels of the model's lines and of the edges, up to 64 (default 1)");
}

void addRenderFlags(FlagSet& flags, RenderSettings& s) {
  flags.addString("o|output", &s.output,
                  "output: .png; .gif, .mp4 or a {frame} PNG template for a turntable "
                  "(default MODEL's name with .png, in the current folder)");
  flags.addCustom("resolution", "W,H", "image size in pixels, W,H or WxH (default 1000,600)",
                  [&](const std::string& v) { return parseSize(v, s.width, s.height); });
  flags.addCustom("background-color|bg-color", "R,G,B",
                  "background, sRGB 0..1 (default 0.2,0.2,0.2)",
                  [&](const std::string& v) { return parseSrgbColor(v, s.background); });
  flags.addCustom("color", "R,G,B",
                  "base colour, sRGB 0..1, of faces the file gives no material (default 0.8 grey; "
                  "f3d's --color)",
                  [&](const std::string& v) {
                    float3 c;
                    std::string problem = parseSrgbColor(v, c);
                    if (problem.empty()) s.color = c;
                    return problem;
                  });
  addCameraFlags(flags, s.camera);
  flags.addChoice("shading", &s.shading, {"flat", "smooth", "gouraud", "unlit", "pbr"},
                  "flat, smooth (per-pixel), gouraud (per-vertex), unlit or pbr (glTF's "
                  "metallic-roughness; default pbr for glTF, smooth for other formats)");
  flags.addChoice("backface-type", &s.backface, {"visible", "hidden"},
                  "draw or cull back faces (default: glTF materials say, else visible)");
  std::vector<std::string> aovs = {"color", "id", "depth", "normal", "coverage"};
  aovs.insert(aovs.end(), diagnosticAovNames().begin(), diagnosticAovNames().end());
  flags.addChoice("aov", &s.aov, aovs,
                  "what to write: colour, triangle id, window depth, world normal (all three at "
                  "the pixel centre, whatever --msaa says), coverage (covered samples) or a "
                  "diagnostic (docs/rendering.md: overdraw, occupancy, material, density, "
                  "tile-occlusion, tile-edges; overdraw-heatmap and occupancy-heatmap for people)");
  flags.addString("stats", &s.stats,
                  "write each frame's pipeline counters, stage times and per-tile diagnostics "
                  "to this JSON file (docs/stats.md)");
  addSamplingFlags(flags, s.sampling);
  addVisibilityFlags(flags, s);
  addLightFlags(flags, s.lights);
  flags.addInt("turntable", &s.turntable, "frames of one full turn about the up axis", 1, 100000);
  flags.addSeconds("duration", &s.duration,
                   "seconds of one full turn (4s, 2.5, 500ms): round(duration x fps) frames");
  flags.addInt("fps", &s.fps, "frames per second of a turntable or animation (default 30)", 1, 100);
  flags.addInt("animation-index", &s.animation_index,
               "play the model's animation N (glTF, from 0) at --fps over its length", 0, 1000000);
  flags.addString("frame-range", &s.frame_range,
                  "A:B: render frames A to B (inclusive, from 0, at --fps) of the animation");
  flags.addInt("workers", &s.workers, "render threads; 0 = all cores (default 0)", 0, 1024);
  flags.addChoice("backend", &s.backend, backendNames(), "renderer (default cpu)");
  addSimdFlag(flags, &s.simd);
  flags.addInt("device", &s.device, "Vulkan device index (default: the first suitable)", 0, 64);
  flags.addSwitch("axes|axis|x", &s.axes, "draw the world axes (f3d's -x, --axis)");
  flags.addString("texture|texture-base-color", &s.texture,
                  "an albedo texture (PNG, JPEG, BMP, TGA) for every material");
  flags.addSwitch("info", &s.info, "print the model's counts, bounds and warnings; do not render");
  flags.addSwitch("crc", &s.crc,
                  "print the CRC-32 of each frame's RGBA8 colour pixels: crc32 frame N HEX");
  addReferenceFlags(flags, s.reference);
  addBudgetFlags(flags, s.budget);
  addProgressFlags(flags, s.progress);
  addSurfaceFlags(flags, s.surface);
}

// --duration as --turntable's frame count (round(duration x fps)): "" or a usage error when it
// gives no frame, too many, or disagrees with a --turntable given beside it.
std::string resolveDuration(RenderSettings& s) {
  if (s.duration <= 0.0f) return "";
  if (s.animation_index >= 0)
    return "--duration sets a turntable's length; an animation plays for its own length "
           "(--frame-range picks part of it)";
  const double frames = std::round(static_cast<double>(s.duration) * s.fps);
  std::ostringstream given;
  given << "--duration " << s.duration << " at --fps " << s.fps << " is "
        << static_cast<long long>(frames) << (frames == 1 ? " frame" : " frames");
  if (frames < 1) return given.str() + ": no frame to render";
  if (frames > 100000) return given.str() + ", more than 100000";
  if (s.turntable > 0 && s.turntable != static_cast<int>(frames))
    return given.str() + ", not --turntable " + std::to_string(s.turntable) +
           ": give one of them, or both agreeing";
  s.turntable = static_cast<int>(frames);
  return "";
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
  if (s.animation_index >= 0 && s.turntable > 0)
    return "--animation-index and --turntable do not go together";
  if (!s.frame_range.empty() && s.animation_index < 0)
    return "--frame-range picks frames of an animation: add --animation-index N";
  if (endsWithIgnoringCase(s.output, ".mp4"))
    if (std::string odd = io::mp4SizeProblem(s.width, s.height); !odd.empty()) return odd;
  if (kind == OutputKind::kVideo && s.aov != "color")
    return "--aov " + s.aov + " needs PNG output (a .png or a {frame} template)";
  if ((s.crc || !s.reference.path.empty()) && s.aov != "color")
    return "--crc and --reference check the colour image: leave out --aov " + s.aov;
  if (!s.reference.path.empty() && kind != OutputKind::kPng)
    return "--reference compares one image: use a .png output without --turntable";
  if (s.reference.update && s.reference.path.empty())
    return "--reference-update needs --reference PATH, the file to write";
  return refuseSurface(s.surface, kind != OutputKind::kVideo, s.aov);
}

// What --visibility painter and --edges cannot go with, or "".
std::string refuseVisibility(const RenderSettings& s, bool diagnostics) {
  if (s.visibility != "painter" && !s.edges) return "";
  const std::string what = s.visibility == "painter" ? "--visibility painter" : "--edges";
  if (s.backend != "cpu") return what + " is drawn by the cpu backend only (use --backend cpu)";
  if (s.camera.projectionMode() != Projection::kPerspective)
    return what + " is drawn for the perspective projection only";
  if (s.visibility == "painter" && diagnostics)
    return "--stats and the diagnostic AOVs measure the z-buffer's work: leave out --visibility "
           "painter";
  return "";
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
  options.frame_kept = true;  // renderFrames only reads the frame between renders
  if (s.visibility == "painter") options.visibility = Visibility::kPainter;
  options.edges.show = s.edges;
  options.shadows.enabled = s.lights.shadows;
  for (int i = 0; i < 3; ++i) options.edges.color[i] = srgbToLinear(s.edge_color[i]);
  applyPointSettings(s.points, options);
  options.edges.width = s.points.line_width;
  options.opacity = s.surface.opacity;
  // The id, depth and normal AOVs are the pixel centre's: one sample, no jitter. Coverage is
  // frame 0's (not jittered) at the --msaa count.
  sampling = s.sampling;
  if (s.aov != "color") sampling.samples = 1;
  if (s.aov == "id" || s.aov == "depth" || s.aov == "normal" || isDiagnosticAov(s.aov))
    sampling.msaa = 1;
  return options;
}

// The scene's instances posed by `clip` at time t (the graph's first instance is object 0).
void poseAnimation(const Animation& clip, float t, SceneGraph& graph, Scene& scene) {
  clip.apply(t, graph);
  graph.updateWorld();
  updateInstances(graph, 0, scene);
}

// The frames to render: the animation clip's (when --animation names one) or the turntable's. An
// exit status other than kExitOk when they cannot be written as asked (printed).
int planFrames(const RenderSettings& s, OutputKind kind, const Animation* clip, FramePlan& plan) {
  plan = FramePlan{0, std::max(s.turntable, 1)};
  if (clip) {
    Expected<FramePlan> frames = animationFrames(*clip, s.fps, s.frame_range);
    if (!frames) {
      printError("render", frames.error().message);
      return kExitUsage;
    }
    plan = *frames;
  }
  if (plan.count > 1 && kind == OutputKind::kPng) {
    printError("render", "the animation has " + std::to_string(plan.count) +
                             " frames: use a .gif, .mp4 or {frame} .png output, or --frame-range "
                             "A:A for one");
    return kExitUsage;
  }
  return kExitOk;
}

// The output's folder, made when missing (for a sequence, frame 0's: the template's folder), and
// for a video its encoder. An exit status other than kExitOk on failure (printed).
int openOutput(const RenderSettings& s, OutputKind kind, std::unique_ptr<io::FrameSink>& sink) {
  const std::filesystem::path first_output = kind == OutputKind::kSequence
                                                 ? io::formatFramePath(s.output, 0)
                                                 : std::filesystem::path(s.output);
  if (Expected<void> folder = io::createParentFolders(first_output); !folder) {
    printError("render", folder.error().message);
    return kExitFailure;
  }
  if (kind == OutputKind::kVideo) {
    Expected<std::unique_ptr<io::FrameSink>> opened =
        io::openFrameSink(s.output, {s.width, s.height, s.fps, true});
    if (!opened) {
      printError("render", opened.error().message);
      return kExitFailure;
    }
    sink = std::move(*opened);
  }
  return kExitOk;
}

// Frame i of `count` posed: the clip's pose at its time, or the turntable's turn, which turns
// every instance about the up axis through the model's centre.
void poseFrame(const RenderSettings& s, const Animation* clip, const FramePlan& plan, int i,
               const Bounds& bounds, SceneGraph& graph, Scene& scene) {
  if (clip) {
    poseAnimation(*clip, frameTime(*clip, s.fps, plan.first + i), graph, scene);
    return;
  }
  const float3 center = bounds.center();
  const quat turn = quat::fromAxisAngle(
      s.camera.upAxis(), 2.0f * kPi * static_cast<float>(i) / static_cast<float>(plan.count));
  for (Object& object : scene.objects) {
    object.transform.rotation = turn;
    object.transform.translation = center - rotate(turn, center);
  }
}

// After the last frame: the video finished, the progress line ended, the stats file committed, the
// summary printed and the reference compared. The exit status.
int finishOutput(const RenderSettings& s, io::FrameSink* sink, Progress& progress,
                 const Scene& scene, const Frame& frame, int frame_count,
                 const std::vector<std::string>& stats_frames,
                 std::optional<io::AtomicFile>& stats_file) {
  if (sink) {
    if (Expected<void> done = sink->finish(); !done) {
      printError("render", done.error().message);
      return kExitFailure;
    }
  }
  progress.finish();
  if (stats_file) {
    const std::string json = statsFileJson(stats_frames);
    Expected<void> done = stats_file->write(json.data(), json.size());
    if (done) done = stats_file->commit();
    if (!done) {
      printError("render", done.error().message);
      return kExitFailure;
    }
  }
  if (!s.progress.quiet) {
    std::cout << "wrote " << s.output << " (" << s.width << "x" << s.height << ", "
              << scene.triangleCount() << " triangles";
    if (frame_count > 1) std::cout << ", " << frame_count << " frames";
    std::cout << ")\n";
  }
  if (!s.reference.path.empty()) return checkReference(s.reference, s.output, frame);
  return kExitOk;
}

// Renders the frames of `scene` and writes them (and the stats file, when open); the exit status.
int renderFrames(const RenderSettings& s, OutputKind kind, Scene& scene, const Bounds& bounds,
                 SceneGraph& graph, bool diagnostics, std::optional<io::AtomicFile>& stats_file) {
  std::vector<std::string> stats_frames;
  Expected<std::unique_ptr<Backend>> backend = makeBackend(s.backend, s.workers, s.device, s.simd);
  if (!backend) {
    printError("render", backend.error().message);
    return kExitFailure;
  }
  Backend& renderer = **backend;
  SamplingSettings sampling;
  const RenderOptions options = renderOptions(s, diagnostics, sampling);
  Accumulator accumulator;
  Frame frame;
  const Animation* clip =
      s.animation_index >= 0 ? &graph.animations[static_cast<size_t>(s.animation_index)] : nullptr;
  FramePlan plan;
  if (int status = planFrames(s, kind, clip, plan); status != kExitOk) return status;
  std::unique_ptr<io::FrameSink> sink;
  if (int status = openOutput(s, kind, sink); status != kExitOk) return status;
  Progress progress("render: frame", plan.count, s.progress);
  for (int i = 0; i < plan.count; ++i) {
    poseFrame(s, clip, plan, i, bounds, graph, scene);
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
      written = writeStill(path, frame, s.aov, s.surface.no_background);
    }
    if (!written) {
      printError("render", written.error().message);
      return kExitFailure;
    }
    if (s.crc) printFrameCrc(i, frame);
    progress.update(i + 1);
  }
  return finishOutput(s, sink.get(), progress, scene, frame, plan.count, stats_frames, stats_file);
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
    std::cerr << flags.hint();
    return kExitUsage;
  };
  if (!positional) return usageError(positional.error().message);
  if (positional->size() != 1)
    return usageError(positional->empty() ? "no model given" : "more than one model given");
  const std::filesystem::path model_path = positional->front();
  if (s.output.empty()) s.output = model_path.stem().string() + ".png";

  if (std::string wrong = resolveDuration(s); !wrong.empty()) return usageError(wrong);
  OutputKind kind = OutputKind::kPng;
  if (std::string wrong = checkOutput(s, kind); !wrong.empty()) return usageError(wrong);
  if (std::string refused = refuseSimd(s.simd, s.backend); !refused.empty())
    return usageError(refused);
  const bool diagnostics = isDiagnosticAov(s.aov) || !s.stats.empty();
  // vulkan-raster's depth tests are the driver's: it fills the diagnostics it can measure
  // (docs/stats.md) but has no overdraw or occupancy to give.
  if (needsPixelTests(s.aov) && s.backend == "vulkan-raster") {
    printError("render", "--aov " + s.aov +
                             " is not measured on the vulkan-raster backend (use --backend cpu "
                             "or vulkan)");
    return kExitFailure;
  }
  if (std::string refused = refuseVisibility(s, diagnostics); !refused.empty()) {
    printError("render", refused);
    return kExitFailure;
  }
  if ((s.camera.orthographic || s.camera.camera_index >= 0) &&
      s.camera.projectionMode() != Projection::kPerspective)
    return usageError(
        std::string(s.camera.orthographic ? "--camera-orthographic" : "--camera-index") +
        " and --projection " + s.camera.projection + " do not go together");
  if (needsPixelTests(s.aov) && s.camera.projectionMode() != Projection::kPerspective) {
    printError("render", "--aov " + s.aov + " is measured for the perspective projection only");
    return kExitFailure;
  }
  // The stats file's temporary is made now: a path that cannot be written fails before any
  // work, and the temporary goes away with any failure below.
  std::optional<io::AtomicFile> stats_file;
  if (!s.stats.empty()) {
    Expected<void> folder = io::createParentFolders(s.stats);
    if (!folder) {
      printError("render", folder.error().message);
      return kExitFailure;
    }
    Expected<io::AtomicFile> created = io::AtomicFile::create(s.stats);
    if (!created) {
      printError("render", created.error().message);
      return kExitFailure;
    }
    stats_file.emplace(std::move(*created));
  }

  Scene scene;
  Bounds bounds;
  SceneGraph graph;
  if (int status = loadScene(s, model_path, scene, bounds, graph, usageError); status != kExitOk)
    return status;
  if (s.info) return kExitOk;

  return renderFrames(s, kind, scene, bounds, graph, diagnostics, stats_file);
}

}  // namespace tessera::cli
