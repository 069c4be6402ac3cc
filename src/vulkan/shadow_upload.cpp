#include "vulkan/shadow_upload.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "vulkan/gpu_types.h"

namespace tessera::vulkan {

namespace {

uint32_t floatWord(float f) {
  uint32_t w;
  std::memcpy(&w, &f, sizeof w);
  return w;
}

void storeFloat3(float3 v, uint32_t* out) {
  out[0] = floatWord(v.x);
  out[1] = floatWord(v.y);
  out[2] = floatWord(v.z);
}

void packView(const render::ShadowView& view, uint32_t depth_word, uint32_t* out) {
  out[0] = view.perspective ? 1u : 0u;
  storeFloat3(view.origin, out + 1);
  storeFloat3(view.right, out + 4);
  storeFloat3(view.up, out + 7);
  storeFloat3(view.forward, out + 10);
  const float params[8] = {view.cx,  view.cy,     view.scale,       view.z_a,
                           view.z_b, view.near_d, view.texel_world, view.reach};
  for (int i = 0; i < 8; ++i) out[13 + i] = floatWord(params[i]);
  out[21] = static_cast<uint32_t>(view.size);
  out[22] = depth_word;
  out[23] = 0;
}

// The block's size in words (GpuShadowBlock) for `lights` table entries and the maps' views.
size_t blockWords(size_t lights, const render::ShadowMaps& maps) {
  size_t words = kShadowHeaderWords + 2 * lights + size_t{kShadowViewWords} * maps.viewCount();
  for (int v = 0; v < maps.viewCount(); ++v)
    words += static_cast<size_t>(maps.view(v).size) * static_cast<size_t>(maps.view(v).size);
  return words;
}

void packBlock(const Scene& scene, const ShadowUpload& upload, uint32_t* words) {
  const render::ShadowMaps& maps = upload.maps;
  const size_t lights = scene.lights.size();
  const uint32_t views_word = static_cast<uint32_t>(kShadowHeaderWords + 2 * lights);
  std::memset(words, 0, kShadowHeaderWords * sizeof(uint32_t));
  words[kShadowLightCount] = static_cast<uint32_t>(lights);
  words[kShadowOmnidirectional] = maps.omnidirectional() ? 1u : 0u;
  words[kShadowNormalOffset] = floatWord(maps.normalOffset());
  words[kShadowViews] = views_word;
  storeFloat3(maps.eye(), words + kShadowEye);
  storeFloat3(maps.eyeForward(), words + kShadowEyeForward);
  for (size_t i = 0; i < lights; ++i) {
    const int shadow = upload.rig.lights[i].shadow;
    uint32_t* entry = words + kShadowHeaderWords + 2 * i;
    entry[0] = shadow < 0 ? 0xffffffffu : static_cast<uint32_t>(maps.lightFirstView(shadow));
    entry[1] = shadow < 0 ? 0u : static_cast<uint32_t>(maps.lightViewCount(shadow));
  }
  size_t depth_word = views_word + size_t{kShadowViewWords} * maps.viewCount();
  for (int v = 0; v < maps.viewCount(); ++v) {
    const render::ShadowView& view = maps.view(v);
    packView(view, static_cast<uint32_t>(depth_word), words + views_word + kShadowViewWords * v);
    const size_t texels = static_cast<size_t>(view.size) * static_cast<size_t>(view.size);
    std::memcpy(words + depth_word, view.depth.data(), texels * sizeof(float));
    depth_word += texels;
  }
}

// A block larger than one storage buffer of the device (lavapipe: 128 MiB, so two suns at 2048
// texels fit and three do not) as an error that says what to change.
Expected<void> checkBlockFits(const Context& context, const render::ShadowMaps& maps,
                              size_t words) {
  const uint64_t bytes = static_cast<uint64_t>(words) * sizeof(uint32_t);
  const uint64_t limit = std::min<uint64_t>(context.max_buffer_bytes, 0xffffffffull);
  if (bytes <= limit) return {};
  const int size = maps.viewCount() > 0 ? maps.view(0).size : 0;
  return makeError("the shadow maps (" + std::to_string(maps.viewCount()) + " of " +
                   std::to_string(size) + "x" + std::to_string(size) + " texels: three per " +
                   "directional light, one per spot) need " + std::to_string((bytes >> 20) + 1) +
                   " MiB, more than the " + std::to_string(limit >> 20) +
                   " MiB this device allows in one storage buffer (maxStorageBufferRange); shadow "
                   "fewer lights, use smaller maps (ShadowOptions::map_size) or the cpu backend");
}

}  // namespace

Expected<void> uploadShadows(Context& context, const Scene& scene, const RenderOptions& options,
                             ShadowUpload& upload) {
  constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  bool drawn = false;
  if (options.shadows.enabled) {
    if (!upload.pool) upload.pool = std::make_unique<render::WorkerPool>(0);
    upload.rig.prepare(scene);
    // As the CPU renderers: the ray renderer's cascades (omnidirectional) for the nonlinear
    // projections, the tile renderer's for perspective; the image's aspect for the fit.
    const bool omnidirectional = options.projection != Projection::kPerspective;
    const float aspect = static_cast<float>(options.width) / static_cast<float>(options.height);
    upload.maps.build(scene, options.shadows, omnidirectional, aspect, *upload.pool, upload.rig);
    drawn = upload.rig.shadows != nullptr;  // null: an empty scene, nothing to shadow
  }
  const size_t words =
      drawn ? blockWords(scene.lights.size(), upload.maps) : size_t{kShadowHeaderWords};
  if (Expected<void> r = checkBlockFits(context, upload.maps, words); !r) return r;
  if (Expected<void> r = context.ensureBuffer(upload.buffer, words * sizeof(uint32_t), kStorage,
                                              MemoryKind::kHost, "shadow map");
      !r)
    return r;
  uint32_t* out = static_cast<uint32_t*>(upload.buffer.mapped);
  if (drawn) {
    packBlock(scene, upload, out);
  } else {
    std::memset(out, 0, kShadowHeaderWords * sizeof(uint32_t));  // names no light
  }
  return {};
}

void destroyShadowUpload(Context& context, ShadowUpload& upload) {
  context.destroyBuffer(upload.buffer);
}

void writeShadowDescriptor(Context& context, VkDescriptorSet set, const ShadowUpload& upload) {
  const VkDescriptorBufferInfo info{upload.buffer.buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet write{};
  write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  write.dstSet = set;
  write.dstBinding = kBindingShadows;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  write.pBufferInfo = &info;
  context.vk.vkUpdateDescriptorSets(context.device, 1, &write, 0, nullptr);
}

}  // namespace tessera::vulkan
