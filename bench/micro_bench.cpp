// Micro-benchmarks of the CPU pipeline on procedural scenes. Run: build/bench/tessera_microbench
#include <benchmark/benchmark.h>

#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/primitives.h>

using namespace tessera;

namespace {

Scene sphereScene(int segments, Shading shading) {
  Scene scene;
  scene.camera.position = {0, 0, 2.6f};
  scene.camera.near_z = 0.5f;
  scene.camera.far_z = 10.0f;
  scene.lights.push_back({normalize(float3{-1, -1, -1}), float3(0.9f)});
  Object o;
  o.mesh = std::make_shared<Mesh>(makeUvSphere(segments, segments / 2));
  o.shading = shading;
  scene.objects.push_back(o);
  return scene;
}

// args: sphere segments, workers. Frame time for a smooth-shaded sphere at 1920x1080.
void BM_SphereFrame1080p(benchmark::State& state) {
  Scene scene = sphereScene(static_cast<int>(state.range(0)), Shading::kPhong);
  CpuRenderer renderer(static_cast<int>(state.range(1)));
  RenderOptions options;
  options.width = 1920;
  options.height = 1080;
  Frame frame;
  float angle = 0;
  for (auto _ : state) {
    scene.objects[0].transform.rotation = quat::fromAxisAngle({0, 1, 0}, angle += 0.01f);
    renderer.render(scene, options, frame);
    benchmark::DoNotOptimize(frame.color.data());
  }
  state.counters["triangles"] = static_cast<double>(scene.triangleCount());
}
BENCHMARK(BM_SphereFrame1080p)
    ->Args({64, 1})
    ->Args({372, 1})
    ->Args({372, 2})
    ->Unit(benchmark::kMillisecond);

}  // namespace
