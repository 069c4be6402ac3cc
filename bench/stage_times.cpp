// Where a frame's time goes: the CPU renderer's stage times (vertex, setup+bin, tiles) of a
// built-in bench scene, frame by frame, as medians, with a hash of every frame's colour so that
// two builds can be checked for the same image while they are timed. For following the numbers
// when changing a hot path; `tessera bench` is the yardstick.
//   build/bench/tessera_stagetimes [scene] [workers] [frames] [width] [height] [simd] [msaa]
//                                  [projection] [shading] [camera position x,y,z]
//   simd: auto, scalar, sse2, avx2, avx512; msaa: 1, 2, 4, 8; projection: projection.h's names
//   (the scene's camera and view angle in that mode); shading: flat, smooth, gouraud, unlit, pbr.
//   Defaults: bunny 2 40 1920 1080 auto 1 perspective gouraud, the bench's camera (a position
//   such as 0,0.2,3 places it as `tessera bench --camera-position` does: run_all.sh's bunny
//   filling the frame).
//   TESSERA_NOHASH=1 leaves the hash out (and the gap it makes between frames); TESSERA_NOCULL=1
//   turns frustum and cluster culling off.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include <tessera/model/model_scene.h>
#include <tessera/render/cpu_renderer.h>

#include <tessera/model/camera_setup.h>
#include "bench/scenes.h"

using namespace tessera;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

SimdLevel parseSimd(const std::string& s) {
  if (s == "scalar") return SimdLevel::kScalar;
  if (s == "sse2") return SimdLevel::kSse2;
  if (s == "avx2") return SimdLevel::kAvx2;
  if (s == "avx512") return SimdLevel::kAvx512;
  return SimdLevel::kAuto;
}

// The bench's camera for the scene's bounds, or one at `position` ("x,y,z"; null: the default),
// and the bench's view lights. 0, or the exit status with a message printed: 2 for a position
// that is not x,y,z, 1 for a camera that cannot be made.
int placeCamera(bench::BenchScene& b, const char* position, int width, int height) {
  model::CameraSettings settings;
  if (position) {
    settings.has_position = std::sscanf(position, "%f,%f,%f", &settings.position.x,
                                        &settings.position.y, &settings.position.z) == 3;
    if (!settings.has_position) {
      std::fprintf(stderr, "tessera_stagetimes: camera position must be x,y,z\n");
      return 2;
    }
  }
  Expected<Camera> camera =
      model::makeCamera(settings, b.bounds, static_cast<float>(width) / static_cast<float>(height));
  if (!camera) {
    std::fprintf(stderr, "tessera_stagetimes: %s\n", camera.error().message.c_str());
    return 1;
  }
  b.scene.camera = *camera;
  model::addViewLights(b.scene);
  return 0;
}

RenderOptions stageOptions(int width, int height, int msaa, Projection projection) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.depth = options.ids = options.normals = options.lines = false;
  options.msaa = msaa;
  options.projection = projection;
  // TESSERA_NOCULL=1: no frustum or cluster culling before the vertex stage, to measure what it
  // costs or saves in the same build.
  options.frustum_cull = std::getenv("TESSERA_NOCULL") == nullptr;
  // TESSERA_NOKEEP=1: every frame's background filled again (RenderOptions::frame_kept off).
  options.frame_kept = std::getenv("TESSERA_NOKEEP") == nullptr;
  return options;
}

// Renders `frames` frames of the scene turning as in the bench and prints the medians of their
// stage times and the hash of their colours (the first line), then the last frame's counts.
void timeFrames(bench::BenchScene& b, const RenderOptions& options, CpuRenderer& renderer,
                const std::string& name, int frames) {
  Frame frame;
  bench::poseForFrame(b, 0);
  renderer.render(b.scene, options, frame);  // the buffers, outside the timing

  // TESSERA_NOHASH=1: no hash between frames, so that the frames follow one another as in
  // `tessera bench` (hashing a 1080p frame takes a millisecond or two, long enough for the
  // workers to go to sleep).
  const bool hash_frames = std::getenv("TESSERA_NOHASH") == nullptr;
  std::vector<double> total, vertex, setup, tiles, overlay;
  uint64_t hash = 14695981039346656037ull;  // FNV-1a over every frame's colour
  for (int i = 0; i < frames; ++i) {
    bench::poseForFrame(b, i);
    const auto start = std::chrono::steady_clock::now();
    renderer.render(b.scene, options, frame);
    const auto stop = std::chrono::steady_clock::now();
    total.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
    const PipelineStats& s = renderer.lastStats();
    vertex.push_back(s.vertex_ms);
    setup.push_back(s.setup_ms);
    tiles.push_back(s.tiles_ms);
    overlay.push_back(s.lines_ms);
    if (hash_frames)
      for (uint32_t c : frame.color) hash = (hash ^ c) * 1099511628211ull;
  }
  std::printf(
      "%s %dx%d, %d workers, %s, %dx msaa, %d frames: total %.3f ms (vertex %.3f, setup %.3f, "
      "tiles %.3f, points and lines %.3f), hash %016llx\n",
      name.c_str(), options.width, options.height, renderer.workerCount(), renderer.simdName(),
      options.msaa, frames, median(total), median(vertex), median(setup), median(tiles),
      median(overlay), static_cast<unsigned long long>(hash));
  const PipelineStats& s = renderer.lastStats();
  std::printf(
      "last frame: %zu triangles set up; culled before the vertex stage: %zu instances, "
      "%zu clusters outside, %zu clusters facing away, %zu triangles\n",
      s.triangles_setup, s.instances_culled, s.clusters_culled, s.clusters_facing,
      s.triangles_skipped);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string name = argc > 1 ? argv[1] : "bunny";
  const int workers = argc > 2 ? std::atoi(argv[2]) : 2;
  const int frames = argc > 3 ? std::max(1, std::atoi(argv[3])) : 40;
  const int width = argc > 4 ? std::atoi(argv[4]) : 1920;
  const int height = argc > 5 ? std::atoi(argv[5]) : 1080;
  const SimdLevel simd = parseSimd(argc > 6 ? argv[6] : "auto");
  const int msaa = argc > 7 ? std::atoi(argv[7]) : 1;
  const std::optional<Projection> projection = parseProjection(argc > 8 ? argv[8] : "perspective");
  if (!projection) {
    std::fprintf(stderr, "tessera_stagetimes: projection must be %s\n",
                 projectionChoices().c_str());
    return 2;
  }
  if (!isSampleCount(msaa)) {
    std::fprintf(stderr, "tessera_stagetimes: msaa must be 1, 2, 4 or 8\n");
    return 2;
  }

  const Shading shading = model::shadingFromName(argc > 9 ? argv[9] : "gouraud");
  Expected<bench::BenchScene> made = bench::makeBuiltinScene(name, shading);
  if (!made) {
    std::fprintf(stderr, "tessera_stagetimes: %s\n", made.error().message.c_str());
    return 1;
  }
  bench::BenchScene& b = *made;
  if (!b.fixed_view) {
    if (const int status = placeCamera(b, argc > 10 ? argv[10] : nullptr, width, height))
      return status;
  }
  const RenderOptions options = stageOptions(width, height, msaa, *projection);
  if (*projection != Projection::kPerspective) model::fitDistanceRange(b.scene.camera, b.bounds);
  CpuRenderer renderer(workers, simd);
  timeFrames(b, options, renderer, name, frames);
  return 0;
}
