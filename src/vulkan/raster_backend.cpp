// The "vulkan-raster" backend: the scene through Vulkan's graphics pipeline. One render pass
// with three colour attachments (packed sRGB colour and triangle id as R32_UINT, the world normal
// as RGBA32F) and a D32 depth attachment; one indexed draw per object; then the attachments are
// copied into a mapped buffer and the CPU's line pass draws the axes on the host.
//
// Window coordinates match the CPU's: the zero-to-one projection gives the same window z, and a
// negative-height viewport puts pixel (0, 0) at the top left with Y up in NDC, so the OpenGL
// winding rule (counter-clockwise in NDC is front-facing) holds unchanged.
#include <tessera/vulkan/vulkan_backend.h>

#include <algorithm>
#include <cstring>
#include <limits>

#include <tessera/base/check.h>

#include "render/fixed_point.h"
#include "shaders/MeshFrag.spv.h"
#include "shaders/MeshVert.spv.h"
#include "vulkan/context.h"
#include "vulkan/gpu_types.h"
#include "vulkan/scene_upload.h"

namespace tessera::vulkan {

namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R32_UINT;  // packed RGBA8, encoded by the shader
constexpr VkFormat kIdFormat = VK_FORMAT_R32_UINT;
constexpr VkFormat kNormalFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr int kAttachmentCount = 4;  // colour, id, normal, depth

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
};

}  // namespace

struct RasterBackend::State {
  std::unique_ptr<Context> context;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
  VkDescriptorPool descriptor_pool = VK_NULL_HANDLE;
  VkDescriptorSet descriptor_set = VK_NULL_HANDLE;
  VkRenderPass render_pass = VK_NULL_HANDLE;
  VkPipeline pipelines[3] = {};  // by CullMode: back, front, none
  VkQueryPool timestamps = VK_NULL_HANDLE;

  int width = 0, height = 0;
  Image attachments[kAttachmentCount];
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  Buffer readback;

  PackedScene packed;
  SceneBuffers scene_buffers;
  RasterStats stats;
  Expected<void> last_result;

  ~State();
  Expected<void> createPipelines();
  Expected<void> ensureTargets(int w, int h);
  void destroyTargets();
  Expected<void> renderFrame(const Scene& scene, const RenderOptions& options, Frame& frame);
};

RasterBackend::State::~State() {
  if (!context) return;
  Context& c = *context;
  // Teardown waits at least 5 s (still bounded) for a frame a short timeout abandoned; past that
  // the Context leaks everything rather than hang.
  c.fence_timeout_ms = std::max<uint32_t>(c.fence_timeout_ms, 5000);
  if (!c.waitForPending()) return;
  destroyTargets();
  for (VkPipeline p : pipelines)
    if (p) c.vk.vkDestroyPipeline(c.device, p, nullptr);
  if (render_pass) c.vk.vkDestroyRenderPass(c.device, render_pass, nullptr);
  if (pipeline_layout) c.vk.vkDestroyPipelineLayout(c.device, pipeline_layout, nullptr);
  if (descriptor_pool) c.vk.vkDestroyDescriptorPool(c.device, descriptor_pool, nullptr);
  if (set_layout) c.vk.vkDestroyDescriptorSetLayout(c.device, set_layout, nullptr);
  if (timestamps) c.vk.vkDestroyQueryPool(c.device, timestamps, nullptr);
  destroySceneBuffers(c, scene_buffers);
  c.destroyBuffer(readback);
}

Expected<void> RasterBackend::State::createPipelines() {
  Context& c = *context;
  const VulkanFunctions& vk = c.vk;
  constexpr VkShaderStageFlags kStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

  VkDescriptorSetLayoutBinding bindings[kSceneBindingCount]{};
  for (uint32_t i = 0; i < kSceneBindingCount; ++i)
    bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, kStages, nullptr};
  VkDescriptorSetLayoutCreateInfo layout_info{};
  layout_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  layout_info.bindingCount = kSceneBindingCount;
  layout_info.pBindings = bindings;
  TESSERA_VK_CHECK(vk.vkCreateDescriptorSetLayout(c.device, &layout_info, nullptr, &set_layout));
  VkPushConstantRange push{kStages, 0, sizeof(uint32_t)};
  VkPipelineLayoutCreateInfo pipeline_layout_info{};
  pipeline_layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  pipeline_layout_info.setLayoutCount = 1;
  pipeline_layout_info.pSetLayouts = &set_layout;
  pipeline_layout_info.pushConstantRangeCount = 1;
  pipeline_layout_info.pPushConstantRanges = &push;
  TESSERA_VK_CHECK(
      vk.vkCreatePipelineLayout(c.device, &pipeline_layout_info, nullptr, &pipeline_layout));
  VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kSceneBindingCount};
  VkDescriptorPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = &pool_size;
  TESSERA_VK_CHECK(vk.vkCreateDescriptorPool(c.device, &pool_info, nullptr, &descriptor_pool));
  VkDescriptorSetAllocateInfo allocate{};
  allocate.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  allocate.descriptorPool = descriptor_pool;
  allocate.descriptorSetCount = 1;
  allocate.pSetLayouts = &set_layout;
  TESSERA_VK_CHECK(vk.vkAllocateDescriptorSets(c.device, &allocate, &descriptor_set));

  // The render pass: every attachment cleared, drawn, then left ready to be copied out.
  VkAttachmentDescription attachments[kAttachmentCount]{};
  const VkFormat formats[kAttachmentCount] = {kColorFormat, kIdFormat, kNormalFormat, kDepthFormat};
  for (int i = 0; i < kAttachmentCount; ++i) {
    attachments[i].format = formats[i];
    attachments[i].samples = VK_SAMPLE_COUNT_1_BIT;
    attachments[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    attachments[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachments[i].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachments[i].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachments[i].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    attachments[i].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  }
  const VkAttachmentReference color_refs[3] = {{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
                                               {1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
                                               {2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}};
  const VkAttachmentReference depth_ref{3, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 3;
  subpass.pColorAttachments = color_refs;
  subpass.pDepthStencilAttachment = &depth_ref;
  constexpr VkPipelineStageFlags kAttachmentStages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                                     VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                                     VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  constexpr VkAccessFlags kAttachmentWrites =
      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  VkSubpassDependency dependencies[2]{};
  // Orders this frame's clears (and the layout transitions out of UNDEFINED) after the previous
  // frame's copies out of the same images.
  dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[0].dstSubpass = 0;
  dependencies[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  dependencies[0].dstStageMask = kAttachmentStages;
  dependencies[0].srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  dependencies[0].dstAccessMask = kAttachmentWrites | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
  // Orders the attachment writes (and the transition to TRANSFER_SRC_OPTIMAL) before the copies
  // into the readback buffer.
  dependencies[1].srcSubpass = 0;
  dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[1].srcStageMask = kAttachmentStages;
  dependencies[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  dependencies[1].srcAccessMask = kAttachmentWrites;
  dependencies[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  VkRenderPassCreateInfo pass_info{};
  pass_info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  pass_info.attachmentCount = kAttachmentCount;
  pass_info.pAttachments = attachments;
  pass_info.subpassCount = 1;
  pass_info.pSubpasses = &subpass;
  pass_info.dependencyCount = 2;
  pass_info.pDependencies = dependencies;
  TESSERA_VK_CHECK(vk.vkCreateRenderPass(c.device, &pass_info, nullptr, &render_pass));

  Expected<VkShaderModule> vert = c.createShaderModule(spirv::kMeshVert);
  if (!vert) return vert.error();
  Expected<VkShaderModule> frag = c.createShaderModule(spirv::kMeshFrag);
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

  const VkVertexInputBindingDescription vertex_binding{0, sizeof(GpuVertex),
                                                       VK_VERTEX_INPUT_RATE_VERTEX};
  const VkVertexInputAttributeDescription vertex_attributes[4] = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(GpuVertex, position)},
      {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(GpuVertex, normal)},
      {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(GpuVertex, uv)},
      {3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(GpuVertex, color)}};
  VkPipelineVertexInputStateCreateInfo vertex_input{};
  vertex_input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
  vertex_input.vertexBindingDescriptionCount = 1;
  vertex_input.pVertexBindingDescriptions = &vertex_binding;
  vertex_input.vertexAttributeDescriptionCount = 4;
  vertex_input.pVertexAttributeDescriptions = vertex_attributes;
  VkPipelineInputAssemblyStateCreateInfo assembly{};
  assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{};
  viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo rasterization{};
  rasterization.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  rasterization.polygonMode = VK_POLYGON_MODE_FILL;
  rasterization.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rasterization.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{};
  multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{};
  depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  depth.depthTestEnable = VK_TRUE;
  depth.depthWriteEnable = VK_TRUE;
  depth.depthCompareOp = VK_COMPARE_OP_LESS;  // the CPU's z < stored: the first of equals wins
  VkPipelineColorBlendAttachmentState blend[3]{};
  for (VkPipelineColorBlendAttachmentState& b : blend)
    b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                       VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo color_blend{};
  color_blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  color_blend.attachmentCount = 3;
  color_blend.pAttachments = blend;
  const VkDynamicState dynamic_states[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{};
  dynamic.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamic_states;

  VkGraphicsPipelineCreateInfo create[3]{};
  VkPipelineRasterizationStateCreateInfo rasterizations[3] = {rasterization, rasterization,
                                                              rasterization};
  rasterizations[0].cullMode = VK_CULL_MODE_BACK_BIT;   // CullMode::kBack
  rasterizations[1].cullMode = VK_CULL_MODE_FRONT_BIT;  // CullMode::kFront
  rasterizations[2].cullMode = VK_CULL_MODE_NONE;       // CullMode::kNone
  for (int i = 0; i < 3; ++i) {
    create[i].sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
    create[i].stageCount = 2;
    create[i].pStages = stages;
    create[i].pVertexInputState = &vertex_input;
    create[i].pInputAssemblyState = &assembly;
    create[i].pViewportState = &viewport;
    create[i].pRasterizationState = &rasterizations[i];
    create[i].pMultisampleState = &multisample;
    create[i].pDepthStencilState = &depth;
    create[i].pColorBlendState = &color_blend;
    create[i].pDynamicState = &dynamic;
    create[i].layout = pipeline_layout;
    create[i].renderPass = render_pass;
  }
  const VkResult created =
      vk.vkCreateGraphicsPipelines(c.device, VK_NULL_HANDLE, 3, create, nullptr, pipelines);
  vk.vkDestroyShaderModule(c.device, *vert, nullptr);
  vk.vkDestroyShaderModule(c.device, *frag, nullptr);
  TESSERA_VK_CHECK(created);

  if (c.caps.timestamp_valid_bits > 0) {
    VkQueryPoolCreateInfo query_info{};
    query_info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
    query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    query_info.queryCount = 2;
    TESSERA_VK_CHECK(vk.vkCreateQueryPool(c.device, &query_info, nullptr, &timestamps));
  }
  return {};
}

void RasterBackend::State::destroyTargets() {
  Context& c = *context;
  if (framebuffer) c.vk.vkDestroyFramebuffer(c.device, framebuffer, nullptr);
  framebuffer = VK_NULL_HANDLE;
  for (Image& image : attachments) {
    if (image.view) c.vk.vkDestroyImageView(c.device, image.view, nullptr);
    if (image.image) c.vk.vkDestroyImage(c.device, image.image, nullptr);
    if (image.memory) c.vk.vkFreeMemory(c.device, image.memory, nullptr);
    image = Image{};
  }
  width = height = 0;
}

Expected<void> RasterBackend::State::ensureTargets(int w, int h) {
  if (w == width && h == height && framebuffer) return {};
  destroyTargets();
  Context& c = *context;
  const VkFormat formats[kAttachmentCount] = {kColorFormat, kIdFormat, kNormalFormat, kDepthFormat};
  VkImageView views[kAttachmentCount];
  for (int i = 0; i < kAttachmentCount; ++i) {
    const bool is_depth = i == 3;
    VkImageCreateInfo create{};
    create.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    create.imageType = VK_IMAGE_TYPE_2D;
    create.format = formats[i];
    create.extent = {static_cast<uint32_t>(w), static_cast<uint32_t>(h), 1};
    create.mipLevels = 1;
    create.arrayLayers = 1;
    create.samples = VK_SAMPLE_COUNT_1_BIT;
    create.tiling = VK_IMAGE_TILING_OPTIMAL;
    create.usage = (is_depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT
                             : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) |
                   VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    create.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    Image& image = attachments[i];
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
    view.format = formats[i];
    view.subresourceRange = {static_cast<VkImageAspectFlags>(is_depth ? VK_IMAGE_ASPECT_DEPTH_BIT
                                                                      : VK_IMAGE_ASPECT_COLOR_BIT),
                             0, 1, 0, 1};
    TESSERA_VK_CHECK(c.vk.vkCreateImageView(c.device, &view, nullptr, &image.view));
    views[i] = image.view;
  }
  VkFramebufferCreateInfo framebuffer_info{};
  framebuffer_info.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
  framebuffer_info.renderPass = render_pass;
  framebuffer_info.attachmentCount = kAttachmentCount;
  framebuffer_info.pAttachments = views;
  framebuffer_info.width = static_cast<uint32_t>(w);
  framebuffer_info.height = static_cast<uint32_t>(h);
  framebuffer_info.layers = 1;
  TESSERA_VK_CHECK(c.vk.vkCreateFramebuffer(c.device, &framebuffer_info, nullptr, &framebuffer));
  width = w;
  height = h;
  // Colour, id and depth are 4 bytes a pixel, the normal 16.
  const size_t pixels = static_cast<size_t>(w) * h;
  return c.ensureBuffer(readback, pixels * 28, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::kHost,
                        "readback");
}

Expected<void> RasterBackend::State::renderFrame(const Scene& scene, const RenderOptions& options,
                                                 Frame& frame) {
  Context& c = *context;
  const VulkanFunctions& vk = c.vk;
  // Nothing the GPU may still read (an earlier frame abandoned after a timeout) is touched
  // before that frame has finished: buffers, descriptors and mapped inputs alike.
  if (Expected<void> r = c.waitForPending(); !r)
    return makeError("an earlier frame is still running: " + r.error().message);
  if (Expected<void> r = packScene(scene, options, IndexPolicy::kDegenerateDropped, packed); !r)
    return r;
  if (Expected<void> r = uploadScene(c, packed, scene_buffers); !r) return r;
  if (Expected<void> r = ensureTargets(options.width, options.height); !r) return r;

  std::vector<VkDescriptorBufferInfo> infos;
  appendSceneDescriptors(scene_buffers, infos);
  VkWriteDescriptorSet writes[kSceneBindingCount]{};
  for (uint32_t i = 0; i < kSceneBindingCount; ++i) {
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = descriptor_set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vk.vkUpdateDescriptorSets(c.device, kSceneBindingCount, writes, 0, nullptr);

  Expected<VkCommandBuffer> begun = c.beginCommands();
  if (!begun) return begun.error();
  VkCommandBuffer cmd = *begun;
  if (timestamps) {
    vk.vkCmdResetQueryPool(cmd, timestamps, 0, 2);
    vk.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps, 0);
  }

  VkClearValue clears[kAttachmentCount]{};
  clears[0].color.uint32[0] = packed.frame.background;
  clears[3].depthStencil = {1.0f, 0};
  VkRenderPassBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  begin.renderPass = render_pass;
  begin.framebuffer = framebuffer;
  begin.renderArea = {{0, 0}, {static_cast<uint32_t>(width), static_cast<uint32_t>(height)}};
  begin.clearValueCount = kAttachmentCount;
  begin.pClearValues = clears;
  vk.vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  // Negative height: y = 0 of the framebuffer is NDC y = +1, the top row, as the CPU's viewport.
  VkViewport viewport{};
  viewport.y = static_cast<float>(height);
  viewport.width = static_cast<float>(width);
  viewport.height = -static_cast<float>(height);
  viewport.maxDepth = 1.0f;
  vk.vkCmdSetViewport(cmd, 0, 1, &viewport);
  const VkRect2D scissor{{0, 0}, {static_cast<uint32_t>(width), static_cast<uint32_t>(height)}};
  vk.vkCmdSetScissor(cmd, 0, 1, &scissor);
  vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout, 0, 1,
                             &descriptor_set, 0, nullptr);
  const VkDeviceSize zero = 0;
  vk.vkCmdBindVertexBuffers(cmd, 0, 1, &scene_buffers.vertices.buffer, &zero);
  vk.vkCmdBindIndexBuffer(cmd, scene_buffers.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
  stats = RasterStats{};
  stats.triangles_in = packed.triangle_count;
  for (uint32_t i = 0; i < packed.objects.size(); ++i) {
    const GpuObject& object = packed.objects[i];
    if (object.triangle_count == 0) continue;
    vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                         pipelines[std::min(object.cull, 2u)]);
    vk.vkCmdPushConstants(cmd, pipeline_layout,
                          VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                          sizeof(uint32_t), &i);
    vk.vkCmdDrawIndexed(cmd, object.triangle_count * 3, 1, object.triangle_base * 3,
                        static_cast<int32_t>(object.vertex_base), 0);
    ++stats.draws;
  }
  vk.vkCmdEndRenderPass(cmd);

  // The render pass's outgoing dependency orders the attachment writes before these copies.
  const size_t pixels = static_cast<size_t>(width) * height;
  // Each region starts at a multiple of its texel size: the 16-byte normals first, then colour,
  // id and depth (4 bytes each).
  const VkDeviceSize offsets[kAttachmentCount] = {pixels * 16, pixels * 20, 0, pixels * 24};
  for (int i = 0; i < kAttachmentCount; ++i) {
    VkBufferImageCopy region{};
    region.bufferOffset = offsets[i];
    region.imageSubresource = {static_cast<VkImageAspectFlags>(i == 3 ? VK_IMAGE_ASPECT_DEPTH_BIT
                                                                      : VK_IMAGE_ASPECT_COLOR_BIT),
                               0, 0, 1};
    region.imageExtent = {static_cast<uint32_t>(width), static_cast<uint32_t>(height), 1};
    vk.vkCmdCopyImageToBuffer(cmd, attachments[i].image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                              readback.buffer, 1, &region);
  }
  // Orders the copies' writes into the readback buffer before the host reads it (after the
  // fence).
  memoryBarrier(vk, cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  if (timestamps) vk.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps, 1);
  if (Expected<void> r = c.submitAndWait(); !r) return r;

  char* bytes = static_cast<char*>(readback.mapped);
  uint32_t* ids = reinterpret_cast<uint32_t*>(bytes + offsets[1]);
  float* depths = reinterpret_cast<float*>(bytes + offsets[3]);
  // The CPU's empty pixels are +inf deep; the depth attachment clears to 1.
  for (size_t p = 0; p < pixels; ++p)
    if (ids[p] == kNoTriangle) depths[p] = std::numeric_limits<float>::infinity();
  copyResults(reinterpret_cast<const uint32_t*>(bytes + offsets[0]),
              reinterpret_cast<const uint32_t*>(depths), ids,
              reinterpret_cast<const float*>(bytes + offsets[2]), 4, frame);
  drawSceneLines(scene, options, packed, frame);

  if (timestamps) {
    uint64_t ticks[2] = {};
    if (vk.vkGetQueryPoolResults(c.device, timestamps, 0, 2, sizeof(ticks), ticks, sizeof(uint64_t),
                                 VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT) == VK_SUCCESS) {
      const uint32_t bits = c.caps.timestamp_valid_bits;
      const uint64_t mask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
      stats.gpu_ms = static_cast<double>((ticks[1] - ticks[0]) & mask) *
                     c.caps.properties.limits.timestampPeriod * 1e-6;
      stats.timings_valid = true;
    }
  }
  return {};
}

Expected<std::unique_ptr<RasterBackend>> RasterBackend::create(const VulkanOptions& options) {
  Expected<std::unique_ptr<Context>> context = Context::create(options, BackendKind::kRaster);
  if (!context) return context.error();
  auto state = std::make_unique<State>();
  state->context = std::move(*context);
  if (Expected<void> r = state->createPipelines(); !r) return r.error();
  return std::unique_ptr<RasterBackend>(new RasterBackend(std::move(state)));
}

RasterBackend::RasterBackend(std::unique_ptr<State> state) : state_(std::move(state)) {}
RasterBackend::~RasterBackend() = default;

void RasterBackend::render(const Scene& scene, const RenderOptions& options, Frame& frame) {
  state_->last_result = renderIntoFrame(scene, options, frame,
                                        [&] { return state_->renderFrame(scene, options, frame); });
}

Expected<void> RasterBackend::lastResult() const {
  return state_->last_result;
}
const RasterStats& RasterBackend::lastStats() const {
  return state_->stats;
}
const DeviceInfo& RasterBackend::device() const {
  return state_->context->info;
}
std::vector<std::string> RasterBackend::validationErrors() const {
  return state_->context->validationErrors();
}
void RasterBackend::setFenceTimeout(uint32_t milliseconds) {
  state_->context->fence_timeout_ms = milliseconds;
}

Expected<std::unique_ptr<Backend>> makeRasterBackend(const VulkanOptions& options) {
  Expected<std::unique_ptr<RasterBackend>> backend = RasterBackend::create(options);
  if (!backend) return backend.error();
  return std::unique_ptr<Backend>(std::move(*backend));
}

}  // namespace tessera::vulkan
