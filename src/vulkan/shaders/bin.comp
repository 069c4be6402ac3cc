#version 460
// Pass 4, binning, run twice with the scan between: mode 0 counts the entries of every tile,
// mode 1 fills them at the offsets the scan computed. One invocation per visible record; a
// record enters each 16x16 tile of its bounding box unless one of its edges is negative at every
// sample point of the tile (an exact test, conservative: no covered sample is ever lost; with
// one sample the points are the pixel centres). Entries past the
// buffer's capacity are not written; the count tells the host, which grows the buffer and
// renders the frame again.
//
// TESSERA_RAY = 1 (the nonlinear projections): a record enters each tile of its one or two pixel
// boxes (conservative, from a cone around the triangle: ray_setup.comp).
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "common.glsl"
#include "records.glsl"

layout(local_size_x = 64) in;

// Counts (mode 0) or writes (mode 1) the entry of record `slot` in tile (tx, ty).
void binInto(uint slot, int tx, int ty) {
  const uint tile = uint(ty * frame.tile_columns + tx);
  if (pass.mode == 0u) {
    atomicAdd(tiles[tile].count, 1u);
  } else {
    const uint entry = tiles[tile].offset + atomicAdd(tiles[tile].cursor, 1u);
    if (entry < frame.bin_capacity) bin_entries[entry] = slot;
  }
}

#if TESSERA_RAY
void main() {
  const uint i = flatWorkgroupIndex() * 64u + gl_LocalInvocationIndex;
  if (i >= counters.visible) return;
  const uint slot = visible_list[i];
  for (int b = 0; b < 2; ++b) {
    const ivec4 box = ray_records[slot].box[b];
    if (box.x > box.z || box.y > box.w) continue;
    for (int ty = box.y >> kTileSizeLog2; ty <= box.w >> kTileSizeLog2; ++ty)
      for (int tx = box.x >> kTileSizeLog2; tx <= box.z >> kTileSizeLog2; ++tx)
        binInto(slot, tx, ty);
  }
  if (pass.mode == 0u) atomicAdd(counters.binned_records, 1u);
}
#else

// Largest value of edge k over the rectangle that holds every sample point of the pixels
// [x0, x1] x [y0, y1].
int64_t edgeMaximum(RasterRecord r, int k, int x0, int x1, int y0, int y1) {
  const int64_t x = r.a[k] >= 0 ? int64_t(x1) * kSubpixelOne + frame.sample_max_x
                                : int64_t(x0) * kSubpixelOne + frame.sample_min_x;
  const int64_t y = r.b[k] >= 0 ? int64_t(y1) * kSubpixelOne + frame.sample_max_y
                                : int64_t(y0) * kSubpixelOne + frame.sample_min_y;
  return int64_t(r.a[k]) * x + int64_t(r.b[k]) * y + r.c[k];
}

void main() {
  const uint i = flatWorkgroupIndex() * 64u + gl_LocalInvocationIndex;
  if (i >= counters.visible) return;
  const uint slot = visible_list[i];
  const RasterRecord r = raster_records[slot];
  const int tx0 = r.min_x >> kTileSizeLog2, tx1 = r.max_x >> kTileSizeLog2;
  const int ty0 = r.min_y >> kTileSizeLog2, ty1 = r.max_y >> kTileSizeLog2;
  bool binned = false;
  for (int ty = ty0; ty <= ty1; ++ty) {
    const int y0 = max(r.min_y, ty * kTileSize), y1 = min(r.max_y, ty * kTileSize + kTileSize - 1);
    for (int tx = tx0; tx <= tx1; ++tx) {
      const int x0 = max(r.min_x, tx * kTileSize);
      const int x1 = min(r.max_x, tx * kTileSize + kTileSize - 1);
      if (edgeMaximum(r, 0, x0, x1, y0, y1) < 0l || edgeMaximum(r, 1, x0, x1, y0, y1) < 0l ||
          edgeMaximum(r, 2, x0, x1, y0, y1) < 0l)
        continue;
      binned = true;
      binInto(slot, tx, ty);
    }
  }
  if (pass.mode == 0u && binned) atomicAdd(counters.binned_records, 1u);
}
#endif
