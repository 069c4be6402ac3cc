// Micro-benchmarks of the CPU pipeline: whole frames of the built-in bench scenes (the scenes of
// `tessera bench`, framed the same way), and the hot stages one at a time through the private
// stage headers (vertex, setup, bin, and the raster and shade kernels per instruction set). Run:
// build/bench/tessera_microbench
// (--benchmark_filter=Frame/bunny, for example).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>

#include <tessera/model/model_scene.h>
#include <tessera/render/cpu_renderer.h>
#include <tessera/render/sampling.h>
#include <tessera/scene/color.h>
#include <tessera/scene/primitives.h>
#include <tessera/scene/tangents.h>

#include <tessera/model/camera_setup.h>
#include "bench/scenes.h"
#include "render/bin.h"
#include "render/clip.h"
#include "render/kernels.h"
#include "render/msaa.h"
#include "render/raster.h"
#include "render/setup.h"
#include "render/shade.h"
#include "render/vertex.h"

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
// "bunny_close" is the bunny from run_all.sh's `--camera-position 0,0.2,3`: filling the frame, its
// triangles tens of pixels each.
Expected<bench::BenchScene> benchScene(const std::string& name, int width, int height) {
  static std::map<std::string, Expected<bench::BenchScene>> cache;
  const bool close = name == "bunny_close";
  const std::string built_in = close ? "bunny" : name;
  auto it = cache.find(built_in);
  if (it == cache.end())
    it = cache.emplace(built_in, bench::makeBuiltinScene(built_in, Shading::kGouraud)).first;
  if (!it->second) return it->second.error();
  bench::BenchScene b = *it->second;
  if (!b.fixed_view) {
    model::CameraSettings settings;
    settings.has_position = close;
    settings.position = {0.0f, 0.2f, 3.0f};
    Expected<Camera> camera = model::makeCamera(
        settings, b.bounds, static_cast<float>(width) / static_cast<float>(height));
    if (!camera) return camera.error();
    b.scene.camera = *camera;
    model::addViewLights(b.scene);
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

// ---- stages, single-threaded, on the bunny at 1920x1080 (the dense sphere without it; the tile
// shading also on the textured sphere) ----

// A bench scene (the bunny unless named) transformed, set up and binned once, for the stages after
// each of those.
struct StageInput {
  int width = 1920, height = 1080;
  bench::BenchScene scene;
  render::ObjectTransforms transforms;
  render::ViewportTransform viewport;
  render::VertexBuffer vertices;
  render::SetupContext context;
  render::LightRig lights;
  render::TileGrid grid;
  std::vector<render::TriangleOrientation> orientation;
  std::vector<size_t> triangle;               // the mesh triangle of each record
  std::vector<render::TriangleChunk> chunks;  // one chunk: every triangle setup keeps, binned
};

// The input of scene `name` at width x height, made on first use; null (with the reason in
// `error`) when the scene cannot be made. The bunny falls back to the dense sphere. With MSAA the
// boxes reach `sample_reach` further (render::sampleReach), as the renderer's setup makes them.
const StageInput* stageInput(const std::string& name, int width, int height, std::string& error,
                             int32_t sample_reach = 0) {
  static std::map<std::string, std::unique_ptr<StageInput>> inputs;
  const std::string key = name + "@" + std::to_string(width) + "x" + std::to_string(height) + "+" +
                          std::to_string(sample_reach);
  if (auto it = inputs.find(key); it != inputs.end()) return it->second.get();
  Expected<bench::BenchScene> b = benchScene(name, width, height);
  if (!b && name == "bunny") b = benchScene("dense", width, height);
  if (!b) {
    error = b.error().message;
    return nullptr;
  }
  auto in = std::make_unique<StageInput>();
  in->width = width;
  in->height = height;
  in->scene = std::move(*b);
  bench::poseForFrame(in->scene, 3);
  const Scene& scene = in->scene.scene;
  const Object& object = scene.objects[0];
  const float4x4 view_projection =
      scene.camera.projection(static_cast<float>(width) / height) * scene.camera.view();
  in->transforms = render::makeObjectTransforms(object, view_projection);
  in->viewport = {static_cast<float>(width), static_cast<float>(height),
                  render::makeGuardBand(width, height)};
  const Mesh& mesh = *object.mesh;
  in->vertices.resize(mesh.vertexCount());
  render::transformVertices(mesh, in->transforms, in->viewport, 0, mesh.vertexCount(),
                            in->vertices);
  in->lights.prepare(in->scene.scene);
  in->context =
      render::objectSetupContext(in->lights, in->scene.scene.objects[0], in->transforms.model,
                                 width, height, false, sample_reach);
  in->grid = render::TileGrid::forViewport(width, height);
  render::TriangleChunk& chunk = in->chunks.emplace_back();
  chunk.triangle_count = mesh.triangleCount();
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    render::ScreenVertex v[3];
    render::VertexAttributes a[3];
    float3 p[3];
    bool inside = true;
    for (int k = 0; k < 3; ++k) {
      const uint32_t i = mesh.indices[t * 3 + k];
      inside = inside && !(in->vertices.outcode[i] & (render::kCutPlanes | render::kNonFinite));
      v[k] = in->vertices.screen[i];
      a[k] = {in->vertices.normal[i],
              in->context.has_uv ? mesh.uvs[i] : float2{},
              in->context.has_color ? mesh.colors[i] : float4{1, 1, 1, 1},
              true,
              {}};
      p[k] = mesh.positions[i];
    }
    if (!inside) continue;  // the clipper's work: not part of these benchmarks
    render::RasterTriangle r;
    render::RasterWide w;
    render::TriangleOrientation o;
    if (!render::setupRaster(in->context, v, r, w, o)) continue;
    render::ShadeTriangle shade;
    render::ShadeExtras extras;
    const float3 face = in->transforms.normal_matrix * cross(p[1] - p[0], p[2] - p[0]);
    render::setupShade(in->context, v, a, o, r, face, static_cast<uint32_t>(t), 0, shade, extras);
    chunk.raster.push_back(r);
    chunk.wide.push_back(w);
    chunk.shade.push_back(shade);
    chunk.extras.push_back(extras);
    in->orientation.push_back(o);
    in->triangle.push_back(t);
  }
  chunk.size = chunk.raster.size();
  chunk.bins.reset(in->grid.tileCount());
  for (size_t i = 0; i < chunk.size; ++i)
    chunk.bins.add(in->grid, chunk.raster[i], static_cast<uint32_t>(i));
  return inputs.emplace(key, std::move(in)).first->second.get();
}

const StageInput* stageInput() {
  std::string error;
  const StageInput* in = stageInput("bunny", 1920, 1080, error);
  TESSERA_CHECK(in) << "no stage input: " << error;
  return in;
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

// MikkTSpace tangents (generateTangents) of a 1M-triangle UV sphere: the load-time cost of a
// normal-mapped mesh without tangents (the copy of the mesh each iteration is not timed).
void BM_GenerateTangents(benchmark::State& state) {
  static const Mesh sphere = makeUvSphere(1000, 500);
  for (auto _ : state) {
    state.PauseTiming();
    Mesh mesh = sphere;
    state.ResumeTiming();
    generateTangents(mesh);
    benchmark::DoNotOptimize(mesh.tangents.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(sphere.triangleCount()));
}
BENCHMARK(BM_GenerateTangents)->Unit(benchmark::kMillisecond);

// Setup of every triangle with its vertices inside the guard band (culled ones included).
void BM_SetupRaster(benchmark::State& state) {
  const StageInput& in = *stageInput();
  const Mesh& mesh = *in.scene.scene.objects[0].mesh;
  std::vector<render::RasterTriangle> out(mesh.triangleCount());
  std::vector<render::RasterWide> wide(mesh.triangleCount());
  for (auto _ : state) {
    size_t kept = 0;
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      render::ScreenVertex v[3];
      for (int k = 0; k < 3; ++k) v[k] = in.vertices.screen[mesh.indices[t * 3 + k]];
      render::TriangleOrientation o;
      kept += render::setupRaster(in.context, v, out[kept], wide[kept], o);
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
  const render::TriangleChunk& chunk = in.chunks[0];
  std::vector<render::ShadeTriangle> out(chunk.size);
  std::vector<render::ShadeExtras> out_extras(chunk.size);
  for (auto _ : state) {
    for (size_t i = 0; i < chunk.size; ++i) {
      const size_t t = in.triangle[i];
      render::ScreenVertex v[3];
      render::VertexAttributes a[3];
      float3 p[3];
      for (int k = 0; k < 3; ++k) {
        const uint32_t vi = mesh.indices[t * 3 + k];
        v[k] = in.vertices.screen[vi];
        a[k] = {in.vertices.normal[vi], {}, {1, 1, 1, 1}, true, {}};
        p[k] = mesh.positions[vi];
      }
      const float3 face = in.transforms.normal_matrix * cross(p[1] - p[0], p[2] - p[0]);
      render::setupShade(in.context, v, a, in.orientation[i], chunk.raster[i], face,
                         static_cast<uint32_t>(t), 0, out[i], out_extras[i]);
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(chunk.size));
}
BENCHMARK(BM_SetupShade)->Unit(benchmark::kMicrosecond);

bool skipUnsupported(benchmark::State& state, render::Isa isa);
void isaArgs(benchmark::internal::Benchmark* b);

// The cull at the head of setup, eight triangles at a time (setup_kernel.h: index range,
// outcodes, area, facing, box), over every triangle of the mesh, per instruction set.
void BM_CullGroups(benchmark::State& state) {
  const auto isa = static_cast<render::Isa>(state.range(0));
  if (skipUnsupported(state, isa)) return;
  const StageInput& in = *stageInput();
  const Mesh& mesh = *in.scene.scene.objects[0].mesh;
  const render::Kernels kernels = render::kernelsFor(isa);
  const size_t groups = mesh.triangleCount() / render::CullGroup::kLanes;
  size_t visible = 0;
  for (auto _ : state) {
    visible = 0;
    for (size_t g = 0; g < groups; ++g) {
      render::CullGroup out;
      kernels.cull_group(&mesh.indices[g * render::CullGroup::kLanes * 3], mesh.vertexCount(),
                         in.vertices.screen.data(), in.vertices.outcode.data(), in.width, in.height,
                         in.context.cull, 0, out);
      for (int l = 0; l < render::CullGroup::kLanes; ++l)
        visible += out.kind[l] == render::CullGroup::kVisible;
    }
    benchmark::DoNotOptimize(visible);
  }
  state.SetLabel(render::isaName(isa));
  state.counters["visible"] = static_cast<double>(visible);
  state.SetItemsProcessed(state.iterations() *
                          static_cast<int64_t>(groups * render::CullGroup::kLanes));
}

// The render's setup path for unclipped triangles: edges and planes eight triangles at a time
// (setup_kernel.h), with the kernel compiled for one instruction set (the argument), for the
// triangles setupRaster kept.
void BM_SetupBatch(benchmark::State& state) {
  const auto isa = static_cast<render::Isa>(state.range(0));
  if (skipUnsupported(state, isa)) return;
  const StageInput& in = *stageInput();
  const Mesh& mesh = *in.scene.scene.objects[0].mesh;
  const render::Kernels kernels = render::kernelsFor(isa);
  const size_t count = in.triangle.size();
  std::vector<render::SetupBatch> batches((count + 7) / 8);
  for (size_t i = 0; i < count; ++i) {
    render::ScreenVertex v[3];
    for (int k = 0; k < 3; ++k) v[k] = in.vertices.screen[mesh.indices[in.triangle[i] * 3 + k]];
    batches[i / 8].push(v[0], v[1], v[2], render::signedArea(v[0], v[1], v[2]),
                        static_cast<uint32_t>(i));
  }
  for (render::SetupBatch& batch : batches) batch.padLanes();
  render::PoolVector<render::RasterTriangle> raster(count);  // aligned: streamed into
  std::vector<render::RasterWide> wide(count);
  std::vector<render::ShadeTriangle> shade(count);
  for (auto _ : state) {
    for (render::SetupBatch& batch : batches)
      kernels.setup_batch(batch, in.width, in.height, 0, raster.data(), wide.data(), shade.data());
    benchmark::DoNotOptimize(raster.data());
  }
  state.SetLabel(render::isaName(isa));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(count));
}
BENCHMARK(BM_SetupBatch)->Apply(isaArgs);
BENCHMARK(BM_CullGroups)->Apply(isaArgs);

void BM_BinTriangles(benchmark::State& state) {
  const StageInput& in = *stageInput();
  const render::TriangleChunk& chunk = in.chunks[0];
  render::ChunkBins bins;
  for (auto _ : state) {
    bins.reset(in.grid.tileCount());
    for (size_t i = 0; i < chunk.size; ++i)
      bins.add(in.grid, chunk.raster[i], static_cast<uint32_t>(i));
    benchmark::DoNotOptimize(bins.count(0));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(chunk.size));
}
BENCHMARK(BM_BinTriangles)->Unit(benchmark::kMicrosecond);

bool skipUnsupported(benchmark::State& state, render::Isa isa) {
  if (static_cast<int>(isa) <= static_cast<int>(render::detectIsa())) return false;
  state.SkipWithError("this CPU does not run that instruction set");
  return true;
}

void isaArgs(benchmark::internal::Benchmark* b) {
  for (render::Isa isa :
       {render::Isa::kScalar, render::Isa::kSse2, render::Isa::kAvx2, render::Isa::kAvx512})
    b->Arg(static_cast<int>(isa));
  b->Unit(benchmark::kMicrosecond);
}

// Rasterizes every tile of the frame into its visibility buffer (depth + triangle key), with the
// kernel compiled for one instruction set (the argument).
void rasterTile(const StageInput& in, const render::Kernels& kernels, int tile_index,
                render::TileVisibility& tile) {
  const int tx = tile_index % in.grid.columns, ty = tile_index / in.grid.columns;
  const int x0 = tx * render::kTileSize, y0 = ty * render::kTileSize;
  tile.clear(x0, y0, std::min(render::kTileSize, in.grid.width - x0),
             std::min(render::kTileSize, in.grid.height - y0));
  kernels.raster_tile(in.chunks, in.chunks.size(), tile_index, tile);
}

void BM_TileRaster(benchmark::State& state) {
  const auto isa = static_cast<render::Isa>(state.range(0));
  if (skipUnsupported(state, isa)) return;
  const StageInput& in = *stageInput();
  const render::Kernels kernels = render::kernelsFor(isa);
  auto tile = std::make_unique<render::TileVisibility>();
  for (auto _ : state) {
    for (int t = 0; t < in.grid.tileCount(); ++t) rasterTile(in, kernels, t, *tile);
    benchmark::DoNotOptimize(tile->key);
  }
  state.SetLabel(render::isaName(isa));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(in.chunks[0].size));
}
BENCHMARK(BM_TileRaster)->Apply(isaArgs);

// The stage input of `name`, or null with the benchmark skipped and told why.
const StageInput* stageInputOrSkip(benchmark::State& state, const std::string& name, int width,
                                   int height, int32_t sample_reach = 0) {
  std::string error;
  const StageInput* input = stageInput(name, width, height, error, sample_reach);
  if (!input) state.SkipWithError(error.c_str());
  return input;
}

// What the shading kernel takes besides the tiles, for a stage input's scene.
struct ShadeInputs {
  uint32_t background;
  render::LightRig lights;
  bool plain;
  std::unique_ptr<render::ShadedTile> out = std::make_unique<render::ShadedTile>();
  explicit ShadeInputs(const Scene& scene)
      : background(packSrgba8(scene.background)), plain(render::plainShading(scene, false)) {
    lights.prepare(scene);
  }
};

// Shades each tile that holds a triangle from its visibility buffer, as the renderer does: the
// tile rasterized just before (not timed), then each visible pixel shaded once and every pixel of
// the tile encoded to sRGB (timed, the time taken by the clock around each tile). The textured
// sphere's rows are the benchmark matrix's worst (docs/perf.md): here without the raster, setup and
// frame writes around their shading.
void BM_TileShade(benchmark::State& state, const std::string& name, int width, int height) {
  const auto isa = static_cast<render::Isa>(state.range(0));
  if (skipUnsupported(state, isa)) return;
  const StageInput* input = stageInputOrSkip(state, name, width, height);
  if (!input) return;
  const StageInput& in = *input;
  const render::Kernels kernels = render::kernelsFor(isa);
  auto tile = std::make_unique<render::TileVisibility>();
  ShadeInputs shade(in.scene.scene);
  int64_t pixels = 0;
  // One frame's shading time in seconds (`pixels`: the shaded tiles' pixels).
  const auto shadeFrame = [&] {
    using Clock = std::chrono::steady_clock;
    Clock::duration spent{};
    pixels = 0;
    for (int t = 0; t < in.grid.tileCount(); ++t) {
      if (in.chunks[0].bins.count(t) == 0) continue;  // the renderer fills it with the background
      rasterTile(in, kernels, t, *tile);
      const Clock::time_point start = Clock::now();
      kernels.shade_tile(*tile, in.chunks, in.chunks.size(), shade.lights, false, shade.plain,
                         shade.background, nullptr, *shade.out);
      spent += Clock::now() - start;
      pixels += static_cast<int64_t>(tile->width) * tile->height;
    }
    return std::chrono::duration<double>(spent).count();
  };
  shadeFrame();  // a texture's decoded copy is made on first use
  for (auto _ : state) {
    state.SetIterationTime(shadeFrame());
    benchmark::DoNotOptimize(shade.out->rgba);
  }
  state.SetLabel(render::isaName(isa));
  state.counters["tile pixels/s"] = benchmark::Counter(
      static_cast<double>(pixels), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK_CAPTURE(BM_TileShade, bunny, std::string("bunny"), 1920, 1080)
    ->Apply(isaArgs)
    ->UseManualTime();
BENCHMARK_CAPTURE(BM_TileShade, bunny_close, std::string("bunny_close"), 1920, 1080)
    ->Apply(isaArgs)
    ->UseManualTime();
BENCHMARK_CAPTURE(BM_TileShade, textured, std::string("textured"), 1920, 1080)
    ->Apply(isaArgs)
    ->UseManualTime();
BENCHMARK_CAPTURE(BM_TileShade, textured_4k, std::string("textured"), 3840, 2160)
    ->Apply(isaArgs)
    ->UseManualTime();

// The tile stage as the renderer runs it for a colour-only frame of the bunny at 1920x1080, with
// `samples` per pixel (the argument after the instruction set): each tile that holds a triangle
// cleared, rasterized (into every sample layer, then combined) and shaded (its mixed pixels
// resolved). The time is the two parts' (the clock around each), also given apart as the raster
// and shade counters (ms a frame): what issue 15's cost of 4x against 1x is made of, without
// setup and the frame's writes.
void BM_TileStage(benchmark::State& state) {
  const auto isa = static_cast<render::Isa>(state.range(0));
  const int samples = static_cast<int>(state.range(1));
  if (skipUnsupported(state, isa)) return;
  const StageInput* input =
      stageInputOrSkip(state, "bunny", 1920, 1080, render::sampleReach(samples));
  if (!input) return;
  const StageInput& in = *input;
  const render::Kernels kernels = render::kernelsFor(isa);
  const Scene& scene = in.scene.scene;
  ShadeInputs shading(scene);
  // The sample layers and their shifts from the pixel centre (CpuRenderer's prepareSampleLayers).
  auto st = std::make_unique<render::SampleTiles>();
  std::vector<render::SampleShift> shifts;
  for (const SamplePosition& p : samplePattern(samples)) shifts.push_back(render::sampleShift(p));
  render::TileVisibility* layers[kMaxSamples];
  for (int i = 0; i < samples; ++i) layers[i] = &st->layer(i);
  const render::MsaaShading msaa{st.get(), samples, samplePattern(samples).data(),
                                 scene.background.xyz()};
  using Clock = std::chrono::steady_clock;
  Clock::duration raster{}, shade{};
  for (auto _ : state) {
    Clock::duration frame{};
    for (int t = 0; t < in.grid.tileCount(); ++t) {
      if (in.chunks[0].bins.count(t) == 0) continue;  // the renderer fills it with the background
      const Clock::time_point start = Clock::now();
      if (samples == 1) {
        rasterTile(in, kernels, t, *st->primary);
      } else {
        const int x0 = (t % in.grid.columns) * render::kTileSize;
        const int y0 = (t / in.grid.columns) * render::kTileSize;
        for (int i = 0; i < samples; ++i)
          layers[i]->clear(x0, y0, std::min(render::kTileSize, in.grid.width - x0),
                           std::min(render::kTileSize, in.grid.height - y0));
        kernels.raster_tile_samples(in.chunks, in.chunks.size(), t, layers, shifts.data(), samples);
        kernels.combine_samples(*st, samples, false);
      }
      const Clock::time_point rastered = Clock::now();
      kernels.shade_tile(*st->primary, in.chunks, in.chunks.size(), shading.lights, false,
                         shading.plain, shading.background, samples > 1 ? &msaa : nullptr,
                         *shading.out);
      const Clock::time_point done = Clock::now();
      raster += rastered - start;
      shade += done - rastered;
      frame += done - start;
    }
    state.SetIterationTime(std::chrono::duration<double>(frame).count());
    benchmark::DoNotOptimize(shading.out->rgba);
  }
  const double per_frame_ms = 1e3 / static_cast<double>(state.iterations());
  state.counters["raster ms"] = std::chrono::duration<double>(raster).count() * per_frame_ms;
  state.counters["shade ms"] = std::chrono::duration<double>(shade).count() * per_frame_ms;
  state.SetLabel(std::string(render::isaName(isa)) + ", " + std::to_string(samples) + "x");
}
BENCHMARK(BM_TileStage)
    ->ArgsProduct({{static_cast<int>(render::Isa::kAvx2), static_cast<int>(render::Isa::kAvx512)},
                   {1, 4}})
    ->Unit(benchmark::kMicrosecond)
    ->UseManualTime();

}  // namespace
