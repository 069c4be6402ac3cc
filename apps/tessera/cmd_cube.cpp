// tessera cube: one full turn of a flat-shaded cube, written as an animated GIF.
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

#include <tessera/io/atomic_file.h>
#include <tessera/io/frame_sink.h>
#include <tessera/io/image_writer.h>
#include <tessera/scene/color.h>
#include <tessera/scene/primitives.h>

#include "backends.h"
#include "commands.h"
#include "flags.h"
#include "progress.h"
#include "sampling_flags.h"
#include "validation.h"

namespace tessera::cli {

namespace {

struct CubeSettings {
  int width = 480;
  int height = 480;
  int fps = 30;
  float duration = 4.0f;
  float fov = 50.0f;
  std::string projection = "perspective";
  std::string output = "cube.gif";
  int workers = 0;
  std::string backend = "cpu";
  int device = -1;
  bool axes = false;
  bool crc = false;
  SamplingSettings sampling;
  ProgressFlags progress;
};

Scene makeCubeScene(const CubeSettings& settings) {
  Scene scene;
  Object cube;
  cube.mesh = std::make_shared<Mesh>(makeCube());
  cube.shading = Shading::kFlat;
  cube.materials[0].base_color = demoCubeColor();
  cube.show_axes = settings.axes;
  cube.axes_length = 0.8f;
  scene.objects.push_back(cube);
  scene.lights.push_back({normalize(float3{-0.6f, -1.0f, -0.8f}), float3(0.85f)});
  scene.lights.push_back({normalize(float3{0.8f, 0.3f, -0.4f}), float3(0.2f)});
  scene.ambient = float3(0.12f);
  scene.background = {srgbToLinear(0.12f), srgbToLinear(0.13f), srgbToLinear(0.16f), 1.0f};
  scene.camera.position = {0.0f, 1.1f, 2.4f};
  scene.camera.target = {0, 0, 0};
  scene.camera.fov_y_degrees = settings.fov;
  scene.camera.near_z = 0.1f;
  scene.camera.far_z = 20.0f;
  scene.show_world_axes = settings.axes;
  scene.world_axes_length = 1.2f;
  return scene;
}

}  // namespace

float4 demoCubeColor() {
  return {srgbToLinear(0.95f), srgbToLinear(0.55f), srgbToLinear(0.15f), 1.0f};
}

namespace {

// The flags of `tessera cube`, writing into s.
void addCubeFlags(FlagSet& flags, CubeSettings& s) {
  flags.addInt("w|width", &s.width, "image width in pixels (default 480)", 1, 16384);
  flags.addInt("h|height", &s.height, "image height in pixels (default 480)", 1, 16384);
  flags.addInt("fps", &s.fps, "frames per second (default 30)", 1, 100);
  flags.addSeconds("dur|duration", &s.duration, "length of one full turn (default 4s)");
  flags.addFloat("fov", &s.fov,
                 "vertical view angle in degrees (default 50); up to the projection's range", 1,
                 360);
  std::vector<std::string> modes;
  for (Projection p : kProjections) modes.push_back(projectionName(p));
  flags.addChoice("projection", &s.projection, modes,
                  "how pixels map to view rays (default perspective)");
  flags.addString("out|o|output", &s.output,
                  "output: .gif, or a PNG sequence such as frames/cube_{frame}.png "
                  "(default cube.gif)");
  flags.addInt("workers", &s.workers, "render threads; 0 = all cores (default 0)", 0, 1024);
  flags.addSwitch("axes", &s.axes, "draw the world axes and the cube's own axes");
  flags.addChoice("backend", &s.backend, backendNames(), "renderer (default cpu)");
  flags.addInt("device", &s.device, "Vulkan device index (default: the first suitable)", 0, 64);
  flags.addSwitch("crc", &s.crc,
                  "print the CRC-32 of each frame's RGBA8 colour pixels: crc32 frame N HEX");
  addSamplingFlags(flags, s.sampling);  // the demo keeps its look: one sample unless asked
  addProgressFlags(flags, s.progress);
}

// The frames the settings ask for (a single .png: one, the turn's first), or the usage error
// printed and 0.
long long cubeFrameCount(const CubeSettings& s, Projection projection, const FlagSet& flags) {
  if (std::string range = checkViewAngle(
          projection, s.fov, static_cast<float>(s.width) / static_cast<float>(s.height));
      !range.empty()) {
    printError("cube", "-fov: " + range);
    return 0;
  }
  long long frame_count = std::llround(static_cast<double>(s.duration) * s.fps);
  if (frame_count < 1 || frame_count > 100000) {
    printError("cube", "-dur times -fps must give between 1 and 100000 frames");
    return 0;
  }
  const bool sequence = s.output.find("{frame}") != std::string::npos;
  std::string extension = std::filesystem::path(s.output).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (!sequence && extension == ".png") frame_count = 1;
  if (!sequence && extension == ".mp4")
    if (std::string odd = io::mp4SizeProblem(s.width, s.height); !odd.empty()) {
      printError("cube", odd);
      std::cerr << flags.hint();
      return 0;
    }
  return frame_count;
}

// The sink for s.output, its folder made first.
Expected<std::unique_ptr<io::FrameSink>> openCubeSink(const CubeSettings& s) {
  const bool sequence = s.output.find("{frame}") != std::string::npos;
  const std::filesystem::path first_output =
      sequence ? io::formatFramePath(s.output, 0) : std::filesystem::path(s.output);
  if (Expected<void> folder = io::createParentFolders(first_output); !folder) return folder.error();
  return io::openFrameSink(s.output, io::AnimationSettings{s.width, s.height, s.fps, true});
}

// The turn's frames rendered and added to `sink`, then finished.
Expected<void> renderTurn(const CubeSettings& s, Projection projection, long long frame_count,
                          Backend& renderer, io::FrameSink& sink) {
  Scene scene = makeCubeScene(s);
  RenderOptions options;
  options.width = s.width;
  options.height = s.height;
  options.depth = false;
  options.ids = false;
  options.projection = projection;
  options.frame_kept = true;  // the loop below only reads the frame between renders
  Accumulator accumulator;
  Frame frame;
  Progress progress("cube: frame", static_cast<int>(frame_count), s.progress);
  for (long long i = 0; i < frame_count; ++i) {
    // One full turn about the vertical axis over the whole animation, on a tilted cube.
    const float angle = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(frame_count);
    scene.objects[0].transform.rotation =
        quat::fromAxisAngle({0, 1, 0}, angle) * quat::fromAxisAngle({1, 0, 0}, 0.35f);
    if (Expected<void> rendered =
            renderSampled(renderer, accumulator, scene, options, s.sampling, frame);
        !rendered)
      return rendered;
    if (Expected<void> added = sink.addFrame(frame.color.data()); !added) return added;
    if (s.crc) printFrameCrc(static_cast<int>(i), frame);
    progress.update(static_cast<int>(i + 1));
  }
  if (Expected<void> done = sink.finish(); !done) return done;
  progress.finish();
  return {};
}

}  // namespace

int runCube(const std::vector<std::string>& args) {
  CubeSettings s;
  FlagSet flags(
      "tessera cube [--width 480] [--height 480] [--fps 30] [--duration 4s] [--fov 50] "
      "[--output cube.gif] [flags]",
      /*single_dash=*/true);
  addCubeFlags(flags, s);
  Expected<std::vector<std::string>> positional = flags.parse(args);
  if (flags.helpRequested()) {
    std::cout << flags.usage();
    return kExitOk;
  }
  if (!positional) {
    printError("cube", positional.error().message);
    std::cerr << flags.hint();
    return kExitUsage;
  }
  if (!positional->empty()) {
    printError("cube", "unexpected argument '" + positional->front() + "'");
    std::cerr << flags.hint();
    return kExitUsage;
  }
  const Projection projection = parseProjection(s.projection).value_or(Projection::kPerspective);
  const long long frame_count = cubeFrameCount(s, projection, flags);
  if (frame_count == 0) return kExitUsage;
  Expected<std::unique_ptr<io::FrameSink>> sink = openCubeSink(s);
  if (!sink) {
    printError("cube", sink.error().message);
    return kExitFailure;
  }
  Expected<std::unique_ptr<Backend>> backend = makeBackend(s.backend, s.workers, s.device);
  if (!backend) {
    printError("cube", backend.error().message);
    return kExitFailure;
  }
  if (Expected<void> done = renderTurn(s, projection, frame_count, **backend, **sink); !done) {
    printError("cube", done.error().message);
    return kExitFailure;
  }
  if (!s.progress.quiet)
    std::cout << "wrote " << s.output << " (" << frame_count
              << (frame_count == 1 ? " frame, " : " frames, ") << s.width << "x" << s.height
              << ")\n";
  return kExitOk;
}

}  // namespace tessera::cli
