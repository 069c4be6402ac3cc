#version 460
// Pass 5, fine raster: one workgroup per segment of a tile's list (a tile with few triangles is
// one segment), one invocation per pixel of the 16x16 tile. The segment's records are staged in
// shared memory kBatch at a time; each invocation evaluates the three edge functions at each of
// its pixel's visibility layers (the sample points, and the pixel centre when the frame's AOVs
// need it: gpu_types.h) exactly (the 64-bit edge test of src/render/raster.cpp, reduced per tile
// and layer to an equivalent 32-bit one) and the depth plane at the point in float as the CPU
// does, and keeps the smallest (ordered depth, triangle key) pair of each layer in registers.
// Then one commit per layer into the visibility buffer (pixel-major: entry pixel * layers +
// layer), by atomic min, since several segments of one tile may run at once.
//
// Specialization constants: kLayers, the layers per pixel (frame.layers), and kBatch, the records
// staged at a time (smaller when more layers would not fit the device's shared memory).
//
// TESSERA_RAY = 1 (the nonlinear projections): the test per point is the ray's plane test
// (rays.glsl) with the distance depth instead of the edge functions and the depth plane; staging,
// buckets and commits are the same.
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
#if TESSERA_RAY
#include "screen.glsl"
#endif

layout(local_size_x = 16, local_size_y = 16) in;

#if TESSERA_RASTER_MODE == 0
layout(std430, set = 0, binding = 17) buffer VisibilityBuffer { uint64_t visibility[]; };
#else
layout(std430, set = 0, binding = 17) buffer VisibilityBuffer { uint visibility_words[]; };
#endif

layout(constant_id = 0) const uint kLayers = 1u;
layout(constant_id = 1) const uint kBatch = 64u;
#if TESSERA_RAY
// Per staged record: the edge normals, the determinant, the owner bits, the key.
shared vec3 s_n0[kBatch], s_n1[kBatch], s_n2[kBatch];
shared float s_det[kBatch];
shared uint s_owner[kBatch], s_key[kBatch];
#else
// Per staged record: the edge coefficients and, per layer and edge, the threshold that turns the
// 64-bit test into a 32-bit one (below; layer l of record j at l * kBatch + j); the depth plane;
// the key.
shared ivec3 s_a[kBatch], s_b[kBatch], s_threshold[kLayers * kBatch];
shared float s_x0[kBatch], s_y0[kBatch], s_z0[kBatch], s_dzdx[kBatch], s_dzdy[kBatch];
shared uint s_key[kBatch];
#endif

// The batch's records sorted into half-rows of the tile (16 rows x 2 halves of 8 pixels): each
// pixel walks only the records whose bounding box touches its half-row. On a GPU the lanes of a
// subgroup share a few lists; on a CPU driver (lavapipe runs 8 lanes at a time, one half-row)
// every lane of a SIMD step walks the same list.
const uint kBuckets = 32u;
shared uint s_bucket_count[kBuckets];
shared uint s_bucket[kBuckets][kBatch];

#if TESSERA_RAY
// Whether box a (inclusive; empty when min > max) meets box b.
bool boxesMeet(ivec4 a, ivec4 b) {
  return a.x <= a.z && a.y <= a.w && max(a.x, b.x) <= min(a.z, b.z) &&
         max(a.y, b.y) <= min(a.w, b.w);
}

// Adds staged record `lane` to the buckets of the half-rows that one of its pixel boxes (relative
// to the tile; empty when min > max) touches: each once.
void addToBuckets(uint lane, ivec4 box0, ivec4 box1) {
  for (int row = 0; row < kTileSize; ++row) {
    for (int column = 0; column < 2; ++column) {
      const ivec4 half_row = ivec4(column * 8, row, column * 8 + 7, row);
      if (!boxesMeet(box0, half_row) && !boxesMeet(box1, half_row)) continue;
      const uint bucket = uint(row * 2 + column);
      s_bucket[bucket][atomicAdd(s_bucket_count[bucket], 1u)] = lane;
    }
  }
}

// Stages ray record r in slot `lane` of the batch and adds it to the buckets of its boxes.
void stageRecord(uint lane, RayRecord r, int tile_x, int tile_y) {
  s_n0[lane] = rayNormal(r, 0);
  s_n1[lane] = rayNormal(r, 1);
  s_n2[lane] = rayNormal(r, 2);
  s_det[lane] = r.det;
  s_owner[lane] = r.owner;
  s_key[lane] = r.key;
  const ivec4 origin = ivec4(tile_x, tile_y, tile_x, tile_y);
  addToBuckets(lane, r.box[0] - origin, r.box[1] - origin);
}

// Whether ray d covers staged record j within the depth range, and its ordered depth there:
// z = (t - near) * inv_range with t = det / S, the distance along the unit ray (ray_setup.h).
bool pointDepth(uint j, vec3 d, out uint depth) {
  const float e0 = dotRay(d, s_n0[j]), e1 = dotRay(d, s_n1[j]), e2 = dotRay(d, s_n2[j]);
  const uint owner = s_owner[j];
  if (!edgeCovers(e0, owner, 0) || !edgeCovers(e1, owner, 1) || !edgeCovers(e2, owner, 2))
    return false;
  precise float s = (e0 + e1) + e2;
  if (!(s > 0.0)) return false;
  const float t = divideRounded(s_det[j], s);
  precise float z = (t - frame.ray_near) * frame.ray_inv_range;
  if (!(z >= 0.0 && z <= 1.0)) return false;
  depth = orderedDepth(z);
  return true;
}
#else
// Edge k at a layer's point of pixel (tile_x + lx, tile_y + ly) is e = origin + 256 * (a lx +
// b ly), with origin its (64-bit) value at that layer's point of the tile's first pixel. Since |a|, |b| < 2^24 and
// lx, ly < 16, d = a lx + b ly is below 2^29 in magnitude: an exact int32. And e >= 0 exactly
// when d >= ceil(-origin / 256) = -(origin >> 8) (arithmetic shift: floor). Clamping that
// threshold to +-2^30 keeps every outcome (d never reaches it) and makes it an int32 too.
int edgeThreshold(int64_t origin) {
  const int64_t threshold = -(origin >> 8);
  return int(clamp(threshold, -(1l << 30), 1l << 30));
}

// Stages record r in slot `lane` of the batch: coefficients, each layer's thresholds, depth
// plane and key, and adds it to the buckets of the half-rows its bounding box touches.
void stageRecord(uint lane, RasterRecord r, int tile_x, int tile_y) {
  const ivec3 a = ivec3(r.a[0], r.a[1], r.a[2]), b = ivec3(r.b[0], r.b[1], r.b[2]);
  s_a[lane] = a;
  s_b[lane] = b;
  for (uint l = 0u; l < kLayers; ++l) {
    const int64_t origin_x = int64_t(tile_x) * kSubpixelOne + frame.layer_x[l];
    const int64_t origin_y = int64_t(tile_y) * kSubpixelOne + frame.layer_y[l];
    s_threshold[l * kBatch + lane] =
        ivec3(edgeThreshold(int64_t(a.x) * origin_x + int64_t(b.x) * origin_y + r.c[0]),
              edgeThreshold(int64_t(a.y) * origin_x + int64_t(b.y) * origin_y + r.c[1]),
              edgeThreshold(int64_t(a.z) * origin_x + int64_t(b.z) * origin_y + r.c[2]));
  }
  s_x0[lane] = r.x0;
  s_y0[lane] = r.y0;
  s_z0[lane] = r.z0;
  s_dzdx[lane] = r.dzdx;
  s_dzdy[lane] = r.dzdy;
  s_key[lane] = r.key;
  // Covered points lie inside the bounding box (setup's pixel range), so a half-row outside it
  // has nothing to find.
  const int row0 = max(r.min_y - tile_y, 0), row1 = min(r.max_y - tile_y, kTileSize - 1);
  const int column0 = max(r.min_x - tile_x, 0) >> 3;
  const int column1 = min(r.max_x - tile_x, kTileSize - 1) >> 3;
  for (int row = row0; row <= row1; ++row) {
    for (int column = column0; column <= column1; ++column) {
      const uint bucket = uint(row * 2 + column);
      s_bucket[bucket][atomicAdd(s_bucket_count[bucket], 1u)] = lane;
    }
  }
}

// Whether layer l's point (px, py) of the pixel passes staged record j's edge tests (d: the
// record's a lx + b ly), and the ordered depth of its plane there.
bool pointDepth(uint j, ivec3 d, uint l, float px, float py, out uint depth) {
  if (any(lessThan(d, s_threshold[l * kBatch + j]))) return false;
  // Window z at the layer's point, as the CPU at a pixel centre: z0 + dzdy * dy, then
  // + dzdx * dx.
  precise float dy = py - s_y0[j];
  precise float z_row = s_z0[j] + s_dzdy[j] * dy;
  precise float dx = px - s_x0[j];
  precise float z = z_row + s_dzdx[j] * dx;
  if (!(z < uintBitsToFloat(0x7f800000u))) return false;  // NaN or +inf never pass z < stored
  depth = orderedDepth(z);
  return true;
}
#endif

void main() {
  const uint segment_index = flatWorkgroupIndex();
  if (segment_index >= counters.segments) return;  // uniform over the workgroup
  const uvec4 segment = segments[segment_index];
  const uint tile = segment.x;
  const int tile_x = int(tile % uint(frame.tile_columns)) * kTileSize;
  const int tile_y = int(tile / uint(frame.tile_columns)) * kTileSize;
  const int lx = int(gl_LocalInvocationID.x), ly = int(gl_LocalInvocationID.y);
  const int x = tile_x + lx, y = tile_y + ly;
  const bool inside = x < frame.width && y < frame.height;
  const uint pixel = uint(y) * uint(frame.width) + uint(x);
#if TESSERA_RAY
  // Each layer's ray.
  vec3 ray[kMaxVisibilityLayers];
  for (uint l = 0u; l < kLayers; ++l) ray[l] = inside ? rayAt(rayLayerOf(l), pixel) : vec3(0.0);
#else
  // Each layer's point in window coordinates (exact: a multiple of 1/256 below 2^15).
  float point_x[kMaxVisibilityLayers], point_y[kMaxVisibilityLayers];
  for (uint l = 0u; l < kLayers; ++l) {
    point_x[l] = float(x) + float(frame.layer_x[l]) * (1.0 / 256.0);
    point_y[l] = float(y) + float(frame.layer_y[l]) * (1.0 / 256.0);
  }
#endif

#if TESSERA_RASTER_MODE == 0
  uint best_depth[kMaxVisibilityLayers], best_key[kMaxVisibilityLayers];
  for (uint l = 0u; l < kLayers; ++l) best_depth[l] = best_key[l] = kEmptyWord;
#elif TESSERA_RASTER_MODE == 1
  uint best_depth[kMaxVisibilityLayers];
  for (uint l = 0u; l < kLayers; ++l) best_depth[l] = kEmptyWord;
#else
  uint target_depth[kMaxVisibilityLayers], best_key[kMaxVisibilityLayers];
  for (uint l = 0u; l < kLayers; ++l) {
    target_depth[l] = inside ? visibility_words[2u * (pixel * kLayers + l) + 1u] : kEmptyWord;
    best_key[l] = kEmptyWord;
  }
#endif

  for (uint first = segment.y; first < segment.z; first += kBatch) {
    const uint n = min(kBatch, segment.z - first);
    barrier();  // every lane is done with the previous batch before it is overwritten
    const uint lane = gl_LocalInvocationIndex;
    if (lane < kBuckets) s_bucket_count[lane] = 0u;
    barrier();  // the buckets are empty before any record is added to them
#if TESSERA_RAY
    if (lane < n) stageRecord(lane, ray_records[bin_entries[first + lane]], tile_x, tile_y);
#else
    if (lane < n) stageRecord(lane, raster_records[bin_entries[first + lane]], tile_x, tile_y);
#endif
    barrier();  // the batch is staged and sorted before any lane reads it
    if (!inside) continue;
    const uint bucket = uint(ly * 2 + (lx >> 3));
    const uint count = s_bucket_count[bucket];
    for (uint i = 0u; i < count; ++i) {
      const uint j = s_bucket[bucket][i];
#if !TESSERA_RAY
      const ivec3 d = s_a[j] * lx + s_b[j] * ly;
#endif
      for (uint l = 0u; l < kLayers; ++l) {
        uint depth;
#if TESSERA_RAY
        if (!pointDepth(j, ray[l], depth)) continue;
#else
        if (!pointDepth(j, d, l, point_x[l], point_y[l], depth)) continue;
#endif
#if TESSERA_RASTER_MODE == 0
        if (depth < best_depth[l] || (depth == best_depth[l] && s_key[j] < best_key[l])) {
          best_depth[l] = depth;
          best_key[l] = s_key[j];
        }
#elif TESSERA_RASTER_MODE == 1
        best_depth[l] = min(best_depth[l], depth);
#else
        if (depth == target_depth[l]) best_key[l] = min(best_key[l], s_key[j]);
#endif
      }
    }
  }

  if (!inside) return;
  for (uint l = 0u; l < kLayers; ++l) {
    const uint entry = pixel * kLayers + l;
#if TESSERA_RASTER_MODE == 0
    if (best_depth[l] != kEmptyWord)
      atomicMin(visibility[entry], (uint64_t(best_depth[l]) << 32) | uint64_t(best_key[l]));
#elif TESSERA_RASTER_MODE == 1
    if (best_depth[l] != kEmptyWord) atomicMin(visibility_words[2u * entry + 1u], best_depth[l]);
#else
    if (best_key[l] != kEmptyWord) atomicMin(visibility_words[2u * entry], best_key[l]);
#endif
  }
}
