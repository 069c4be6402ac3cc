// Shadow maps (RenderOptions::shadows) for both Vulkan backends. The maps are the CPU's: each frame
// the CPU's own ShadowMaps::build draws them (the same depth texels, the same cascade fits), and
// this packs them, with what ShadowMaps::visibility reads, into one mapped storage buffer (binding
// 21) that shaders/shadow.glsl reads. The buffer is reused frame to frame and only grows.
#pragma once

#include <cstdint>
#include <memory>

#include <tessera/base/expected.h>
#include <tessera/render/options.h>
#include <tessera/scene/scene.h>

#include "render/lights.h"
#include "render/shadow_map.h"
#include "render/worker_pool.h"
#include "vulkan/context.h"

namespace tessera::vulkan {

// The shadow block, in 32-bit words (uint, int or float bits), as shaders/shadow.glsl reads it:
//   header (kShadowHeaderWords): the number of lights with a table entry, the omnidirectional
//     flag, the normal offset (texels), the views' first word, the eye (3 floats) and its
//     forward axis (3 floats);
//   per scene light: its first view (-1: unshadowed) and its view count;
//   per view (kShadowViewWords): ShadowView's perspective flag, origin, right, up, forward, cx, cy,
//     scale, z_a, z_b, near_d, texel_world, reach, size and the word of its first depth texel;
//   then every view's depth texels (size x size floats, row by row, +inf where nothing is).
// A frame without shadows holds only a header that names no light.
enum GpuShadowBlock : uint32_t {
  kShadowLightCount = 0,
  kShadowOmnidirectional = 1,
  kShadowNormalOffset = 2,
  kShadowViews = 3,
  kShadowEye = 4,
  kShadowEyeForward = 7,
  kShadowHeaderWords = 16,
  kShadowViewWords = 24,
};

struct ShadowUpload {
  render::ShadowMaps maps;                   // this frame's, reused frame to frame
  render::LightRig rig;                      // build() marks the lights that have maps
  std::unique_ptr<render::WorkerPool> pool;  // made for the first frame with shadows
  Buffer buffer;                             // host-visible, coherent
};

// Draws the frame's shadow maps when options.shadows asks for them (the nonlinear projections'
// omnidirectional cascades when options.projection is not perspective, as the CPU's ray renderer)
// and writes the block; an Error when it does not fit in a storage buffer of the device.
Expected<void> uploadShadows(Context& context, const Scene& scene, const RenderOptions& options,
                             ShadowUpload& upload);
void destroyShadowUpload(Context& context, ShadowUpload& upload);
// The descriptor write of binding 21 (kBindingShadows) of `set`.
void writeShadowDescriptor(Context& context, VkDescriptorSet set, const ShadowUpload& upload);

}  // namespace tessera::vulkan
