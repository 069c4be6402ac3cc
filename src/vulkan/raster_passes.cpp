#include "vulkan/raster_passes.h"

#include "shaders/MeshVert.spv.h"
#include "vulkan/gpu_types.h"

namespace tessera::vulkan {

namespace {

constexpr VkPipelineStageFlags kAttachmentStages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                                   VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                                   VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
constexpr VkAccessFlags kAttachmentWrites =
    VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;

VkAttachmentDescription attachment(VkFormat format, int samples, bool keep) {
  VkAttachmentDescription a{};
  a.format = format;
  a.samples = static_cast<VkSampleCountFlagBits>(samples);
  a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  a.storeOp = keep ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  const bool depth = format == kRasterDepthFormat;
  a.finalLayout = keep    ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL
                  : depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL
                          : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  return a;
}

Expected<VkRenderPass> createPass(Context& c, std::span<const VkAttachmentDescription> attachments,
                                  const VkSubpassDescription& subpass) {
  VkSubpassDependency dependencies[2]{};
  // Orders this frame's clears (and the layout transitions out of UNDEFINED) after the previous
  // frame's attachment writes and its copies out of the same images.
  dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[0].dstSubpass = 0;
  dependencies[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | kAttachmentStages;
  dependencies[0].dstStageMask = kAttachmentStages;
  dependencies[0].srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT | kAttachmentWrites;
  dependencies[0].dstAccessMask = kAttachmentWrites | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
  // Orders the attachment writes and the resolve (and the transition to TRANSFER_SRC_OPTIMAL)
  // before the copies into the readback buffer.
  dependencies[1].srcSubpass = 0;
  dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[1].srcStageMask = kAttachmentStages;
  dependencies[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  dependencies[1].srcAccessMask = kAttachmentWrites;
  dependencies[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  VkRenderPassCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  info.attachmentCount = static_cast<uint32_t>(attachments.size());
  info.pAttachments = attachments.data();
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = dependencies;
  VkRenderPass pass = VK_NULL_HANDLE;
  TESSERA_VK_CHECK(c.vk.vkCreateRenderPass(c.device, &info, nullptr, &pass));
  return pass;
}

}  // namespace

Expected<void> createAttachment(Context& c, VkFormat format, int w, int h, int samples,
                                VkImageUsageFlags usage, Image& image) {
  const bool is_depth = format == kRasterDepthFormat;
  VkImageCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  create.imageType = VK_IMAGE_TYPE_2D;
  create.format = format;
  create.extent = {static_cast<uint32_t>(w), static_cast<uint32_t>(h), 1};
  create.mipLevels = 1;
  create.arrayLayers = 1;
  create.samples = static_cast<VkSampleCountFlagBits>(samples);
  create.tiling = VK_IMAGE_TILING_OPTIMAL;
  create.usage = usage;
  create.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  TESSERA_VK_CHECK(c.vk.vkCreateImage(c.device, &create, nullptr, &image.image));
  VkMemoryRequirements requirements{};
  c.vk.vkGetImageMemoryRequirements(c.device, image.image, &requirements);
  Expected<uint32_t> type =
      c.findMemoryType(requirements.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (!type) return type.error();
  VkMemoryAllocateInfo allocate{};
  allocate.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  allocate.allocationSize = requirements.size;
  allocate.memoryTypeIndex = *type;
  TESSERA_VK_CHECK(c.vk.vkAllocateMemory(c.device, &allocate, nullptr, &image.memory));
  TESSERA_VK_CHECK(c.vk.vkBindImageMemory(c.device, image.image, image.memory, 0));
  VkImageViewCreateInfo view{};
  view.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  view.image = image.image;
  view.viewType = VK_IMAGE_VIEW_TYPE_2D;
  view.format = format;
  view.subresourceRange = {static_cast<VkImageAspectFlags>(is_depth ? VK_IMAGE_ASPECT_DEPTH_BIT
                                                                    : VK_IMAGE_ASPECT_COLOR_BIT),
                           0, 1, 0, 1};
  TESSERA_VK_CHECK(c.vk.vkCreateImageView(c.device, &view, nullptr, &image.view));
  return {};
}

void destroyImage(Context& c, Image& image) {
  if (image.view) c.vk.vkDestroyImageView(c.device, image.view, nullptr);
  if (image.image) c.vk.vkDestroyImage(c.device, image.image, nullptr);
  if (image.memory) c.vk.vkFreeMemory(c.device, image.memory, nullptr);
  image = Image{};
}

Expected<VkRenderPass> createAovPass(Context& c) {
  // Every attachment cleared, drawn, then left ready to be copied out.
  VkAttachmentDescription attachments[kAovAttachmentCount];
  const VkFormat formats[kAovAttachmentCount] = {kRasterColorFormat, kRasterIdFormat,
                                                 kRasterNormalFormat, kRasterDepthFormat};
  for (int i = 0; i < kAovAttachmentCount; ++i) attachments[i] = attachment(formats[i], 1, true);
  const VkAttachmentReference color_refs[3] = {
      {kAovColor, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
      {kAovId, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
      {kAovNormal, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}};
  const VkAttachmentReference depth_ref{kAovDepth,
                                        VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 3;
  subpass.pColorAttachments = color_refs;
  subpass.pDepthStencilAttachment = &depth_ref;
  return createPass(c, attachments, subpass);
}

Expected<VkRenderPass> createMultisamplePass(Context& c, int samples) {
  if (samples == 1) {
    // The linear pass at one sample (a frame with blended materials): the colour is kept as is.
    const VkAttachmentDescription attachments[2] = {attachment(kRasterLinearFormat, 1, true),
                                                    attachment(kRasterDepthFormat, 1, false)};
    const VkAttachmentReference color_ref{kMsColor, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    const VkAttachmentReference depth_ref{kMsDepth,
                                          VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &color_ref;
    subpass.pDepthStencilAttachment = &depth_ref;
    return createPass(c, attachments, subpass);
  }
  // The multisampled colour and depth live only inside the pass; the resolve is kept.
  VkAttachmentDescription attachments[kMsAttachmentCount] = {
      attachment(kRasterLinearFormat, samples, false),
      attachment(kRasterDepthFormat, samples, false), attachment(kRasterLinearFormat, 1, true)};
  attachments[kMsResolve].loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;  // every pixel is resolved
  const VkAttachmentReference color_ref{kMsColor, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference resolve_ref{kMsResolve, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference depth_ref{kMsDepth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &color_ref;
  subpass.pResolveAttachments = &resolve_ref;
  subpass.pDepthStencilAttachment = &depth_ref;
  return createPass(c, attachments, subpass);
}

Expected<void> createPassTargets(Context& c, VkRenderPass pass, int w, int h, int samples,
                                 PassTargets& targets, bool linear) {
  destroyPassTargets(c, targets);
  constexpr VkImageUsageFlags kColor = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  constexpr VkImageUsageFlags kDepth = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  constexpr VkImageUsageFlags kCopied = VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  struct Want {
    VkFormat format;
    int samples;
    VkImageUsageFlags usage;
  };
  std::vector<Want> wants;
  if (samples == 1 && linear) {
    wants = {{kRasterLinearFormat, 1, kColor | kCopied}, {kRasterDepthFormat, 1, kDepth}};
  } else if (samples == 1) {
    wants = {{kRasterColorFormat, 1, kColor | kCopied},
             {kRasterIdFormat, 1, kColor | kCopied},
             {kRasterNormalFormat, 1, kColor | kCopied},
             {kRasterDepthFormat, 1, kDepth | kCopied}};
  } else {
    // Transient: the multisampled images never leave the pass (tile memory on a tiled GPU).
    constexpr VkImageUsageFlags kTransient = VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT;
    wants = {{kRasterLinearFormat, samples, kColor | kTransient},
             {kRasterDepthFormat, samples, kDepth | kTransient},
             {kRasterLinearFormat, 1, kColor | kCopied}};
  }
  VkImageView views[kAovAttachmentCount];
  for (size_t i = 0; i < wants.size(); ++i) {
    ++targets.image_count;
    if (Expected<void> r = createAttachment(c, wants[i].format, w, h, wants[i].samples,
                                            wants[i].usage, targets.images[i]);
        !r)
      return r;
    views[i] = targets.images[i].view;
  }
  VkFramebufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
  info.renderPass = pass;
  info.attachmentCount = static_cast<uint32_t>(wants.size());
  info.pAttachments = views;
  info.width = static_cast<uint32_t>(w);
  info.height = static_cast<uint32_t>(h);
  info.layers = 1;
  TESSERA_VK_CHECK(c.vk.vkCreateFramebuffer(c.device, &info, nullptr, &targets.framebuffer));
  targets.width = w;
  targets.height = h;
  targets.samples = samples;
  return {};
}

void destroyPassTargets(Context& c, PassTargets& targets) {
  if (targets.framebuffer) c.vk.vkDestroyFramebuffer(c.device, targets.framebuffer, nullptr);
  for (int i = 0; i < targets.image_count; ++i) destroyImage(c, targets.images[i]);
  targets = PassTargets{};
}

namespace {

// The fixed-function state the mesh pipelines share, filled in place (it points into itself).
struct MeshPipelineState {
  VkVertexInputBindingDescription vertex_binding{0, sizeof(GpuVertex), VK_VERTEX_INPUT_RATE_VERTEX};
  VkVertexInputAttributeDescription vertex_attributes[6] = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(GpuVertex, position)},
      {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(GpuVertex, normal)},
      {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(GpuVertex, uv)},
      {3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(GpuVertex, color)},
      {4, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(GpuVertex, tangent)},
      {5, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(GpuVertex, uv1)}};
  VkPipelineVertexInputStateCreateInfo vertex_input{};
  VkPipelineInputAssemblyStateCreateInfo assembly{};
  VkPipelineViewportStateCreateInfo viewport{};
  VkPipelineRasterizationStateCreateInfo rasterizations[3]{};  // by CullMode
  VkPipelineMultisampleStateCreateInfo multisample{};
  VkPipelineDepthStencilStateCreateInfo depth{};
  VkPipelineColorBlendAttachmentState blend[3]{};
  VkPipelineColorBlendStateCreateInfo color_blend{};
  VkDynamicState dynamic_states[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{};

  MeshPipelineState(int samples, uint32_t color_attachments) {
    vertex_input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
    vertex_input.vertexBindingDescriptionCount = 1;
    vertex_input.pVertexBindingDescriptions = &vertex_binding;
    vertex_input.vertexAttributeDescriptionCount = 6;
    vertex_input.pVertexAttributeDescriptions = vertex_attributes;
    assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    const VkCullModeFlags culls[3] = {VK_CULL_MODE_BACK_BIT, VK_CULL_MODE_FRONT_BIT,
                                      VK_CULL_MODE_NONE};  // CullMode::kBack, kFront, kNone
    for (int i = 0; i < 3; ++i) {
      VkPipelineRasterizationStateCreateInfo& r = rasterizations[i];
      r.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
      r.polygonMode = VK_POLYGON_MODE_FILL;
      r.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
      r.lineWidth = 1.0f;
      r.cullMode = culls[i];
    }
    // Shading stays once per pixel and triangle (no sample shading), as the CPU's resolve.
    multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
    multisample.rasterizationSamples = static_cast<VkSampleCountFlagBits>(samples);
    depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
    depth.depthTestEnable = VK_TRUE;
    depth.depthWriteEnable = VK_TRUE;
    depth.depthCompareOp = VK_COMPARE_OP_LESS;  // the CPU's z < stored: the first of equals wins
    for (VkPipelineColorBlendAttachmentState& b : blend)
      b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                         VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    color_blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
    color_blend.attachmentCount = color_attachments;
    color_blend.pAttachments = blend;
    dynamic.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamic_states;
  }
  MeshPipelineState(const MeshPipelineState&) = delete;
  MeshPipelineState& operator=(const MeshPipelineState&) = delete;
};

}  // namespace

Expected<void> createMeshPipelines(Context& c, VkPipelineLayout layout, VkRenderPass pass,
                                   int samples, uint32_t color_attachments,
                                   std::span<const uint32_t> fragment_spirv,
                                   VkPipeline pipelines[3], uint32_t cull_modes, bool blended) {
  const VulkanFunctions& vk = c.vk;
  for (int i = 0; i < 3; ++i)
    if (pipelines[i]) cull_modes &= ~(1u << i);
  if (cull_modes == 0) return {};
  Expected<VkShaderModule> vert = c.createShaderModule(spirv::kMeshVert);
  if (!vert) return vert.error();
  Expected<VkShaderModule> frag = c.createShaderModule(fragment_spirv);
  if (!frag) {
    vk.vkDestroyShaderModule(c.device, *vert, nullptr);
    return frag.error();
  }
  VkPipelineShaderStageCreateInfo stages[2]{};
  stages[0].sType = stages[1].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = *vert;
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = *frag;
  stages[1].pName = "main";

  MeshPipelineState state(samples, color_attachments);
  if (blended) {
    // The transparent pass: tested against the opaque depth, never written; straight alpha over
    // in linear light, C A + D (1 - A), and the coverage A + a (1 - A), each sample on its own.
    state.depth.depthWriteEnable = VK_FALSE;
    VkPipelineColorBlendAttachmentState& b = state.blend[0];
    b.blendEnable = VK_TRUE;
    b.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
    b.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    b.colorBlendOp = VK_BLEND_OP_ADD;
    b.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    b.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    b.alphaBlendOp = VK_BLEND_OP_ADD;
  }
  VkGraphicsPipelineCreateInfo create[3]{};
  uint32_t modes[3], count = 0;
  for (uint32_t i = 0; i < 3; ++i)
    if (cull_modes & (1u << i)) modes[count++] = i;
  for (uint32_t k = 0; k < count; ++k) {
    const uint32_t i = modes[k];
    create[k].sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
    create[k].stageCount = 2;
    create[k].pStages = stages;
    create[k].pVertexInputState = &state.vertex_input;
    create[k].pInputAssemblyState = &state.assembly;
    create[k].pViewportState = &state.viewport;
    create[k].pRasterizationState = &state.rasterizations[i];
    create[k].pMultisampleState = &state.multisample;
    create[k].pDepthStencilState = &state.depth;
    create[k].pColorBlendState = &state.color_blend;
    create[k].pDynamicState = &state.dynamic;
    create[k].layout = layout;
    create[k].renderPass = pass;
  }
  VkPipeline made[3] = {};
  const VkResult created =
      vk.vkCreateGraphicsPipelines(c.device, VK_NULL_HANDLE, count, create, nullptr, made);
  vk.vkDestroyShaderModule(c.device, *vert, nullptr);
  vk.vkDestroyShaderModule(c.device, *frag, nullptr);
  if (created != VK_SUCCESS)
    for (VkPipeline p : made)
      if (p) vk.vkDestroyPipeline(c.device, p, nullptr);
  TESSERA_VK_CHECK(created);
  for (uint32_t k = 0; k < count; ++k) pipelines[modes[k]] = made[k];
  return {};
}

}  // namespace tessera::vulkan
