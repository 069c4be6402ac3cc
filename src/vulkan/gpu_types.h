// The structures the host shares with the shaders, laid out as GLSL's std430 lays them out. Each
// mirrors a struct of shaders/common.glsl or shaders/records.glsl; the static_asserts hold the
// two in step.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tessera::vulkan {

// Descriptor bindings of set 0. Both backends use the scene inputs (0..7) at the same numbers.
enum Binding : uint32_t {
  kBindingFrame = 0,              // GpuFrameConstants, then the lights
  kBindingObjects = 1,            // GpuObject[]
  kBindingMaterials = 2,          // GpuMaterial[]
  kBindingVertices = 3,           // GpuVertex[] (object space, every object one after another)
  kBindingIndices = 4,            // uint[], three per triangle, object-local vertex numbers
  kBindingTriangleMaterials = 5,  // uint[], one per triangle
  kBindingTexels = 6,             // uint[] RGBA8 texels of every texture
  kBindingColorTables = 7,        // sRGB decode (256 floats) and encode (65536 bytes)
  kSceneBindingCount = 8,
  // Compute backend only.
  kBindingTransformed = 8,  // GpuTransformedVertex[]
  kBindingRasterRecords = 9,
  kBindingShadeRecords = 10,
  kBindingExtraBase = 11,  // uint per triangle: first extra record of a clipped triangle
  kBindingCounters = 12,
  kBindingVisibleList = 13,  // uint record slots that survived setup
  kBindingTiles = 14,        // GpuTileBin per tile
  kBindingBinEntries = 15,   // uint record slots, grouped by tile
  kBindingSegments = 16,     // uvec4 (tile, first entry, end entry, 0): fine-raster work items
  kBindingVisibility = 17,   // uint64 per pixel: ordered depth << 32 | triangle key
  kBindingOutput = 18,       // colour, depth, id, normal words
  kBindingRays = 19,         // float[]: the nonlinear projections' rays (RayTable), xyz per pixel
  kBindingDiagnostics = 20,  // uint[]: the diagnostics passes' counts (GpuDiagnosticsLayout)
  // Both backends (the raster one's set holds 0..7 and this): the shadow maps (shadow_upload.h).
  kBindingShadows = 21,
  kComputeBindingCount = 22,
};

// GpuFrameConstants::flags
constexpr uint32_t kFrameNormals = 1u;   // write the normal AOV
constexpr uint32_t kFrameCoverage = 2u;  // write the coverage AOV
constexpr uint32_t kFrameMaskPass = 4u;  // masked records go to the MASK pass, not the raster
// The tone curve (tessera::ToneMapping) in bits 8..9; ambient[3] holds 2^exposure.
constexpr uint32_t kFrameToneShift = 8u;

// Visibility layers per pixel (compute backend): the samples, and before them the pixel centre
// when the frame's AOVs need it and the pattern has more than one sample (none of the standard
// patterns of 2, 4 or 8 samples has one at the centre).
constexpr int kMaxVisibilityLayers = 9;

// GpuObject::flags
constexpr uint32_t kObjectHasUv = 1u;
constexpr uint32_t kObjectHasColor = 2u;
constexpr uint32_t kObjectHasNormals = 4u;
constexpr uint32_t kObjectHasTriangleMaterials = 8u;
// kPbr with a normal map, UVs, normals and tangents: the vertices' tangents apply (the CPU's
// SetupContext::tangents)
constexpr uint32_t kObjectHasTangents = 16u;

// GpuMaterial::texture_flags
constexpr uint32_t kTexturePresent = 1u;
constexpr uint32_t kTextureSrgb = 2u;
constexpr uint32_t kTextureNearest = 4u;
constexpr uint32_t kTextureClampS = 8u;
constexpr uint32_t kTextureTrilinear = 16u;  // and the texture has mip levels
constexpr uint32_t kTextureClampT = 32u;
constexpr uint32_t kTextureMirrorS = 64u;  // MIRRORED_REPEAT along s
constexpr uint32_t kTextureMirrorT = 128u;
constexpr uint32_t kTextureTransformed = 512u;  // uv_transform applies (Sampler::transform)
// alphaMode MASK: the raster backend discards where alpha < uv_transform[0][3] (the cutoff)
constexpr uint32_t kMaterialMask = 1024u;
// The texture is read through TEXCOORD_1 (Sampler::texcoord == 1): GpuVertex::uv1, the shading
// record's uv1.
constexpr uint32_t kTextureSet1 = 2048u;
// alphaMode BLEND: out of the compute backend's opaque passes (setup leaves it out of the visible
// list), drawn by the transparent pass (blend_pass.glsl).
constexpr uint32_t kMaterialBlend = 4096u;

// A texture in the texel buffer: a header (level count, then offset, width and height of each
// level, offsets in words from the start of the buffer), then the levels' texels.

// Tiles and the fine raster.
constexpr int kGpuTileSizeLog2 = 4;
constexpr int kGpuTileSize = 1 << kGpuTileSizeLog2;  // 16x16 pixels: one workgroup, one lane each
// A tile's list is cut into work items of at most this many entries; the items of one tile run
// in parallel and commit with atomic min.
constexpr uint32_t kEntriesPerSegment = 512;
// Triangle keys: scene triangle index << 3 | fan piece (a clipped triangle gives at most 7).
constexpr int kFanPieceBits = 3;
constexpr uint64_t kMaxGpuTriangles = (1ull << (32 - kFanPieceBits)) - 1;

struct GpuFrameConstants {
  int32_t width, height, tile_columns, tile_rows;
  float guard_x, guard_y;
  uint32_t triangle_count, vertex_count;
  uint32_t object_count, light_count, extra_capacity, bin_capacity;
  uint32_t background, flags, segment_capacity;
  uint32_t projection;  // tessera::Projection; anything but 0 takes the ray passes
  float ambient[4];
  // Sampling (compute backend): samples per pixel, visibility layers per pixel, the first
  // layer that is a sample (1 when layer 0 is the pixel centre), the bounds of the layers'
  // positions and each layer's position, in 1/256 pixel from the pixel's top-left corner.
  uint32_t samples, layers, first_sample_layer;
  float view_half_angle;  // the ray passes: half the vertical view angle, radians
  int32_t sample_min_x, sample_min_y, sample_max_x, sample_max_y;
  float background_linear[4];
  int32_t layer_x[kMaxVisibilityLayers], layer_y[kMaxVisibilityLayers];
  // The ray passes' depth: z = (distance - ray_near) * ray_inv_range (render/ray_setup.h).
  float ray_near, ray_inv_range;
  // The viewer, for kPbr (render::LightRig): xyz the camera's position, w 1 for a parallel
  // projection, whose unit direction towards the camera is toward_eye.
  float eye[4];
  float toward_eye[4];
  // kPbr's image-based light: 1 + the word offset of the environment block in the texel buffer
  // (GpuEnvironmentBlock), 0 when the scene has none.
  uint32_t environment;
  uint32_t pad[3];
};
static_assert(sizeof(GpuFrameConstants) == 256);

// The environment block (Scene::environment, for kPbr; shaders/environment.glsl), in the texel
// buffer as float bits: the irradiance's nine SH coefficients (RGB each), world_to_environment
// (three columns), per level of the specular chain its texels' offset, width and height, the
// split-sum table (kSplitSumTableSize^2 pairs), then each level's texels (RGB floats).
enum GpuEnvironmentBlock : uint32_t {
  kEnvironmentSh = 0,
  kEnvironmentMatrix = 27,
  kEnvironmentLevels = 36,  // 3 words a level, Environment::kSpecularLevels of them
  kEnvironmentSplitSum = 54,
  kEnvironmentHeaderWords = 54 + 2 * 32 * 32,
};

// The CPU's render::ShadeLight (src/render/lights.h).
struct GpuLight {
  float direction[4];  // xyz: the way the light travels; w: tessera::LightType
  float color[4];      // xyz: radiance (colour x intensity); w: 1 / range^4 (0: no range)
  float position[4];   // xyz: point and spot; w: the spot's scale
  float spot[4];       // x: the spot's offset
};
static_assert(sizeof(GpuLight) == 64);

struct GpuObject {
  float model_view_projection[16];     // column-major, OpenGL clip space (compute backend)
  float model_view_projection_zo[16];  // zero-to-one clip space (raster backend)
  float normal_matrix[3][4];           // columns
  uint32_t vertex_base, vertex_count, triangle_base, triangle_count;
  uint32_t material_base, material_count, flags, pad0;
  float winding_sign;
  uint32_t cull, shading, pad1;
  float model[16];  // column-major: world positions for point and spot lights
};
static_assert(sizeof(GpuObject) == 288);

// A texture of a material's slot: where its header is, its level 0 size (0 when it has no whole
// texels: it samples as white) and its sampler's kTexture* flags.
struct GpuTextureRef {
  uint32_t texel_offset;
  int32_t width, height;
  uint32_t flags;
};
static_assert(sizeof(GpuTextureRef) == 16);

// The material's PBR maps (GpuMaterial::maps), in this order.
enum GpuPbrMap : uint32_t {
  kMapMetallicRoughness = 0,
  kMapNormal = 1,
  kMapOcclusion = 2,
  kMapEmissive = 3,
  kPbrMapCount = 4,
};

struct GpuMaterial {
  float base_color[4];
  uint32_t texel_offset;  // the texture's header
  int32_t texture_width, texture_height;
  uint32_t texture_flags;
  float uv_transform[2][4];  // rows of UvAffine (m00 m01 m02, m10 m11 m12), each padded
  float pbr[4];              // metallic, roughness, normal_scale, occlusion_strength
  float emissive[4];         // xyz: emissive_factor
  GpuTextureRef maps[kPbrMapCount];
  // Each map's KHR_texture_transform (its flags say kTextureTransformed): rows of UvAffine.
  float map_transform[kPbrMapCount][2][4];
};
static_assert(sizeof(GpuMaterial) == 288);

struct GpuVertex {
  float position[3];
  float normal[3];
  float uv[2];
  float color[4];
  float tangent[4];  // object space, w the bitangent's sign (kObjectHasTangents; else zero)
  float uv1[2];      // TEXCOORD_1 (Mesh::uvs1), TEXCOORD_0 where the mesh has none
};
static_assert(sizeof(GpuVertex) == 72);

// The transform pass's output per vertex (the CPU's VertexBuffer entry).
struct GpuTransformedVertex {
  float clip[4];
  float normal[3];
  uint32_t outcode;
  int32_t screen[2];  // snapped window position in 1/256 pixel
  float z, inv_w;
};
static_assert(sizeof(GpuTransformedVertex) == 48);

// Setup's output for coverage and depth (the CPU's RasterTriangle).
struct GpuRasterRecord {
  int64_t c[3];
  int32_t a[3], b[3];
  int32_t min_x, min_y, max_x, max_y;
  float x0, y0, z0, dzdx, dzdy;
  uint32_t key;
};
static_assert(sizeof(GpuRasterRecord) == 88);

// The ray passes' setup output for coverage and depth (the CPU's render::RayTriangle): edge
// normals n_k (a ray d covers the triangle when every d . n_k > 0, or == 0 with owner bit k), the
// determinant, up to two inclusive pixel boxes (the second empty unless the triangle crosses the
// seam of a 360-degree image). Lives in the raster record buffer, whose slots are larger.
struct GpuRayRecord {
  float n[9];  // n[3 k + i]: component i of n_k
  float det;
  uint32_t key;       // scene triangle index << 3
  uint32_t owner;     // bit k: rays exactly on edge k are covered
  int32_t box[2][4];  // min_x, min_y, max_x, max_y
};
static_assert(sizeof(GpuRayRecord) == 80 && sizeof(GpuRayRecord) <= sizeof(GpuRasterRecord));

// Setup's output for shading (the CPU's ShadeTriangle).
struct GpuShadeRecord {
  // The corners' world positions (Phong with point and spot lights) ride in the spare floats:
  // normal[k][3], color[k][3] and world_z[k].
  float normal[3][4];  // xyz
  float color[3][4];   // xyz: base x vertex colour, lit for flat and Gouraud
  float uv[3][2];
  float uv1[3][2];  // TEXCOORD_1 (GpuVertex::uv1)
  float inv_w0, p1dx, p1dy, p2dx, p2dy, sdx, sdy;
  uint32_t triangle_id;
  uint32_t material;  // index into the material buffer
  uint32_t shading;   // Shading | kShadeHasUv
  float world_z[3];
  uint32_t pad[3];  // std430 aligns the tangents to 16 bytes
  // kPbr with tangents: the corners' world tangents (w the bitangent's sign), facing the viewer
  // as the normals do (the CPU's ShadeExtras::tangent).
  float tangent[3][4];
};
constexpr uint32_t kShadeHasUv = 1u << 8;
// kPbr: the mesh has UVs (the material's maps apply) and tangents (so does its normal map); the
// CPU's kPbrUv and kPbrTangents.
constexpr uint32_t kShadePbrUv = 1u << 9;
constexpr uint32_t kShadePbrTangents = 1u << 10;
static_assert(sizeof(GpuShadeRecord) == 256);

struct GpuCounters {
  uint32_t visible;  // records in the visible list
  uint32_t extra;    // extra records the clipped triangles asked for
  uint32_t culled, clipped;
  uint32_t bin_entries;  // asked for; more than the capacity means overflow
  uint32_t segments;
  uint32_t max_tile_entries, occupied_tiles;
  uint32_t binned_records;
  uint32_t pad[3];
  uint32_t bin_dispatch[4];     // VkDispatchIndirectCommand + pad
  uint32_t raster_dispatch[4];  // VkDispatchIndirectCommand + pad
};
static_assert(sizeof(GpuCounters) == 80);
constexpr size_t kBinDispatchOffset = offsetof(GpuCounters, bin_dispatch);
constexpr size_t kRasterDispatchOffset = offsetof(GpuCounters, raster_dispatch);

struct GpuTileBin {
  uint32_t count, offset, cursor, segment_offset;
};
static_assert(sizeof(GpuTileBin) == 16);

// The diagnostics buffer (RenderOptions::diagnostics; shaders/diagnostics.glsl), in 32-bit words:
// the cull reasons and clip splits setup's diagnostics variant counts, then per pixel the depth
// tests at its centre (the overdraw), per 16x16 tile the tests and the passes, and per tile of
// the CPU's grid (kDiagnosticsTileSize) the records binned into it (the occupancy).
enum GpuDiagnosticsWord : uint32_t {
  kDiagInvalid = 0,
  kDiagNonFinite,
  kDiagFrustum,
  kDiagDegenerate,
  kDiagFacing,
  kDiagNoPixel,
  kDiagClippedAway,
  kDiagClipSplits,
  kDiagHeaderWords = 16,
};
// The occupancy's tiles: the CPU's (render::kTileSize), so that the two backends' per-tile
// arrays describe the same tiles; shaders/diagnostics.glsl has the same constant.
constexpr int kDiagnosticsTileSizeLog2 = 6;

struct GpuDiagnosticsLayout {
  size_t overdraw = 0, tile_tested = 0, tile_passed = 0, occupancy = 0, words = 0;

  static GpuDiagnosticsLayout of(int width, int height) {
    const size_t pixels = static_cast<size_t>(width) * height;
    const size_t gpu_tiles = static_cast<size_t>((width + kGpuTileSize - 1) / kGpuTileSize) *
                             ((height + kGpuTileSize - 1) / kGpuTileSize);
    constexpr int kCpuTile = 1 << kDiagnosticsTileSizeLog2;
    const size_t cpu_tiles = static_cast<size_t>((width + kCpuTile - 1) / kCpuTile) *
                             ((height + kCpuTile - 1) / kCpuTile);
    GpuDiagnosticsLayout l;
    l.overdraw = kDiagHeaderWords;
    l.tile_tested = l.overdraw + pixels;
    l.tile_passed = l.tile_tested + gpu_tiles;
    l.occupancy = l.tile_passed + gpu_tiles;
    l.words = l.occupancy + cpu_tiles;
    return l;
  }
};

// Push constants of every compute pass.
struct GpuPassConstants {
  uint32_t mode, count, pad0, pad1;
};

}  // namespace tessera::vulkan
