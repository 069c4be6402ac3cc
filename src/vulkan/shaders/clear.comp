#version 460
// Pass 1, clear: the visibility buffer (every layer of every pixel) to "empty" (all ones:
// farther than any depth), every tile's bin counters to zero, and the frame's counters to zero.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "common.glsl"
#include "records.glsl"

layout(local_size_x = 256) in;

layout(std430, set = 0, binding = 17) buffer VisibilityBuffer { uint visibility_words[]; };

void main() {
  const uint i = flatWorkgroupIndex() * 256u + gl_LocalInvocationIndex;
  const uint entries = uint(frame.width) * uint(frame.height) * frame.layers;
  const uint tiles_count = uint(frame.tile_columns) * uint(frame.tile_rows);
  if (i < entries) {
    visibility_words[2u * i] = kEmptyWord;
    visibility_words[2u * i + 1u] = kEmptyWord;
  }
  if (i < tiles_count) tiles[i] = TileBin(0u, 0u, 0u, 0u);
  if (i == 0u) {
    counters.visible = 0u;
    counters.extra = 0u;
    counters.culled = 0u;
    counters.clipped = 0u;
    counters.bin_entries = 0u;
    counters.segments = 0u;
    counters.max_tile_entries = 0u;
    counters.occupied_tiles = 0u;
    counters.binned_records = 0u;
    counters.bin_dispatch = uint[4](0u, 1u, 1u, 0u);
    counters.raster_dispatch = uint[4](0u, 1u, 1u, 0u);
  }
}
