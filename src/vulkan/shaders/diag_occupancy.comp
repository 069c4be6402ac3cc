#version 460
// Diagnostics pass (RenderOptions::diagnostics, perspective frames), after shading: the occupancy
// of the CPU's 64x64 tiles. One invocation per visible record (the bin passes' indirect
// dispatch); a record counts in every 64x64 tile its bounding box touches, as the CPU bins
// (render/bin.h, ChunkBins::add), so both backends give the same numbers for the same records.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "common.glsl"
#include "records.glsl"
#include "diagnostics.glsl"

layout(local_size_x = 64) in;

void main() {
  const uint i = flatWorkgroupIndex() * 64u + gl_LocalInvocationIndex;
  if (i >= counters.visible) return;
  const RasterRecord r = raster_records[visible_list[i]];
  const uint columns = diagTileColumns();
  const uint base = diagOccupancyOffset();
  for (int ty = r.min_y >> kDiagTileSizeLog2; ty <= r.max_y >> kDiagTileSizeLog2; ++ty)
    for (int tx = r.min_x >> kDiagTileSizeLog2; tx <= r.max_x >> kDiagTileSizeLog2; ++tx)
      atomicAdd(diagnostics_words[base + uint(ty) * columns + uint(tx)], 1u);
}
