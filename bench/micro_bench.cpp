// Micro-benchmarks of the CPU pipeline: whole frames of the built-in bench scenes (the scenes of
// `tessera bench`, framed the same way), and the hot stages one at a time through the private
// stage headers (vertex, setup, bin, raster, shade). Run: build/bench/tessera_microbench
// (--benchmark_filter=Frame/bunny, for example).
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/primitives.h>

#include "bench/scenes.h"
#include "render/bin.h"
#include "render/clip.h"
#include "render/raster.h"
#include "render/setup.h"
#include "render/shade.h"
#include "render/vertex.h"
#include "view_setup.h"

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

// A built-in scene placed for width x height as `tessera bench` places it (default camera flags,
// Gouraud shading, back faces culled). Built once per name: the dense sphere takes a while.
Expected<bench::BenchScene> benchScene(const std::string& name, int width, int height) {
  static std::map<std::string, Expected<bench::BenchScene>> cache;
  auto it = cache.find(name);
  if (it == cache.end())
    it = cache.emplace(name, bench::makeBuiltinScene(name, Shading::kGouraud)).first;
  if (!it->second) return it->second.error();
  bench::BenchScene b = *it->second;
  if (!b.fixed_view) {
    Expected<Camera> camera = cli::makeCamera(
        cli::CameraSettings{}, b.bounds, static_cast<float>(width) / static_cast<float>(height));
    if (!camera) return camera.error();
    b.scene.camera = *camera;
    cli::addViewLights(b.scene);
  }
  return b;
}

RenderOptions colorOnly(int width, int height) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.depth = false;
  options.ids = false;
  options.normals = false;
  options.lines = false;
  return options;
}

// Whole frames of one bench scene; args: width, height, workers. The model turns a little every
// frame, as in `tessera bench`.
void frameBenchmark(benchmark::State& state, const std::string& name) {
  const int width = static_cast<int>(state.range(0)), height = static_cast<int>(state.range(1));
  Expected<bench::BenchScene> b = benchScene(name, width, height);
  if (!b) {
    state.SkipWithError(b.error().message.c_str());
    return;
  }
  CpuRenderer renderer(static_cast<int>(state.range(2)));
  const RenderOptions options = colorOnly(width, height);
  Frame frame;
  renderer.render(b->scene, options, frame);  // allocate the buffers outside the timed loop
  int index = 0;
  for (auto _ : state) {
    bench::poseForFrame(*b, index++);
    renderer.render(b->scene, options, frame);
    benchmark::DoNotOptimize(frame.color.data());
  }
  state.counters["triangles"] = static_cast<double>(b->scene.triangleCount());
  state.counters["pixels/s"] = benchmark::Counter(static_cast<double>(width) * height,
                                                  benchmark::Counter::kIsIterationInvariantRate);
}

void frameArgs(benchmark::internal::Benchmark* b) {
  b->Args({640, 480, 0})->Args({1920, 1080, 0})->Unit(benchmark::kMillisecond)->UseRealTime();
}
BENCHMARK_CAPTURE(frameBenchmark, cube, std::string("cube"))->Apply(frameArgs);
BENCHMARK_CAPTURE(frameBenchmark, bunny, std::string("bunny"))
    ->Apply(frameArgs)
    ->Args({1920, 1080, 1})
    ->Args({1920, 1080, 2});
BENCHMARK_CAPTURE(frameBenchmark, dense, std::string("dense"))->Apply(frameArgs);
BENCHMARK_CAPTURE(frameBenchmark, fill, std::string("fill"))->Apply(frameArgs);
BENCHMARK_CAPTURE(frameBenchmark, textured, std::string("textured"))->Apply(frameArgs);

// ---- stages, single-threaded, on the bunny at 1920x1080 (the dense sphere without it) ----

// The vertices of one scene transformed and projected once, for the stages after the vertex one.
struct StageInput {
  bench::BenchScene scene;
  render::ObjectTransforms transforms;
  render::ViewportTransform viewport;
  render::VertexBuffer vertices;
  render::SetupContext context;
  std::vector<render::RasterTriangle> raster;  // the triangles setup keeps, in order
  std::vector<render::TriangleOrientation> orientation;
  std::vector<size_t> triangle;  // their mesh triangle index
};

const StageInput* stageInput() {
  static std::unique_ptr<StageInput> input = [] {
    constexpr int kWidth = 1920, kHeight = 1080;
    Expected<bench::BenchScene> b = benchScene("bunny", kWidth, kHeight);
    if (!b) b = benchScene("dense", kWidth, kHeight);
    auto in = std::make_unique<StageInput>();
    in->scene = std::move(*b);
    bench::poseForFrame(in->scene, 3);
    const Scene& scene = in->scene.scene;
    const Object& object = scene.objects[0];
    const float4x4 view_projection =
        scene.camera.projection(static_cast<float>(kWidth) / kHeight) * scene.camera.view();
    in->transforms = render::makeObjectTransforms(object, view_projection);
    in->viewport = {static_cast<float>(kWidth), static_cast<float>(kHeight),
                    render::makeGuardBand(kWidth, kHeight)};
    const Mesh& mesh = *object.mesh;
    in->vertices.resize(mesh.vertexCount());
    render::transformVertices(mesh, in->transforms, in->viewport, 0, mesh.vertexCount(),
                              in->vertices);
    in->context.width = kWidth;
    in->context.height = kHeight;
    in->context.cull = object.cull;
    in->context.shading = object.shading;
    in->context.scene = &in->scene.scene;
    in->context.object = &in->scene.scene.objects[0];
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      render::ScreenVertex v[3];
      bool inside = true;
      for (int k = 0; k < 3; ++k) {
        const uint32_t i = mesh.indices[t * 3 + k];
        inside = inside && !(in->vertices.outcode[i] & (render::kCutPlanes | render::kNonFinite));
        v[k] = in->vertices.screen[i];
      }
      if (!inside) continue;  // the clipper's work: not measured here
      render::RasterTriangle r;
      render::TriangleOrientation o;
      if (!render::setupRaster(in->context, v, r, o)) continue;
      in->raster.push_back(r);
      in->orientation.push_back(o);
      in->triangle.push_back(t);
    }
    return in;
  }();
  return input.get();
}

void BM_TransformVertices(benchmark::State& state) {
  const StageInput& in = *stageInput();
  const Mesh& mesh = *in.scene.scene.objects[0].mesh;
  render::VertexBuffer out;
  out.resize(mesh.vertexCount());
  for (auto _ : state) {
    render::transformVertices(mesh, in.transforms, in.viewport, 0, mesh.vertexCount(), out);
    benchmark::DoNotOptimize(out.screen.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(mesh.vertexCount()));
}
BENCHMARK(BM_TransformVertices)->Unit(benchmark::kMicrosecond);

// Setup of every triangle with its vertices inside the guard band (culled ones included).
void BM_SetupRaster(benchmark::State& state) {
  const StageInput& in = *stageInput();
  const Mesh& mesh = *in.scene.scene.objects[0].mesh;
  std::vector<render::RasterTriangle> out(mesh.triangleCount());
  for (auto _ : state) {
    size_t kept = 0;
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      render::ScreenVertex v[3];
      for (int k = 0; k < 3; ++k) v[k] = in.vertices.screen[mesh.indices[t * 3 + k]];
      render::TriangleOrientation o;
      kept += render::setupRaster(in.context, v, out[kept], o);
    }
    benchmark::DoNotOptimize(kept);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(mesh.triangleCount()));
}
BENCHMARK(BM_SetupRaster)->Unit(benchmark::kMicrosecond);

// The shading half of setup, for the triangles setupRaster kept.
void BM_SetupShade(benchmark::State& state) {
  const StageInput& in = *stageInput();
  const Mesh& mesh = *in.scene.scene.objects[0].mesh;
  std::vector<render::ShadeTriangle> out(in.raster.size());
  for (auto _ : state) {
    for (size_t i = 0; i < in.raster.size(); ++i) {
      const size_t t = in.triangle[i];
      render::ScreenVertex v[3];
      render::VertexAttributes a[3];
      float3 p[3];
      for (int k = 0; k < 3; ++k) {
        const uint32_t vi = mesh.indices[t * 3 + k];
        v[k] = in.vertices.screen[vi];
        a[k] = {in.vertices.normal(vi), {}, {1, 1, 1, 1}};
        p[k] = mesh.positions[vi];
      }
      const float3 face = in.transforms.normal_matrix * cross(p[1] - p[0], p[2] - p[0]);
      render::setupShade(in.context, v, a, in.orientation[i], in.raster[i], face,
                         static_cast<uint32_t>(t), 0, out[i]);
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(in.raster.size()));
}
BENCHMARK(BM_SetupShade)->Unit(benchmark::kMicrosecond);

void BM_BinTriangles(benchmark::State& state) {
  const StageInput& in = *stageInput();
  const render::TileGrid grid = render::TileGrid::forViewport(in.context.width, in.context.height);
  render::ChunkBins bins;
  for (auto _ : state) {
    bins.reset(grid.tileCount());
    for (size_t i = 0; i < in.raster.size(); ++i)
      bins.add(grid, in.raster[i], static_cast<uint32_t>(i));
    bins.finish();
    benchmark::DoNotOptimize(bins.count(0));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(in.raster.size()));
}
BENCHMARK(BM_BinTriangles)->Unit(benchmark::kMicrosecond);

// A triangle of about `size` pixels on a side inside a 64x64 tile at the origin.
render::RasterTriangle tileTriangle(float x, float y, float size, float z) {
  render::SetupContext ctx;
  ctx.width = render::kTileSize;
  ctx.height = render::kTileSize;
  ctx.cull = CullMode::kNone;
  auto snap = [](float p) { return static_cast<int32_t>(p * render::kSubpixelOne); };
  const render::ScreenVertex v[3] = {{snap(x), snap(y), z, 1.0f},
                                     {snap(x + size), snap(y + size * 0.3f), z, 1.0f},
                                     {snap(x + size * 0.4f), snap(y + size), z, 1.0f}};
  render::RasterTriangle r;
  render::TriangleOrientation o;
  render::setupRaster(ctx, v, r, o);
  return r;
}

// args: instruction set (RasterIsa), triangle size in pixels. Triangles spread over one tile,
// each in front of the last (every pixel passes the depth test).
void BM_RasterTriangle(benchmark::State& state) {
  const auto isa = static_cast<render::RasterIsa>(state.range(0));
  if (static_cast<int>(isa) > static_cast<int>(render::detectRasterIsa())) {
    state.SkipWithError("this CPU does not run that instruction set");
    return;
  }
  const float size = static_cast<float>(state.range(1));
  std::vector<render::RasterTriangle> triangles;
  for (int i = 0; i < 256; ++i) {
    const float x = static_cast<float>((i * 37) % 61), y = static_cast<float>((i * 23) % 59);
    triangles.push_back(tileTriangle(std::min(x, 63.0f - size), std::min(y, 63.0f - size), size,
                                     1.0f - static_cast<float>(i) / 512.0f));
  }
  const render::RasterTriangleFn raster = render::rasterTriangleFunction(isa);
  auto tile = std::make_unique<render::TileVisibility>();
  for (auto _ : state) {
    tile->clear(0, 0, render::kTileSize, render::kTileSize);
    for (size_t i = 0; i < triangles.size(); ++i)
      raster(triangles[i], static_cast<uint32_t>(i), *tile);
    benchmark::DoNotOptimize(tile->key);
  }
  state.SetLabel(render::rasterIsaName(isa));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(triangles.size()));
}
BENCHMARK(BM_RasterTriangle)
    ->ArgsProduct(
        {{static_cast<int>(render::RasterIsa::kScalar), static_cast<int>(render::RasterIsa::kSse2),
          static_cast<int>(render::RasterIsa::kAvx2), static_cast<int>(render::RasterIsa::kAvx512)},
         {3, 12, 60}})
    ->Unit(benchmark::kMicrosecond);

// One pixel shaded from its setup record; args: shading (0 Gouraud, 1 Phong).
void BM_ShadePixel(benchmark::State& state) {
  const StageInput& in = *stageInput();
  render::SetupContext ctx = in.context;
  ctx.shading = state.range(0) ? Shading::kPhong : Shading::kGouraud;
  const render::ScreenVertex v[3] = {
      {0, 0, 0.5f, 1.0f}, {64 * 256, 0, 0.5f, 0.9f}, {0, 64 * 256, 0.5f, 0.8f}};
  render::RasterTriangle r;
  render::TriangleOrientation o;
  render::setupRaster(ctx, v, r, o);
  const render::VertexAttributes a[3] = {
      {{0, 0, 1}, {}, {1, 1, 1, 1}}, {{0, 1, 0}, {}, {1, 1, 1, 1}}, {{1, 0, 0}, {}, {1, 1, 1, 1}}};
  render::ShadeTriangle t;
  render::setupShade(ctx, v, a, o, r, {0, 0, 1}, 0, 0, t);
  float x = 0.5f;
  for (auto _ : state) {
    float3 c = render::shadePixel(t, in.scene.scene, x, 10.5f, nullptr);
    benchmark::DoNotOptimize(c);
    x = x < 40.0f ? x + 1.0f : 0.5f;
  }
  state.SetLabel(state.range(0) ? "phong" : "gouraud");
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ShadePixel)->Arg(0)->Arg(1);

}  // namespace
