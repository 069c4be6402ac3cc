// The CPU pipeline: vertex -> clip -> setup -> bin -> raster -> shade -> resolve.
// A CpuRenderer owns every per-frame buffer and its worker threads; after the first frame at a
// resolution it allocates nothing (unless the scene grows). The image is bit-identical for any
// worker count.
#pragma once

#include <memory>

#include <tessera/render/backend.h>

namespace tessera {

struct PipelineStats {
  size_t triangles_in = 0;
  size_t triangles_culled = 0;   // back/front-face culled, degenerate, non-finite or off-screen
  size_t triangles_clipped = 0;  // triangles that crossed near/far or left the guard band
  size_t triangles_setup = 0;    // setup records (after clipping)
  // Culled before the vertex stage (RenderOptions::frustum_cull): whole instances outside the
  // frustum, clusters outside it, clusters wholly facing away, and the triangles they hold.
  size_t instances_culled = 0;
  size_t clusters_culled = 0;
  size_t clusters_facing = 0;
  size_t triangles_skipped = 0;
  // Wall-clock milliseconds of each stage of the last frame (all workers together).
  double vertex_ms = 0;  // vertex stage (scenes transformed once per worker: the longest copy)
  double setup_ms = 0;   // assembly, cull, clip, setup and binning
  double tiles_ms = 0;   // raster, shade and resolve
  double lines_ms = 0;   // the point pass and the line pass
};

// The instruction set of the raster kernel. Every choice gives the same image; kAuto takes the
// best the CPU runs. A choice the CPU cannot run falls back to kAuto's.
enum class SimdLevel { kAuto, kScalar, kSse2, kAvx2, kAvx512 };

class CpuRenderer final : public Backend {
 public:
  // workers: 0 = one per hardware thread, 1 = run on the calling thread only.
  explicit CpuRenderer(int workers = 0, SimdLevel simd = SimdLevel::kAuto);
  ~CpuRenderer() override;
  CpuRenderer(const CpuRenderer&) = delete;
  CpuRenderer& operator=(const CpuRenderer&) = delete;

  const char* name() const override { return "cpu"; }
  void render(const Scene& scene, const RenderOptions& options, Frame& frame) override;

  int workerCount() const;
  const char* simdName() const;  // the raster kernel in use: scalar, sse2, avx2 or avx512
  const PipelineStats& lastStats() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace tessera
