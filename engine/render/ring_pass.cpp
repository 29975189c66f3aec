#include "render/ring_pass.h"

#include <algorithm>
#include <cmath>
#include <span>

#include <fmt/format.h>

#include "core/error.h"
#include "render/sky_tables.h"
#include "spv/ring.frag.h"
#include "spv/ring_air.frag.h"
#include "spv/ring.vert.h"
#include "vk/context.h"
#include "vk/graphics_pipeline.h"
#include "vk/pipeline.h"
#include "vk/timer.h"

namespace planet {
namespace {

constexpr VkDescriptorType kBindingTypes[] = {
    VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,          // kRingBindingUniforms
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // kRingBindingTransmittance (with air only)
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // kRingBindingMultipleScattering (with air only)
};

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool finite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

bool positive(double value) { return std::isfinite(value) && value > 0.0; }

}  // namespace

RingPass::RingPass(vk::Context& context, const RingDescription& ring, VkFormat colorFormat, VkFormat depthFormat,
                   const SkyTables* air)
    : context_(context), ring_(ring), air_(air && air->atmosphere().radii.w > 0.5f ? air : nullptr) {
  static_assert(gpu::kRingBindingUniforms == 0 && gpu::kRingBindingTransmittance == 1 &&
                gpu::kRingBindingMultipleScattering == 2);
  validateRingDescription(ring);
  const std::span<const VkDescriptorType> bindings(kBindingTypes, air_ ? 3 : 1);
  for (vk::Owned<vk::Buffer>& buffer : uniforms_)
    buffer = {context, vk::createBuffer(context, sizeof(gpu::RingUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                        vk::MemoryUsage::Upload)};
  setLayout_ = {context,
                vk::createSetLayout(context, bindings, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT)};
  pool_ = {context, vk::createDescriptorPool(context, bindings, vk::kFramesInFlight)};
  for (uint32_t slot = 0; slot < vk::kFramesInFlight; ++slot) {
    sets_[slot] = vk::allocateSet(context, pool_.get(), setLayout_.get());
    vk::writeBufferDescriptor(context, sets_[slot], gpu::kRingBindingUniforms, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                              *uniforms_[slot]);
    if (!air_) continue;
    vk::writeImageDescriptor(context, sets_[slot], gpu::kRingBindingTransmittance,
                             VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, air_->transmittanceView(),
                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, air_->sampler());
    vk::writeImageDescriptor(context, sets_[slot], gpu::kRingBindingMultipleScattering,
                             VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, air_->multipleScatteringView(),
                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, air_->sampler());
  }
  layout_ = {context, vk::createPipelineLayout(context, setLayout_.get(), 0, 0)};
  vk::GraphicsPipelineDesc desc;
  desc.vertexSpirv = kSpv_ring_vert;
  desc.fragmentSpirv = air_ ? std::span<const uint32_t>(kSpv_ring_air_frag) : std::span<const uint32_t>(kSpv_ring_frag);
  desc.layout = layout_.get();
  desc.colorFormat = colorFormat;
  desc.depthFormat = depthFormat;
  // Seen from both sides.
  desc.cullMode = VK_CULL_MODE_NONE;
  // Transparent, after the opaque bodies: hidden behind them (reversed Z: nearer is larger,
  // as the terrain's GREATER test), showing over them in front. Its depth is written (where
  // ring.frag keeps the fragment) for the compose passes of nearer atmospheres, which treat
  // what has depth as geometry seen through their air; the other transparent layers (clouds,
  // haze) are composed, not drawn, so nothing drawn later is cut off by it.
  desc.depthTest = depthFormat != VK_FORMAT_UNDEFINED;
  desc.depthWrite = depthFormat != VK_FORMAT_UNDEFINED;
  desc.depthCompare = VK_COMPARE_OP_GREATER;
  desc.alphaBlend = true;
  desc.premultipliedAlpha = true;
  pipeline_ = {context, vk::createGraphicsPipeline(context, desc)};
}

void RingPass::prepare(const RingView& view, uint32_t slot) {
  vk::checkFrameSlot(slot);
  if (!finite(view.viewProjection)) throw Error("ring view: the view-projection matrix is not finite");
  const glm::dmat4 clipToRelative = glm::inverse(view.viewProjection);
  if (!finite(clipToRelative)) throw Error("ring view: the view-projection matrix is singular");
  if (!finite(view.cameraBody)) throw Error("ring view: the camera position is not finite");
  const double sunLength = glm::length(view.sunBody);
  if (!(finite(view.sunBody) && sunLength > 0.0)) throw Error("ring view: the sun direction is zero or not finite");
  if (!positive(view.nearPlaneM))
    throw Error(fmt::format("ring view: near plane {} m is not a positive number", view.nearPlaneM));
  if (view.width == 0 || view.height == 0)
    throw Error(fmt::format("ring view: viewport {}x{} has no pixels", view.width, view.height));
  if (!(std::isfinite(view.sunIrradiance) && view.sunIrradiance >= 0.0))
    throw Error(fmt::format("ring view: sun irradiance {} is not a number >= 0", view.sunIrradiance));
  if (!(std::isfinite(view.ambient) && view.ambient >= 0.0))
    throw Error(fmt::format("ring view: ambient {} is not a number >= 0", view.ambient));
  const glm::dvec3 sun = view.sunBody / sunLength;

  gpu::RingUniforms& u = uniformData_;
  u = gpu::RingUniforms{};
  u.relativeToClip = glm::mat4(view.viewProjection);
  u.clipToRelative = glm::mat4(clipToRelative);
  // The camera sees the sunlit face when it is on the sun's side of the plane.
  const double side = view.cameraBody.z * sun.z > 0.0 ? 1.0 : -1.0;
  u.camera = glm::vec4(glm::vec3(view.cameraBody), float(side));
  u.sun = glm::vec4(glm::vec3(sun), float(view.sunIrradiance));
  u.viewport = glm::vec4(float(1.0 / view.width), float(1.0 / view.height), float(view.ambient), 0.0f);
  u.ring = ringGpuParams(ring_, view.planetRadiusM, view.sunAngularRadiusRad);
  u.eclipse = eclipseGpuParams(view.occluders, glm::dmat3(1.0), view.sunAngularRadiusRad);
  if (air_) {
    if (!(std::isfinite(view.sunIrradianceScale) && view.sunIrradianceScale >= 0.0))
      throw Error(fmt::format("ring view: sun irradiance scale {} is not a number >= 0", view.sunIrradianceScale));
    if (!std::isfinite(view.groundSphereM))
      throw Error(fmt::format("ring view: ground sphere {} m is not finite", view.groundSphereM));
    // As the sky pass's block (SkyPass::prepare): this frame's sun disc and irradiance.
    u.atmosphere = air_->atmosphere();
    u.atmosphere.radii.z = float(view.sunAngularRadiusRad);
    u.atmosphere.ozoneSun.y *= float(view.sunIrradianceScale);
    // The altitude in double: a float camera position 10^9 m away is only good to ~60 m.
    const double altitude = glm::length(view.cameraBody) - view.planetRadiusM;
    u.air = glm::vec4(float(altitude), float(std::min(view.groundSphereM, altitude)), 0.0f, 0.0f);
  }
  vk::uploadBuffer(context_, *uniforms_[slot], &u, sizeof(u));
  edgeOn_ = std::abs(view.cameraBody.z) < 1e-3 * view.nearPlaneM;
  slot_ = slot;
  prepared_ = true;
}

void RingPass::recordDraw(VkCommandBuffer cmd, vk::GpuTimer* timer) {
  if (!prepared_) throw Error("RingPass::recordDraw before prepare: no frame to draw");
  drawn_ = !edgeOn_;
  if (!drawn_) return;
  if (timer) timer->begin(cmd, "rings");
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 1, &sets_[slot_], 0, nullptr);
  vkCmdDraw(cmd, gpu::kRingVertexCount, 1, 0, 0);
  if (timer) timer->end(cmd);
}

}  // namespace planet
