#include "view/imgui_layer.h"

#include <algorithm>

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include "core/error.h"
#include "vk/commands.h"
#include "vk/context.h"

namespace planet::view {

ImGuiLayer::ImGuiLayer(vk::Context& context, GLFWwindow* window, const vk::Swapchain& swapchain) : context_(context) {
  // A constructor that throws runs no destructor: what was started so far goes here.
  try {
    start(window, swapchain);
  } catch (...) {
    release();
    throw;
  }
}

ImGuiLayer::~ImGuiLayer() { release(); }

void ImGuiLayer::start(GLFWwindow* window, const vk::Swapchain& swapchain) {
  createFramebuffers(swapchain);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini next to wherever the viewer was started
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 4.0f;
  if (!ImGui_ImplGlfw_InitForVulkan(window, true)) throw Error("Dear ImGui could not attach to the window");
  glfwBackend_ = true;

  // Room for the font texture's descriptor set (the only one the backend allocates).
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4};
  VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pool.maxSets = 4;
  pool.poolSizeCount = 1;
  pool.pPoolSizes = &size;
  VK_CHECK(vkCreateDescriptorPool(context_.device, &pool, nullptr, &pool_));

  if (!pass_) throw Error("the window is minimised at start; nothing to draw into");
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = context_.instance;
  info.PhysicalDevice = context_.physicalDevice;
  info.Device = context_.device;
  info.QueueFamily = context_.universalFamily;
  info.Queue = context_.graphicsQueue;
  info.DescriptorPool = pool_;
  info.MinImageCount = std::max<uint32_t>(2, uint32_t(swapchain.images.size()));
  info.ImageCount = info.MinImageCount;
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = [](VkResult result) {
    if (result != VK_SUCCESS) throwVulkanError(result, "Dear ImGui Vulkan backend", __FILE__, __LINE__);
  };
  if (!ImGui_ImplVulkan_Init(&info, pass_)) throw Error("Dear ImGui's Vulkan backend failed to start");
  vulkanBackend_ = true;
  vk::submitAndWait(context_, [](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

void ImGuiLayer::createFramebuffers(const vk::Swapchain& swapchain) {
  if (swapchain.images.empty()) return;  // minimised
  if (!pass_) {
    // The panel is drawn over the blitted frame: load what the blit wrote, leave it for present.
    VkAttachmentDescription attachment{};
    attachment.format = swapchain.format;
    attachment.samples = VK_SAMPLE_COUNT_1_BIT;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachment.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    attachment.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &reference;
    // The UI blends over the blit's writes.
    VkSubpassDependency dependency{};
    dependency.srcSubpass = VK_SUBPASS_EXTERNAL;
    dependency.dstSubpass = 0;
    dependency.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependency.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    dependency.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependency.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = 1;
    info.pAttachments = &attachment;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 1;
    info.pDependencies = &dependency;
    VK_CHECK(vkCreateRenderPass(context_.device, &info, nullptr, &pass_));
  }
  for (VkImageView view : swapchain.views) {
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = pass_;
    info.attachmentCount = 1;
    info.pAttachments = &view;
    info.width = swapchain.extent.width;
    info.height = swapchain.extent.height;
    info.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    VK_CHECK(vkCreateFramebuffer(context_.device, &info, nullptr, &framebuffer));
    framebuffers_.push_back(framebuffer);
  }
  extent_ = swapchain.extent;
}

void ImGuiLayer::detach() {
  for (VkFramebuffer framebuffer : framebuffers_) vkDestroyFramebuffer(context_.device, framebuffer, nullptr);
  framebuffers_.clear();
}

void ImGuiLayer::attach(const vk::Swapchain& swapchain) {
  createFramebuffers(swapchain);
  if (vulkanBackend_ && !swapchain.images.empty()) ImGui_ImplVulkan_SetMinImageCount(uint32_t(swapchain.images.size()));
}

void ImGuiLayer::beginFrame() {
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void ImGuiLayer::endFrame() { ImGui::Render(); }

void ImGuiLayer::record(VkCommandBuffer cmd, uint32_t imageIndex) const {
  VkRenderPassBeginInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  pass.renderPass = pass_;
  pass.framebuffer = framebuffers_[imageIndex];
  pass.renderArea = {{0, 0}, extent_};
  vkCmdBeginRenderPass(cmd, &pass, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
  vkCmdEndRenderPass(cmd);
}

void ImGuiLayer::release() {
  if (vulkanBackend_) ImGui_ImplVulkan_Shutdown();
  if (glfwBackend_) ImGui_ImplGlfw_Shutdown();
  if (ImGui::GetCurrentContext()) ImGui::DestroyContext();
  vulkanBackend_ = glfwBackend_ = false;
  if (pool_) vkDestroyDescriptorPool(context_.device, pool_, nullptr);
  pool_ = VK_NULL_HANDLE;
  detach();
  if (pass_) vkDestroyRenderPass(context_.device, pass_, nullptr);
  pass_ = VK_NULL_HANDLE;
}

}  // namespace planet::view
