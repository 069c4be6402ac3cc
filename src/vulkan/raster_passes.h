// vulkan-raster's render passes, their attachments and the mesh pipelines drawn in them.
//
//   AOV pass (one sample): packed sRGB colour and triangle id (R32_UINT), the world normal
//   (RGBA32F) and D32 depth: what the pixel centre shows, exactly as without MSAA.
//   Multisample pass (2, 4 or 8 samples): linear colour (RGBA16F, alpha 1 where a triangle covers
//   the sample, 0 where the background shows) and D32 depth, resolved (averaged) into a
//   single-sample RGBA16F image; the host encodes its sRGB colour and reads its alpha as
//   covered samples / samples.
#pragma once

#include <span>

#include <tessera/base/expected.h>

#include "vulkan/context.h"

namespace tessera::vulkan {

constexpr VkFormat kRasterColorFormat = VK_FORMAT_R32_UINT;  // packed RGBA8, encoded by the shader
constexpr VkFormat kRasterIdFormat = VK_FORMAT_R32_UINT;
constexpr VkFormat kRasterNormalFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kRasterDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr VkFormat kRasterLinearFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // the multisample colour

// Attachment order of the AOV pass and of the multisample pass.
enum AovAttachment { kAovColor, kAovId, kAovNormal, kAovDepth, kAovAttachmentCount };
enum MultisampleAttachment { kMsColor, kMsDepth, kMsResolve, kMsAttachmentCount };

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
};

// A 2D attachment of w x h pixels and `samples` samples, in device memory, with its view.
Expected<void> createAttachment(Context& context, VkFormat format, int w, int h, int samples,
                                VkImageUsageFlags usage, Image& image);
void destroyImage(Context& context, Image& image);

Expected<VkRenderPass> createAovPass(Context& context);
// At one sample: the linear colour (kept) and depth, without a resolve (blended materials).
Expected<VkRenderPass> createMultisamplePass(Context& context, int samples);

// The images and framebuffer of one pass at one size (and sample count).
struct PassTargets {
  int width = 0, height = 0, samples = 0;
  Image images[kAovAttachmentCount];
  int image_count = 0;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
};
// Creates the targets of the AOV pass (samples == 1) or of the multisample pass (`linear`: also
// at one sample, a frame with blended materials; its colour is then kMsColor, kept).
Expected<void> createPassTargets(Context& context, VkRenderPass pass, int w, int h, int samples,
                                 PassTargets& targets, bool linear = false);
void destroyPassTargets(Context& context, PassTargets& targets);

// The mesh pipelines of `pass` (by CullMode: back, front, none) that `cull_modes` names (bit i for
// CullMode i) and `pipelines` does not hold yet, drawing with `samples` per pixel into
// `color_attachments` colour attachments with the given fragment shader. `blended`: the
// transparent pass's (depth write off, the over operator; raster_blend.h). Made as a frame first
// needs them: lavapipe takes about half a second to compile each.
Expected<void> createMeshPipelines(Context& context, VkPipelineLayout layout, VkRenderPass pass,
                                   int samples, uint32_t color_attachments,
                                   std::span<const uint32_t> fragment_spirv,
                                   VkPipeline pipelines[3], uint32_t cull_modes,
                                   bool blended = false);

}  // namespace tessera::vulkan
