#version 460
// Diagnostics pass (RenderOptions::diagnostics, perspective frames), after shading: the depth
// tests a plain depth-buffered rasterizer makes at pixel centres, as the CPU's countTileTests
// (src/render/diagnostics.cpp) counts them. One workgroup per 16x16 tile, one invocation per
// pixel, walking the tile's whole bin list (binning is conservative: every record that covers a
// centre of the tile is in it).
//
// A test is a record covering the pixel centre (the edge functions in 64 bits, the top-left
// rule folded into c); it passes when its depth there is below every depth stored before it in
// submission order, i.e. below the depth of every covering record with a smaller key (the keys
// order records as the CPU submits them). The bins are in no particular order, so each pixel
// keeps its first kHeld tests (key and depth) and compares them pairwise; a pixel with more
// tests than that walks the list again once per test, taking them in key order.
//
// Writes the overdraw (tests per pixel) and each tile's tests and passes.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "common.glsl"
#include "records.glsl"
#include "diagnostics.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

const uint kHeld = 32u;
const uint kNoKey = 0xffffffffu;

// Whether record r covers the centre of pixel (x, y), and its window depth there (computed as
// the CPU's depthAt: the row's depth, then across).
bool coversCentre(RasterRecord r, int x, int y, out float z) {
  if (x < r.min_x || x > r.max_x || y < r.min_y || y > r.max_y) return false;
  const int64_t px = int64_t(x) * kSubpixelOne + kSubpixelHalf;
  const int64_t py = int64_t(y) * kSubpixelOne + kSubpixelHalf;
  for (int k = 0; k < 3; ++k)
    if (int64_t(r.a[k]) * px + int64_t(r.b[k]) * py + r.c[k] < 0l) return false;
  precise float z_row = r.z0 + r.dzdy * (float(y) + 0.5 - r.y0);
  precise float z_pixel = z_row + r.dzdx * ((float(x) + 0.5) - r.x0);
  z = z_pixel;
  return true;
}

// The passes of a pixel with more than kHeld tests: the tests in key order, each walk of the
// list finding the next key.
uint passesInKeyOrder(uint first, uint end, int x, int y, uint tests) {
  uint passes = 0u, last_key = 0u;
  float stored = uintBitsToFloat(0x7f800000u);  // +inf, the cleared depth
  for (uint step = 0u; step < tests; ++step) {
    uint next_key = kNoKey;
    float next_z = 0.0;
    for (uint e = first; e < end; ++e) {
      const RasterRecord r = raster_records[bin_entries[e]];
      if ((step > 0u && r.key <= last_key) || r.key >= next_key) continue;
      float z;
      if (!coversCentre(r, x, y, z)) continue;
      next_key = r.key;
      next_z = z;
    }
    if (next_z < stored) {
      stored = next_z;
      ++passes;
    }
    last_key = next_key;
  }
  return passes;
}

void main() {
  const uint tile = flatWorkgroupIndex();
  const uint tile_count = uint(frame.tile_columns) * uint(frame.tile_rows);
  if (tile >= tile_count) return;  // uniform over the workgroup
  const uint first = tiles[tile].offset, end = first + tiles[tile].count;
  if (end > frame.bin_capacity) return;  // an overflowing round: rendered again, not read
  const int x = int(tile % uint(frame.tile_columns)) * kTileSize + int(gl_LocalInvocationID.x);
  const int y = int(tile / uint(frame.tile_columns)) * kTileSize + int(gl_LocalInvocationID.y);
  if (x >= frame.width || y >= frame.height) return;

  uint held_key[kHeld];
  float held_z[kHeld];
  uint tests = 0u;
  for (uint e = first; e < end; ++e) {
    const RasterRecord r = raster_records[bin_entries[e]];
    float z;
    if (!coversCentre(r, x, y, z)) continue;
    if (tests < kHeld) {
      held_key[tests] = r.key;
      held_z[tests] = z;
    }
    ++tests;
  }
  uint passes = 0u;
  if (tests <= kHeld) {
    // Test i passes when z_i < stored, stored being the smallest earlier depth (+inf at first;
    // a NaN is never stored): no earlier test has a depth <= z_i.
    for (uint i = 0u; i < tests; ++i) {
      bool passed = held_z[i] < uintBitsToFloat(0x7f800000u);
      for (uint j = 0u; j < tests && passed; ++j)
        if (held_key[j] < held_key[i] && held_z[j] <= held_z[i]) passed = false;
      if (passed) ++passes;
    }
  } else {
    passes = passesInKeyOrder(first, end, x, y, tests);
  }
  diagnostics_words[diagOverdrawOffset() + uint(y) * uint(frame.width) + uint(x)] = tests;
  if (tests > 0u) atomicAdd(diagnostics_words[diagTileTestedOffset() + tile], tests);
  if (passes > 0u) atomicAdd(diagnostics_words[diagTilePassedOffset() + tile], passes);
}
