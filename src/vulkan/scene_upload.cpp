#include "vulkan/scene_upload.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <numbers>
#include <span>

#include <tessera/base/check.h>
#include <tessera/render/composite.h>
#include <tessera/scene/color.h>
#include <tessera/scene/texture.h>

#include "render/clip.h"
#include "render/fixed_point.h"
#include "render/lines.h"
#include "render/tone.h"
#include "render/vertex.h"
#include "vulkan/mesh_pack.h"

namespace tessera::vulkan {

namespace {

void storeMatrix(const float4x4& m, float out[16]) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out[c * 4 + r] = m.col[c][r];
}

// The zero-to-one projection for the raster backend: perspectiveZeroToOne for the usual camera;
// a custom or orthographic projection keeps its x, y and w and has z remapped from [-w, w] to
// [0, w].
float4x4 zeroToOneProjection(const Camera& camera, float aspect) {
  if (!camera.projection_override && !camera.orthographic)
    return perspectiveZeroToOne(radians(camera.fov_y_degrees), aspect, camera.near_z, camera.far_z);
  float4x4 remap;
  remap(2, 2) = 0.5f;
  remap(2, 3) = 0.5f;
  return remap * camera.projection(aspect);
}

bool drawsLines(const Scene& scene, const RenderOptions& options) {
  return options.lines && (!scene.lines.points.empty() || scene.show_world_axes ||
                           std::any_of(scene.objects.begin(), scene.objects.end(),
                                       [](const Object& o) { return o.show_axes; }));
}

// Whether the overlays test the frame's depth (and so need it, at the pixel centres).
bool drawsOverDepth(const Scene& scene, const RenderOptions& options) {
  return drawsLines(scene, options) || render::PointPass::wanted(scene);
}

// The compute backend's visibility layers: the pixel centre first when the frame's centre AOVs
// (depth, ids, normals, or the depth the lines test against) need it and the pattern does not
// sample it, then the samples in pattern order.
void fillSampling(const Scene& scene, const RenderOptions& options, GpuFrameConstants& f) {
  const std::span<const SamplePosition> pattern = samplePattern(options.msaa);
  const bool centre = pattern.size() > 1 && (options.depth || options.ids || options.normals ||
                                             drawsOverDepth(scene, options));
  f.samples = static_cast<uint32_t>(pattern.size());
  f.first_sample_layer = centre ? 1u : 0u;
  f.layers = f.samples + f.first_sample_layer;
  if (centre) f.layer_x[0] = f.layer_y[0] = render::kSubpixelHalf;
  for (size_t s = 0; s < pattern.size(); ++s) {
    f.layer_x[f.first_sample_layer + s] = pattern[s].x;
    f.layer_y[f.first_sample_layer + s] = pattern[s].y;
  }
  f.sample_min_x = f.sample_min_y = render::kSubpixelOne;
  f.sample_max_x = f.sample_max_y = 0;
  for (uint32_t l = 0; l < f.layers; ++l) {
    f.sample_min_x = std::min(f.sample_min_x, f.layer_x[l]);
    f.sample_max_x = std::max(f.sample_max_x, f.layer_x[l]);
    f.sample_min_y = std::min(f.sample_min_y, f.layer_y[l]);
    f.sample_max_y = std::max(f.sample_max_y, f.layer_y[l]);
  }
  // The background in linear light, as the resolve averages it: its sRGB code decoded.
  const float* decode = srgbDecodeTable();
  for (int k = 0; k < 3; ++k) f.background_linear[k] = decode[(f.background >> (8 * k)) & 255u];
  f.background_linear[3] = 1.0f;
}

bool levelIsWhole(int width, int height, const std::vector<uint32_t>& texels) {
  return width > 0 && height > 0 && texels.size() >= static_cast<size_t>(width) * height;
}

uint32_t wrapFlags(TextureWrap wrap, uint32_t clamp, uint32_t mirror) {
  if (wrap == TextureWrap::kClamp) return clamp;
  return wrap == TextureWrap::kMirroredRepeat ? mirror : 0u;
}

// Appends the texture (header, then every level) once per frame; returns its header's offset.
uint32_t textureOffset(const Texture& texture, PackedScene& out) {
  auto found = out.texture_offsets.find(&texture);
  if (found != out.texture_offsets.end()) return found->second;
  // Mip levels are used only when every one of them is whole.
  bool mips_whole = true;
  for (const TextureLevel& level : texture.mips)
    mips_whole = mips_whole && levelIsWhole(level.width, level.height, level.texels);
  const size_t levels = 1 + (mips_whole ? texture.mips.size() : 0);
  const uint32_t header = static_cast<uint32_t>(out.texels.size());
  out.texels.push_back(static_cast<uint32_t>(levels));
  out.texels.resize(out.texels.size() + 3 * levels);
  for (size_t i = 0; i < levels; ++i) {
    const int w = i == 0 ? texture.width : texture.mips[i - 1].width;
    const int h = i == 0 ? texture.height : texture.mips[i - 1].height;
    const std::vector<uint32_t>& texels = i == 0 ? texture.texels : texture.mips[i - 1].texels;
    out.texels[header + 1 + 3 * i] = static_cast<uint32_t>(out.texels.size());
    out.texels[header + 2 + 3 * i] = static_cast<uint32_t>(w);
    out.texels[header + 3 + 3 * i] = static_cast<uint32_t>(h);
    out.texels.insert(out.texels.end(), texels.begin(),
                      texels.begin() + static_cast<ptrdiff_t>(static_cast<size_t>(w) * h));
  }
  out.texture_offsets.emplace(&texture, header);
  return header;
}

// A texture slot's reference and sampler flags (the albedo's, and each PBR map's).
GpuTextureRef textureRef(const Texture& texture, const Sampler& sampler, PackedScene& out) {
  GpuTextureRef ref{0, 0, 0, kTexturePresent};
  if (levelIsWhole(texture.width, texture.height, texture.texels)) {
    ref.texel_offset = textureOffset(texture, out);
    ref.width = texture.width;
    ref.height = texture.height;
  }
  if (texture.srgb) ref.flags |= kTextureSrgb;
  if (sampler.filter == TextureFilter::kNearest) ref.flags |= kTextureNearest;
  if (sampler.filter == TextureFilter::kTrilinear && !texture.mips.empty())
    ref.flags |= kTextureTrilinear;
  ref.flags |= wrapFlags(sampler.wrap_s, kTextureClampS, kTextureMirrorS) |
               wrapFlags(sampler.wrap_t, kTextureClampT, kTextureMirrorT);
  if (sampler.texcoord == 1) ref.flags |= kTextureSet1;
  if (!sampler.transform.identity()) ref.flags |= kTextureTransformed;
  return ref;
}

// A sampler's KHR_texture_transform as two rows of UvAffine (each padded to four floats).
void packTransform(const Sampler& sampler, float rows[2][4]) {
  const UvAffine a = sampler.transform.affine();
  const float m[2][3] = {{a.m00, a.m01, a.m02}, {a.m10, a.m11, a.m12}};
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) rows[r][c] = m[r][c];
}

GpuMaterial packMaterial(const Material& material, PackedScene& out) {
  GpuMaterial m{};
  for (int c = 0; c < 4; ++c) m.base_color[c] = material.base_color[c];
  if (const Texture* texture = material.albedo.get()) {
    const GpuTextureRef ref = textureRef(*texture, material.sampler, out);
    m.texel_offset = ref.texel_offset;
    m.texture_width = ref.width;
    m.texture_height = ref.height;
    m.texture_flags = ref.flags;
    if (ref.flags & kTextureTransformed) packTransform(material.sampler, m.uv_transform);
  }
  if (material.alpha_mode == AlphaMode::kMask) {
    m.texture_flags |= kMaterialMask;
    m.uv_transform[0][3] = material.alpha_cutoff;
  }
  if (material.alpha_mode == AlphaMode::kBlend) m.texture_flags |= kMaterialBlend;
  // kPbr's factors and maps, each map with its own set and KHR_texture_transform.
  m.pbr[0] = material.metallic;
  m.pbr[1] = material.roughness;
  m.pbr[2] = material.normal_scale;
  m.pbr[3] = material.occlusion_strength;
  m.emissive[0] = material.emissive_factor.x;
  m.emissive[1] = material.emissive_factor.y;
  m.emissive[2] = material.emissive_factor.z;
  const TextureSlot* slots[kPbrMapCount] = {&material.metallic_roughness, &material.normal,
                                            &material.occlusion, &material.emissive};
  for (uint32_t i = 0; i < kPbrMapCount; ++i) {
    if (!slots[i]->texture) continue;
    m.maps[i] = textureRef(*slots[i]->texture, slots[i]->sampler, out);
    if (m.maps[i].flags & kTextureTransformed) packTransform(slots[i]->sampler, m.map_transform[i]);
  }
  return m;
}

uint32_t floatWord(float f) {
  uint32_t w;
  std::memcpy(&w, &f, sizeof w);
  return w;
}

// Appends the environment block (GpuEnvironmentBlock) when a kPbr object will take the scene's
// environment; returns 1 + its offset, or 0.
uint32_t appendEnvironment(const Scene& scene, PackedScene& out) {
  const Environment* environment = scene.environment.get();
  if (!environment || environment->empty() ||
      std::none_of(scene.objects.begin(), scene.objects.end(),
                   [](const Object& o) { return o.shading == Shading::kPbr; }))
    return 0;
  const size_t base = out.texels.size();
  out.texels.resize(base + kEnvironmentHeaderWords);
  uint32_t* header = out.texels.data() + base;
  for (int k = 0; k < 9; ++k)
    for (int c = 0; c < 3; ++c)
      header[kEnvironmentSh + 3 * k + c] = floatWord(environment->irradianceSh()[k][c]);
  for (int col = 0; col < 3; ++col)
    for (int r = 0; r < 3; ++r)
      header[kEnvironmentMatrix + 3 * col + r] = floatWord(scene.world_to_environment.col[col][r]);
  const float2* table = splitSumTable();
  for (int i = 0; i < kSplitSumTableSize * kSplitSumTableSize; ++i) {
    header[kEnvironmentSplitSum + 2 * i] = floatWord(table[i].x);
    header[kEnvironmentSplitSum + 2 * i + 1] = floatWord(table[i].y);
  }
  for (int level = 0; level < Environment::kSpecularLevels; ++level) {
    const EnvironmentImage& image = environment->specularLevel(level);
    const size_t h = base + kEnvironmentLevels + 3 * static_cast<size_t>(level);
    out.texels[h] = static_cast<uint32_t>(out.texels.size());
    out.texels[h + 1] = static_cast<uint32_t>(image.width);
    out.texels[h + 2] = static_cast<uint32_t>(image.height);
    for (const float3& texel : image.texels)
      out.texels.insert(out.texels.end(),
                        {floatWord(texel.x), floatWord(texel.y), floatWord(texel.z)});
  }
  return static_cast<uint32_t>(base) + 1;
}

// kPbr's viewer, as render::LightRig::prepare finds it: the camera's frame in world space is the
// inverse view matrix's last two columns; a projection whose w does not depend on z is parallel.
void fillViewer(const Scene& scene, GpuFrameConstants& f) {
  const float4x4 camera = inverse(scene.camera.view());
  const float3 eye = camera.col[3].xyz();
  const float3 toward_eye = normalize(camera.col[2].xyz());
  f.eye[0] = eye.x;
  f.eye[1] = eye.y;
  f.eye[2] = eye.z;
  f.eye[3] = scene.camera.projection(1.0f)(3, 3) != 0.0f ? 1.0f : 0.0f;
  f.toward_eye[0] = toward_eye.x;
  f.toward_eye[1] = toward_eye.y;
  f.toward_eye[2] = toward_eye.z;
}

// Empties every packed array, keeping its memory for the next frame.
void clearPackedArrays(PackedScene& out) {
  out.objects.clear();
  out.models.clear();
  out.materials.clear();
  out.vertices.clear();
  out.indices.clear();
  out.triangle_materials.clear();
  out.texels.clear();
  out.texture_offsets.clear();
  out.lights.clear();
}

// The object's matrices and where its vertices, triangles and materials start; records its model
// matrix. packMesh fills the mesh's counts and flags.
GpuObject packObject(const Object& object, const float4x4& view_projection_zo, size_t vertex_base,
                     size_t triangle_base, PackedScene& out) {
  const render::ObjectTransforms xf = render::makeObjectTransforms(object, out.view_projection);
  GpuObject gpu{};
  storeMatrix(xf.model_view_projection, gpu.model_view_projection);
  storeMatrix(view_projection_zo * xf.model, gpu.model_view_projection_zo);
  for (int c = 0; c < 3; ++c) {
    gpu.normal_matrix[c][0] = xf.normal_matrix.col[c].x;
    gpu.normal_matrix[c][1] = xf.normal_matrix.col[c].y;
    gpu.normal_matrix[c][2] = xf.normal_matrix.col[c].z;
  }
  gpu.winding_sign = xf.winding_sign;
  storeMatrix(xf.model, gpu.model);
  gpu.vertex_base = static_cast<uint32_t>(vertex_base);
  gpu.triangle_base = static_cast<uint32_t>(triangle_base);
  gpu.material_base = static_cast<uint32_t>(out.materials.size());
  gpu.material_count = static_cast<uint32_t>(object.materials.size());
  gpu.cull = static_cast<uint32_t>(object.cull);
  gpu.shading = static_cast<uint32_t>(object.shading);
  out.models.push_back(xf.model);
  return gpu;
}

// Packs every object, its materials and its mesh, one after another; an Error when the vertices
// pass what a 32-bit index reaches.
Expected<void> packObjects(const Scene& scene, IndexPolicy policy,
                           const float4x4& view_projection_zo, PackedScene& out) {
  size_t vertex_base = 0, triangle_base = 0;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& object = scene.objects[i];
    TESSERA_CHECK(!object.materials.empty()) << "object " << i << " has no material";
    GpuObject gpu = packObject(object, view_projection_zo, vertex_base, triangle_base, out);

    for (const Material& material : object.materials)
      out.materials.push_back(packMaterial(material, out));

    if (object.mesh) {
      packMesh(object, policy, gpu, out);
      vertex_base += object.mesh->vertexCount();
      triangle_base += object.mesh->triangleCount();
      if (vertex_base > 0xffffffffull)
        return makeError("the scene has more than 2^32 vertices; the Vulkan backends take fewer");
    }
    out.objects.push_back(gpu);
  }
  out.triangle_count = triangle_base;
  out.vertex_count = vertex_base;
  return {};
}

// The scene's lights as the CPU's shading takes them (render::shadeLight).
void packLights(const Scene& scene, PackedScene& out) {
  for (const Light& light : scene.lights) {
    const render::ShadeLight s = render::shadeLight(light);
    out.lights.push_back(
        GpuLight{{s.direction.x, s.direction.y, s.direction.z, static_cast<float>(s.type)},
                 {s.radiance.x, s.radiance.y, s.radiance.z, s.inv_range4},
                 {s.position.x, s.position.y, s.position.z, s.spot_scale},
                 {s.spot_offset, 0, 0, 0}});
  }
}

// The frame constants, after the objects and lights are packed: viewport and tiles, counts,
// background, ambient and tone, sampling, viewer, environment, and the nonlinear projections'
// rays when `rays`.
void fillFrameConstants(const Scene& scene, const RenderOptions& options, bool rays,
                        PackedScene& out) {
  GpuFrameConstants& f = out.frame;
  f = GpuFrameConstants{};
  f.width = options.width;
  f.height = options.height;
  f.tile_columns = (options.width + kGpuTileSize - 1) / kGpuTileSize;
  f.tile_rows = (options.height + kGpuTileSize - 1) / kGpuTileSize;
  const render::GuardBand guard = render::makeGuardBand(options.width, options.height);
  f.guard_x = guard.x_factor;
  f.guard_y = guard.y_factor;
  f.triangle_count = static_cast<uint32_t>(out.triangle_count);
  f.vertex_count = static_cast<uint32_t>(out.vertex_count);
  f.object_count = static_cast<uint32_t>(out.objects.size());
  f.light_count = static_cast<uint32_t>(out.lights.size());
  f.background = packSrgba8(scene.background);
  f.flags = (options.normals ? kFrameNormals : 0u) | (options.coverage ? kFrameCoverage : 0u);
  f.ambient[0] = scene.ambient.x;
  f.ambient[1] = scene.ambient.y;
  f.ambient[2] = scene.ambient.z;
  const render::ToneCurve tone = render::ToneCurve::of(scene);
  f.ambient[3] = tone.scale;
  f.flags |= static_cast<uint32_t>(tone.mapping) << kFrameToneShift;
  fillSampling(scene, options, f);
  fillViewer(scene, f);
  f.environment = appendEnvironment(scene, out);
  f.projection = static_cast<uint32_t>(options.projection);
  if (rays) {
    f.view_half_angle = radians(scene.camera.fov_y_degrees) * 0.5f;
    f.ray_near = scene.camera.near_z;
    f.ray_inv_range = 1.0f / (scene.camera.far_z - scene.camera.near_z);
  }
}

}  // namespace

Expected<void> packScene(const Scene& scene, const RenderOptions& options, IndexPolicy policy,
                         PackedScene& out) {
  const size_t triangle_total = scene.triangleCount();
  if (triangle_total > kMaxGpuTriangles)
    return makeError("the scene has " + std::to_string(triangle_total) +
                     " triangles; the Vulkan backends take at most " +
                     std::to_string(kMaxGpuTriangles) + " (29-bit triangle keys)");

  const float aspect = static_cast<float>(options.width) / static_cast<float>(options.height);
  // Jitter moves the geometry by -jitter pixels after the projection (sampling.h), so the sample
  // pattern, fixed on the pixel grid, moves by +jitter relative to the scene.
  const Jitter j = options.jitter;
  // The nonlinear projections' passes take camera-space positions (the view matrix in place of
  // view-projection, as the CPU's vertex stage in those modes) and carry the jitter in the rays.
  const bool rays = options.projection != Projection::kPerspective;
  out.view_projection =
      rays ? scene.camera.view()
           : jitteredProjection(scene.camera.projection(aspect), j, options.width, options.height) *
                 scene.camera.view();
  const float4x4 view_projection_zo = jitteredProjection(zeroToOneProjection(scene.camera, aspect),
                                                         j, options.width, options.height) *
                                      scene.camera.view();

  clearPackedArrays(out);
  if (Expected<void> r = packObjects(scene, policy, view_projection_zo, out); !r) return r;
  packLights(scene, out);
  fillFrameConstants(scene, options, rays, out);
  return {};
}

namespace {

template <typename T>
Expected<void> uploadArray(Context& context, Buffer& buffer, const T* data, size_t count,
                           VkBufferUsageFlags usage, const char* what) {
  const size_t bytes = count * sizeof(T);
  if (Expected<void> r = context.ensureBuffer(buffer, bytes, usage, MemoryKind::kHost, what); !r)
    return r;
  if (bytes) std::memcpy(buffer.mapped, data, bytes);
  return {};
}

}  // namespace

std::vector<uint32_t> makeColorTables() {
  std::vector<float> values(srgbDecodeTable(), srgbDecodeTable() + 256);
  values.insert(values.end(), SrgbEncode::kScale, SrgbEncode::kScale + 10);
  values.insert(values.end(), SrgbEncode::kPoly, SrgbEncode::kPoly + 5);
  values.push_back(SrgbEncode::kLinearEnd);
  values.push_back(SrgbEncode::kLinearFactor);
  values.push_back(SrgbEncode::kOffset);
  TESSERA_CHECK(values.size() == kColorConstantWords)
      << "shading.glsl's kFixedScale expects " << kColorConstantWords << " floats before it";
  values.push_back(FixedFilter::kScale);
  std::vector<uint32_t> words(values.size());
  std::memcpy(words.data(), values.data(), values.size() * sizeof(float));
  // The bilinear filter's 15-bit texel values (texelFixedTable): unorm, then sRGB.
  for (bool srgb : {false, true}) {
    const int32_t* table = texelFixedTable(srgb);
    words.insert(words.end(), table, table + 256);
  }
  return words;
}

Expected<void> uploadScene(Context& context, const PackedScene& packed, SceneBuffers& buffers) {
  constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  // The frame constants, then the lights (the shaders' FrameBuffer block).
  const size_t frame_bytes = sizeof(GpuFrameConstants) + packed.lights.size() * sizeof(GpuLight);
  if (Expected<void> r = context.ensureBuffer(buffers.frame, frame_bytes, kStorage,
                                              MemoryKind::kHost, "frame constants");
      !r)
    return r;
  std::memcpy(buffers.frame.mapped, &packed.frame, sizeof(GpuFrameConstants));
  if (!packed.lights.empty())
    std::memcpy(static_cast<char*>(buffers.frame.mapped) + sizeof(GpuFrameConstants),
                packed.lights.data(), packed.lights.size() * sizeof(GpuLight));

  Expected<void> r = uploadArray(context, buffers.objects, packed.objects.data(),
                                 packed.objects.size(), kStorage, "object");
  if (r)
    r = uploadArray(context, buffers.materials, packed.materials.data(), packed.materials.size(),
                    kStorage, "material");
  if (r)
    r = uploadArray(context, buffers.vertices, packed.vertices.data(), packed.vertices.size(),
                    kStorage | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "vertex");
  if (r)
    r = uploadArray(context, buffers.indices, packed.indices.data(), packed.indices.size(),
                    kStorage | VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "index");
  if (r)
    r = uploadArray(context, buffers.triangle_materials, packed.triangle_materials.data(),
                    packed.triangle_materials.size(), kStorage, "triangle material");
  if (r)
    r = uploadArray(context, buffers.texels, packed.texels.data(), packed.texels.size(), kStorage,
                    "texture");
  if (!r) return r;
  if (!buffers.color_tables_written) {
    const std::vector<uint32_t> tables = makeColorTables();
    if (Expected<void> t = uploadArray(context, buffers.color_tables, tables.data(), tables.size(),
                                       kStorage, "colour table");
        !t)
      return t;
    buffers.color_tables_written = true;
  }
  return {};
}

void destroySceneBuffers(Context& context, SceneBuffers& buffers) {
  for (Buffer* b :
       {&buffers.frame, &buffers.objects, &buffers.materials, &buffers.vertices, &buffers.indices,
        &buffers.triangle_materials, &buffers.texels, &buffers.color_tables})
    context.destroyBuffer(*b);
  buffers.color_tables_written = false;
}

void appendSceneDescriptors(const SceneBuffers& buffers,
                            std::vector<VkDescriptorBufferInfo>& infos) {
  for (const Buffer* b :
       {&buffers.frame, &buffers.objects, &buffers.materials, &buffers.vertices, &buffers.indices,
        &buffers.triangle_materials, &buffers.texels, &buffers.color_tables})
    infos.push_back(VkDescriptorBufferInfo{b->buffer, 0, VK_WHOLE_SIZE});
}

void resizeFrame(const Scene& scene, const RenderOptions& options, Frame& frame) {
  frame.resize(options.width, options.height, options.depth || drawsOverDepth(scene, options),
               options.ids, options.normals, options.coverage);
}

void copyResults(const uint32_t* color, const uint32_t* depth, const uint32_t* ids,
                 const float* normals, int normal_stride, Frame& frame) {
  const size_t n = frame.pixelCount();
  std::memcpy(frame.color.data(), color, n * sizeof(uint32_t));
  if (!frame.depth.empty()) std::memcpy(frame.depth.data(), depth, n * sizeof(float));
  if (!frame.triangle_id.empty()) std::memcpy(frame.triangle_id.data(), ids, n * sizeof(uint32_t));
  if (!frame.normal.empty() && normals)
    for (size_t p = 0; p < n; ++p) {
      const float* v = normals + p * static_cast<size_t>(normal_stride);
      frame.normal[p] = float3{v[0], v[1], v[2]};
    }
}

void clearFrame(Frame& frame) {
  std::fill(frame.color.begin(), frame.color.end(), 0u);
  std::fill(frame.depth.begin(), frame.depth.end(), std::numeric_limits<float>::infinity());
  std::fill(frame.triangle_id.begin(), frame.triangle_id.end(), kNoTriangle);
  std::fill(frame.normal.begin(), frame.normal.end(), float3{});
  std::fill(frame.coverage.begin(), frame.coverage.end(), uint8_t{0});
}

Expected<void> renderIntoFrame(const Scene& scene, const RenderOptions& options, Frame& frame,
                               const std::function<Expected<void>()>& draw) {
  TESSERA_CHECK(options.width > 0 && options.height > 0 && options.width <= render::kMaxViewport &&
                options.height <= render::kMaxViewport)
      << "viewport " << options.width << "x" << options.height << " is outside 1.."
      << render::kMaxViewport;
  TESSERA_CHECK(isSampleCount(options.msaa))
      << "msaa " << options.msaa << " is not a sample count (1, 2, 4 or 8)";
  resizeFrame(scene, options, frame);
  Expected<void> result = draw();
  if (!result) clearFrame(frame);
  return result;
}

void drawSceneOverlay(const Scene& scene, const RenderOptions& options, const PackedScene& packed,
                      SceneOverlay& overlay, Frame& frame) {
  const bool antialiased = options.msaa > 1;
  const bool perspective = options.projection == Projection::kPerspective;
  compositeFrame(scene, options, frame);
  // The nonlinear projections' points and lines: the CPU's, through the same mapping
  // (packed.view_projection is the view matrix then).
  const double fov = static_cast<double>(scene.camera.fov_y_degrees) * std::numbers::pi / 180.0;
  const render::RayLines mode{options.projection, fov, scene.camera.near_z, scene.camera.far_z};
  if (render::PointPass::wanted(scene)) {
    if (!overlay.pool) overlay.pool = std::make_unique<render::WorkerPool>(0);
    const render::PointCamera camera =
        perspective ? render::PointCamera::perspective(packed.view_projection, scene.camera.view())
                    : render::PointCamera{options.projection, {}, packed.view_projection, mode};
    overlay.points.draw(scene, options, camera, antialiased, *overlay.pool, frame);
  }
  if (!drawsLines(scene, options)) return;
  LineList& axes = overlay.axes;
  axes.points.clear();
  axes.colors.clear();
  if (scene.show_world_axes)
    render::appendAxes(axes, float4x4::identity(), scene.world_axes_length);
  for (size_t i = 0; i < scene.objects.size(); ++i)
    if (scene.objects[i].show_axes)
      render::appendAxes(axes, packed.models[i], scene.objects[i].axes_length);
  if (perspective) {
    render::drawLines(scene.lines, packed.view_projection, frame, antialiased,
                      render::LineStyle{options.line_width});
    render::drawLines(axes, packed.view_projection, frame, antialiased);
    return;
  }
  render::drawRayLines(scene.lines, packed.view_projection, mode, frame, antialiased,
                       options.line_width);
  render::drawRayLines(axes, packed.view_projection, mode, frame, antialiased);
}

}  // namespace tessera::vulkan
