#version 460
// Pass 4, between count and fill: an exclusive prefix sum of the tiles' entry counts (each tile's
// first entry in the bin buffer) and of their work items (a tile's list is cut into segments of
// at most kEntriesPerSegment entries; each segment is one fine-raster workgroup), then the
// segments themselves and the fine raster's indirect dispatch size. One workgroup walks the
// tiles 1024 at a time, carrying the running totals.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "common.glsl"
#include "records.glsl"

layout(local_size_x = 256) in;

const uint kPerInvocation = 4u;
const uint kChunk = 256u * kPerInvocation;

shared uint s_entries[256];
shared uint s_segments[256];
shared uint s_max_entries;
shared uint s_occupied;

void main() {
  const uint lane = gl_LocalInvocationIndex;
  const uint tile_count = uint(frame.tile_columns) * uint(frame.tile_rows);
  if (lane == 0u) {
    s_max_entries = 0u;
    s_occupied = 0u;
  }
  barrier();  // the shared totals are zero before any lane adds to them
  uint entry_base = 0u, segment_base = 0u;  // the same in every lane
  for (uint chunk = 0u; chunk < tile_count; chunk += kChunk) {
    uint counts[kPerInvocation];
    uint my_entries = 0u, my_segments = 0u, my_max = 0u, my_occupied = 0u;
    for (uint j = 0u; j < kPerInvocation; ++j) {
      const uint tile = chunk + lane * kPerInvocation + j;
      counts[j] = tile < tile_count ? tiles[tile].count : 0u;
      my_entries += counts[j];
      my_segments += (counts[j] + kEntriesPerSegment - 1u) / kEntriesPerSegment;
      my_max = max(my_max, counts[j]);
      my_occupied += counts[j] > 0u ? 1u : 0u;
    }
    atomicMax(s_max_entries, my_max);
    atomicAdd(s_occupied, my_occupied);
    s_entries[lane] = my_entries;
    s_segments[lane] = my_segments;
    barrier();
    // Inclusive Hillis-Steele scan over the 256 lanes.
    for (uint step = 1u; step < 256u; step *= 2u) {
      const uint add_entries = lane >= step ? s_entries[lane - step] : 0u;
      const uint add_segments = lane >= step ? s_segments[lane - step] : 0u;
      barrier();
      s_entries[lane] += add_entries;
      s_segments[lane] += add_segments;
      barrier();
    }
    uint entry = entry_base + s_entries[lane] - my_entries;
    uint segment = segment_base + s_segments[lane] - my_segments;
    for (uint j = 0u; j < kPerInvocation; ++j) {
      const uint tile = chunk + lane * kPerInvocation + j;
      if (tile >= tile_count) break;
      tiles[tile].offset = entry;
      tiles[tile].segment_offset = segment;
      for (uint first = 0u; first < counts[j]; first += kEntriesPerSegment) {
        if (segment < frame.segment_capacity)
          segments[segment] = uvec4(tile, entry + first,
                                    entry + min(first + kEntriesPerSegment, counts[j]), 0u);
        ++segment;
      }
      entry += counts[j];
    }
    entry_base += s_entries[255];
    segment_base += s_segments[255];
    barrier();  // every lane has read s_*[255] before the next chunk overwrites them
  }
  if (lane == 0u) {
    counters.bin_entries = entry_base;
    counters.max_tile_entries = s_max_entries;
    counters.occupied_tiles = s_occupied;
    // An overflowing frame is rendered again: skip its fine raster.
    const bool overflow = entry_base > frame.bin_capacity || segment_base > frame.segment_capacity;
    const uint groups = overflow ? 0u : segment_base;
    counters.segments = groups;
    const uint x = min(groups, 32768u);
    counters.raster_dispatch[0] = x;
    counters.raster_dispatch[1] = x == 0u ? 1u : (groups + x - 1u) / x;
    counters.raster_dispatch[2] = 1u;
  }
}
