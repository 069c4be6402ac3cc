#version 460
// Pass 5, fine raster: one workgroup per segment of a tile's list (a tile with few triangles is
// one segment), one invocation per pixel of the 16x16 tile. The segment's records are staged in
// shared memory 128 at a time; each invocation evaluates the three edge functions at its pixel
// centre in 64-bit integers and the depth plane in float, exactly as src/render/raster.cpp, and
// keeps the smallest (ordered depth << 32 | triangle key) in a register. Then one commit per
// pixel into the visibility buffer, by atomic min, since several segments of one tile may run at
// once.
//
// TESSERA_RASTER_MODE 0: 64-bit atomicMin of the whole key (shaderBufferInt64Atomics).
// Without 64-bit atomics the same result takes two passes over the segments, each with 32-bit
// atomics: mode 1 commits the smallest ordered depth (the high word), then mode 2 commits the
// smallest triangle key among the triangles whose depth equals the committed one (the low
// word). Exact for depth and for ties; what it gives up is time: every segment is rasterized
// twice.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#if TESSERA_RASTER_MODE == 0
#extension GL_EXT_shader_atomic_int64 : require
#endif
#include "common.glsl"
#include "records.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

#if TESSERA_RASTER_MODE == 0
layout(std430, set = 0, binding = 17) buffer VisibilityBuffer { uint64_t visibility[]; };
#else
layout(std430, set = 0, binding = 17) buffer VisibilityBuffer { uint visibility_words[]; };
#endif

const uint kBatch = 128u;
shared int64_t s_c0[kBatch], s_c1[kBatch], s_c2[kBatch];
shared int s_a0[kBatch], s_a1[kBatch], s_a2[kBatch];
shared int s_b0[kBatch], s_b1[kBatch], s_b2[kBatch];
shared float s_x0[kBatch], s_y0[kBatch], s_z0[kBatch], s_dzdx[kBatch], s_dzdy[kBatch];
shared uint s_key[kBatch];

void main() {
  const uint segment_index = flatWorkgroupIndex();
  if (segment_index >= counters.segments) return;  // uniform over the workgroup
  const uvec4 segment = segments[segment_index];
  const uint tile = segment.x;
  const int x = int(tile % uint(frame.tile_columns)) * kTileSize + int(gl_LocalInvocationID.x);
  const int y = int(tile / uint(frame.tile_columns)) * kTileSize + int(gl_LocalInvocationID.y);
  const bool inside = x < frame.width && y < frame.height;
  const uint pixel = uint(y) * uint(frame.width) + uint(x);
  const int64_t px = int64_t(x) * kSubpixelOne + kSubpixelHalf;
  const int64_t py = int64_t(y) * kSubpixelOne + kSubpixelHalf;
  precise float centre_x = float(x) + 0.5;
  precise float centre_y = float(y) + 0.5;

#if TESSERA_RASTER_MODE == 0
  uint64_t best = ~0ul;
#elif TESSERA_RASTER_MODE == 1
  uint best_depth = kEmptyWord;
#else
  const uint target_depth = inside ? visibility_words[2u * pixel + 1u] : kEmptyWord;
  uint best_key = kEmptyWord;
#endif

  for (uint first = segment.y; first < segment.z; first += kBatch) {
    const uint n = min(kBatch, segment.z - first);
    barrier();  // every lane is done with the previous batch before it is overwritten
    const uint lane = gl_LocalInvocationIndex;
    if (lane < n) {
      const RasterRecord r = raster_records[bin_entries[first + lane]];
      s_c0[lane] = r.c[0];
      s_c1[lane] = r.c[1];
      s_c2[lane] = r.c[2];
      s_a0[lane] = r.a[0];
      s_a1[lane] = r.a[1];
      s_a2[lane] = r.a[2];
      s_b0[lane] = r.b[0];
      s_b1[lane] = r.b[1];
      s_b2[lane] = r.b[2];
      s_x0[lane] = r.x0;
      s_y0[lane] = r.y0;
      s_z0[lane] = r.z0;
      s_dzdx[lane] = r.dzdx;
      s_dzdy[lane] = r.dzdy;
      s_key[lane] = r.key;
    }
    barrier();  // the batch is staged before any lane reads it
    if (!inside) continue;
    for (uint j = 0u; j < n; ++j) {
      const int64_t e0 = int64_t(s_a0[j]) * px + int64_t(s_b0[j]) * py + s_c0[j];
      const int64_t e1 = int64_t(s_a1[j]) * px + int64_t(s_b1[j]) * py + s_c1[j];
      const int64_t e2 = int64_t(s_a2[j]) * px + int64_t(s_b2[j]) * py + s_c2[j];
      if ((e0 | e1 | e2) < 0l) continue;
      // Window z at the pixel centre, as the CPU: z0 + dzdy * dy, then + dzdx * dx.
      precise float dy = centre_y - s_y0[j];
      precise float z_row = s_z0[j] + s_dzdy[j] * dy;
      precise float dx = centre_x - s_x0[j];
      precise float z = z_row + s_dzdx[j] * dx;
      if (!(z < uintBitsToFloat(0x7f800000u))) continue;  // NaN or +inf never pass z < stored
      const uint depth = orderedDepth(z);
#if TESSERA_RASTER_MODE == 0
      best = min(best, (uint64_t(depth) << 32) | uint64_t(s_key[j]));
#elif TESSERA_RASTER_MODE == 1
      best_depth = min(best_depth, depth);
#else
      if (depth == target_depth) best_key = min(best_key, s_key[j]);
#endif
    }
  }

  if (!inside) return;
#if TESSERA_RASTER_MODE == 0
  if (best != ~0ul) atomicMin(visibility[pixel], best);
#elif TESSERA_RASTER_MODE == 1
  if (best_depth != kEmptyWord) atomicMin(visibility_words[2u * pixel + 1u], best_depth);
#else
  if (best_key != kEmptyWord) atomicMin(visibility_words[2u * pixel], best_key);
#endif
}
