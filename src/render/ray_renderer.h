// The CPU backend's nonlinear projections (RenderOptions::projection other than perspective):
//
//   vertex:  the usual vertex stage with the view matrix in place of view-projection, so that
//            "clip" x, y, z are camera-space positions (normals and per-vertex lighting as usual)
//   setup:   per chunk of triangles: ray_setup.h's planes and pixel boxes, the shading corners,
//            binning into 64x64 tiles
//   tiles:   per tile: each pixel's (each sample's) ray against the tile's triangles in submission
//            order, shading from the rays' barycentrics, the resolve (ray_kernel.h)
//   points:  the point pass (point_pass.h) through the same mapping
//   lines:   the line pass through the same mapping
//
// No clipping: a ray meets a triangle or not, in front of the eye or not, and hits nearer than
// near or past far are not drawn. The image is bit-identical for any worker count (a tile's
// triangles in submission order, one worker per tile) and any SIMD level (the kernels' lanes do
// the same operations on every instruction set).
#pragma once

#include <memory>
#include <vector>

#include <tessera/render/cpu_renderer.h>
#include <tessera/render/frame.h>
#include <tessera/render/options.h>
#include <tessera/render/projection.h>
#include <tessera/scene/scene.h>

#include "render/bin.h"
#include "render/kernels.h"
#include "render/msaa.h"
#include "render/point_pass.h"
#include "render/shade.h"
#include "render/shadow_map.h"
#include "render/vertex.h"
#include "render/worker_pool.h"

namespace tessera::render {

class RayRenderer {
 public:
  // `shadows`: where this frame's shadow maps are rendered when options.shadows asks for them.
  void render(const Scene& scene, const RenderOptions& options, Frame& frame, WorkerPool& pool,
              const Kernels& kernels, PipelineStats& stats, ShadowMaps& shadows);

 private:
  struct VertexJob {
    uint32_t object;
    size_t first, count;
  };
  void transform(const Scene& scene, const RenderOptions& options, WorkerPool& pool,
                 const Kernels& kernels);
  void setupChunk(const Scene& scene, const RenderOptions& options, int workers,
                  TriangleChunk& chunk) const;
  void renderTile(const Scene& scene, const RenderOptions& options, int tile, int worker,
                  bool with_centre, Frame& frame);
  // The scene's points and lines (`points`, `lines`: whether it draws them) over the frame, each
  // along the projection's curves.
  void drawOverlays(const Scene& scene, const RenderOptions& options, bool points, bool lines,
                    WorkerPool& pool, Frame& frame);

  const Kernels* kernels_ = nullptr;  // this frame's (the sample combine is integer logic: the
                                      // same bits for every instruction set)
  RayTable rays_;
  std::vector<ObjectTransforms> objects_;
  std::vector<VertexJob> vertex_jobs_;
  VertexBuffer vertices_;
  std::vector<TriangleChunk> chunks_;
  size_t chunk_count_ = 0;
  bool stream_ = false;  // this frame's colour written past the caches (streamsFrame)
  TileGrid grid_;
  std::vector<uint8_t> tile_empty_;
  std::vector<std::unique_ptr<TileVisibility>> tiles_;  // one per worker
  std::vector<std::unique_ptr<ShadedTile>> shaded_;     // one per worker
  std::vector<std::unique_ptr<SampleTiles>> sampled_;   // one per worker, made for MSAA
  LineList lines_;                                      // the axes
  PointPass points_;
  LightRig lights_;                // this frame's
  ShadowMaps* shadows_ = nullptr;  // this frame's (render's argument)
};

}  // namespace tessera::render
