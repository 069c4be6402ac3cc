// The CPU backend's state across frames (CpuRenderer::State), shared by the frame loop
// (cpu_renderer.cpp) and the setup stage (chunk_setup.cpp).
#pragma once

#include <array>
#include <memory>
#include <utility>
#include <vector>

#include <tessera/render/cpu_renderer.h>

#include "render/bin.h"
#include "render/blend.h"
#include "render/cull.h"
#include "render/diagnostics.h"
#include "render/kernels.h"
#include "render/line_pass.h"
#include "render/msaa.h"
#include "render/painter.h"
#include "render/point_pass.h"
#include "render/raster.h"
#include "render/ray_renderer.h"
#include "render/replication.h"
#include "render/resolve.h"
#include "render/setup.h"
#include "render/shadow_map.h"
#include "render/vertex.h"
#include "render/worker_pool.h"

namespace tessera {

struct CpuRenderer::State {
  State(int workers, render::Isa isa) : pool(workers), isa(isa), kernels(render::kernelsFor(isa)) {
    transformed.resize(static_cast<size_t>(pool.size()));
    for (int i = 0; i < pool.size(); ++i) {
      tiles.push_back(std::make_unique<render::TileVisibility>());
      shaded.push_back(std::make_unique<render::ShadedTile>());
      blend_tiles.push_back(std::make_unique<render::BlendTile>());
    }
  }

  render::WorkerPool pool;
  render::Isa isa;
  render::Kernels kernels;
  std::vector<render::ObjectTransforms> objects;
  render::FrustumCull cull;  // what each object draws this frame
  std::vector<render::VertexJob> vertex_jobs;
  // The vertex stage's output: one buffer, or one per worker (mayReplicate).
  std::vector<render::VertexBuffer> vertex_buffers;
  // Per worker, this frame (replicated scenes): its copy of the vertices is made, in how long.
  struct alignas(64) WorkerCopy {
    bool done = false;
    double ms = 0;
  };
  std::vector<WorkerCopy> transformed;
  render::ReplicationChoice replication;
  std::vector<render::TriangleChunk> chunks;
  size_t chunk_count = 0;
  std::vector<std::unique_ptr<render::TileVisibility>> tiles;  // one per worker
  std::vector<std::unique_ptr<render::ShadedTile>> shaded;     // one per worker
  std::vector<std::unique_ptr<render::SampleTiles>> sampled;   // one per worker, made for MSAA
  std::vector<render::SampleShift> shifts;                     // this frame's sample layers
  std::vector<uint8_t> tile_empty;                             // this frame's: no triangle binned
  std::vector<uint8_t> tile_fill;  // this frame's empty tiles that are filled (chooseFills)
  // What the last render left in its frame (RenderOptions::frame_kept): the buffers' addresses
  // and sizes, the frame's width and height (a frame turned to as many pixels keeps its buffers),
  // the background, and per tile whether it holds the background and nothing else.
  struct KeptFrame {
    std::array<std::pair<const void*, size_t>, 5> buffers{};
    int width = 0, height = 0;
    uint32_t background = 0;
    std::vector<uint8_t> clean;
    bool valid = false;
  };
  KeptFrame kept;
  render::PainterOrder painter;  // RenderOptions::visibility kPainter
  render::BlendOrder blend;      // alphaMode BLEND, this frame's
  std::vector<std::unique_ptr<render::BlendTile>> blend_tiles;  // one per worker
  render::LinePass line_pass;
  render::PointPass point_pass;
  PipelineStats stats;
  render::RayRenderer rays;             // the nonlinear projections
  render::DiagnosticsPass diagnostics;  // RenderOptions::diagnostics
  render::LightRig lights;              // this frame's
  render::ShadowMaps shadows;           // RenderOptions::shadows, this frame's

  // tile_fill: this frame's empty tiles, less, where the caller promises the frame is as the
  // last render left it (RenderOptions::frame_kept), those that render left holding
  // `background` in the same buffers.
  void chooseFills(bool frame_kept, const Frame& frame, uint32_t background);
  // After the frame: its empty tiles hold `background` and nothing else where `only_tiles` (no
  // pass after the tile stage drew into the frame).
  void recordKept(const Frame& frame, uint32_t background, bool only_tiles);
  // With MSAA: this frame's sample layers (`shifts`), the centre's last when `with_centre`.
  void prepareSampleLayers(const RenderOptions& options, bool with_centre);
  // Every object's triangle base, the transforms of those that may draw (of every object with
  // `every_matrix`: the line pass reads them all), and what frustum culling keeps; the triangles
  // of the scene, drawn or not.
  size_t prepareObjects(const Scene& scene, const RenderOptions& options,
                        const float4x4& projection, const float4x4& view_projection,
                        bool every_matrix);
  // The vertex stage (replicated per worker or not: replication.h) and the setup stage (per
  // chunk, then the painter's order and the blended triangles' order), timed.
  struct Geometry {
    bool replicable = false, replicate = false;
    double vertex_ms = 0, setup_ms = 0;
  };
  Geometry transformAndSetUp(const Scene& scene, const RenderOptions& options,
                             const render::TileGrid& grid, size_t triangle_total,
                             int32_t sample_reach);
  // What every tile of the frame's tile pass shares.
  struct TilePass {
    bool with_centre = false;        // MSAA: the pixel centres are a layer of their own
    bool plain = false;              // plainShading
    uint32_t background = 0;         // sRGB
    bool stream = false;             // the colour written past the caches (streamsFrame)
    bool stream_background = false;  // the empty tiles' too (streamsBackground)
  };
  // The tile pass over the whole frame: finds the empty tiles, completes `pass` (with_centre is
  // the caller's) and renders every tile on the workers.
  void renderTiles(const Scene& scene, const RenderOptions& options, const render::TileGrid& grid,
                   TilePass& pass, Frame& frame);
  // Raster, shade and resolve of one tile (or, for the first of a run of empty tiles along a row,
  // the background of the run).
  void renderTile(const Scene& scene, const RenderOptions& options, const render::TileGrid& grid,
                  const TilePass& pass, int tile, int worker, Frame& frame);
  void recordStats(const Geometry& geometry, double tiles_ms, double lines_ms,
                   size_t triangle_total);

  void setupChunk(const Scene& scene, const render::VertexBuffer& vertices,
                  const render::TileGrid& grid, const render::GuardBand& guard, bool want_normals,
                  int32_t sample_reach, render::TriangleChunk& chunk) const;
  // The transparent pass over one resolved tile (blend.h), when some blended record is binned to
  // it: `layers` hold the opaque depths of the samples, one layer without MSAA.
  void blendTile(const RenderOptions& options, int tile, int worker,
                 const render::TileVisibility* const* layers, Frame& frame);
  // Raster, shade and resolve of one tile with several samples per pixel (msaa.h).
  void renderSampledTile(const Scene& scene, const RenderOptions& options, int tile, int worker,
                         const render::TileGrid& grid, const TilePass& pass, Frame& frame);
};

}  // namespace tessera
