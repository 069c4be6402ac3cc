// Declarations shared by every shader: the scene inputs (bindings 0..7), laid out as
// src/vulkan/gpu_types.h lays them out (std430). No 64-bit types here: the raster backend's
// shaders include this file too and must run without shaderInt64.

// TESSERA_RAY = 1: the compute backend's ray passes (the nonlinear projections; rays.glsl).
#ifndef TESSERA_RAY
#define TESSERA_RAY 0
#endif

const uint kFrameNormals = 1u;
const uint kFrameCoverage = 2u;
const uint kFrameMaskPass = 4u;  // masked records go to the MASK pass (mask_pass.glsl)
const uint kFrameToneShift = 8u;  // the tone curve's bits; frame.ambient.w: 2^exposure
const int kMaxVisibilityLayers = 9;
const uint kObjectHasUv = 1u;
const uint kObjectHasColor = 2u;
const uint kObjectHasNormals = 4u;
const uint kObjectHasTriangleMaterials = 8u;
const uint kObjectHasTangents = 16u;
const uint kTexturePresent = 1u;
const uint kTextureSrgb = 2u;
const uint kTextureNearest = 4u;
const uint kTextureClampS = 8u;
const uint kTextureTrilinear = 16u;
const uint kTextureClampT = 32u;
const uint kTextureMirrorS = 64u;
const uint kTextureMirrorT = 128u;
const uint kTextureTransformed = 512u;
const uint kMaterialMask = 1024u;  // alphaMode MASK, cutoff in uv_transform[0].w
const uint kTextureSet1 = 2048u;   // read through TEXCOORD_1
const uint kMaterialBlend = 4096u;  // alphaMode BLEND: the transparent pass draws it
const uint kShadeHasUv = 256u;
const uint kShadePbrUv = 512u;
const uint kShadePbrTangents = 1024u;

// tessera::Shading and tessera::CullMode.
const uint kShadingFlat = 0u;
const uint kShadingGouraud = 1u;
const uint kShadingPhong = 2u;
const uint kShadingUnlit = 3u;
const uint kShadingPbr = 4u;
const uint kCullBack = 0u;
const uint kCullFront = 1u;
const uint kCullNone = 2u;

struct FrameConstants {
  int width, height, tile_columns, tile_rows;
  float guard_x, guard_y;
  uint triangle_count, vertex_count;
  uint object_count, light_count, extra_capacity, bin_capacity;
  uint background, flags, segment_capacity;
  uint projection;  // tessera::Projection
  vec4 ambient;
  uint samples, layers, first_sample_layer;
  float view_half_angle;  // radians
  int sample_min_x, sample_min_y, sample_max_x, sample_max_y;
  vec4 background_linear;
  int layer_x[kMaxVisibilityLayers];
  int layer_y[kMaxVisibilityLayers];
  float ray_near, ray_inv_range;  // the ray passes' depth: (distance - near) * inv_range
  vec4 eye;         // kPbr's viewer: the camera's position; w = 1: a parallel projection
  vec4 toward_eye;  // xyz: the unit direction towards the camera of a parallel projection
  uint environment;  // 1 + the environment block's offset in the texels; 0: none
  uint environment_pad0, environment_pad1, environment_pad2;
};

// gpu_types.h's GpuLight (the CPU's render::ShadeLight).
struct Light {
  vec4 direction;  // travelling from the light into the scene; w: tessera::LightType
  vec4 color;      // radiance; w: 1 / range^4
  vec4 position;   // w: the spot's scale
  vec4 spot;       // x: the spot's offset
};

struct GpuObject {
  mat4 model_view_projection;
  mat4 model_view_projection_zo;
  vec4 normal_matrix[3];
  uint vertex_base, vertex_count, triangle_base, triangle_count;
  uint material_base, material_count, flags, pad0;
  float winding_sign;
  uint cull, shading, pad1;
  mat4 model;
};

// A material slot's texture (gpu_types.h: GpuTextureRef).
struct TextureRef {
  uint texel_offset;  // the texture's header: level count, then offset, width, height per level
  int width, height;  // level 0; 0: no texels, samples as white
  uint flags;         // kTexture*
};

// GpuMaterial::maps
const int kMapMetallicRoughness = 0;
const int kMapNormal = 1;
const int kMapOcclusion = 2;
const int kMapEmissive = 3;

struct GpuMaterial {
  vec4 base_color;
  uint texel_offset;  // the albedo texture's header
  int texture_width, texture_height;
  uint texture_flags;
  vec4 uv_transform[2];  // rows of the sampler's UvAffine (xyz)
  vec4 pbr;              // metallic, roughness, normal_scale, occlusion_strength
  vec4 emissive;         // xyz: emissive_factor
  TextureRef maps[4];    // metallic-roughness, normal, occlusion, emissive
  vec4 map_transform[8];  // map i's KHR_texture_transform: rows 2 i and 2 i + 1 (xyz)
};

struct GpuVertex {
  float position[3];
  float normal[3];
  float uv[2];
  float color[4];
  float tangent[4];  // object space; w: the bitangent's sign
  float uv1[2];      // TEXCOORD_1, or TEXCOORD_0 where the mesh has none
};

layout(std430, set = 0, binding = 0) readonly buffer FrameBuffer {
  FrameConstants frame;
  Light lights[];
};
layout(std430, set = 0, binding = 1) readonly buffer ObjectBuffer { GpuObject objects[]; };
layout(std430, set = 0, binding = 2) readonly buffer MaterialBuffer { GpuMaterial materials[]; };
layout(std430, set = 0, binding = 3) readonly buffer VertexBuffer { GpuVertex vertices[]; };
layout(std430, set = 0, binding = 4) readonly buffer IndexBuffer { uint indices[]; };
layout(std430, set = 0, binding = 5) readonly buffer TriangleMaterialBuffer {
  uint triangle_materials[];
};
layout(std430, set = 0, binding = 6) readonly buffer TexelBuffer { uint texels[]; };
layout(std430, set = 0, binding = 7) readonly buffer ColorTableBuffer {
  // Float bits: [0, 256) the decode table; then the encode's constants (tessera::SrgbEncode; see
  // encodeSrgb8 in shading.glsl) and FixedFilter::kScale; then the bilinear filter's 15-bit texel
  // values as integers, unorm and sRGB (texelFixedTable; see sampleLevel in shading.glsl).
  uint color_tables[];
};

vec3 vertexPosition(uint v) {
  return vec3(vertices[v].position[0], vertices[v].position[1], vertices[v].position[2]);
}
vec3 vertexNormal(uint v) {
  return vec3(vertices[v].normal[0], vertices[v].normal[1], vertices[v].normal[2]);
}
vec4 vertexTangent(uint v) {
  return vec4(vertices[v].tangent[0], vertices[v].tangent[1], vertices[v].tangent[2],
              vertices[v].tangent[3]);
}
vec2 vertexUv(uint v) { return vec2(vertices[v].uv[0], vertices[v].uv[1]); }
vec2 vertexUv1(uint v) { return vec2(vertices[v].uv1[0], vertices[v].uv1[1]); }
vec4 vertexColor(uint v) {
  return vec4(vertices[v].color[0], vertices[v].color[1], vertices[v].color[2],
              vertices[v].color[3]);
}

// The CPU's normalize(): a * (1 / length), zero for a zero vector.
vec3 normalizeAsCpu(vec3 a) {
  precise float len = sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
  precise vec3 result = len > 0.0 ? a * (1.0 / len) : vec3(0.0);
  return result;
}

// M * v for a 3x3 matrix given as columns, summed in the CPU's order.
vec3 multiply3x3(vec4 columns[3], vec3 v) {
  precise vec3 result = columns[0].xyz * v.x + columns[1].xyz * v.y + columns[2].xyz * v.z;
  return result;
}
