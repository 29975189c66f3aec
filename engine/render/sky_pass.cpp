#include "render/sky_pass.h"

#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "render/sky_tables.h"
#include "spv/sky.comp.h"
#include "vk/context.h"
#include "vk/pipeline.h"
#include "vk/timer.h"

namespace planet {
namespace {

// The compose pass reads its per-frame values from a storage buffer, not a uniform buffer:
// lavapipe (Mesa 22.3) folds uniform-buffer values that steer branches and loops into the
// shader, compiling a new variant at every dispatch whose values changed and never freeing the
// old one (+1 MB of process memory and a shader-cache lookup per frame, measured; the
// recompile costs ~400 ms when the shader cache is off). Storage buffers are not folded.
constexpr VkDescriptorType kComposeBindings[] = {
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,          // per-frame values (SkyUniforms)
    VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,           // HDR colour
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // depth
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // transmittance
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // cloud cover
};

void validateSkySettings(const SkySettings& settings) {
  if (settings.viewSamples < 2 || settings.viewSamples > 256)
    throw Error(fmt::format("atmosphere samples {} are outside 2..256", settings.viewSamples));
  if (!(settings.exposure > 0.0 && std::isfinite(settings.exposure)))
    throw Error(fmt::format("exposure {} must be a positive number", settings.exposure));
}

}  // namespace

SkyPass::SkyPass(vk::Context& context, const PlanetDescription& planet, const SkyTables& tables,
                 const SkySettings& settings)
    : context_(context), planet_(planet), tables_(tables), settings_(settings) {
  validateSkySettings(settings);
  for (vk::Owned<vk::Buffer>& uniforms : uniforms_)
    uniforms = {context, vk::createBuffer(context, sizeof(gpu::SkyUniforms), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                          vk::MemoryUsage::Upload)};
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = info.minFilter = VK_FILTER_NEAREST;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  depthSampler_ = {context, vk::createSampler(context, info)};

  setLayout_ = {context, vk::createSetLayout(context, kComposeBindings, VK_SHADER_STAGE_COMPUTE_BIT)};
  pool_ = {context, vk::createDescriptorPool(context, kComposeBindings, vk::kFramesInFlight)};
  layout_ = {context, vk::createPipelineLayout(context, setLayout_.get(), 0, 0)};
  pipeline_ = {context, vk::createComputePipelineWithLayout(context, kSpv_sky_comp, layout_.get())};
  for (uint32_t slot = 0; slot < vk::kFramesInFlight; ++slot) {
    VkDescriptorSet set = sets_[slot] = vk::allocateSet(context, pool_.get(), setLayout_.get());
    vk::writeBufferDescriptor(context, set, gpu::kSkyBindingUniforms, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                              *uniforms_[slot]);
    vk::writeImageDescriptor(context, set, gpu::kSkyBindingTransmittance, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                             tables.transmittanceView(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, tables.sampler());
    vk::writeImageDescriptor(context, set, gpu::kSkyBindingClouds, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                             tables.clouds().view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                             tables.clouds().sampler());
  }
}

void SkyPass::setTargets(const vk::Image& hdr, const vk::Image& depth) {
  for (VkDescriptorSet set : sets_) {
    vk::writeImageDescriptor(context_, set, gpu::kSkyBindingColor, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, hdr.view,
                             VK_IMAGE_LAYOUT_GENERAL);
    vk::writeImageDescriptor(context_, set, gpu::kSkyBindingDepth, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                             depth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depthSampler_.get());
  }
  width_ = hdr.extent.width;
  height_ = hdr.extent.height;
}

void SkyPass::setSettings(const SkySettings& settings) {
  validateSkySettings(settings);
  settings_ = settings;
}

void SkyPass::prepare(const SkyView& view, uint32_t width, uint32_t height, uint32_t slot) {
  vk::checkFrameSlot(slot);
  slot_ = slot;
  gpu::SkyUniforms& u = uniformData_;
  u = gpu::SkyUniforms{};
  u.atmosphere = tables_.atmosphere();
  u.atmosphere.radii.z = float(view.sunAngularRadiusRad);
  u.atmosphere.ozoneSun.y *= float(view.sunIrradianceScale);
  u.clipToLocal = glm::mat4(glm::inverse(view.viewProjection));
  u.localToPlanet = glm::mat4(glm::mat3(view.localToPlanet));
  u.camera = glm::vec4(float(view.altitudeM), float(view.nearPlaneM), float(settings_.exposure), float(view.timeS));
  u.forward = glm::vec4(glm::vec3(view.forward), float(settings_.viewSamples));
  u.sunLocal = glm::vec4(glm::vec3(view.sunLocal), float(planet_.stars.brightness));
  const bool clouds = settings_.clouds && planet_.clouds.enabled && planet_.atmosphere.enabled;
  u.cameraPlanet = glm::vec4(glm::vec3(view.cameraPlanet), clouds ? 1.0f : 0.0f);
  tables_.clouds().writeUniforms(u, view.timeS);
  for (int k = 0; k < kSkyIrradianceSamples; ++k)
    u.skyIrradiance[k] = tables_.skyIrradiance()[size_t(k)] * float(view.sunIrradianceScale);
  u.extent = glm::vec4(float(width), float(height), float(view.pixelAngleRad), view.drawSun ? 1.0f : 0.0f);
  const double lowest = planet_.hasOcean ? planet_.seaLevelM : view.lowestSurfaceM;
  u.surface = glm::vec4(float(lowest), planet_.hasOcean ? 1.0f : 0.0f, 0.0f, 0.0f);
  // Host-visible: a plain copy, no submission (the slot's previous frame has completed).
  vk::uploadBuffer(context_, *uniforms_[slot], &u, sizeof(u));
}

void SkyPass::recordCompose(VkCommandBuffer cmd, vk::GpuTimer* timer) {
  if (timer) timer->begin(cmd, "sky");
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &sets_[slot_], 0, nullptr);
  const uint32_t group = gpu::kSkyWorkgroupSize;
  vkCmdDispatch(cmd, (width_ + group - 1) / group, (height_ + group - 1) / group, 1);
  if (timer) timer->end(cmd);
}

}  // namespace planet
