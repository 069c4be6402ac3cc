// tessera-vulkan-stats: renders one scene with the compute backend for a few frames and prints
// its counters and per-pass GPU times (median over the frames), with the CPU renderer and the
// raster backend beside it; optionally writes the frame and the tile-occupancy heatmap as PNGs.
// The numbers in docs/vulkan.md and docs/vulkan-features.md come from it.
//
//   tessera-vulkan-stats [MODEL.obj] [--size W,H] [--frames N] [--32bit] [--heatmap PATH]
//                        [--image PATH]
// Without a model it renders a 200x100 UV sphere.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <tessera/io/image_writer.h>
#include <tessera/io/model_loader.h>
#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/primitives.h>
#include <tessera/vulkan/vulkan_backend.h>

using namespace tessera;

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

int fail(const std::string& message) {
  std::fprintf(stderr, "tessera-vulkan-stats: error: %s\n", message.c_str());
  return 1;
}

struct Arguments {
  std::string model_path, heatmap_path, image_path;
  int width = 480, height = 360, frames = 5;
  vulkan::VulkanOptions vk;
};

// The arguments, or the message of what is wrong with them.
Expected<Arguments> parseArguments(int argc, char** argv) {
  Arguments a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--size" && has_value) {
      if (std::sscanf(argv[++i], "%d,%d", &a.width, &a.height) != 2 || a.width < 1 ||
          a.height < 1 || a.width > 16384 || a.height > 16384)
        return Error{"--size takes W,H in 1..16384"};
    } else if (arg == "--frames" && has_value) {
      a.frames = std::clamp(std::atoi(argv[++i]), 1, 1000);
    } else if (arg == "--32bit") {
      a.vk.force_32bit_atomics = true;
    } else if (arg == "--heatmap" && has_value) {
      a.heatmap_path = argv[++i];
    } else if (arg == "--image" && has_value) {
      a.image_path = argv[++i];
    } else if (!arg.empty() && arg[0] != '-' && a.model_path.empty()) {
      a.model_path = arg;
    } else {
      return Error{"unknown argument '" + arg + "'"};
    }
  }
  return a;
}

// The model (or the UV sphere), Gouraud-lit by two lights and framed from three quarters.
Expected<Scene> makeScene(const Arguments& a) {
  Scene scene;
  Object object;
  if (a.model_path.empty()) {
    object.mesh = std::make_shared<Mesh>(makeUvSphere(200, 100));
    object.materials[0].base_color = {0.2f, 0.5f, 0.9f, 1.0f};
  } else {
    Expected<io::Model> model = io::loadModel(a.model_path);
    if (!model) return model.error();
    object.mesh = std::make_shared<Mesh>(std::move(model->mesh));
    object.materials = std::move(model->materials);
  }
  object.shading = Shading::kGouraud;
  scene.objects.push_back(object);
  scene.lights.push_back({normalize(float3{-0.6f, -1.0f, -0.8f}), float3(0.85f)});
  scene.lights.push_back({normalize(float3{0.8f, 0.3f, -0.4f}), float3(0.2f)});
  const float aspect = static_cast<float>(a.width) / static_cast<float>(a.height);
  scene.camera =
      frameBounds(scene.bounds(), normalize(float3{0.6f, 0.45f, 1.0f}), {0, 1, 0}, 30, aspect);
  return scene;
}

// The compute backend's frames: its counters and the medians of its pass times; `frame` keeps
// the last.
Expected<void> timeCompute(const Arguments& a, const Scene& scene, const RenderOptions& options,
                           vulkan::ComputeBackend& gpu, Frame& frame) {
  gpu.render(scene, options, frame);  // warm-up: lavapipe compiles shaders at first use
  if (Expected<void> r = gpu.lastResult(); !r) return r;
  std::vector<double> clear, transform, setup, bin, raster, shade, total, wall;
  for (int f = 0; f < a.frames; ++f) {
    const auto start = std::chrono::steady_clock::now();
    gpu.render(scene, options, frame);
    wall.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    if (Expected<void> r = gpu.lastResult(); !r) return r;
    const vulkan::PassTimings& t = gpu.lastStats().timings;
    clear.push_back(t.clear);
    transform.push_back(t.transform);
    setup.push_back(t.setup);
    bin.push_back(t.bin);
    raster.push_back(t.raster);
    shade.push_back(t.shade);
    total.push_back(t.total);
  }
  const vulkan::ComputeStats& s = gpu.lastStats();
  std::printf("device: %s (%s)\n", gpu.device().name.c_str(), gpu.device().compute_note.c_str());
  std::printf("scene: %s, %dx%d, %zu triangles\n",
              a.model_path.empty() ? "UV sphere 200x100" : a.model_path.c_str(), a.width, a.height,
              s.triangles_in);
  std::printf(
      "counters: culled %zu, clipped %zu, set up %zu, binned %zu, bin entries %zu "
      "(capacity %zu, overflow rounds %zu), tiles %zu, occupied %zu, fullest %zu, "
      "raster workgroups %zu, 64-bit atomics %s, double setup %s\n",
      s.triangles_culled, s.triangles_clipped, s.triangles_setup, s.triangles_binned, s.bin_entries,
      s.bin_capacity, s.bin_overflows, s.tiles, s.tiles_occupied, s.max_tile_entries,
      s.raster_workgroups, s.int64_atomics ? "yes" : "no", s.fp64_setup ? "yes" : "no");
  if (s.timings.valid)
    std::printf(
        "GPU ms (median of %d): clear %.2f, transform %.2f, setup %.2f, bin %.2f, "
        "raster %.2f, shade %.2f, total %.2f; wall %.2f\n",
        a.frames, median(clear), median(transform), median(setup), median(bin), median(raster),
        median(shade), median(total), median(wall));
  return {};
}

// The raster backend's median GPU time, where it runs.
void timeRasterBackend(const Arguments& a, const Scene& scene, const RenderOptions& options) {
  Expected<std::unique_ptr<vulkan::RasterBackend>> raster_backend =
      vulkan::RasterBackend::create(a.vk);
  if (!raster_backend) return;
  Frame other;
  (*raster_backend)->render(scene, options, other);
  std::vector<double> gpu_ms;
  for (int f = 0; f < a.frames; ++f) {
    (*raster_backend)->render(scene, options, other);
    gpu_ms.push_back((*raster_backend)->lastStats().gpu_ms);
  }
  std::printf("vulkan-raster GPU ms (median): %.2f\n", median(gpu_ms));
}

// The CPU renderer's median frame time, and on how many covered pixels its triangle ids are the
// compute backend's (`frame`).
void compareWithCpu(const Arguments& a, const Scene& scene, const RenderOptions& options,
                    const Frame& frame) {
  CpuRenderer cpu;
  Frame cpu_frame;
  cpu.render(scene, options, cpu_frame);
  std::vector<double> cpu_ms;
  for (int f = 0; f < a.frames; ++f) {
    const auto start = std::chrono::steady_clock::now();
    cpu.render(scene, options, cpu_frame);
    cpu_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
  }
  size_t same = 0, covered = 0;
  for (size_t p = 0; p < frame.pixelCount(); ++p) {
    if (frame.triangle_id[p] == kNoTriangle && cpu_frame.triangle_id[p] == kNoTriangle) continue;
    ++covered;
    same += frame.triangle_id[p] == cpu_frame.triangle_id[p];
  }
  std::printf(
      "cpu (%d workers) ms (median): %.2f; ids equal to the CPU's on %zu of %zu covered "
      "pixels\n",
      cpu.workerCount(), median(cpu_ms), same, covered);
}

}  // namespace

int main(int argc, char** argv) {
  Expected<Arguments> parsed = parseArguments(argc, argv);
  if (!parsed) return fail(parsed.error().message);
  const Arguments& a = *parsed;
  Expected<Scene> scene = makeScene(a);
  if (!scene) return fail(scene.error().message);
  RenderOptions options;
  options.width = a.width;
  options.height = a.height;

  Expected<std::unique_ptr<vulkan::ComputeBackend>> created = vulkan::ComputeBackend::create(a.vk);
  if (!created) return fail(created.error().message);
  vulkan::ComputeBackend& gpu = **created;
  Frame frame;
  if (Expected<void> r = timeCompute(a, *scene, options, gpu, frame); !r)
    return fail(r.error().message);
  timeRasterBackend(a, *scene, options);
  compareWithCpu(a, *scene, options, frame);

  if (!a.heatmap_path.empty()) {
    const std::vector<uint32_t> heatmap =
        vulkan::makeOccupancyHeatmap(gpu.lastTileOccupancy(), a.width, a.height);
    if (Expected<void> r = io::writePngRgba8(a.heatmap_path, a.width, a.height, heatmap.data()); !r)
      return fail(r.error().message);
  }
  if (!a.image_path.empty()) {
    if (Expected<void> r = io::writePngRgba8(a.image_path, a.width, a.height, frame.color.data());
        !r)
      return fail(r.error().message);
  }
  return 0;
}
