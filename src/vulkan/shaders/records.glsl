// The compute backend's working buffers (bindings 8..16 and 18), as src/vulkan/gpu_types.h.
// Needs GL_EXT_shader_explicit_arithmetic_types_int64. TESSERA_RAY = 1 (the ray passes of the
// nonlinear projections): binding 9 holds RayRecords instead of RasterRecords (rays.glsl).

// The transform pass's output (the CPU's VertexBuffer).
struct TransformedVertex {
  vec4 clip;
  vec3 normal;   // world space, unit (zero when the mesh has none)
  uint outcode;  // clip planes the vertex is outside of, or kNonFinite (screen.glsl)
  ivec2 screen;  // snapped window position, valid only without a cut-plane bit in outcode
  float z;       // window depth
  float inv_w;   // 1 / clip w
};

// The CPU's RasterTriangle: edge k covers pixel centre (px, py) (1/256 pixel) when
// a[k] * px + b[k] * py + c[k] >= 0, the top-left rule folded into c.
struct RasterRecord {
  int64_t c[3];
  int a[3];
  int b[3];
  int min_x, min_y, max_x, max_y;
  float x0, y0, z0, dzdx, dzdy;
  uint key;  // scene triangle index << 3 | fan piece
};

// The CPU's ShadeTriangle.
struct ShadeRecord {
  // xyz: world shading normals, facing the viewer for drawn back faces; w: the corners' world x
  vec4 normal[3];
  vec4 color[3];  // xyz: base colour x vertex colour, already lit for flat and Gouraud; w: world y
  vec2 uv[3];
  vec2 uv1[3];  // TEXCOORD_1 (the vertices' uv1)
  float inv_w0, p1dx, p1dy, p2dx, p2dy, sdx, sdy;
  uint triangle_id;
  uint material;  // index into the material buffer
  uint shading;   // Shading | kShadeHasUv
  float world_z[3];  // the corners' world z (world positions: Phong with point and spot lights)
  vec4 tangent[3];   // kPbr with kShadePbrTangents: world tangents, w the bitangent's sign
};

struct Counters {
  uint visible;
  uint extra;
  uint culled, clipped;
  uint bin_entries;
  uint segments;
  uint max_tile_entries, occupied_tiles;
  uint binned_records;
  uint pad[3];
  uint bin_dispatch[4];
  uint raster_dispatch[4];
};

struct TileBin {
  uint count, offset, cursor, segment_offset;
};

layout(std430, set = 0, binding = 8) buffer TransformedBuffer { TransformedVertex transformed[]; };
#if TESSERA_RAY
#include "rays.glsl"
#else
layout(std430, set = 0, binding = 9) buffer RasterRecordBuffer { RasterRecord raster_records[]; };
#endif
layout(std430, set = 0, binding = 10) buffer ShadeRecordBuffer { ShadeRecord shade_records[]; };
layout(std430, set = 0, binding = 11) buffer ExtraBaseBuffer { uint extra_base[]; };
layout(std430, set = 0, binding = 12) buffer CounterBuffer { Counters counters; };
layout(std430, set = 0, binding = 13) buffer VisibleListBuffer { uint visible_list[]; };
layout(std430, set = 0, binding = 14) buffer TileBuffer { TileBin tiles[]; };
layout(std430, set = 0, binding = 15) buffer BinEntryBuffer { uint bin_entries[]; };
layout(std430, set = 0, binding = 16) buffer SegmentBuffer { uvec4 segments[]; };
layout(std430, set = 0, binding = 18) buffer OutputBuffer { uint output_words[]; };

layout(push_constant) uniform PassConstants {
  uint mode;
  uint count;
  uint pad0, pad1;
} pass;

// The workgroup index of a grid split by dispatchGrid() (x at most 32768).
uint flatWorkgroupIndex() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

const int kTileSizeLog2 = 4;
const int kTileSize = 16;
const uint kEntriesPerSegment = 512u;
const int kSubpixelBits = 8;
const int kSubpixelOne = 256;
const int kSubpixelHalf = 128;
const uint kEmptyWord = 0xffffffffu;

// Float depth to a uint whose order is the float order (negative values included); -0 counts as
// +0, as it does for the CPU's z < stored.
uint orderedDepth(float z) {
  uint bits = floatBitsToUint(z);
  if (bits == 0x80000000u) bits = 0u;
  return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}
float depthFromOrdered(uint ordered) {
  return uintBitsToFloat((ordered & 0x80000000u) != 0u ? ordered & 0x7fffffffu : ~ordered);
}
