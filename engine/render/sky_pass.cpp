#include "render/sky_pass.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include <fmt/format.h>

#include "core/error.h"
#include "render/sky_tables.h"
#include "spv/aerial_perspective.comp.h"
#include "spv/sky.comp.h"
#include "spv/sky_camera_transmittance.comp.h"
#include "spv/sky_classify.comp.h"
#include "spv/sky_cloud_classify.comp.h"
#include "spv/sky_cloud_shadow.comp.h"
#include "spv/sky_clouds.comp.h"
#include "spv/sky_reference.comp.h"
#include "spv/sky_view.comp.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/pipeline.h"
#include "vk/timer.h"

namespace planet {
namespace {

// Both sets' binding 0 is the per-frame values, a uniform buffer that the shaders reach through
// an array of one (why: shaders/sky_uniforms.glsl).
static_assert(gpu::kSkyBindingUniforms == 0 && gpu::kSkyTableBindingUniforms == 0,
              "shaders/sky_uniforms.glsl declares SkyUniforms at binding 0 of every sky pass");
constexpr VkDescriptorType kComposeBindings[] = {
    VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,          // per-frame values (SkyUniforms)
    VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,           // HDR colour
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // depth
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // transmittance
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // cloud cover
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // multiple scattering (reference)
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // sky view
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // aerial light
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // aerial transmittance
    VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,           // cloud light (the cloud pass writes it, the compose reads it)
    VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,           // cloud end (likewise)
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,  // the tiles by class (the classify pass writes them, the compose reads them)
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // the camera's transmittance
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // the clouds' shadow table (the compose and the cloud pass read it)
    VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,           // the same (its build writes it)
};
static_assert(std::size(kComposeBindings) == gpu::kSkyBindingCloudShadowTarget + 1,
              "one descriptor type per compose binding");

// The per-frame table builds (sky_view.comp, aerial_perspective.comp, sky_camera_transmittance.comp):
// one layout for all.
constexpr VkDescriptorType kTableBindings[] = {
    VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,          // per-frame values (SkyUniforms)
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // transmittance
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // multiple scattering
    VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,           // sky view
    VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,           // aerial light
    VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,           // aerial transmittance
    VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,           // the camera's transmittance
};
static_assert(std::size(kTableBindings) == gpu::kSkyTableBindingCameraTransmittance + 1,
              "one descriptor type per table binding");

// The camera's transmittance table's build runs whole workgroups, one row each invocation.
static_assert(gpu::kCameraTransmittanceDirections % gpu::kCameraTransmittanceWorkgroup == 0,
              "the camera's transmittance table's rows fill its build's workgroups");

// The cloud pass's images (shaders/shared/sky_params.h, kSkyBindingCloudLight and kSkyBindingCloudEnd):
// distances need float's range and precision; light and transmittance do with half floats, the
// light scaled by gpu::kSkyHalfLightScale (deep twilight's is below a half float's normals).
constexpr VkFormat kCloudLightFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kCloudEndFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
// The clouds' shadow table: one density per texel, written, then filtered.
constexpr VkFormat kCloudShadowFormat = VK_FORMAT_R32_SFLOAT;

// The sky-view table holds radiance in float (192 × 108 texels: the format's cost does not show);
// the aerial volume does with half floats, its light scaled by gpu::kSkyHalfLightScale.
constexpr VkFormat kTableFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kAerialFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkImageUsageFlags kTableUsage =
    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;

// The tile classifiers' push constant (shaders/sky_tile_classes.glsl).
struct ClassifyPush {
  uint32_t tilesX, tilesY;            // the compose region's tiles
  uint32_t cloudTilesX, cloudTilesY;  // the cloud region's
  uint32_t classes;                   // bit c set: tiles may be of class c (else they are mixed, or marched)
  uint32_t checkAirExit;              // 1: a tile is of the ground's classes only if its rays end inside the air
};

}  // namespace

void validateSkySettings(const SkySettings& settings) {
  if (settings.viewSamples < 2 || settings.viewSamples > 256)
    throw Error(fmt::format("atmosphere samples {} are outside 2..256", settings.viewSamples));
  if (!(settings.exposure > 0.0 && std::isfinite(settings.exposure)))
    throw Error(fmt::format("exposure {} must be a positive number", settings.exposure));
  if (settings.cloudScale > 2)
    throw Error(fmt::format("cloud pass scale {} is not 0 (by the view), 1 or 2", settings.cloudScale));
}

uint32_t cloudPassScale(double aboveCloudsM, double coverTexelM, double pixelAngleRad) {
  // A cover texel straight below spans coverTexelM / (aboveCloudsM · pixelAngleRad) pixels.
  if (aboveCloudsM <= 0.0) return 2;
  return coverTexelM >= kHalfResolutionTexelPixels * aboveCloudsM * pixelAngleRad ? 2 : 1;
}

PixelRect unite(const PixelRect& a, const PixelRect& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

PixelRect coneScreenRect(const glm::dmat4& viewProjection, const glm::dvec3& axis, double halfAngleRad, uint32_t width,
                         uint32_t height) {
  const PixelRect whole{0, 0, width, height};
  if (!(halfAngleRad < 0.5 * std::numbers::pi - 1e-6)) return whole;
  // The polygon of kSides sides around the cone's circle at unit distance along the axis (its
  // vertices 1 / cos(π / kSides) out, so the circle is inscribed), in clip coordinates (linear in
  // the point), cut to the part in front of the camera (w ≥ kFront: what the cut leaves out
  // projects far outside any image). Projected from the camera, that convex polygon holds the
  // projection of every ray of the cone in front of the camera, and its bounding box is its
  // vertices'.
  constexpr int kSides = 32;
  constexpr double kFront = 1e-6;
  const glm::dvec3 u =
      glm::normalize(glm::cross(axis, std::abs(axis.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0)));
  const glm::dvec3 v = glm::cross(axis, u);
  const double reach = std::tan(halfAngleRad) / std::cos(std::numbers::pi / kSides);
  std::vector<glm::dvec4> polygon;
  for (int k = 0; k < kSides; ++k) {
    const double t = 2.0 * std::numbers::pi * k / kSides;
    polygon.push_back(viewProjection * glm::dvec4(axis + reach * (std::cos(t) * u + std::sin(t) * v), 1.0));
  }
  std::vector<glm::dvec4> front;
  for (size_t k = 0; k < polygon.size(); ++k) {
    const glm::dvec4& a = polygon[k];
    const glm::dvec4& b = polygon[(k + 1) % polygon.size()];
    if (a.w >= kFront) front.push_back(a);
    if ((a.w >= kFront) != (b.w >= kFront)) front.push_back(a + (b - a) * ((kFront - a.w) / (b.w - a.w)));
  }
  if (front.empty()) return {};
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const glm::dvec4& clip : front) {
    // As the sky passes map pixels to clip space (sky_compose.glsl, viewRay): ndc = 2 p / extent − 1.
    const double px = 0.5 * (clip.x / clip.w + 1.0) * width, py = 0.5 * (clip.y / clip.w + 1.0) * height;
    x0 = std::min(x0, px);
    y0 = std::min(y0, py);
    x1 = std::max(x1, px);
    y1 = std::max(y1, py);
  }
  const auto clampTo = [](double value, uint32_t size) { return uint32_t(std::clamp(value, 0.0, double(size))); };
  constexpr double kMarginPixels = 2.0;
  const PixelRect rect{clampTo(std::floor(x0 - kMarginPixels), width), clampTo(std::floor(y0 - kMarginPixels), height),
                       clampTo(std::ceil(x1 + kMarginPixels), width), clampTo(std::ceil(y1 + kMarginPixels), height)};
  return rect.empty() ? PixelRect{} : rect;
}

std::string_view skyModeName(SkyMode mode) { return mode == SkyMode::Reference ? "reference" : "tables"; }

SkyMode parseSkyMode(std::string_view name) {
  if (name == "tables") return SkyMode::Tables;
  if (name == "reference") return SkyMode::Reference;
  throw Error(fmt::format("sky mode '{}' is not tables or reference", name));
}

SkyPass::SkyPass(vk::Context& context, const PlanetDescription& planet, const SkyTables& tables,
                 const SkySettings& settings, bool eclipses)
    : context_(context), planet_(planet), airglow_(makeAirglowParams(planet)), tables_(tables), settings_(settings) {
  specialization_[0][0] = specialization_[1][0] = eclipses ? 1u : 0u;
  validateSkySettings(settings);
  vk::requireFormatFeatures(context, kTableFormat,
                            VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT,
                            "the sky-view table (written, then filtered)");
  vk::requireFormatFeatures(context, kCloudShadowFormat,
                            VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT,
                            "the clouds' shadow table (written, then filtered)");
  for (vk::Owned<vk::Buffer>& uniforms : uniforms_)
    uniforms = {context, vk::createBuffer(context, sizeof(gpu::SkyUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                          vk::MemoryUsage::Upload)};
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = info.minFilter = VK_FILTER_NEAREST;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  depthSampler_ = {context, vk::createSampler(context, info)};

  setLayout_ = {context, vk::createSetLayout(context, kComposeBindings, VK_SHADER_STAGE_COMPUTE_BIT)};
  pool_ = {context, vk::createDescriptorPool(context, kComposeBindings, vk::kFramesInFlight)};
  layout_ = {context, vk::createPipelineLayout(context, setLayout_.get(), 0, 0)};
  skyView_ = {context,
              vk::createImage2D(context, {gpu::kSkyViewWidth, gpu::kSkyViewHeight}, kTableFormat, kTableUsage)};
  // The aerial-perspective volume: the camera's slice (no air) and kAerialSize more
  // (shaders/aerial_perspective.comp), 3D so that the compose filters between slices in one read.
  aerialLight_ = {context, vk::createImage3D(context, {gpu::kAerialSize, gpu::kAerialSize}, gpu::kAerialSize + 1,
                                             kAerialFormat, kTableUsage)};
  aerialTransmittance_ = {context, vk::createImage3D(context, {gpu::kAerialSize, gpu::kAerialSize},
                                                     gpu::kAerialSize + 1, kAerialFormat, kTableUsage)};
  // The camera's transmittance table (shaders/sky_camera_transmittance.comp): optical depth in
  // float, filtered (the sky-view table's format).
  cameraTransmittance_ = {
      context, vk::createImage2D(context, {gpu::kCameraTransmittanceDistances, gpu::kCameraTransmittanceDirections},
                                 kTableFormat, kTableUsage)};
  cloudShadow_ = {context, vk::createImage2D(context, {gpu::kCloudShadowTableSize, gpu::kCloudShadowTableSize},
                                             kCloudShadowFormat, kTableUsage)};
  tableSetLayout_ = {context, vk::createSetLayout(context, kTableBindings, VK_SHADER_STAGE_COMPUTE_BIT)};
  tablePool_ = {context, vk::createDescriptorPool(context, kTableBindings, vk::kFramesInFlight)};
  tableLayout_ = {context, vk::createPipelineLayout(context, tableSetLayout_.get(), 0, 0)};
  constexpr VkImageLayout kGeneral = VK_IMAGE_LAYOUT_GENERAL;
  constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  for (uint32_t slot = 0; slot < vk::kFramesInFlight; ++slot) {
    VkDescriptorSet set = sets_[slot] = vk::allocateSet(context, pool_.get(), setLayout_.get());
    vk::writeBufferDescriptor(context, set, gpu::kSkyBindingUniforms, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                              *uniforms_[slot]);
    vk::writeImageDescriptor(context, set, gpu::kSkyBindingTransmittance, kSampled, tables.transmittanceView(),
                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, tables.sampler());
    vk::writeImageDescriptor(context, set, gpu::kSkyBindingClouds, kSampled, tables.clouds().view(),
                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, tables.clouds().sampler());
    vk::writeImageDescriptor(context, set, gpu::kSkyBindingMultipleScattering, kSampled,
                             tables.multipleScatteringView(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                             tables.sampler());
    vk::writeImageDescriptor(context, set, gpu::kSkyBindingSkyView, kSampled, skyView_->view, kGeneral,
                             tables.sampler());
    vk::writeImageDescriptor(context, set, gpu::kSkyBindingAerialLight, kSampled, aerialLight_->view, kGeneral,
                             tables.sampler());
    vk::writeImageDescriptor(context, set, gpu::kSkyBindingAerialTransmittance, kSampled, aerialTransmittance_->view,
                             kGeneral, tables.sampler());
    vk::writeImageDescriptor(context, set, gpu::kSkyBindingCameraTransmittance, kSampled, cameraTransmittance_->view,
                             kGeneral, tables.sampler());
    vk::writeImageDescriptor(context, set, gpu::kSkyBindingCloudShadowTable, kSampled, cloudShadow_->view, kGeneral,
                             tables.sampler());
    vk::writeImageDescriptor(context, set, gpu::kSkyBindingCloudShadowTarget, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                             cloudShadow_->view, kGeneral);

    VkDescriptorSet tableSet = tableSets_[slot] = vk::allocateSet(context, tablePool_.get(), tableSetLayout_.get());
    vk::writeBufferDescriptor(context, tableSet, gpu::kSkyTableBindingUniforms, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                              *uniforms_[slot]);
    vk::writeImageDescriptor(context, tableSet, gpu::kSkyTableBindingTransmittance, kSampled,
                             tables.transmittanceView(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, tables.sampler());
    vk::writeImageDescriptor(context, tableSet, gpu::kSkyTableBindingMultipleScattering, kSampled,
                             tables.multipleScatteringView(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                             tables.sampler());
    vk::writeImageDescriptor(context, tableSet, gpu::kSkyTableBindingSkyView, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                             skyView_->view, kGeneral);
    vk::writeImageDescriptor(context, tableSet, gpu::kSkyTableBindingAerialLight, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                             aerialLight_->view, kGeneral);
    vk::writeImageDescriptor(context, tableSet, gpu::kSkyTableBindingAerialTransmittance,
                             VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, aerialTransmittance_->view, kGeneral);
    vk::writeImageDescriptor(context, tableSet, gpu::kSkyTableBindingCameraTransmittance,
                             VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cameraTransmittance_->view, kGeneral);
  }
  makePipelines();
}

bool SkyPass::cloudsDrawn() const { return settings_.clouds && planet_.clouds.enabled && planet_.atmosphere.enabled; }

void SkyPass::makePipelines() { makePipelines(cloudsDrawn()); }

void SkyPass::prepareAllPipelines() {
  makePipelines(false);
  if (planet_.clouds.enabled && planet_.atmosphere.enabled) makePipelines(true);
}

void SkyPass::makePipelines(bool clouds) {
  const uint32_t* constants = specialization_[clouds ? 1 : 0];
  // sky.comp's kSpecAirglow (constant 3).
  const uint32_t airglow = airglow_.radiance.w > 0.5f ? 1u : 0u;
  // The sky-view table in every mode: the sea mirrors it (TerrainPass::setSkyView).
  if (!skyViewBuild_.get())
    skyViewBuild_ = {context_, vk::createComputePipelineWithLayout(context_, kSpv_sky_view_comp, tableLayout_.get())};
  if (settings_.mode == SkyMode::Tables) {
    for (uint32_t above = 0; above < 2; ++above) {
      if (aerialBuild_[above].get()) continue;
      // Specialized on the eclipses (constant 0, as the compose's), its steps per slice and the side.
      const uint32_t aerialConstants[] = {specialization_[0][0],
                                          above ? gpu::kAerialStepsPerSliceAbove : gpu::kAerialStepsPerSlice, above};
      aerialBuild_[above] = {context_, vk::createComputePipelineWithLayout(context_, kSpv_aerial_perspective_comp,
                                                                           tableLayout_.get(), aerialConstants)};
    }
    if (!cameraTransmittanceBuild_.get())
      cameraTransmittanceBuild_ = {context_, vk::createComputePipelineWithLayout(
                                                 context_, kSpv_sky_camera_transmittance_comp, tableLayout_.get())};
    if (!classify_.get()) {
      classifyLayout_ = {context_, vk::createPipelineLayout(context_, setLayout_.get(), sizeof(ClassifyPush),
                                                            VK_SHADER_STAGE_COMPUTE_BIT)};
      classify_ = {context_,
                   vk::createComputePipelineWithLayout(context_, kSpv_sky_classify_comp, classifyLayout_.get())};
    }
    for (uint32_t tileClass = 0; tileClass < gpu::kSkyTileClasses; ++tileClass) {
      if (tablesCompose_[clouds][tileClass].get()) continue;
      const uint32_t classConstants[] = {constants[0], constants[1], tileClass, airglow};
      tablesCompose_[clouds][tileClass] = {
          context_, vk::createComputePipelineWithLayout(context_, kSpv_sky_comp, layout_.get(), classConstants)};
    }
    if (clouds && !cloudsPass_[0].get()) {
      cloudClassify_ = {
          context_, vk::createComputePipelineWithLayout(context_, kSpv_sky_cloud_classify_comp, classifyLayout_.get())};
      for (uint32_t list = 0; list < kCloudTileClasses; ++list) {
        const uint32_t cloudConstants[] = {constants[0], constants[1], gpu::kSkyCloudTileMarch + list};
        cloudsPass_[list] = {context_, vk::createComputePipelineWithLayout(context_, kSpv_sky_clouds_comp,
                                                                           layout_.get(), cloudConstants)};
      }
      cloudShadowBuild_ = {context_,
                           vk::createComputePipelineWithLayout(context_, kSpv_sky_cloud_shadow_comp, layout_.get())};
    }
  }
  if (settings_.mode == SkyMode::Reference && !referenceCompose_[clouds].get()) {
    const uint32_t referenceConstants[] = {constants[0], constants[1], gpu::kSkyTileMixed, airglow};
    referenceCompose_[clouds] = {context_, vk::createComputePipelineWithLayout(context_, kSpv_sky_reference_comp,
                                                                               layout_.get(), referenceConstants)};
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
  // The targets' size: the cloud pass runs at full resolution from far away (cloudPassScale).
  const VkExtent2D extent{width_, height_};
  cloudLight_.reset();
  cloudEnd_.reset();
  cloudLight_ = {context_, vk::createImage2D(context_, extent, kCloudLightFormat, VK_IMAGE_USAGE_STORAGE_BIT)};
  cloudEnd_ = {context_, vk::createImage2D(context_, extent, kCloudEndFormat, VK_IMAGE_USAGE_STORAGE_BIT)};
  cloudImagesInitialised_ = false;
  // The tile lists: room for every tile of the image in each class (the cloud pass has no more
  // tiles than the compose: at most a sample per pixel), and each compose tile's depth.
  const uint32_t group = gpu::kSkyWorkgroupSize;
  tileCapacity_ = ((width_ + group - 1) / group) * ((height_ + group - 1) / group);
  tiles_.reset();
  tiles_ = {context_,
            vk::createBuffer(context_, kTileHeaderBytes + VkDeviceSize(gpu::kSkyTileLists + 1) * tileCapacity_ * 4,
                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                                 VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                             vk::MemoryUsage::DeviceLocal)};
  for (VkDescriptorSet set : sets_) {
    vk::writeBufferDescriptor(context_, set, gpu::kSkyBindingTiles, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, *tiles_);
    vk::writeImageDescriptor(context_, set, gpu::kSkyBindingCloudLight, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                             cloudLight_->view, VK_IMAGE_LAYOUT_GENERAL);
    vk::writeImageDescriptor(context_, set, gpu::kSkyBindingCloudEnd, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cloudEnd_->view,
                             VK_IMAGE_LAYOUT_GENERAL);
  }
}

double SkyPass::skyViewAltitudeToleranceM(double radiusM, double altitudeM) {
  const double r = radiusM + std::max(altitudeM, 0.0);
  return std::max(kSkyViewHorizonToleranceRad * r * std::sqrt(r * r - radiusM * radiusM) / radiusM,
                  kSkyViewAltitudeSlackM);
}

void SkyPass::setSettings(const SkySettings& settings) {
  validateSkySettings(settings);
  settings_ = settings;
  makePipelines();
  skyViewBuiltFor_.reset();
  cameraTransmittanceBuiltFor_.reset();
}

void SkyPass::prepare(const SkyView& view, uint32_t width, uint32_t height, uint32_t slot) {
  vk::checkFrameSlot(slot);
  slot_ = slot;
  gpu::SkyUniforms& u = uniformData_;
  u = gpu::SkyUniforms{};
  u.atmosphere = tables_.atmosphere();
  u.airglow = airglow_;
  u.atmosphere.radii.z = float(view.sunAngularRadiusRad);
  u.atmosphere.ozoneSun.y *= float(view.sunIrradianceScale);
  u.clipToLocal = glm::mat4(glm::inverse(view.viewProjection));
  u.localToPlanet = glm::mat4(glm::mat3(view.localToPlanet));
  u.camera = glm::vec4(float(view.altitudeM), float(view.nearPlaneM), 0.0f, float(view.timeS));
  u.forward = glm::vec4(glm::vec3(view.forward), float(settings_.viewSamples));
  u.sunLocal = glm::vec4(glm::vec3(view.sunLocal), float(planet_.stars.brightness));
  const bool clouds = cloudsDrawn();
  u.cameraPlanet = glm::vec4(glm::vec3(view.cameraPlanet), clouds ? 1.0f : 0.0f);
  u.eclipse = eclipseGpuParams(view.occluders, glm::transpose(view.localToPlanet), view.sunAngularRadiusRad);
  tables_.clouds().writeUniforms(u, view.timeS);
  cloudScale_ = settings_.cloudScale != 0
                    ? settings_.cloudScale
                    : cloudPassScale(view.altitudeM - planet_.clouds.topM, double(u.cloudShape.x) * planet_.radiusM,
                                     view.pixelAngleRad);
  u.cloudShape.w = float(cloudScale_);
  // Where the compose runs: the pixels whose rays can meet the air (from above its top, the cone
  // it fills around the nadir; from inside, all) and the sun's disc (its smooth edge reaches
  // 1.2 of its radius). Elsewhere a ray meets no air and no cloud, and the pixel keeps what was
  // drawn (the stars, a scene's other bodies): from orbit that is most of the image.
  PixelRect region;
  if (u.atmosphere.radii.w > 0.5f) {
    const double top = planet_.radiusM + planet_.atmosphere.heightM, distance = planet_.radiusM + view.altitudeM;
    region = distance > top ? coneScreenRect(view.viewProjection, glm::dvec3(0.0, 0.0, -1.0), std::asin(top / distance),
                                             width, height)
                            : PixelRect{0, 0, width, height};
  }
  if (!settings_.regions) region = PixelRect{0, 0, width, height};
  if (view.drawSun)
    region = unite(region,
                   coneScreenRect(view.viewProjection, view.sunLocal, 1.5 * view.sunAngularRadiusRad, width, height));
  // The dispatch's whole workgroups run the compose (up to the image's edge): all of them read
  // the cloud samples below.
  const uint32_t group = gpu::kSkyWorkgroupSize;
  if (!region.empty()) {
    region.x1 = std::min(region.x0 + (region.width() + group - 1) / group * group, width);
    region.y1 = std::min(region.y0 + (region.height() + group - 1) / group * group, height);
  }
  composeRegion_ = region;
  ownSurfacesOnly_ = view.ownSurfacesOnly;
  // The cloud pass's samples that the compose's pixels read (each pixel the four around it).
  const uint32_t samplesX = (width + cloudScale_ - 1) / cloudScale_,
                 samplesY = (height + cloudScale_ - 1) / cloudScale_;
  cloudRegion_ = region.empty() ? PixelRect{}
                                : PixelRect{region.x0 / cloudScale_ - std::min(region.x0 / cloudScale_, 1u),
                                            region.y0 / cloudScale_ - std::min(region.y0 / cloudScale_, 1u),
                                            std::min((region.x1 + cloudScale_ - 1) / cloudScale_ + 1, samplesX),
                                            std::min((region.y1 + cloudScale_ - 1) / cloudScale_ + 1, samplesY)};
  u.region =
      glm::vec4(float(composeRegion_.x0), float(composeRegion_.y0), float(cloudRegion_.x0), float(cloudRegion_.y0));
  // Below the cloud layer the whole image shows air, so both regions start at its corner and a
  // cloud tile's pixels are those of whole compose tiles (sky_cloud_classify.comp).
  clearCloudTiles_ = settings_.tileClasses && clouds && view.altitudeM < planet_.clouds.bottomM &&
                     composeRegion_.x0 == 0 && composeRegion_.y0 == 0 && cloudRegion_.x0 == 0 && cloudRegion_.y0 == 0;
  for (int k = 0; k < kSkyIrradianceSamples; ++k)
    u.skyIrradiance[k] = tables_.skyIrradiance()[size_t(k)] * float(view.sunIrradianceScale);
  u.extent = glm::vec4(float(width), float(height), float(view.pixelAngleRad), view.drawSun ? 1.0f : 0.0f);
  const double lowest = planet_.hasOcean ? planet_.seaLevelM : view.lowestSurfaceM;
  // The sphere a ray that met no geometry ends on: the radius sphere under a sea; without one,
  // the deepest terrain when that is below it (basins seen past the radius sphere's horizon).
  const double groundSphere = planet_.hasOcean ? 0.0 : std::min(lowest, 0.0);
  u.surface = glm::vec4(float(lowest), planet_.hasOcean ? 1.0f : 0.0f, float(groundSphere), 0.0f);
  if (clearCloudTiles_) u.cloudShadowTable = cloudShadowSquare(view, lowest);
  // The aerial-perspective slices (shaders/sky_aerial.glsl): from inside the air, out to the
  // farthest distance at which the volume is read. That is where a ray past the ground sphere's
  // horizon leaves the air; but when nothing is drawn in the air but this body's own ground, sea
  // and clouds (ownSurfacesOnly), only where the highest of them passes out of view beyond the
  // horizon: the volume serves drawn surfaces only (the sky reads the sky-view table), and its
  // slices, gathered toward the camera, then sit closer: from 10 km up 700 km instead of 1,490,
  // from the ground 340 instead of 1,140. A slice near the camera was long next to the haze's
  // scale height (from 10 km up the fourth ran from 23 to 36 km), and the light filtered by
  // distance between slices fell short of the march by up to 7 of 255 on the sea at sunset, in
  // bands at the slices.
  const double radius = planet_.radiusM, top = planet_.atmosphere.heightM;
  const double altitude = std::max(view.altitudeM, groundSphere);
  const bool above = view.altitudeM >= top;
  above_ = above;
  const double toHorizon = std::sqrt((altitude - groundSphere) * (2.0 * radius + altitude + groundSphere));
  const double highest =
      view.ownSurfacesOnly ? std::min(std::max(view.highestSurfaceM, clouds ? planet_.clouds.topM : 0.0), top) : top;
  const double horizonToTop =
      std::sqrt(std::max(highest - groundSphere, 0.0) * (2.0 * radius + highest + groundSphere));
  // The ground's compose tiles clear of the clouds: sorted with the cloud tiles, which start at
  // the same corner; their pipeline reads the aerial volume as from inside the air.
  // The ground's tiles: when the depth may hold surfaces past the air's far side (another body,
  // a ring, terrain whose bound reaches above the top), only from inside the air, tile by tile
  // where the classify passes show that no ray of the tile leaves the air (sky_tile_classes.glsl,
  // composeTileInsideAir; from above, a ray crosses the air before it meets anything).
  groundTiles_ = ownSurfacesOnly_ || !above;
  clearGroundTiles_ = clearCloudTiles_ && !above;
  // The zenith angle of the ground sphere's horizon, as skyViewZenithRange finds it (from inside the
  // air its range starts at the zenith): the ground's half of the sky-view table's rows.
  const double horizonZenith = std::atan2(radius + std::min(groundSphere, view.altitudeM), -toHorizon);
  u.aerial = glm::vec4(above ? 1.0f : 0.0f, float(std::max(toHorizon + horizonToTop, 1.0)), float(horizonZenith),
                       float(std::cos(horizonZenith)));
  // The camera's transmittance table (from inside the air): built again only when the air changed,
  // the altitude moved beyond the sky-view table's tolerance (2.5 m at 50 m, 16 m at 2 km: 1.3 %
  // of the haze's 1.2 km scale height, by which the haze's optical depths change), or the slices'
  // reach by more than kCameraTransmittanceReachTolerance. A kept table is read with its own
  // mapping. Its reach grows with the altitude (a tolerance higher at 50 m: 0.05 %); a read past
  // it clamps to its last texel, where the rays have left the air or run at the highest surface's
  // altitude, along 0.1 % of their length at most.
  const AirAndAltitude air{u.atmosphere, view.altitudeM};
  if (above) {
    cameraTransmittanceBuiltFor_.reset();
    buildCameraTransmittance_ = false;
  } else {
    const CameraTransmittanceInputs inputs{air, u.aerial.y, u.aerial.w};
    const CameraTransmittanceInputs* kept = cameraTransmittanceBuiltFor_ ? &*cameraTransmittanceBuiltFor_ : nullptr;
    buildCameraTransmittance_ = !kept || !kept->air.serves(air, planet_.radiusM) ||
                                std::abs(double(inputs.farthestM) - double(kept->farthestM)) >
                                    kCameraTransmittanceReachTolerance * double(kept->farthestM);
    if (buildCameraTransmittance_) cameraTransmittanceBuiltFor_ = inputs;
    u.camera.z = cameraTransmittanceBuiltFor_->farthestM;
    u.aerial.w = cameraTransmittanceBuiltFor_->muHorizon;
  }
  // The sky-view table: built again only when its inputs moved beyond the tolerances.
  const SkyViewInputs inputs{air, u.surface.z, u.sunLocal.z};
  const SkyViewInputs* built = skyViewBuiltFor_ ? &*skyViewBuiltFor_ : nullptr;
  buildSkyView_ = !built || !built->air.serves(air, planet_.radiusM) || built->groundSphereM != inputs.groundSphereM ||
                  std::abs(double(inputs.sunCosZenith) - double(built->sunCosZenith)) > kSkyViewSunTolerance;
  if (buildSkyView_) skyViewBuiltFor_ = inputs;
  // Host-visible: a plain copy, no submission (the slot's previous frame has completed).
  vk::uploadBuffer(context_, *uniforms_[slot], &u, sizeof(u));
}

bool SkyPass::AirAndAltitude::serves(const AirAndAltitude& frame, double radiusM) const {
  return std::memcmp(&atmosphere, &frame.atmosphere, sizeof(atmosphere)) == 0 &&
         std::abs(frame.altitudeM - altitudeM) <= skyViewAltitudeToleranceM(radiusM, altitudeM);
}

glm::vec4 SkyPass::cloudShadowSquare(const SkyView& view, double lowestM) const {
  const double radius = planet_.radiusM;
  const double r = radius + view.altitudeM;
  const double rMiddle = radius + 0.5 * (planet_.clouds.bottomM + planet_.clouds.topM);
  // The centre: where the sun's ray from the camera crosses the layer's middle (on the sphere's
  // horizon when the sun is below the camera's).
  const double mu = std::max(view.sunLocal.z, 0.0);
  const double toLayer = -r * mu + std::sqrt(std::max(r * r * mu * mu + rMiddle * rMiddle - r * r, 0.0));
  // The half side. The surfaces a ray that ends before the layer shows (the camera below its base)
  // lie inside the ball under the base and no lower than the lowest surface, on a straight ray from
  // the camera that stays above that: at most the horizon angles of the camera and of the base over
  // the lowest sphere from the nadir. The sun's ray from such a surface, at zenith angle θ there
  // (at most the camera's plus that angle, and below a right angle where it is lit), crosses the
  // layer's middle θ − asin(r sin θ / r_mid) further on (the triangle of the centre, the surface at
  // radius r and the crossing), most from the lowest surface. The table's square holds the sphere's
  // points out to the sum of both angles from the nadir (so also from its centre, the camera's own
  // crossing: the two crossings' offsets lie along the sun's direction, each at most the largest),
  // and one edge texel more (their centres lie half a texel in).
  constexpr double kRightAngle = 0.5 * std::numbers::pi;
  const double rLow = radius + std::min(lowestM, view.altitudeM);
  const double rBase = radius + planet_.clouds.bottomM;
  const double reach = std::acos(std::min(rLow / r, 1.0)) + std::acos(std::min(rLow / rBase, 1.0));
  const double sunZenith = std::min(std::acos(std::clamp(view.sunLocal.z, -1.0, 1.0)) + reach, kRightAngle);
  const double alongSun = sunZenith - std::asin(rLow * std::sin(sunZenith) / rMiddle);
  const double halfSide = rMiddle * std::sin(std::min(reach + alongSun, kRightAngle));
  // (The last texel's centre lies at u = 1 − 1 / size, x = c + s (1 − 1 / size)².)
  const double lastCentre = 1.0 - 1.0 / double(gpu::kCloudShadowTableSize);
  return glm::vec4(float(view.sunLocal.x * toLayer), float(view.sunLocal.y * toLayer),
                   float(halfSide / (lastCentre * lastCentre) * 1.001), 0.0f);
}

void SkyPass::recordSkyView(VkCommandBuffer cmd, vk::GpuTimer* timer) {
  const VkPipelineStageFlags2 compute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  // Its readers: the sea's fragments and the compose.
  const VkPipelineStageFlags2 readers = compute | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
  if (!buildSkyView_) return;  // the last table built still holds
  if (timer) timer->begin(cmd, "sky");
  if (!skyViewInitialised_) {
    // The table starts undefined and stays in GENERAL: written by the build, sampled after.
    vk::transitionImage(cmd, *skyView_, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, 0, compute,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    skyViewInitialised_ = true;
  } else {
    // The previous frame's readers (earlier on the queue) have read it before it is rewritten.
    vk::memoryBarrier(cmd, readers, 0, compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  }
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, tableLayout_.get(), 0, 1, &tableSets_[slot_], 0,
                          nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, skyViewBuild_.get());
  const uint32_t group = gpu::kSkyWorkgroupSize;
  vkCmdDispatch(cmd, (gpu::kSkyViewWidth + group - 1) / group, (gpu::kSkyViewHeight + group - 1) / group, 1);
  vk::memoryBarrier(cmd, compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, readers, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  if (timer) timer->end(cmd);
}

void SkyPass::recordCompose(VkCommandBuffer cmd, vk::GpuTimer* timer) {
  const uint32_t group = gpu::kSkyWorkgroupSize;
  const bool tables = settings_.mode == SkyMode::Tables;
  const VkPipelineStageFlags2 compute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  if (timer) timer->begin(cmd, tables ? "aerial" : "compose");
  if (!cloudImagesInitialised_) {
    // New images start undefined and stay in GENERAL, in every mode: the compose's descriptor set
    // names them (a compose without clouds still binds them, its reads specialized away).
    for (vk::Owned<vk::Image>* image : {&cloudLight_, &cloudEnd_, &cloudShadow_})
      vk::transitionImage(cmd, **image, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, 0, compute,
                          VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    cloudImagesInitialised_ = true;
  }
  if (tables) {
    if (!tablesInitialised_) {
      // The volume starts undefined and stays in GENERAL: written by the build, sampled after.
      for (vk::Owned<vk::Image>* image : {&aerialLight_, &aerialTransmittance_, &cameraTransmittance_})
        vk::transitionImage(cmd, **image, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, 0, compute,
                            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
      tablesInitialised_ = true;
    } else {
      // The previous frame's compose (earlier on the queue) has read the volume before it is rewritten.
      vk::memoryBarrier(cmd, compute, 0, compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    }
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, tableLayout_.get(), 0, 1, &tableSets_[slot_], 0,
                            nullptr);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, aerialBuild_[above_ ? 1 : 0].get());
    vkCmdDispatch(cmd, (gpu::kAerialSize + group - 1) / group, (gpu::kAerialSize + group - 1) / group, 1);
    if (buildCameraTransmittance_) {  // from inside the air, unless kept (from above, the volume's is read)
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cameraTransmittanceBuild_.get());
      vkCmdDispatch(cmd, gpu::kCameraTransmittanceDirections / gpu::kCameraTransmittanceWorkgroup, 1, 1);
    }
    // The cloud pass and the compose sample what the builds wrote.
    vk::memoryBarrier(cmd, compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, compute, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  }
  const bool clouds = cloudsDrawn();
  const uint32_t groupsX = (composeRegion_.width() + group - 1) / group,
                 groupsY = (composeRegion_.height() + group - 1) / group;
  if (tables) {
    // The cloud pass's and the compose's tiles sorted by class (sky_cloud_classify.comp,
    // sky_classify.comp); then each class run by its own pipeline, as many workgroups as the
    // class has tiles. The lists are emptied first, after the previous frame's passes (earlier
    // on the queue) have read them.
    if (timer) timer->next(cmd, clouds ? "clouds" : "compose");
    vk::memoryBarrier(cmd, compute | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, 0, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT);
    uint32_t header[kTileHeaderBytes / 4] = {};
    for (uint32_t list = 0; list < gpu::kSkyTileLists; ++list)
      header[4 * list + 1] = header[4 * list + 2] = 1;  // y and z of each list's dispatch
    header[3] = tileCapacity_;
    vkCmdUpdateBuffer(cmd, tiles_->buffer, 0, sizeof(header), header);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, compute,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, classify_.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, classifyLayout_.get(), 0, 1, &sets_[slot_], 0,
                            nullptr);
    uint32_t classes = 0;
    if (settings_.tileClasses) classes = (1u << gpu::kSkyTileSky) | (groundTiles_ ? 1u << gpu::kSkyTileAerial : 0u);
    if (clearCloudTiles_) classes |= 1u << gpu::kSkyCloudTileClear;
    if (clearGroundTiles_) classes |= 1u << gpu::kSkyTileAerialClear;
    // The ground's tiles whose rays all end well short of the ground sphere (kSkyTileNear): from
    // inside the air only, where the compose's aerial perspective reads the tables it leaves out.
    if (settings_.tileClasses && !above_) classes |= 1u << gpu::kSkyTileAerialNear;
    const uint32_t cloudGroupsX = (cloudRegion_.width() + group - 1) / group,
                   cloudGroupsY = (cloudRegion_.height() + group - 1) / group;
    const ClassifyPush push{groupsX, groupsY, cloudGroupsX, cloudGroupsY, classes, ownSurfacesOnly_ ? 0u : 1u};
    vkCmdPushConstants(cmd, classifyLayout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    // One invocation per tile.
    vkCmdDispatch(cmd, (groupsX + group - 1) / group, (groupsY + group - 1) / group, 1);
    if (clouds) {
      // From the compose tiles' depths.
      vk::memoryBarrier(cmd, compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, compute,
                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cloudClassify_.get());
      vkCmdDispatch(cmd, (cloudGroupsX + group - 1) / group, (cloudGroupsY + group - 1) / group, 1);
    }
    // (The classify's layout has a push constant, so the set is bound again for the passes'.)
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &sets_[slot_], 0, nullptr);
    if (clearCloudTiles_) {
      // The clouds' shadow table, for the tiles clear of the layer (the barrier below covers it).
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cloudShadowBuild_.get());
      const uint32_t shadowGroups = (gpu::kCloudShadowTableSize + group - 1) / group;
      vkCmdDispatch(cmd, shadowGroups, shadowGroups, 1);
    }
    vk::memoryBarrier(cmd, compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      compute | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT |
                          VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
    if (clouds) {
      // Only the samples the compose reads (prepare); none when nothing shows the air.
      for (uint32_t list = 0; list < kCloudTileClasses; ++list) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cloudsPass_[list].get());
        vkCmdDispatchIndirect(cmd, tiles_->buffer, VkDeviceSize(16) * (gpu::kSkyCloudTileMarch + list));
      }
      // The compose reads what the cloud pass wrote.
      vk::memoryBarrier(cmd, compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, compute,
                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
      if (timer) timer->next(cmd, "compose");
    }
    for (uint32_t tileClass = 0; tileClass < gpu::kSkyTileClasses; ++tileClass) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, tablesCompose_[clouds][tileClass].get());
      vkCmdDispatchIndirect(cmd, tiles_->buffer, VkDeviceSize(16) * tileClass);
    }
  } else {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, referenceCompose_[clouds].get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &sets_[slot_], 0, nullptr);
    vkCmdDispatch(cmd, groupsX, groupsY, 1);
  }
  if (timer) timer->end(cmd);
}

std::array<uint32_t, gpu::kSkyTileLists> SkyPass::readTileCounts() {
  uint32_t header[kTileHeaderBytes / 4] = {};
  vk::readbackBuffer(context_, *tiles_, header, sizeof(header));
  std::array<uint32_t, gpu::kSkyTileLists> counts{};
  for (uint32_t list = 0; list < gpu::kSkyTileLists; ++list) counts[list] = header[4 * list];
  return counts;
}

uint32_t SkyPass::groundTiles(const std::array<uint32_t, gpu::kSkyTileLists>& counts) {
  return counts[gpu::kSkyTileAerial] + counts[gpu::kSkyTileAerialClear] + counts[gpu::kSkyTileAerialNear] +
         counts[gpu::kSkyTileAerialClearNear];
}

namespace {

// A table's texels, left in GENERAL again for the builds and the compose.
std::vector<glm::vec4> readTable(vk::Context& context, vk::Image& table) {
  std::vector<glm::vec4> texels = vk::readbackRgbaFloat(context, table);
  vk::submitAndWait(context, [&](VkCommandBuffer cmd) {
    vk::transitionImage(cmd, table, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  });
  return texels;
}

}  // namespace

std::vector<glm::vec4> SkyPass::readSkyView() { return readTable(context_, *skyView_); }

std::vector<glm::vec4> SkyPass::readCameraTransmittance() { return readTable(context_, *cameraTransmittance_); }

}  // namespace planet
