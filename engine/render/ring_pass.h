// A planetary ring (issue 8, points 2 and 3; seed 001 §4.5): a disc in the ringed body's
// equatorial plane whose opacity and colour come from 1D noise of the radius
// (shaders/common/rings.glsl), lit by the sun from either side, shadowed by the body, drawn
// transparent (premultiplied "over") into the HDR colour target after the opaque bodies: depth
// tested against them, no face culled, its depth written where it is not nearly clear
// (kRingMinAlpha). With the body's sky tables it also applies the body's air that lies between
// the camera and the ring (shaders/ring.frag explains why that composes right when the ring is
// drawn after that atmosphere).
//
// The ring's own shadow on the body is ringShadow in shaders/common/rings.glsl (CPU:
// ringShadowCpu, reference/ring_density.h), for the body's shader to call with the same
// gpu::RingParams (ringGpuParams).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "reference/atmosphere_model.h"
#include "reference/eclipse.h"
#include "planet/ring_description.h"
#include "reference/ring_density.h"
#include "shared/ring_params.h"
#include "shared/sky_params.h"
#include "vk/buffer.h"
#include "vk/owned.h"

namespace planet::vk {
class Context;
class GpuTimer;
}  // namespace planet::vk

namespace planet {

class SkyTables;

// One frame's view of the ring, in the ringed body's frame (the ring lies in its plane z = 0,
// centred on the origin).
struct RingView {
  // Camera-relative body-frame position (w = 1) → clip space (reversed Z, e.g. reversedZPerspective
  // · viewMatrix): clip = viewProjection · (p_body − cameraBody, 1).
  glm::dmat4 viewProjection{1.0};
  glm::dvec3 cameraBody{0.0, 0.0, 1.0e9};  // camera position, body frame, metres
  glm::dvec3 sunBody{0.0, 0.0, 1.0};       // toward the sun, body frame (normalised by prepare)
  double planetRadiusM = 5.8232e7;         // the body the ring circles: casts its shadow on the ring
  double nearPlaneM = 1.0;                 // viewProjection's near plane
  // The viewport the draw is recorded with: at (0, 0), this many pixels. The fragment shader
  // turns gl_FragCoord into the pixel's view ray with it.
  uint32_t width = 960;
  uint32_t height = 540;
  double sunIrradiance = gpu::kSunIrradiance;  // as the terrain's (TerrainSettings::sunIntensity scales it)
  double ambient = 0.01;                       // fill light, share of the irradiance (as TerrainSettings::ambient)
  double sunAngularRadiusRad = kSunAngularRadiusRad;  // penumbrae of both shadows
  // A scene's other bodies, which may hide the sun from the ring (eclipses): centres relative to
  // the camera, body frame.
  std::vector<Occluder> occluders;
  // The body's air (a pass made with sky tables of a body with an atmosphere): the sun at the
  // body's distance as a share of the tables' irradiance (as SkyView::sunIrradianceScale), and
  // the sphere (m above planetRadiusM) where a ray that passes the limb meets the ground.
  double sunIrradianceScale = 1.0;
  double groundSphereM = 0.0;
};

class RingPass {
 public:
  // Timing scopes a frame records at most: "rings".
  static constexpr uint32_t kTimingScopes = 1;

  // Validates the description and creates the per-slot uniform buffers and the pipeline, which
  // is compatible with a dynamic-rendering scope of colorFormat and depthFormat (VK_FORMAT_UNDEFINED:
  // none; then nothing hides the ring). `air` (optional; must outlive the pass, built before the
  // first draw): the ringed body's sky tables; when its atmosphere is enabled, the ring is seen
  // through the part of it in front (ring_air.frag), else the air is left out.
  RingPass(vk::Context& context, const RingDescription& ring, VkFormat colorFormat, VkFormat depthFormat,
           const SkyTables* air = nullptr);

  // CPU half of a frame: the uniforms, in double until they are camera-relative, into frame slot
  // `slot`'s host-visible buffer (< vk::kFramesInFlight): call it while no frame recorded for
  // that slot is executing. Throws planet::Error for a bad slot or view (a non-finite or singular
  // matrix, camera or sun, a radius, near plane or viewport that is not positive).
  void prepare(const RingView& view, uint32_t slot = 0);
  // Records the draw of the last prepared frame, inside an active dynamic-rendering scope with
  // the viewport and scissor set (the viewport as RingView::width × height at (0, 0)). Nothing is
  // drawn while the camera lies in the ring plane (within 1/1000 of the near plane): the disc
  // is edge-on and has no area. `timer` (optional) gets a scope "rings".
  // Throws planet::Error before the first prepare().
  void recordDraw(VkCommandBuffer cmd, vk::GpuTimer* timer);

  const RingDescription& description() const { return ring_; }
  // Whether the pass applies the body's air (made with tables of a body with an atmosphere).
  bool hasAir() const { return air_ != nullptr; }
  // The last prepared frame's block (ring: ringGpuParams of the description and the view).
  const gpu::RingUniforms& uniforms() const { return uniformData_; }
  // Whether the last recordDraw drew anything.
  bool drawn() const { return drawn_; }

 private:
  vk::Context& context_;
  RingDescription ring_;
  const SkyTables* air_ = nullptr;  // null: no air to apply
  // In the order of creation (destroyed in reverse).
  vk::Owned<vk::Buffer> uniforms_[vk::kFramesInFlight];
  vk::Owned<VkDescriptorSetLayout> setLayout_;
  vk::Owned<VkDescriptorPool> pool_;
  VkDescriptorSet sets_[vk::kFramesInFlight] = {};  // from pool_, each points at its slot's buffer
  vk::Owned<VkPipelineLayout> layout_;
  vk::Owned<VkPipeline> pipeline_;

  gpu::RingUniforms uniformData_{};
  bool prepared_ = false;
  bool edgeOn_ = false;
  bool drawn_ = false;
  uint32_t slot_ = 0;  // of the last prepare()
};

}  // namespace planet
