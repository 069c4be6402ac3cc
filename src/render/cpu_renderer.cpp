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
                                           bool with_centre, bool plain, Frame& frame) {
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
  kernels.shade_tile(*st.primary, chunks, chunk_count, lights, options.normals, plain,
                     packSrgba8(scene.background), &msaa, out);
  // The AOVs are the centre layer's: the same as one sample gives.
  resolveTile(with_centre ? *layers[options.msaa] : *st.primary, out, chunks, frame);
  if (options.coverage) resolveCoverage(*st.primary, st.covered, options.msaa, frame);
  blendTile(options, tile, worker, layers, frame);
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
  const bool with_centre =
      sampled && (options.depth || options.ids || options.normals || draws_lines || draws_points);
  const int32_t sample_reach = sampled ? kSampleReach : 0;
  if (sampled) {
    s.shifts.clear();
    for (const SamplePosition& p : samplePattern(options.msaa)) {
      const int32_t dx = p.x - kSubpixelHalf, dy = p.y - kSubpixelHalf;
      constexpr float kToPixels = 1.0f / static_cast<float>(kSubpixelOne);
      s.shifts.push_back(
          {dx, dy, static_cast<float>(dx) * kToPixels, static_cast<float>(dy) * kToPixels});
    }
    if (with_centre) s.shifts.push_back({});
    if (s.sampled.empty())
      for (int i = 0; i < s.pool.size(); ++i) s.sampled.push_back(std::make_unique<SampleTiles>());
  }

  // Per-object constants and triangle bases (the ids: every object's, drawn or not); then what
  // frustum culling keeps, and vertex bases for the objects that draw.
  s.objects.resize(scene.objects.size());
  size_t triangle_total = 0;
  // A scene graph's instances share one T * R * S (identity, or a turntable's): computed once
  // for each run of objects that share it.
  float4x4 trs;
  const Transform* trs_of = nullptr;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& object = scene.objects[i];
    TESSERA_CHECK(!object.materials.empty()) << "object " << i << " has no material";
    if (!trs_of || !trs_of->sameTrs(object.transform)) {
      trs = object.transform.trs();
      trs_of = &object.transform;
    }
    // What culling reads; the rest of makeObjectTransforms' constants only for what draws.
    s.objects[i].model = object.transform.withBase(trs);
    s.objects[i].model_view_projection = view_projection * s.objects[i].model;
    s.objects[i].triangle_base = triangle_total;
    if (object.mesh) triangle_total += object.mesh->triangleCount();
  }
  s.cull.run(scene, scene.camera.view(), projection, {options.width, options.height},
             options.frustum_cull, s.objects);
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    if (!s.cull.drawsTriangles(i)) continue;
    s.objects[i].normal_matrix = normalMatrix(s.objects[i].model);
    s.objects[i].winding_sign = determinant(upper3x3(s.objects[i].model)) < 0.0f ? -1.0f : 1.0f;
  }
  const size_t vertex_total = s.cull.planVertices(scene, kVerticesPerJob, s.objects, s.vertex_jobs);

  using Clock = std::chrono::steady_clock;
  auto elapsed_ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  const Clock::time_point t_start = Clock::now();

  // Vertex stage.
  const TileGrid grid = TileGrid::forViewport(options.width, options.height);
  const GuardBand guard = makeGuardBand(options.width, options.height);
  const ViewportTransform viewport{static_cast<float>(options.width),
                                   static_cast<float>(options.height), guard};
  // The painter's sort reads one whole copy of the vertices (painter.h).
  const bool replicable = !painter && mayReplicate(vertex_total, s.pool.size());
  const bool replicate = replicable && s.replication.next(vertex_total, triangle_total);
  const size_t copies = replicate ? static_cast<size_t>(s.pool.size()) : 1;
  if (s.vertex_buffers.size() < copies) s.vertex_buffers.resize(copies);
  for (size_t i = 0; i < copies; ++i) s.vertex_buffers[i].resize(vertex_total);
  s.lights.prepare(scene);
  if (options.shadows.enabled)
    s.shadows.build(scene, options.shadows, false, aspect, s.pool, s.lights);
  const VertexLighting lighting{s.lights.ambient, s.lights.lights};
  auto transformJob = [&](size_t j, VertexBuffer& out) {
    const VertexJob& job = s.vertex_jobs[j];
    const Object& object = scene.objects[job.object];
    s.kernels.transform_vertices(*object.mesh, s.objects[job.object], viewport,
                                 litPerVertex(object, s.lights) ? &lighting : nullptr, job.first,
                                 job.count, out);
  };
  // Replicated, each worker transforms its copy in the setup stage, before its first chunk (no
  // barrier between the two: a worker reads no copy but its own). Every copy holds the same
  // bits, so which copy a chunk reads never shows in the image.
  if (!replicate)
    s.pool.parallelFor(s.vertex_jobs.size(),
                       [&](size_t j, int) { transformJob(j, s.vertex_buffers[0]); });
  for (auto& copy : s.transformed) copy = {};

  const Clock::time_point t_vertex = Clock::now();

  // Assembly, culling, clipping, setup and binning, per chunk.
  const size_t chunk_size =
      std::max(kMinTrianglesPerChunk, (triangle_total + kMaxChunks - 1) / kMaxChunks);
  s.chunk_count = layOutChunks(triangle_total, chunk_size, s.pool.size(), s.chunks);
  s.pool.parallelFor(s.chunk_count, [&](size_t c, int worker) {
    const size_t w = static_cast<size_t>(worker);
    if (replicate && !s.transformed[w].done) {
      const Clock::time_point start = Clock::now();
      for (size_t j = 0; j < s.vertex_jobs.size(); ++j) transformJob(j, s.vertex_buffers[w]);
      s.transformed[w].done = true;
      s.transformed[w].ms = elapsed_ms(start, Clock::now());
    }
    s.chunks[c].count_reasons = options.diagnostics;
    s.setupChunk(scene, s.vertex_buffers[replicate ? w : 0], grid, guard, options.normals,
                 sample_reach, s.chunks[c]);
  });
  if (painter)
    s.painter.build(s.pool, s.chunks, s.chunk_count, scene, s.objects, s.vertex_buffers[0], grid);
  s.blend.build(s.chunks, s.chunk_count, s.objects, grid);

  const Clock::time_point t_setup = Clock::now();

  // Raster, shade and resolve, per tile.
  // Tiles no triangle touches (the background), found before the workers start so that a run of
  // them along a row can be filled in one go.
  s.tile_empty.assign(static_cast<size_t>(grid.tileCount()), 1);
  for (size_t c = 0; c < s.chunk_count; ++c)
    for (uint32_t tile : s.chunks[c].bins.usedTiles()) s.tile_empty[tile] = 0;
  if (!s.blend.empty())
    for (uint32_t tile : s.blend.bins().usedTiles()) s.tile_empty[tile] = 0;
  const bool plain = plainShading(scene, options.normals);
  const uint32_t background = packSrgba8(scene.background);
  s.pool.parallelFor(static_cast<size_t>(grid.tileCount()), [&](size_t tile_index, int worker) {
    const int tile = static_cast<int>(tile_index);
    const int tx = tile % grid.columns, ty = tile / grid.columns;
    const int x0 = tx * kTileSize, y0 = ty * kTileSize;
    const int width = std::min(kTileSize, options.width - x0);
    const int height = std::min(kTileSize, options.height - y0);
    if (s.tile_empty[tile_index]) {
      // A run of empty tiles along the row is filled by its first tile, row by row across the
      // whole run: long runs of stores instead of 64-pixel pieces.
      if (tx > 0 && s.tile_empty[tile_index - 1]) return;
      int run_end = tx + 1;
      while (run_end < grid.columns && s.tile_empty[tile_index + (run_end - tx)]) ++run_end;
      resolveEmptyTile(x0, y0, std::min(run_end * kTileSize, options.width) - x0, height,
                       background, frame);
      return;
    }
    if (sampled) {
      s.renderSampledTile(scene, options, tile, worker, grid, with_centre, plain, frame);
      return;
    }
    TileVisibility& visibility = *s.tiles[static_cast<size_t>(worker)];
    visibility.clear(x0, y0, width, height);
    if (painter)
      s.kernels.raster_painter_tile(s.chunks, s.painter.slices(), tile, visibility);
    else
      s.kernels.raster_tile(s.chunks, s.chunk_count, tile, visibility);
    ShadedTile& shaded = *s.shaded[static_cast<size_t>(worker)];
    s.kernels.shade_tile(visibility, s.chunks, s.chunk_count, s.lights, options.normals, plain,
                         background, nullptr, shaded);
    resolveTile(visibility, shaded, s.chunks, frame);
    if (options.coverage) resolveCoverage(visibility, nullptr, 1, frame);
    const TileVisibility* const layers[1] = {&visibility};
    s.blendTile(options, tile, worker, layers, frame);
  });

  const Clock::time_point t_tiles = Clock::now();
  if (replicable) s.replication.record(replicate, elapsed_ms(t_start, t_tiles));

  compositeFrame(scene, options, frame);
  // Points, then lines (which the points hide).
  if (draws_points)
    s.point_pass.draw(scene, options,
                      PointCamera::perspective(view_projection, scene.camera.view()), sampled,
                      s.pool, frame);
  if (draws_lines) s.line_pass.draw(scene, s.objects, options, view_projection, sampled, frame);

  const Clock::time_point t_lines = Clock::now();

  // Statistics.
  s.stats = {};
  s.stats.vertex_ms = elapsed_ms(t_start, t_vertex);
  s.stats.setup_ms = elapsed_ms(t_vertex, t_setup);
  if (replicate) {
    // The copies were made inside the setup stage: count the longest as the vertex stage.
    double copy_ms = 0;
    for (const auto& copy : s.transformed) copy_ms = std::max(copy_ms, copy.ms);
    s.stats.vertex_ms += copy_ms;
    s.stats.setup_ms = std::max(0.0, s.stats.setup_ms - copy_ms);
  }
  s.stats.tiles_ms = elapsed_ms(t_setup, t_tiles);
  s.stats.lines_ms = elapsed_ms(t_tiles, t_lines);
  s.stats.triangles_in = triangle_total;
  for (size_t c = 0; c < s.chunk_count; ++c) {
    s.stats.triangles_culled += s.chunks[c].culled;
    s.stats.triangles_clipped += s.chunks[c].clipped;
    s.stats.triangles_setup += s.chunks[c].size;
  }
  s.cull.addTo(s.stats);
  if (options.diagnostics)
    s.diagnostics.run(s.pool, s.chunks, s.chunk_count, scene, grid, true, s.stats, frame);
}

}  // namespace tessera
