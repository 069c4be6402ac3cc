// The CPU backend: runs the stages in order over a worker pool.
//
//   vertex:  parallel over fixed ranges of vertices, or (small scenes) once per worker
//   setup:   parallel over fixed chunks of triangles (assembly, cull, clip, setup, bin per chunk;
//            chunk_setup.cpp)
//   raster:  parallel over 64x64 tiles; each tile reads the chunks' bins in chunk order
//   resolve: in the same tile job, shade each visible pixel once and write the frame
//   points:  after every tile, over the worker pool (point_pass.h)
//   lines:   on the calling thread, after the points
//
// Where the chunks end depends on the worker count (chunk_layout.h), but they cover the scene's
// triangles in order, and each tile is processed by one worker that reads the chunks in order:
// every pixel sees its triangles in submission order, so the image is bit-identical for any
// worker count.
#include <tessera/render/cpu_renderer.h>

#include <algorithm>
#include <chrono>
#include <memory>

#include <tessera/base/check.h>
#include <tessera/render/composite.h>
#include <tessera/scene/color.h>

#include "render/chunk_layout.h"
#include "render/cpu_renderer_state.h"
#include "render/raster.h"
#include "render/resolve.h"
#include "render/shade.h"

namespace tessera {

using namespace render;

namespace {

constexpr size_t kVerticesPerJob =
    4096;  // the bunny's 35k vertices: 9 jobs, balanced over 2 workers
constexpr size_t kMinTrianglesPerChunk = 4096;
// Objects a job of the per-object work before the vertex stage (transforms and the frustum test
// of their bounds): 10,000 instances take about 0.2 ms on one core here, so a job about 5 us.
constexpr size_t kObjectsPerJob = 256;

using Clock = std::chrono::steady_clock;
double elapsedMs(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// Points the tile's shading at the frame (ShadedTile::direct) where its encode can write the
// colour there itself, saving resolveTile's copy of it: not when the frame streams (the copy's
// streaming stores), and only for a tile a whole number of the encode's sixteen-pixel steps wide
// (every tile of a frame whose width is a multiple of 16; the others' last step would pass the
// frame's row). The copy took 5-11% of the cube's frames on an Intel Xeon
// (docs/perf-notes/frame-passes.md).
void directColour(bool stream, int x0, int y0, int width, Frame& frame, ShadedTile& out) {
  const bool direct = !stream && width % 16 == 0;
  out.direct = direct ? &frame.color[static_cast<size_t>(y0) * frame.width + x0] : nullptr;
  out.direct_stride = static_cast<size_t>(frame.width);
}

}  // namespace

CpuRenderer::CpuRenderer(int workers, SimdLevel simd)
    : state_(std::make_unique<State>(workers, isaFor(simd))) {}
CpuRenderer::~CpuRenderer() = default;

int CpuRenderer::workerCount() const {
  return state_->pool.size();
}
const char* CpuRenderer::simdName() const {
  return isaName(state_->isa);
}
const PipelineStats& CpuRenderer::lastStats() const {
  return state_->stats;
}

void CpuRenderer::State::blendTile(const RenderOptions& options, int tile, int worker,
                                   const TileVisibility* const* layers, Frame& frame) {
  if (blend.empty() || blend.bins().count(tile) == 0) return;
  const int samples = options.msaa;
  const SampleShift centre[1] = {};
  BlendTile& out = *blend_tiles[static_cast<size_t>(worker)];
  out.begin(layers[0]->x0, layers[0]->y0, samples, frame);
  kernels.blend_tile(chunks, blend.bins(), tile, layers, samples > 1 ? shifts.data() : centre,
                     samples, lights, out);
  out.finish();
}

void CpuRenderer::State::renderSampledTile(const Scene& scene, const RenderOptions& options,
                                           int tile, int worker, const TileGrid& grid,
                                           const TilePass& pass, Frame& frame) {
  const bool with_centre = pass.with_centre;
  const int tx = tile % grid.columns, ty = tile / grid.columns;
  const int x0 = tx * kTileSize, y0 = ty * kTileSize;
  const int width = std::min(kTileSize, options.width - x0);
  const int height = std::min(kTileSize, options.height - y0);
  SampleTiles& st = *sampled[static_cast<size_t>(worker)];
  const int layer_count = static_cast<int>(shifts.size());
  TileVisibility* layers[kMaxSamples + 1];
  for (int i = 0; i < layer_count; ++i) {
    layers[i] = &st.layer(i);
    layers[i]->clear(x0, y0, width, height);
  }
  if (options.visibility == Visibility::kPainter)
    kernels.raster_painter_tile_samples(chunks, painter.slices(), tile, layers, shifts.data(),
                                        layer_count);
  else
    kernels.raster_tile_samples(chunks, chunk_count, tile, layers, shifts.data(), layer_count);
  kernels.combine_samples(st, options.msaa, with_centre);
  const MsaaShading msaa{&st, options.msaa, samplePattern(options.msaa).data(),
                         scene.background.xyz()};
  ShadedTile& out = *shaded[static_cast<size_t>(worker)];
  directColour(pass.stream, x0, y0, width, frame, out);
  kernels.shade_tile(*st.primary, chunks, chunk_count, lights, options.normals, pass.plain,
                     packSrgba8(scene.background), &msaa, out);
  // The AOVs are the centre layer's: the same as one sample gives.
  resolveTile(with_centre ? *layers[options.msaa] : *st.primary, out, chunks, pass.stream, frame);
  if (options.coverage) resolveCoverage(*st.primary, st.covered, options.msaa, frame);
  blendTile(options, tile, worker, layers, frame);
}

void CpuRenderer::State::prepareSampleLayers(const RenderOptions& options, bool with_centre) {
  shifts.clear();
  for (const SamplePosition& p : samplePattern(options.msaa)) shifts.push_back(sampleShift(p));
  if (with_centre) shifts.push_back({});
  if (sampled.empty())
    for (int i = 0; i < pool.size(); ++i) sampled.push_back(std::make_unique<SampleTiles>());
}

size_t CpuRenderer::State::prepareObjects(const Scene& scene, const RenderOptions& options,
                                          const float4x4& projection,
                                          const float4x4& view_projection, bool every_matrix) {
  // Per object, on every worker (kObjectsPerJob objects a job: 10,000 instances once took 0.5 ms
  // a frame on one core while the other waited), its matrices and its bounds against the frustum.
  // The matrices of an object culled whole are not kept (only the line pass would read them:
  // every_matrix), so that its ObjectTransforms are not touched: 10,000 instances, 52 in view,
  // 640x480, 1 worker, 0.432 -> 0.381 ms a frame. Then culling's walk over the objects in order
  // sets the triangle bases (the ids: every object's, drawn or not) and what each draws, and the
  // rest of makeObjectTransforms' constants follow for what draws.
  const size_t object_count = scene.objects.size();
  objects.resize(object_count);
  cull.resize(object_count);
  const size_t jobs = (object_count + kObjectsPerJob - 1) / kObjectsPerJob;
  pool.parallelFor(jobs, [&](size_t job, int) {
    // A scene graph's instances share one T * R * S (identity, or a turntable's): computed once
    // for each run of objects that share it.
    float4x4 trs;
    const Transform* trs_of = nullptr;
    const size_t end = std::min(object_count, (job + 1) * kObjectsPerJob);
    for (size_t i = job * kObjectsPerJob; i < end; ++i) {
      const Object& object = scene.objects[i];
      TESSERA_CHECK(!object.materials.empty()) << "object " << i << " has no material";
      if (!trs_of || !trs_of->sameTrs(object.transform)) {
        trs = object.transform.trs();
        // Kept in memory, as one matrix: left to itself GCC held its sixteen floats apart and
        // stored them again one by one for every object, and the product's wide loads of them
        // waited on those narrow stores (a store-forwarding stall: 43% of this loop's time).
        asm("" : "+m"(trs));
        trs_of = &object.transform;
      }
      const float4x4 model = object.transform.withBase(trs);
      const float4x4 model_view_projection = view_projection * model;
      if (cull.classify(object, i, model_view_projection, options.frustum_cull) != Side::kOutside ||
          every_matrix) {
        objects[i].model = model;
        objects[i].model_view_projection = model_view_projection;
      }
    }
  });
  const size_t triangle_total =
      cull.run(scene, scene.camera.view(), projection, {options.width, options.height}, objects);
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    if (!cull.drawsTriangles(i)) continue;
    objects[i].normal_matrix = normalMatrix(objects[i].model);
    objects[i].winding_sign = determinant(upper3x3(objects[i].model)) < 0.0f ? -1.0f : 1.0f;
  }
  return triangle_total;
}

CpuRenderer::State::Geometry CpuRenderer::State::transformAndSetUp(const Scene& scene,
                                                                   const RenderOptions& options,
                                                                   const TileGrid& grid,
                                                                   size_t triangle_total,
                                                                   int32_t sample_reach) {
  const size_t vertex_total = cull.planVertices(kVerticesPerJob, objects, vertex_jobs);
  const Clock::time_point t_start = Clock::now();
  const GuardBand guard = makeGuardBand(options.width, options.height);
  const ViewportTransform viewport{static_cast<float>(options.width),
                                   static_cast<float>(options.height), guard};
  // The painter's sort reads one whole copy of the vertices (painter.h).
  const bool painters = options.visibility == Visibility::kPainter;
  Geometry g;
  g.replicable = !painters && mayReplicate(vertex_total, pool.size());
  g.replicate = g.replicable && replication.next(vertex_total, triangle_total);
  const size_t copies = g.replicate ? static_cast<size_t>(pool.size()) : 1;
  if (vertex_buffers.size() < copies) vertex_buffers.resize(copies);
  for (size_t i = 0; i < copies; ++i) vertex_buffers[i].resize(vertex_total);
  lights.prepare(scene);
  if (options.shadows.enabled) {
    const float aspect = static_cast<float>(options.width) / static_cast<float>(options.height);
    shadows.build(scene, options.shadows, false, aspect, pool, lights);
  }
  const VertexLighting lighting{lights.ambient, lights.lights};
  auto transformJob = [&](size_t j, VertexBuffer& out) {
    const VertexJob& job = vertex_jobs[j];
    const Object& object = scene.objects[job.object];
    kernels.transform_vertices(*object.mesh, objects[job.object], viewport,
                               litPerVertex(object, lights) ? &lighting : nullptr, job.first,
                               job.count, out);
  };
  // Replicated, each worker transforms its copy in the setup stage, before its first chunk (no
  // barrier between the two: a worker reads no copy but its own). Every copy holds the same
  // bits, so which copy a chunk reads never shows in the image.
  if (!g.replicate)
    pool.parallelFor(vertex_jobs.size(),
                     [&](size_t j, int) { transformJob(j, vertex_buffers[0]); });
  for (auto& copy : transformed) copy = {};
  g.vertex_ms = elapsedMs(t_start, Clock::now());

  // Assembly, culling, clipping, setup and binning, per chunk.
  const Clock::time_point t_vertex = Clock::now();
  // Chunks of the triangles culling keeps, not of the scene's (chunk_layout.h).
  const size_t drawn_total = cull.drawnTriangles();
  const size_t chunk_size =
      std::max(kMinTrianglesPerChunk, (drawn_total + kMaxChunks - 1) / kMaxChunks);
  chunk_count = layOutChunks(drawn_total, chunk_size, pool.size(), chunks);
  toSceneIndices(cull.triangleRanges(), triangle_total, chunks, chunk_count);
  pool.parallelFor(chunk_count, [&](size_t c, int worker) {
    const size_t w = static_cast<size_t>(worker);
    if (g.replicate && !transformed[w].done) {
      const Clock::time_point start = Clock::now();
      for (size_t j = 0; j < vertex_jobs.size(); ++j) transformJob(j, vertex_buffers[w]);
      transformed[w].done = true;
      transformed[w].ms = elapsedMs(start, Clock::now());
    }
    chunks[c].count_reasons = options.diagnostics;
    setupChunk(scene, vertex_buffers[g.replicate ? w : 0], grid, guard, options.normals,
               sample_reach, chunks[c]);
  });
  if (painters) painter.build(pool, chunks, chunk_count, scene, objects, vertex_buffers[0], grid);
  blend.build(chunks, chunk_count, objects, grid);
  g.setup_ms = elapsedMs(t_vertex, Clock::now());
  if (g.replicate) {
    // The copies were made inside the setup stage: count the longest as the vertex stage.
    double copy_ms = 0;
    for (const auto& copy : transformed) copy_ms = std::max(copy_ms, copy.ms);
    g.vertex_ms += copy_ms;
    g.setup_ms = std::max(0.0, g.setup_ms - copy_ms);
  }
  return g;
}

void CpuRenderer::State::renderTile(const Scene& scene, const RenderOptions& options,
                                    const TileGrid& grid, const TilePass& pass, int tile,
                                    int worker, Frame& frame) {
  const size_t tile_index = static_cast<size_t>(tile);
  const int tx = tile % grid.columns, ty = tile / grid.columns;
  const int x0 = tx * kTileSize, y0 = ty * kTileSize;
  const int width = std::min(kTileSize, options.width - x0);
  const int height = std::min(kTileSize, options.height - y0);
  if (tile_empty[tile_index]) {
    if (tile_fill[tile_index])
      resolveEmptyRun(grid, tile_fill, tile, pass.background, pass.stream_background, frame);
    return;
  }
  if (options.msaa > 1) {
    renderSampledTile(scene, options, tile, worker, grid, pass, frame);
    return;
  }
  TileVisibility& visibility = *tiles[static_cast<size_t>(worker)];
  visibility.clear(x0, y0, width, height);
  if (options.visibility == Visibility::kPainter)
    kernels.raster_painter_tile(chunks, painter.slices(), tile, visibility);
  else
    kernels.raster_tile(chunks, chunk_count, tile, visibility);
  ShadedTile& out = *shaded[static_cast<size_t>(worker)];
  directColour(pass.stream, x0, y0, width, frame, out);
  kernels.shade_tile(visibility, chunks, chunk_count, lights, options.normals, pass.plain,
                     pass.background, nullptr, out);
  resolveTile(visibility, out, chunks, pass.stream, frame);
  if (options.coverage) resolveCoverage(visibility, nullptr, 1, frame);
  const TileVisibility* const layers[1] = {&visibility};
  blendTile(options, tile, worker, layers, frame);
}

namespace {

// The frame's buffers, as KeptFrame holds them.
std::array<std::pair<const void*, size_t>, 5> buffersOf(const Frame& frame) {
  return {{{frame.color.data(), frame.color.size()},
           {frame.depth.data(), frame.depth.size()},
           {frame.triangle_id.data(), frame.triangle_id.size()},
           {frame.normal.data(), frame.normal.size()},
           {frame.coverage.data(), frame.coverage.size()}}};
}

}  // namespace

void CpuRenderer::State::chooseFills(bool frame_kept, const Frame& frame, uint32_t background) {
  tile_fill = tile_empty;
  const bool same = kept.valid && kept.buffers == buffersOf(frame) && kept.width == frame.width &&
                    kept.height == frame.height && kept.background == background;
  kept.valid = false;  // until recordKept: nothing is known of a frame left half drawn
  if (!frame_kept || !same) return;
  for (size_t t = 0; t < tile_fill.size(); ++t)
    tile_fill[t] &= static_cast<uint8_t>(!kept.clean[t]);
}

void CpuRenderer::State::recordKept(const Frame& frame, uint32_t background, bool only_tiles) {
  if (!only_tiles) return;
  // Every empty tile holds the background: filled now, or kept from the last frame.
  kept.buffers = buffersOf(frame);
  kept.width = frame.width;
  kept.height = frame.height;
  kept.background = background;
  kept.clean = tile_empty;
  kept.valid = true;
}

void CpuRenderer::State::recordStats(const Geometry& geometry, double tiles_ms, double lines_ms,
                                     size_t triangle_total) {
  stats = {};
  stats.vertex_ms = geometry.vertex_ms;
  stats.setup_ms = geometry.setup_ms;
  stats.tiles_ms = tiles_ms;
  stats.lines_ms = lines_ms;
  stats.triangles_in = triangle_total;
  for (size_t c = 0; c < chunk_count; ++c) {
    stats.triangles_culled += chunks[c].culled;
    stats.triangles_clipped += chunks[c].clipped;
    stats.triangles_setup += chunks[c].size;
  }
  cull.addTo(stats);
}

void CpuRenderer::State::renderTiles(const Scene& scene, const RenderOptions& options,
                                     const TileGrid& grid, TilePass& pass, Frame& frame) {
  // Tiles no triangle touches (the background), found before the workers start so that a run of
  // them along a row can be filled in one go.
  const size_t triangles_setup =
      markEmptyTiles(chunks, chunk_count, static_cast<size_t>(grid.tileCount()), tile_empty);
  if (!blend.empty())
    for (uint32_t tile : blend.bins().usedTiles()) tile_empty[tile] = 0;
  pass.plain = plainShading(scene, options.normals);
  pass.background = packSrgba8(scene.background);
  pass.stream = streamsFrame(frame.pixelCount(), triangles_setup);
  pass.stream_background = streamsBackground(frame.pixelCount(), triangles_setup);
  chooseFills(options.frame_kept, frame, pass.background);
  pool.parallelFor(static_cast<size_t>(grid.tileCount()), [&](size_t tile, int worker) {
    renderTile(scene, options, grid, pass, static_cast<int>(tile), worker, frame);
  });
}

void CpuRenderer::render(const Scene& scene, const RenderOptions& options, Frame& frame) {
  TESSERA_CHECK(options.width > 0 && options.height > 0 && options.width <= kMaxViewport &&
                options.height <= kMaxViewport)
      << "viewport " << options.width << "x" << options.height << " is outside 1.." << kMaxViewport;
  TESSERA_CHECK(isSampleCount(options.msaa))
      << options.msaa << " samples per pixel: not 1, 2, 4 or 8";
  State& s = *state_;
  if (options.diagnostics && !(options.depth && options.ids)) {
    render(scene, withDiagnosticInputs(options), frame);
    return;
  }
  if (needsComposite(scene, options) && !options.coverage) {
    render(scene, withCompositeInputs(scene, options), frame);
    return;
  }
  frame.diagnostics.valid = false;
  const bool painter = options.visibility == Visibility::kPainter;
  if (options.projection != Projection::kPerspective) {
    TESSERA_CHECK(!painter) << "the painter's algorithm draws the perspective projection only";
    s.kept.valid = false;  // the rays write every pixel; their frame is not kept
    s.rays.render(scene, options, frame, s.pool, s.kernels, s.stats, s.shadows);
    if (options.diagnostics)
      s.diagnostics.run(s.pool, {}, 0, scene, TileGrid::forViewport(options.width, options.height),
                        false, s.stats, frame);
    return;
  }
  const bool draws_lines = LinePass::wanted(scene, options);
  const bool draws_points = PointPass::wanted(scene);
  frame.resize(options.width, options.height, options.depth || draws_lines || draws_points,
               options.ids, options.normals, options.coverage);

  const float aspect = static_cast<float>(options.width) / static_cast<float>(options.height);
  const float4x4 projection = jitteredProjection(scene.camera.projection(aspect), options.jitter,
                                                 options.width, options.height);
  const float4x4 view_projection = projection * scene.camera.view();
  // With MSAA the pixel centres are a layer of their own, rasterized only for what reads them.
  const bool sampled = options.msaa > 1;
  State::TilePass pass;
  pass.with_centre =
      sampled && (options.depth || options.ids || options.normals || draws_lines || draws_points);
  if (sampled) s.prepareSampleLayers(options, pass.with_centre);
  const size_t triangle_total =
      s.prepareObjects(scene, options, projection, view_projection, draws_lines);

  // Vertex and setup stages.
  const TileGrid grid = TileGrid::forViewport(options.width, options.height);
  const State::Geometry geometry =
      s.transformAndSetUp(scene, options, grid, triangle_total, sampleReach(options.msaa));

  // Raster, shade and resolve, per tile.
  const Clock::time_point t_setup = Clock::now();
  s.renderTiles(scene, options, grid, pass, frame);
  const Clock::time_point t_tiles = Clock::now();
  if (geometry.replicable)
    s.replication.record(geometry.replicate,
                         geometry.vertex_ms + geometry.setup_ms + elapsedMs(t_setup, t_tiles));

  compositeFrame(scene, options, frame);
  // Points, then lines (which the points hide).
  if (draws_points)
    s.point_pass.draw(scene, options,
                      PointCamera::perspective(view_projection, scene.camera.view()), sampled,
                      s.pool, frame);
  if (draws_lines) s.line_pass.draw(scene, s.objects, options, view_projection, sampled, frame);
  s.recordKept(
      frame, pass.background,
      !draws_points && !draws_lines && !needsComposite(scene, options) && !options.diagnostics);

  s.recordStats(geometry, elapsedMs(t_setup, t_tiles), elapsedMs(t_tiles, Clock::now()),
                triangle_total);
  if (options.diagnostics)
    s.diagnostics.run(s.pool, s.chunks, s.chunk_count, scene, grid, true, s.stats, frame);
}

}  // namespace tessera
