#include "render/sky_pass.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "core/error.h"
#include "noise/noise_settings.h"
#include "render/sky_tables.h"
#include "spv/sky.comp.h"
#include "spv/tonemap.frag.h"
#include "spv/tonemap.vert.h"
#include "vk/context.h"
#include "vk/graphics_pipeline.h"
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
constexpr VkDescriptorType kTonemapBindings[] = {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};

float uintBitsAsFloat(uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, sizeof(f));
  return f;
}

// The detail noise's seed, mixed once here as the noise code would (noise_settings.h).
uint32_t detailSeedMix(uint32_t seed) {
  noise::NoiseSettings settings;
  settings.seed = seed + 99u;
  return noise::toNoiseParams(settings).seedMix;
}

void validateSkySettings(const SkySettings& settings) {
  if (settings.viewSamples < 2 || settings.viewSamples > 256)
    throw Error(fmt::format("atmosphere samples {} are outside 2..256", settings.viewSamples));
  if (!(settings.exposure > 0.0 && std::isfinite(settings.exposure)))
    throw Error(fmt::format("exposure {} must be a positive number", settings.exposure));
}

}  // namespace

SkyPass::SkyPass(vk::Context& context, const PlanetDescription& planet, const SkyTables& tables,
                 const SkySettings& settings, VkFormat outputFormat)
    : context_(context), planet_(planet), tables_(tables), settings_(settings) {
  validateSkySettings(settings);
  try {
    for (vk::Buffer& uniforms : uniforms_)
      uniforms = vk::createBuffer(context, sizeof(gpu::SkyUniforms), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                  vk::MemoryUsage::Upload);
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = info.minFilter = VK_FILTER_NEAREST;
    info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    VK_CHECK(vkCreateSampler(context.device, &info, nullptr, &depthSampler_));

    composeSetLayout_ = vk::createSetLayout(context, kComposeBindings, VK_SHADER_STAGE_COMPUTE_BIT);
    composePool_ = vk::createDescriptorPool(context, kComposeBindings, vk::kFramesInFlight);
    composeLayout_ = vk::createPipelineLayout(context, composeSetLayout_, 0, 0);
    composePipeline_ = vk::createComputePipelineWithLayout(context, kSpv_sky_comp, composeLayout_);
    for (uint32_t slot = 0; slot < vk::kFramesInFlight; ++slot) {
      VkDescriptorSet set = composeSets_[slot] = vk::allocateSet(context, composePool_, composeSetLayout_);
      vk::writeBufferDescriptor(context, set, gpu::kSkyBindingUniforms, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                uniforms_[slot]);
      vk::writeImageDescriptor(context, set, gpu::kSkyBindingTransmittance, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                               tables.transmittanceView(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, tables.sampler());
      vk::writeImageDescriptor(context, set, gpu::kSkyBindingClouds, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                               tables.cloudCoverView(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, tables.sampler());
    }

    tonemapSetLayout_ = vk::createSetLayout(context, kTonemapBindings, VK_SHADER_STAGE_FRAGMENT_BIT);
    tonemapPool_ = vk::createDescriptorPool(context, kTonemapBindings, 1);
    tonemapSet_ = vk::allocateSet(context, tonemapPool_, tonemapSetLayout_);
    tonemapLayout_ =
        vk::createPipelineLayout(context, tonemapSetLayout_, sizeof(glm::vec4), VK_SHADER_STAGE_FRAGMENT_BIT);
    vk::GraphicsPipelineDesc desc;
    desc.vertexSpirv = kSpv_tonemap_vert;
    desc.fragmentSpirv = kSpv_tonemap_frag;
    desc.layout = tonemapLayout_;
    desc.colorFormat = outputFormat;
    desc.cullMode = VK_CULL_MODE_NONE;
    desc.depthTest = false;
    desc.depthWrite = false;
    tonemapPipeline_ = vk::createGraphicsPipeline(context, desc);
  } catch (...) {
    release();
    throw;
  }
}

SkyPass::~SkyPass() { release(); }

void SkyPass::release() {
  VkDevice device = context_.device;
  if (tonemapPipeline_) vkDestroyPipeline(device, tonemapPipeline_, nullptr);
  if (tonemapLayout_) vkDestroyPipelineLayout(device, tonemapLayout_, nullptr);
  if (tonemapPool_) vkDestroyDescriptorPool(device, tonemapPool_, nullptr);
  if (tonemapSetLayout_) vkDestroyDescriptorSetLayout(device, tonemapSetLayout_, nullptr);
  if (composePipeline_) vkDestroyPipeline(device, composePipeline_, nullptr);
  if (composeLayout_) vkDestroyPipelineLayout(device, composeLayout_, nullptr);
  if (composePool_) vkDestroyDescriptorPool(device, composePool_, nullptr);
  if (composeSetLayout_) vkDestroyDescriptorSetLayout(device, composeSetLayout_, nullptr);
  if (depthSampler_) vkDestroySampler(device, depthSampler_, nullptr);
  tonemapPipeline_ = composePipeline_ = VK_NULL_HANDLE;
  tonemapLayout_ = composeLayout_ = VK_NULL_HANDLE;
  tonemapPool_ = composePool_ = VK_NULL_HANDLE;
  tonemapSetLayout_ = composeSetLayout_ = VK_NULL_HANDLE;
  depthSampler_ = VK_NULL_HANDLE;
  for (uint32_t slot = vk::kFramesInFlight; slot-- > 0;) vk::destroyBuffer(context_, uniforms_[slot]);
  for (VkDescriptorSet& set : composeSets_) set = VK_NULL_HANDLE;  // went with the pool
}

void SkyPass::setTargets(const vk::Image& hdr, const vk::Image& depth) {
  for (VkDescriptorSet set : composeSets_) {
    vk::writeImageDescriptor(context_, set, gpu::kSkyBindingColor, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, hdr.view,
                             VK_IMAGE_LAYOUT_GENERAL);
    vk::writeImageDescriptor(context_, set, gpu::kSkyBindingDepth, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                             depth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depthSampler_);
  }
  vk::writeImageDescriptor(context_, tonemapSet_, 0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, hdr.view,
                           VK_IMAGE_LAYOUT_GENERAL);
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
  u.clipToLocal = glm::mat4(glm::inverse(view.viewProjection));
  u.localToPlanet = glm::mat4(glm::mat3(view.localToPlanet));
  u.camera = glm::vec4(float(view.altitudeM), float(view.nearPlaneM), float(settings_.exposure), float(view.timeS));
  u.forward = glm::vec4(glm::vec3(view.forward), float(settings_.viewSamples));
  u.sunLocal = glm::vec4(glm::vec3(view.sunLocal), float(planet_.stars.brightness));
  const CloudDescription& c = planet_.clouds;
  const bool clouds = settings_.clouds && c.enabled && planet_.atmosphere.enabled;
  u.cameraPlanet = glm::vec4(glm::vec3(view.cameraPlanet), clouds ? 1.0f : 0.0f);
  u.clouds = glm::vec4(float(c.bottomM), float(c.topM), float(c.coverage), float(c.sharpness));
  // Detail noise: 3 octaves from 12 km down, finer than the cover images' texels.
  const double detailWavelengthM = 12'000.0;
  u.cloudShape =
      glm::vec4(float(c.opacity), float(1.0 / detailWavelengthM), 0.12f, uintBitsAsFloat(detailSeedMix(c.seed)));
  const CloudMotion motion = cloudMotion(c, planet_.radiusM, view.timeS);
  u.cloudMotion = glm::vec4(motion.weights, motion.driftRad);
  for (int k = 0; k < kSkyIrradianceSamples; ++k) u.skyIrradiance[k] = tables_.skyIrradiance()[size_t(k)];
  u.extent = glm::vec4(float(width), float(height), float(view.pixelAngleRad), view.drawSun ? 1.0f : 0.0f);
  const double lowest = planet_.hasOcean ? planet_.seaLevelM : view.lowestSurfaceM;
  u.surface = glm::vec4(float(lowest), planet_.hasOcean ? 1.0f : 0.0f, 0.0f, 0.0f);
  // Host-visible: a plain copy, no submission (the slot's previous frame has completed).
  vk::uploadBuffer(context_, uniforms_[slot], &u, sizeof(u));
}

void SkyPass::recordCompose(VkCommandBuffer cmd, vk::GpuTimer* timer) {
  if (timer) timer->begin(cmd, "sky");
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, composePipeline_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, composeLayout_, 0, 1, &composeSets_[slot_], 0, nullptr);
  const uint32_t group = gpu::kSkyWorkgroupSize;
  vkCmdDispatch(cmd, (width_ + group - 1) / group, (height_ + group - 1) / group, 1);
  if (timer) timer->end(cmd);
}

void SkyPass::recordTonemap(VkCommandBuffer cmd, vk::GpuTimer* timer) {
  if (timer) timer->begin(cmd, "tonemap");
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, tonemapPipeline_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, tonemapLayout_, 0, 1, &tonemapSet_, 0, nullptr);
  const glm::vec4 params(float(settings_.exposure), 0.0f, 0.0f, 0.0f);
  vkCmdPushConstants(cmd, tonemapLayout_, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(params), &params);
  vkCmdDraw(cmd, 3, 1, 0, 0);
  if (timer) timer->end(cmd);
}

}  // namespace planet
