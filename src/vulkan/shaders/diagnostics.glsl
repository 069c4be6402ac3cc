// The diagnostics buffer (binding 20, RenderOptions::diagnostics), as GpuDiagnosticsLayout in
// src/vulkan/gpu_types.h lays it out: only the diagnostics passes and setup's diagnostics variant
// include this file, so a frame without diagnostics runs shaders without it. Needs common.glsl.

layout(std430, set = 0, binding = 20) buffer DiagnosticsBuffer { uint diagnostics_words[]; };

// GpuDiagnosticsWord
const uint kDiagInvalid = 0u;
const uint kDiagNonFinite = 1u;
const uint kDiagFrustum = 2u;
const uint kDiagDegenerate = 3u;
const uint kDiagFacing = 4u;
const uint kDiagNoPixel = 5u;
const uint kDiagClippedAway = 6u;
const uint kDiagClipSplits = 7u;
const uint kDiagHeaderWords = 16u;
// The occupancy's tiles: the CPU's 64x64 (render::kTileSize; gpu_types.h asserts it).
const int kDiagTileSizeLog2 = 6;

uint diagOverdrawOffset() { return kDiagHeaderWords; }
uint diagTileTestedOffset() { return diagOverdrawOffset() + uint(frame.width) * uint(frame.height); }
uint diagTilePassedOffset() {
  return diagTileTestedOffset() + uint(frame.tile_columns) * uint(frame.tile_rows);
}
uint diagOccupancyOffset() {
  return diagTilePassedOffset() + uint(frame.tile_columns) * uint(frame.tile_rows);
}
uint diagTileColumns() { return uint((frame.width + (1 << kDiagTileSizeLog2) - 1) >> kDiagTileSizeLog2); }
