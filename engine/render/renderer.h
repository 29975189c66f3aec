// Headless rendering of a planet into an offscreen target (issues 3 and 4): one frame is CPU
// preparation in double; compute (sky tables once, heights, normals, patch textures); the
// terrain and water draws into an HDR target with a reversed-Z float depth buffer; the sky
// compose pass (atmosphere, clouds, sun, star fading); with eye adaptation the luminance pass
// that measures the frame; the tonemap into an sRGB target, read back as RGBA8. Every pass is
// timed. The viewer records the same passes into its swapchain.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/image_file.h"
#include "planet/planet_description.h"
#include "planet/scene_description.h"
#include "camera/camera.h"
#include "camera/scene_view.h"
#include "render/exposure.h"
#include "render/sky_pass.h"
#include "render/terrain_pass.h"
#include "vk/image.h"
#include "vk/owned.h"
#include "vk/timer.h"

namespace planet::vk {
class Context;
}

namespace planet {

inline constexpr uint32_t kRenderMaxSize = 8192;   // per side
inline constexpr double kRenderMaxFovDeg = 179.0;  // vertical field of view, degrees
// A camera closer to the ground than this is raised to it (a person's eye height).
inline constexpr double kMinEyeHeightM = 1.7;

struct RenderSettings {
  uint32_t width = 960;
  uint32_t height = 540;
  double fovYDeg = 60.0;
  TerrainSettings terrain;
  SkySettings sky;
  // Eye adaptation (issue 21, point 4): the exposure from the frame's own luminance
  // (LuminancePass) instead of sky.exposure. (Which stars show does not depend on either: each
  // fades by its magnitude against the sky's radiance, common/star_visibility.glsl.)
  bool autoExposure = false;
};

// Throws planet::Error naming the first bad value (size 0 or above kRenderMaxSize, field of
// view outside (0, 179] degrees).
void validateRenderSettings(const RenderSettings& settings);

struct RenderResult {
  Rgba8Image image;            // the tonemapped frame (empty after setReadImage(false))
  std::vector<glm::vec4> hdr;  // the HDR frame before the tonemap (when asked for)
  TerrainFrameInfo terrain;
  std::vector<vk::GpuTiming> timings;  // per pass, in recording order
  std::optional<ExposureReport> exposure;  // with autoExposure: what the luminance pass measured and applied
  CameraPose camera;                   // as rendered (raised when it was below the ground)
  bool cameraRaised = false;
  // Wall clock of the frame's CPU preparation (render, renderScene: the terrain's LOD, culling
  // and uniforms, the sky's and the other passes'), before anything is recorded or submitted.
  double prepareMs = 0.0;
};

class LuminancePass;
class RingPass;
class SkyTables;
class StarPass;
class TonemapPass;

class Renderer {
 public:
  Renderer(vk::Context& context, const PlanetDescription& planet, const RenderSettings& settings);
  // A scene: one terrain (and atmosphere, when the preset has one, and rings) per body, drawn into one
  // frame with camera-relative positions and one depth buffer. The stars are those of the
  // first body whose preset has them, fixed in the scene frame.
  Renderer(vk::Context& context, const SceneDescription& scene, const RenderSettings& settings);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders one frame and reads it back. Frames of one Renderer form a sequence: the clipmap
  // orientation is carried from one to the next, and unchanged heights are not recomputed.
  // `timeS` is the animation phase (clouds, waves); `readHdr` also returns the HDR frame.
  RenderResult render(const CameraPose& camera, const SunPose& sun, double timeS = 0.0, bool readHdr = false);
  // Whether render() and renderScene() read the tonemapped frame back into RenderResult::image
  // (default: yes). A benchmark turns it off, so that its frame times are the frame's, as in the
  // viewer, without a copy to the host through a staging buffer (on an H200 the wall-clock frame
  // at 1080p was twice the GPU span, that copy part of the difference); the image is then empty.
  void setReadImage(bool read) { readImage_ = read; }

  // The two halves of render(), for a caller that records into its own command buffer (the
  // viewer), with up to kFramesInFlight frames in flight: frame slot `slot` (0 ..
  // kFramesInFlight − 1) owns its own copy of everything the CPU writes per frame (uniforms,
  // octave tables, patch-level parameters, CPU heights staging) and its own timestamp queries.
  // prepare(): the CPU half (eye-height rule, clipmap orientation, cuts, uniforms); `sunPlanet`
  // is the unit direction toward the sun in the planet frame. It may be called while the frame
  // of the other slot is still executing; it must not be called while a frame of the same slot
  // is (wait for that slot's fence first).
  // record(): every pass into `cmd` for the frame just prepared (same slot; no other prepare()
  // in between), ending with output() in COLOR_ATTACHMENT_OPTIMAL. Submit the command buffers
  // in the order of the record() calls, on the context's queue: the GPU-written resources the
  // slots share (heights, patch textures, targets) are ordered by that queue and the barriers.
  // Throws planet::Error for a slot outside 0 .. kFramesInFlight − 1 or a record() whose slot
  // is not the last prepared one.
  static constexpr uint32_t kFramesInFlight = vk::kFramesInFlight;
  struct Prepared {
    CameraPose camera;  // as rendered
    bool cameraRaised = false;
    TerrainFrameInfo terrain;
  };
  Prepared prepare(const CameraPose& camera, const glm::dvec3& sunPlanet, double timeS, uint32_t slot);
  // A scene frame (a Renderer built for that many bodies). The primary body, whose surface is
  // nearest the camera relative to its radius, applies the eye-height rule, gets the patch
  // textures and draws the sun's disc; the others are composed far to near before it.
  // Prepared::camera is the primary body's pose of the (possibly raised) camera.
  Prepared prepareScene(const SceneView& view, uint32_t slot);
  RenderResult renderScene(const SceneView& view, bool readHdr = false);
  void record(VkCommandBuffer cmd, uint32_t slot);
  // The tonemapped sRGB frame (RGBA8) that record() leaves (shared by the slots: the next
  // recorded frame rewrites it, so read it only when no frame is in flight), and the GPU times
  // of the passes of the last frame recorded for `slot` (read after its fence signalled; empty
  // without timestamps or before that slot's first frame).
  vk::Image& output() { return *color_; }
  std::vector<vk::GpuTiming> lastTimings(uint32_t slot) const;
  // When the last frame recorded for `slot` ended on the GPU's clock (ms; GpuTimer::lastStampMs),
  // to compare with another slot's: the interval between two frames' ends includes the time the
  // GPU waited for the later one's commands. Read after that slot's fence signalled; 0 without
  // timestamps or before the slot's first frame.
  double lastFrameEndMs(uint32_t slot) const;
  // With autoExposure: what the luminance pass measured and applied in the last frame recorded
  // for `slot` (read after its fence signalled; zeros before that slot's first frame). Without:
  // nothing.
  std::optional<ExposureReport> lastExposure(uint32_t slot) const;
  // New target size (the window was resized); the passes keep everything else. Call only
  // when no submitted frame still uses the targets.
  void resize(uint32_t width, uint32_t height);
  // Exposure, clouds and sky samples change without rebuilding (the compose pass reads them
  // per frame).
  void setSkySettings(const SkySettings& sky);
  // Eye adaptation on or off (RenderSettings::autoExposure), from the next record(). Turned on,
  // the first frame takes its own exposure outright.
  void setAutoExposure(bool enabled);
  // The next record() adapts the exposure toward its frame's over `seconds` of wall time from
  // the last frame's (the viewer, every frame); without a call a frame takes its own exposure
  // outright, so that a render is the same whatever came before it. Throws planet::Error for a
  // negative or non-finite time.
  void adaptExposureOver(double seconds);

  // The camera after the eye-height rule: an altitude below the ground (or the water) plus
  // kMinEyeHeightM is raised to it.
  CameraPose clampToGround(const CameraPose& camera, bool* raised = nullptr) const;

  TerrainPass& terrain() { return *bodies_[0].terrain; }
  // Builds now the pipelines that frames would otherwise build on first use (the terrain's
  // per-frame shading, the sky without clouds): for the viewer, so that no frame waits for a
  // compile, and for the soak, so that no compile's memory comes after its warm-up.
  void prepareAllPipelines();
  TerrainPass& terrain(size_t body) { return *bodies_.at(body).terrain; }
  SkyPass& sky(size_t body = 0) { return *bodies_.at(body).sky; }
  size_t bodyCount() const { return bodies_.size(); }
  // The body the last prepared frame treated as the camera's own.
  size_t primaryBody() const { return primary_; }
  const RenderSettings& settings() const { return settings_; }

 private:
  // One body's passes, in the order of creation (destroyed in reverse: each pass before the
  // tables it reads).
  struct Body {
    PlanetDescription planet;
    std::unique_ptr<SkyTables> skyTables;
    std::unique_ptr<TerrainPass> terrain;  // with its water pass
    std::unique_ptr<SkyPass> sky;
    std::unique_ptr<RingPass> rings;  // null without rings
    glm::dvec3 refracted{0.0};        // the sunlight its air bends into its shadow (refractedIntoShadow)
    // The timing scopes its passes record in a frame, at most.
    uint32_t timingScopes() const;
  };
  Renderer(vk::Context& context, const std::vector<PlanetDescription>& planets,
           const std::vector<std::optional<RingDescription>>& rings, const RenderSettings& settings);
  void createBodies(const std::vector<PlanetDescription>& planets,
                    const std::vector<std::optional<RingDescription>>& rings);
  // The frame of a camera already through the eye-height rule (which costs a full-detail CPU
  // height), with the primary body's pose of it (Prepared::camera).
  Prepared prepareFrame(const SceneView& view, size_t primary, const CameraPose& primaryPose, bool raised,
                        uint32_t slot);
  static CameraPose raisedAboveGround(const PlanetDescription& planet, const CameraPose& camera, bool* raised);
  RenderResult finishFrame(const Prepared& prepared, bool readHdr, double prepareMs);
  // One ring draw between compose passes: the HDR colour and depth from their compute layouts
  // to attachments and back.
  // The HDR target to GENERAL and the depth to SHADER_READ_ONLY after a draw, for compose passes.
  void toComposeLayouts(VkCommandBuffer cmd);
  void recordRings(VkCommandBuffer cmd, RingPass& rings, vk::GpuTimer* timer);
  // The one-planet calls (prepare, render) on a renderer of one body: throws otherwise.
  void checkOnePlanet(const char* call, const char* sceneCall) const;
  SceneView onePlanetView(const CameraPose& camera, const glm::dvec3& sunPlanet, double timeS) const;
  void createTargets();
  std::vector<glm::vec4> readHdrImage();
  // The timing scopes a frame records at most: the sum of what each pass declares.
  uint32_t timingScopes() const;

  vk::Context& context_;
  RenderSettings settings_;
  std::vector<Body> bodies_;
  size_t primary_ = 0;
  // What is laid over the opaque frame after its render pass, far to near (Renderer::record):
  // a body's atmosphere (its compose pass), or its rings.
  struct ComposeStep {
    size_t body = 0;
    bool rings = false;  // the body's ring draw, else its compose pass
  };
  std::vector<ComposeStep> composeOrder_;  // the primary's compose (and rings) last
  std::unique_ptr<StarPass> stars_;   // null when no preset has stars
  std::unique_ptr<LuminancePass> luminance_;  // before the tonemap, which reads its exposure
  std::unique_ptr<TonemapPass> tonemap_;
  double exposureStepS_ = -1.0;  // of the next record(): adaptExposureOver's time, < 0: none
  bool readImage_ = true;        // render() reads the frame back (setReadImage)
  bool exposureReset_ = false;   // the next adapted frame takes its own exposure outright
  vk::Owned<vk::Image> hdr_;
  vk::Owned<vk::Image> color_;
  vk::Owned<vk::Image> depth_;
  // The ground's G-buffer (TerrainSettings::deferredShading; TerrainPass::kGBufferTargets), else empty.
  std::vector<vk::Owned<vk::Image>> gbuffer_;
  glm::mat4 starsToClip_{1.0f};
  uint32_t preparedSlot_ = UINT32_MAX;    // of the last prepare(), until its record()
  vk::GpuTimer timers_[kFramesInFlight];  // one query pool per frame slot
  bool timerCreated_ = false;
};

}  // namespace planet
