// The Vulkan backends' frame diagnostics (RenderOptions::diagnostics). The measures that derive
// from the frame's ids and depths (material, density, tile coverage, depth range and edges) come
// from the CPU's own code (render/diagnostics.h) run on the read-back frame; the compute
// backend's counts from its diagnostics passes on the GPU (the cull reasons, the depth tests at
// pixel centres, the 64x64 tiles' occupancy); the raster backend has no setup or bins of its
// own to count (docs/stats.md).
#pragma once

#include <cstdint>
#include <vector>

#include <tessera/render/diagnostics.h>
#include <tessera/render/frame.h>
#include <tessera/scene/scene.h>

#include "vulkan/gpu_types.h"

namespace tessera::vulkan {

struct ComputeDiagnosticsInput {
  const uint32_t* words = nullptr;  // the diagnostics buffer (GpuDiagnosticsLayout)
  const GpuCounters* counters = nullptr;
  int gpu_tile_columns = 0, gpu_tile_rows = 0;
  bool pixel_tests = false;  // the diagnostics passes ran (perspective frames)
  uint64_t triangles_in = 0;
  uint64_t bin_overflow = 0;  // bin entries that did not fit, over the rounds rendered again
  StageTimes times;           // diagnostics_ms: the GPU's diagnostics passes only
};

// Fills frame.diagnostics; adds the time this takes on the host to times.diagnostics_ms.
// `triangle_bases`: scratch kept by the caller.
void fillComputeDiagnostics(const Scene& scene, const ComputeDiagnosticsInput& input,
                            std::vector<size_t>& triangle_bases, Frame& frame);

// The raster backend's: the measures from the frame, the triangles in, the times (its one
// render pass in tiles_ms); the setup and pixel-test counters are marked not measured.
void fillRasterDiagnostics(const Scene& scene, uint64_t triangles_in, const StageTimes& times,
                           std::vector<size_t>& triangle_bases, Frame& frame);

}  // namespace tessera::vulkan
