#include "render/ray_renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <tessera/base/check.h>
#include <tessera/render/composite.h>
#include <tessera/scene/color.h>

#include "render/chunk_layout.h"
#include "render/clip.h"
#include "render/line_pass.h"
#include "render/lines.h"
#include "render/point_pass.h"
#include "render/ray_setup.h"
#include "render/resolve.h"

namespace tessera::render {

namespace {

constexpr size_t kVerticesPerJob = 4096;
constexpr size_t kMinTrianglesPerChunk = 4096;

// The record slot of the chunk's next triangle; the vectors only grow.
uint32_t nextRayRecord(TriangleChunk& chunk) {
  const uint32_t local = static_cast<uint32_t>(chunk.size);
  TESSERA_CHECK(local < kMaxTrianglesPerChunk) << "chunk holds too many triangles";
  if (local >= chunk.ray.size()) chunk.ray.emplace_back();
  if (local >= chunk.shade.size()) chunk.shade.emplace_back();
  if (local >= chunk.extras.size()) chunk.extras.emplace_back();
  return local;
}

bool finite(float3 p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

}  // namespace

void RayRenderer::transform(const Scene& scene, const RenderOptions& options, WorkerPool& pool,
                            const Kernels& kernels) {
  // The view matrix in place of view-projection: the vertex stage's clip x, y, z are then the
  // camera-space position (w = 1), with the same arithmetic as every other vertex.
  const float4x4 view = scene.camera.view();
  objects_.resize(scene.objects.size());
  vertex_jobs_.clear();
  size_t vertex_total = 0, triangle_total = 0;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& object = scene.objects[i];
    TESSERA_CHECK(!object.materials.empty()) << "object " << i << " has no material";
    objects_[i] = makeObjectTransforms(object, view);
    objects_[i].vertex_base = vertex_total;
    objects_[i].triangle_base = triangle_total;
    if (!object.mesh) continue;
    const size_t count = object.mesh->vertexCount();
    for (size_t first = 0; first < count; first += kVerticesPerJob)
      vertex_jobs_.push_back(
          {static_cast<uint32_t>(i), first, std::min(kVerticesPerJob, count - first)});
    vertex_total += count;
    triangle_total += object.mesh->triangleCount();
  }
  vertices_.resize(vertex_total);
  const ViewportTransform viewport{static_cast<float>(options.width),
                                   static_cast<float>(options.height),
                                   makeGuardBand(options.width, options.height)};
  lights_.prepare(scene);
  if (options.shadows.enabled)
    shadows_->build(scene, options.shadows, true,
                    static_cast<float>(options.width) / static_cast<float>(options.height), pool,
                    lights_);
  const VertexLighting lighting{lights_.ambient, lights_.lights};
  pool.parallelFor(vertex_jobs_.size(), [&](size_t j, int) {
    const VertexJob& job = vertex_jobs_[j];
    const Object& object = scene.objects[job.object];
    kernels.transform_vertices(*object.mesh, objects_[job.object], viewport,
                               litPerVertex(object, lights_) ? &lighting : nullptr, job.first,
                               job.count, vertices_);
  });
  const size_t chunk_size =
      std::max(kMinTrianglesPerChunk, (triangle_total + kMaxChunks - 1) / kMaxChunks);
  chunk_count_ = layOutChunks(triangle_total, chunk_size, pool.size(), chunks_);
}

void RayRenderer::setupChunk(const Scene& scene, const RenderOptions& options, int workers,
                             TriangleChunk& chunk) const {
  chunk.size = 0;
  chunk.bins.reset(grid_.tileCount(), workers > 1);
  chunk.culled = 0;
  chunk.clipped = 0;
  const size_t begin = chunk.first_triangle, end = begin + chunk.triangle_count;
  size_t object_index = objectHolding(objects_, begin);
  RaySetupContext rctx;
  rctx.projection = options.projection;
  rctx.width = options.width;
  rctx.height = options.height;
  rctx.fov_y_radians = static_cast<double>(scene.camera.fov_y_degrees) * std::numbers::pi / 180.0;
  const bool centre_only =
      options.msaa == 1 && options.jitter.x == 0.0f && options.jitter.y == 0.0f;
  rctx.sample_reach = centre_only ? 0.0 : kRayReach;
  for (size_t t = begin; t < end; ++object_index) {
    const Object& object = scene.objects[object_index];
    const ObjectTransforms& xf = objects_[object_index];
    const size_t object_end = xf.triangle_base + (object.mesh ? object.mesh->triangleCount() : 0);
    if (!object.mesh || t >= object_end) continue;
    const Mesh& mesh = *object.mesh;
    const size_t vertex_count = mesh.vertexCount();
    const SetupContext ctx = objectSetupContext(lights_, object, xf.model, options.width,
                                                options.height, options.normals, 0);
    rctx.cull = object.cull;
    const bool has_materials = mesh.triangle_materials.size() == mesh.triangleCount();
    const bool needs_face_normal = object.shading == Shading::kFlat ||
                                   mesh.normals.size() != vertex_count || xf.winding_sign < 0.0f;
    const MeshVertices corners{
        nullptr,
        vertices_.normal.data() + xf.vertex_base,
        litPerVertex(object, lights_) ? vertices_.lit.data() + xf.vertex_base : nullptr,
        ctx.has_uv ? mesh.uvs.data() : nullptr,
        ctx.has_color ? mesh.colors.data() : nullptr,
        mesh.positions.data(),
        meshUv1(ctx, mesh)};
    for (const size_t stop = std::min(end, object_end); t < stop; ++t) {
      const size_t local = t - xf.triangle_base;
      const uint32_t* idx = &mesh.indices[local * 3];
      if (idx[0] >= vertex_count || idx[1] >= vertex_count || idx[2] >= vertex_count) {
        ++chunk.culled;
        continue;
      }
      float3 p[3];
      for (int k = 0; k < 3; ++k) {
        const size_t v = xf.vertex_base + idx[k];
        p[k] = {vertices_.clip_x[v], vertices_.clip_y[v], vertices_.clip_z[v]};
      }
      const uint32_t record = nextRayRecord(chunk);
      TriangleOrientation o;
      if (!finite(p[0]) || !finite(p[1]) || !finite(p[2]) ||
          !setupRayTriangle(rctx, p, chunk.ray[record], o)) {
        ++chunk.culled;
        continue;
      }
      ++chunk.size;
      float3 face_normal{};
      if (needs_face_normal) {
        const float3 m0 = mesh.positions[idx[0]], m1 = mesh.positions[idx[1]],
                     m2 = mesh.positions[idx[2]];
        face_normal = xf.normal_matrix * cross(m1 - m0, m2 - m0) * xf.winding_sign;
      }
      const uint16_t material = has_materials ? mesh.triangle_materials[local] : uint16_t{0};
      setupShadeCorners(ctx, corners, idx, o, face_normal, static_cast<uint32_t>(t), material,
                        chunk.shade[record], chunk.extras[record]);
      markSolid(chunk.shade[record]);  // the record whole, though the ray kernels do not read it
      const RayTriangle& r = chunk.ray[record];
      for (const int16_t* box : {r.box[0], r.box[1]})
        if (box[0] <= box[2])
          chunk.bins.add(grid_, PixelBox{box[0], box[1], box[2], box[3]}, record);
    }
  }
}

void RayRenderer::renderTile(const Scene& scene, const RenderOptions& options, int tile, int worker,
                             bool with_centre, Frame& frame) {
  const int tx = tile % grid_.columns, ty = tile / grid_.columns;
  const int x0 = tx * kTileSize, y0 = ty * kTileSize;
  const int width = std::min(kTileSize, options.width - x0);
  const int height = std::min(kTileSize, options.height - y0);
  const RayDepth depth{scene.camera.near_z, 1.0f / (scene.camera.far_z - scene.camera.near_z)};
  ShadedTile& out = *shaded_[static_cast<size_t>(worker)];
  const uint32_t background = packSrgba8(scene.background);
  if (options.msaa == 1) {
    TileVisibility& visibility = *tiles_[static_cast<size_t>(worker)];
    visibility.clear(x0, y0, width, height);
    kernels_->raster_ray_tile(chunks_, chunk_count_, tile, rays_.centre(), options.width, depth,
                              visibility);
    kernels_->shade_ray_tile(visibility, chunks_, chunk_count_, lights_, options.normals,
                             background, rays_, nullptr, out);
    resolveTile(visibility, out, chunks_, stream_, frame);
    if (options.coverage) resolveCoverage(visibility, nullptr, 1, frame);
    return;
  }
  SampleTiles& st = *sampled_[static_cast<size_t>(worker)];
  const int samples = options.msaa;
  for (int i = 0; i < samples + (with_centre ? 1 : 0); ++i) {
    TileVisibility& layer = st.layer(i);
    layer.clear(x0, y0, width, height);
    kernels_->raster_ray_tile(chunks_, chunk_count_, tile,
                              i < samples ? rays_.sample(i) : rays_.centre(), options.width, depth,
                              layer);
  }
  kernels_->combine_samples(st, samples, with_centre);
  const MsaaShading msaa{&st, samples, samplePattern(samples).data(), scene.background.xyz()};
  kernels_->shade_ray_tile(*st.primary, chunks_, chunk_count_, lights_, options.normals, background,
                           rays_, &msaa, out);
  resolveTile(with_centre ? st.layer(samples) : *st.primary, out, chunks_, stream_, frame);
  if (options.coverage) resolveCoverage(*st.primary, st.covered, samples, frame);
}

void RayRenderer::render(const Scene& scene, const RenderOptions& options, Frame& frame,
                         WorkerPool& pool, const Kernels& kernels, PipelineStats& stats,
                         ShadowMaps& shadows) {
  kernels_ = &kernels;
  shadows_ = &shadows;
  const float aspect = static_cast<float>(options.width) / static_cast<float>(options.height);
  TESSERA_CHECK(checkViewAngle(options.projection, scene.camera.fov_y_degrees, aspect).empty())
      << checkViewAngle(options.projection, scene.camera.fov_y_degrees, aspect);
  TESSERA_CHECK(scene.camera.far_z > scene.camera.near_z && scene.camera.near_z >= 0.0f)
      << "near " << scene.camera.near_z << " and far " << scene.camera.far_z;
  const bool draws_lines =
      options.lines && (!scene.lines.points.empty() || scene.show_world_axes ||
                        std::any_of(scene.objects.begin(), scene.objects.end(),
                                    [](const Object& o) { return o.show_axes; }));
  const bool draws_points = PointPass::wanted(scene);
  frame.resize(options.width, options.height, options.depth || draws_lines || draws_points,
               options.ids, options.normals, options.coverage);
  const bool with_centre = options.msaa > 1 && (options.depth || options.ids || options.normals ||
                                                draws_lines || draws_points);

  using Clock = std::chrono::steady_clock;
  auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  const Clock::time_point t_start = Clock::now();
  rays_.update(options.projection, options.width, options.height, scene.camera.fov_y_degrees,
               options.msaa, options.jitter,
               [&pool](int rows, const std::function<void(int)>& row) {
                 pool.parallelFor(static_cast<size_t>(rows),
                                  [&](size_t y, int) { row(static_cast<int>(y)); });
               });
  transform(scene, options, pool, kernels);
  const Clock::time_point t_vertex = Clock::now();

  grid_ = TileGrid::forViewport(options.width, options.height);
  pool.parallelFor(chunk_count_,
                   [&](size_t c, int) { setupChunk(scene, options, pool.size(), chunks_[c]); });
  const Clock::time_point t_setup = Clock::now();

  const size_t triangles_setup =
      markEmptyTiles(chunks_, chunk_count_, static_cast<size_t>(grid_.tileCount()), tile_empty_);
  stream_ = streamsFrame(frame.pixelCount(), triangles_setup);
  const bool stream_background = streamsBackground(frame.pixelCount(), triangles_setup);
  while (tiles_.size() < static_cast<size_t>(pool.size())) {
    tiles_.push_back(std::make_unique<TileVisibility>());
    shaded_.push_back(std::make_unique<ShadedTile>());
  }
  while (options.msaa > 1 && sampled_.size() < static_cast<size_t>(pool.size()))
    sampled_.push_back(std::make_unique<SampleTiles>());
  const uint32_t background = packSrgba8(scene.background);
  pool.parallelFor(static_cast<size_t>(grid_.tileCount()), [&](size_t tile, int worker) {
    if (!tile_empty_[tile]) {
      renderTile(scene, options, static_cast<int>(tile), worker, with_centre, frame);
      return;
    }
    resolveEmptyRun(grid_, tile_empty_, static_cast<int>(tile), background, stream_background,
                    frame);
  });
  const Clock::time_point t_tiles = Clock::now();

  compositeFrame(scene, options, frame);
  drawOverlays(scene, options, draws_points, draws_lines, pool, frame);
  const Clock::time_point t_lines = Clock::now();

  stats = {};
  stats.vertex_ms = ms(t_start, t_vertex);
  stats.setup_ms = ms(t_vertex, t_setup);
  stats.tiles_ms = ms(t_setup, t_tiles);
  stats.lines_ms = ms(t_tiles, t_lines);
  for (const Object& object : scene.objects)
    stats.triangles_in += object.mesh ? object.mesh->triangleCount() : 0;
  for (size_t c = 0; c < chunk_count_; ++c) {
    stats.triangles_culled += chunks_[c].culled;
    stats.triangles_setup += chunks_[c].size;
  }
}

void RayRenderer::drawOverlays(const Scene& scene, const RenderOptions& options, bool points,
                               bool lines, WorkerPool& pool, Frame& frame) {
  const RayLines mode{options.projection,
                      static_cast<double>(scene.camera.fov_y_degrees) * std::numbers::pi / 180.0,
                      scene.camera.near_z, scene.camera.far_z};
  if (points)
    points_.draw(scene, options, {options.projection, {}, scene.camera.view(), mode},
                 options.msaa > 1, pool, frame);
  if (lines) {
    drawRayLines(scene.lines, scene.camera.view(), mode, frame, options.msaa > 1,
                 options.line_width);
    axisLines(scene, objects_, lines_);
    drawRayLines(lines_, scene.camera.view(), mode, frame, options.msaa > 1);
  }
}

}  // namespace tessera::render
