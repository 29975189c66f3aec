#include "view/imgui_layer.h"

#include <algorithm>
#include <utility>

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include "core/error.h"
#include "vk/commands.h"
#include "vk/context.h"

namespace planet::view {

ImGuiLayer::ImGuiLayer(vk::Context& context, GLFWwindow* window, const vk::Swapchain& swapchain) : context_(context) {
  createFramebuffers(swapchain);
  // Room for the font texture's descriptor set (the only one the backend allocates).
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  poolInfo.maxSets = 4;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &size;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorPool(context_.device, &poolInfo, nullptr, &pool));
  pool_ = {context_, pool};

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  imguiContext_ = ShutdownGuard([] { ImGui::DestroyContext(); });
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini next to wherever the viewer was started
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 4.0f;
  if (!ImGui_ImplGlfw_InitForVulkan(window, true)) throw Error("Dear ImGui could not attach to the window");
  glfwBackend_ = ShutdownGuard(ImGui_ImplGlfw_Shutdown);

  if (!pass_.get()) throw Error("the window is minimised at start; nothing to draw into");
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = context_.instance;
  info.PhysicalDevice = context_.physicalDevice;
  info.Device = context_.device;
  info.QueueFamily = context_.universalFamily;
  info.Queue = context_.graphicsQueue;
  info.DescriptorPool = pool_.get();
  info.MinImageCount = std::max<uint32_t>(2, uint32_t(swapchain.images.size()));
  info.ImageCount = info.MinImageCount;
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = [](VkResult result) {
    if (result != VK_SUCCESS) throwVulkanError(result, "Dear ImGui Vulkan backend", __FILE__, __LINE__);
  };
  if (!ImGui_ImplVulkan_Init(&info, pass_.get())) throw Error("Dear ImGui's Vulkan backend failed to start");
  vulkanBackend_ = ShutdownGuard(ImGui_ImplVulkan_Shutdown);
  vk::submitAndWait(context_, [](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

void ImGuiLayer::createFramebuffers(const vk::Swapchain& swapchain) {
  if (swapchain.images.empty()) return;  // minimised
  if (!pass_.get()) {
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
    VkRenderPass pass = VK_NULL_HANDLE;
    VK_CHECK(vkCreateRenderPass(context_.device, &info, nullptr, &pass));
    pass_ = {context_, pass};
  }
  for (VkImageView view : swapchain.views) {
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = pass_.get();
    info.attachmentCount = 1;
    info.pAttachments = &view;
    info.width = swapchain.extent.width;
    info.height = swapchain.extent.height;
    info.layers = 1;
    VkFramebuffer handle = VK_NULL_HANDLE;
    VK_CHECK(vkCreateFramebuffer(context_.device, &info, nullptr, &handle));
    vk::Owned<VkFramebuffer> framebuffer(context_, handle);
    framebuffers_.push_back(std::move(framebuffer));
  }
  extent_ = swapchain.extent;
}

void ImGuiLayer::detach() { framebuffers_.clear(); }

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
  pass.renderPass = pass_.get();
  pass.framebuffer = framebuffers_[imageIndex].get();
  pass.renderArea = {{0, 0}, extent_};
  vkCmdBeginRenderPass(cmd, &pass, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
  vkCmdEndRenderPass(cmd);
}

}  // namespace planet::view
