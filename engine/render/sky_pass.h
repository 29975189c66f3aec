// The sky pass (issue 4, point 2; issue 21, points 1 and 2; DESIGN.md "One frame", step 3):
// after stars, terrain and water are drawn into the HDR target, compute passes build this
// frame's sky-view table and aerial-perspective volume (shaders/sky_view.comp,
// aerial_perspective.comp) and compose the atmosphere (sky, aerial perspective) from them, with
// the clouds and their shadows (cloud_cover.h), the sun's disc and the star fading
// (shaders/sky.comp). In the reference mode the compose pass marches every pixel's ray instead.
// The tonemap pass (tonemap_pass.h) then maps the HDR target to the display.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "planet/planet_description.h"
#include "reference/atmosphere_model.h"
#include "reference/eclipse.h"
#include "shared/sky_params.h"
#include "vk/buffer.h"
#include "vk/image.h"
#include "vk/owned.h"

namespace planet::vk {
class Context;
class GpuTimer;
}  // namespace planet::vk

namespace planet {

class SkyTables;

// How the compose pass gets the atmosphere: from the per-frame tables (the default), or by
// marching each pixel's ray through the air (`--sky reference`, the tables' test reference).
enum class SkyMode { Tables, Reference };
// "tables" / "reference"; parseSkyMode throws planet::Error naming anything else.
std::string_view skyModeName(SkyMode mode);
SkyMode parseSkyMode(std::string_view name);

// The cloud pass's pixels per sample along each axis (shaders/sky_clouds.comp): 2, a quarter of
// the rays, unless the cloud cover's finest detail is small on the screen, which happens only
// far above the layer: where its finest texel straight below, coverTexelM wide, spans fewer than
// kHalfResolutionTexelPixels pixels (aboveCloudsM above the layer's top, pixelAngleRad per
// pixel), 1. Upsampled from half resolution, clouds a few pixels wide lose their outline (the
// display image differed from the full resolution's by 63 dB PSNR from 200 km, 58 dB from 400
// km, 49 dB from 1,000 km, Earth at 640×360); with 16 the pass runs at full resolution above
// ~530 km there (Earth's 512² cover, a 60° field of view).
constexpr double kHalfResolutionTexelPixels = 16.0;
uint32_t cloudPassScale(double aboveCloudsM, double coverTexelM, double pixelAngleRad);

// A rectangle of an image's pixels (or the cloud pass's samples), [x0, x1) × [y0, y1).
struct PixelRect {
  uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  uint32_t width() const { return empty() ? 0 : x1 - x0; }
  uint32_t height() const { return empty() ? 0 : y1 - y0; }
};
// The smallest rectangle that holds both (an empty one holds nothing).
PixelRect unite(const PixelRect& a, const PixelRect& b);
// The pixels of a width × height image that can show a direction within halfAngleRad of the unit
// `axis` (the camera at the origin, seen through viewProjection), with 2 pixels of margin: the
// bounding box of a polygon circumscribing the cone's circle, cut to the part in front of the
// camera and projected. Empty when the cone lies behind the camera or outside the image; the
// whole image when it is 90° wide or wider.
PixelRect coneScreenRect(const glm::dmat4& viewProjection, const glm::dvec3& axis, double halfAngleRad, uint32_t width,
                         uint32_t height);

struct SkySettings {
  SkyMode mode = SkyMode::Tables;
  uint32_t viewSamples = 64;  // reference mode: samples along each pixel's ray (split over cloud crossings)
  double exposure = 10.0;     // HDR scale before the tonemap curve
  bool clouds = true;         // draw the preset's clouds (if it has any)
  // The cloud pass's pixels per sample along each axis: 0 picks 2 or 1 by the view
  // (cloudPassScale); 1 or 2 forces it (the tests hold the two against each other).
  uint32_t cloudScale = 0;
  // Run the cloud pass and the compose only over the pixels where the air or the sun's disc can
  // show (SkyPass::composeRegion); off, over the whole image (the tests hold the two against each
  // other: the pictures are the same).
  bool regions = true;
  // In tables mode, compose the tiles whose pixels all take one side of the compose's branch (the
  // sky-view table, or the aerial-perspective volume) by pipelines without the other side's code
  // (shaders/sky_classify.comp), and run the cloud pass's tiles whose rays all end before the
  // layer by a pipeline without the march (shaders/sky_cloud_classify.comp); off, every tile by
  // the pipelines with everything (the tests hold the two against each other: the pictures are
  // the same).
  bool tileClasses = true;
};
// Throws planet::Error naming the first bad field: samples outside 2..256, a non-positive
// exposure, a cloud scale past 2.
void validateSkySettings(const SkySettings& settings);

// What the compose pass needs to know about the frame (local frame of the terrain pass:
// camera at (0, 0, altitude) above the anchor, +z up).
struct SkyView {
  glm::dmat4 viewProjection;  // local, camera at the origin → clip
  glm::dmat3 localToPlanet;
  glm::dvec3 forward;       // local
  glm::dvec3 sunLocal;      // local, unit
  // The sun at the body's distance (reference/sunlight.h): irradiance as a share of
  // gpu::kSunIrradiance (the sky's radiance is linear in it) and the disc's angular radius.
  double sunIrradianceScale = 1.0;
  double sunAngularRadiusRad = kSunAngularRadiusRad;
  glm::dvec3 cameraPlanet;  // planet frame, m
  double altitudeM = 0.0;   // above the radius sphere
  double nearPlaneM = 1.0;
  double timeS = 0.0;
  double pixelAngleRad = 1e-3;  // view angle of one pixel (vertical field of view / height)
  // Without a sea, the deepest terrain (m above the radius sphere, TerrainPass::lowestSurfaceM):
  // the sphere below which a ray that met no geometry has met the ground. With a sea the pass
  // uses the sea level instead (where the haze march of a sea pixel ends).
  double lowestSurfaceM = 0.0;
  // The highest terrain (m above the radius sphere, TerrainPass::maxTerrainHeightM): with
  // ownSurfacesOnly, the aerial-perspective volume reaches only as far as it or the clouds' top can
  // be seen.
  double highestSurfaceM = 0.0;
  // The sun's disc is drawn by one compose pass per frame: in a scene of several bodies, by the
  // last one (the camera's own body), after the farther bodies' atmospheres were composed.
  bool drawSun = true;
  // A scene's other bodies, which may hide the sun from the air (eclipses): centres relative to
  // the camera, planet frame.
  std::vector<Occluder> occluders;
  // Whether the depth holds only this body's surfaces, all below the top of its air (no other
  // body, no rings, no terrain above the air): then a tile where every pixel shows geometry is
  // composed by the aerial-perspective volume alone (shaders/sky_classify.comp). Otherwise it is,
  // from inside the air, where the classify passes show that none of its rays leaves the air.
  bool ownSurfacesOnly = false;
};

class SkyPass {
 public:
  // Timing scopes a frame records at most: "sky" (the sky-view table, recordSkyView, in a frame
  // that builds it), "aerial" (the aerial-perspective volume), "clouds" (the cloud pass, half
  // resolution) and "compose" (the tiles' classes, then the compose; the reference mode records
  // only "sky" and "compose", its march).
  static constexpr uint32_t kTimingScopes = 4;

  // `tables` (transmittance, cloud cover) must outlive the pass.
  // `eclipses` false leaves the eclipse code out of the compose shader (no other body).
  SkyPass(vk::Context& context, const PlanetDescription& planet, const SkyTables& tables, const SkySettings& settings,
          bool eclipses = true);

  // Points the pass at the frame's HDR colour (storage, GENERAL while composing) and depth
  // (sampled) images; call again when they are recreated.
  void setTargets(const vk::Image& hdr, const vk::Image& depth);
  // Writes the frame's uniforms (before recording) into frame slot `slot`'s buffer (<
  // vk::kFramesInFlight): call it while no frame recorded for that slot is executing; a frame of
  // the other slot may be.
  void prepare(const SkyView& view, uint32_t width, uint32_t height, uint32_t slot = 0);
  // The sky-view table of the last prepared frame, in every mode, unless the last one built
  // still holds (skyViewBuilt): before the draws, as the sea mirrors it (TerrainPass::setSkyView);
  // the compose of tables mode reads it too. Leaves it visible to fragment and compute shaders.
  void recordSkyView(VkCommandBuffer cmd, vk::GpuTimer* timer);
  // The aerial-perspective volume (tables mode) and the compose, reading the last prepared
  // frame's uniforms: hdr in GENERAL and depth in SHADER_READ_ONLY_OPTIMAL, both after the
  // draws; after recordSkyView.
  void recordCompose(VkCommandBuffer cmd, vk::GpuTimer* timer);
  // The sky-view table (kSkyViewWidth × kSkyViewHeight, RGBA16F, GENERAL once a frame has built it).
  const vk::Image& skyViewTable() const { return *skyView_; }

  const SkySettings& settings() const { return settings_; }
  // Takes effect at the next prepare() (every field is a per-frame uniform or a pipeline already
  // made or made here); throws planet::Error for bad settings (validateSkySettings).
  void setSettings(const SkySettings& settings);

  // For tests: this frame's sky-view table (rgb, row-major kSkyViewWidth × kSkyViewHeight), after
  // a frame recorded in tables mode has completed.
  std::vector<glm::vec4> readSkyView();
  // For tests: the camera's transmittance table (optical depth in rgb, row-major
  // kCameraTransmittanceDistances × kCameraTransmittanceDirections), after a frame recorded in
  // tables mode from inside the air has completed; and the last prepared frame's uniforms
  // (camera.z and aerial.w give the table's reach and its horizon).
  std::vector<glm::vec4> readCameraTransmittance();
  const gpu::SkyUniforms& uniforms() const { return uniformData_; }

  // The sky-view table depends on the atmosphere, the camera's altitude, the ground sphere and
  // the sun's zenith angle only (sky_view.comp). A frame whose altitude is within
  // skyViewAltitudeToleranceM of the one the table was last built for and whose sun's zenith
  // cosine is within kSkyViewSunTolerance of its, the rest equal, reads that table instead of
  // building it again: a flight's frames mostly do (400 m/s at 60 fps turns the sun by 1e-6 rad).
  // The altitude's tolerance moves the horizon (the edge of the ground sphere, sin α = R/(R + h))
  // by at most kSkyViewHorizonToleranceRad, a tenth of a pixel at 1080p (dα/dh = R / ((R + h)
  // √((R + h)² − R²))): 9 m at 600 m, 0.1 % of the altitude at 100 km, 11 km at 20,000 km; never
  // under kSkyViewAltitudeSlackM.
  static constexpr double kSkyViewHorizonToleranceRad = 1e-4;
  static constexpr double kSkyViewAltitudeSlackM = 0.5;
  static constexpr double kSkyViewSunTolerance = 2e-4;
  static double skyViewAltitudeToleranceM(double radiusM, double altitudeM);
  // Whether the last prepared frame builds the sky-view table (else it reads the last one built).
  bool skyViewBuilt() const { return buildSkyView_; }
  // Whether the last prepared frame builds the camera's transmittance table (from inside the air,
  // when the air or the camera's altitude moved beyond the sky-view table's tolerance, or the
  // slices' reach by more than kCameraTransmittanceReachTolerance; else it reads the last one).
  bool cameraTransmittanceBuilt() const { return buildCameraTransmittance_; }
  static constexpr double kCameraTransmittanceReachTolerance = 1e-3;
  // The last prepared frame's compose pixels (SkySettings::regions).
  const PixelRect& composeRegion() const { return composeRegion_; }
  // For tests: how many of the last frame's compose tiles were of each class (mixed, sky,
  // aerial, aerial clear of the clouds, and those two near: shaders/shared/sky_params.h,
  // kSkyTileMixed...), and of its cloud tiles (marched, clear: kSkyCloudTileMarch...), after a
  // frame recorded in tables mode has completed.
  std::array<uint32_t, gpu::kSkyTileLists> readTileCounts();
  // Of such counts: the compose tiles of the ground's classes (aerial, clear of the clouds, near).
  static uint32_t groundTiles(const std::array<uint32_t, gpu::kSkyTileLists>& counts);
  // The last prepared frame's cloud samples (SkySettings::cloudScale pixels per sample each way).
  const PixelRect& cloudRegion() const { return cloudRegion_; }

  // Builds now the pipelines that a later change of settings (the clouds toggled) would build
  // on first use, in the current mode: the viewer's and the soak's, so that no frame waits for
  // a compile and no compile's memory comes after a warm-up.
  void prepareAllPipelines();

 private:
  // Makes the pipelines the settings' mode needs (compiling is milliseconds to a second on
  // lavapipe, so the mode not in use costs nothing).
  void makePipelines();
  void makePipelines(bool clouds);
  // Whether frames draw clouds (the settings', with the planet's clouds and air): without them
  // the compose pipelines leave the cloud code out (sky.comp's kSpecClouds: lavapipe would run
  // it for every pixel) and the cloud pass is not dispatched.
  bool cloudsDrawn() const;
  // The clouds' shadow table's square (SkyUniforms::cloudShadowTable: xy its centre in the local
  // frame, z its half side, m) for a camera below the cloud layer's base, lowestM the lowest
  // surface a ray can end on (m above the radius).
  glm::vec4 cloudShadowSquare(const SkyView& view, double lowestM) const;

  vk::Context& context_;
  uint32_t specialization_[2][2] = {{1u, 0u}, {1u, 1u}};  // [clouds]: sky.comp's kSpecEclipses, kSpecClouds
  PlanetDescription planet_;
  const gpu::AirglowParams airglow_;  // the preset's (makeAirglowParams), in the compose's uniforms
  const SkyTables& tables_;
  SkySettings settings_;
  gpu::SkyUniforms uniformData_{};
  uint32_t slot_ = 0;  // of the last prepare()
  uint32_t width_ = 0, height_ = 0;
  uint32_t cloudScale_ = 2;  // of the last prepare() (cloudPassScale)
  // Of the last prepare(): the compose's pixels (where the air or the sun's disc can show) and
  // the cloud pass's samples (those the compose reads there).
  PixelRect composeRegion_, cloudRegion_;
  // In the order of creation (destroyed in reverse).
  vk::Owned<vk::Buffer> uniforms_[vk::kFramesInFlight];  // per frame slot, host-visible
  vk::Owned<VkSampler> depthSampler_;
  vk::Owned<VkDescriptorSetLayout> setLayout_;
  vk::Owned<VkDescriptorPool> pool_;
  vk::Owned<VkPipelineLayout> layout_;
  // Made when first needed, [0] without clouds, [1] with (a frame in flight may still use the other).
  vk::Owned<VkPipeline> tablesCompose_[2][gpu::kSkyTileClasses];  // sky.comp, [clouds][tile class]
  vk::Owned<VkPipelineLayout> classifyLayout_;                    // the compose's set and a push constant
  vk::Owned<VkPipeline> classify_;                                // sky_classify.comp (tables mode)
  vk::Owned<VkPipeline> referenceCompose_[2];       // sky.comp with SKY_REFERENCE
  vk::Owned<VkPipeline> cloudClassify_;             // sky_cloud_classify.comp (tables mode, clouds)
  // The cloud pass's tile classes: lists kSkyCloudTileMarch .. kSkyTileLists − 1.
  static constexpr uint32_t kCloudTileClasses = gpu::kSkyTileLists - gpu::kSkyCloudTileMarch;
  vk::Owned<VkPipeline> cloudsPass_[kCloudTileClasses];  // sky_clouds.comp, [0] the marched tiles, [1] the clear
  vk::Owned<VkPipeline> cloudShadowBuild_;               // sky_cloud_shadow.comp (tables mode, clouds)
  VkDescriptorSet sets_[vk::kFramesInFlight] = {};  // from pool_, each reads its slot's uniforms
  // The per-frame tables, kept in GENERAL (written by the builds, sampled by the compose).
  vk::Owned<vk::Image> skyView_;
  vk::Owned<vk::Image> aerialLight_;
  vk::Owned<vk::Image> aerialTransmittance_;
  vk::Owned<vk::Image> cameraTransmittance_;  // from inside the air (shaders/sky_camera_transmittance.comp)
  vk::Owned<VkDescriptorSetLayout> tableSetLayout_;
  vk::Owned<VkDescriptorPool> tablePool_;
  vk::Owned<VkPipelineLayout> tableLayout_;
  vk::Owned<VkPipeline> skyViewBuild_;
  vk::Owned<VkPipeline> aerialBuild_[2];  // [from above the air]: its steps per slice and its stores differ
  vk::Owned<VkPipeline> cameraTransmittanceBuild_;       // sky_camera_transmittance.comp (tables mode)
  VkDescriptorSet tableSets_[vk::kFramesInFlight] = {};  // from tablePool_
  bool tablesInitialised_ = false;  // the aerial volume and the camera's table left UNDEFINED for GENERAL
  bool skyViewInitialised_ = false;                      // the sky-view table left UNDEFINED for GENERAL
  // The air and the camera's altitude a table was built for (the sky-view table's and the camera's
  // transmittance table's inputs share them): it serves a frame in the same air within
  // skyViewAltitudeToleranceM of that altitude.
  struct AirAndAltitude {
    gpu::AtmosphereParams atmosphere{};
    double altitudeM = 0.0;
    bool serves(const AirAndAltitude& frame, double radiusM) const;
  };
  // What the sky-view table was last built for, and whether the last prepared frame builds it.
  struct SkyViewInputs {
    AirAndAltitude air;
    float groundSphereM = 0.0f;
    float sunCosZenith = 0.0f;
  };
  std::optional<SkyViewInputs> skyViewBuiltFor_;
  bool buildSkyView_ = true;
  // What the camera's transmittance table was last built for (from inside the air), and whether
  // the last prepared frame builds it. It depends on the air and the camera's altitude only; its
  // mapping (the reach, SkyUniforms::camera.z, and the horizon's cosine, aerial.w) is the kept
  // table's while it is kept.
  struct CameraTransmittanceInputs {
    AirAndAltitude air;
    float farthestM = 0.0f;
    float muHorizon = 0.0f;
  };
  std::optional<CameraTransmittanceInputs> cameraTransmittanceBuiltFor_;
  bool buildCameraTransmittance_ = true;
  // The cloud pass's samples (setTargets makes them the targets' size; a frame uses the top-left
  // (width / scale) × (height / scale) of them, cloudScale_), in GENERAL.
  vk::Owned<vk::Image> cloudLight_;
  vk::Owned<vk::Image> cloudEnd_;
  // The clouds' shadow table (shaders/sky_cloud_shadow.comp), built from below the layer's base
  // (clearCloudTiles_), in GENERAL.
  vk::Owned<vk::Image> cloudShadow_;
  bool cloudImagesInitialised_ = false;  // the three above left UNDEFINED for GENERAL
  // The compose's and the cloud pass's tiles by class (shaders/shared/sky_params.h,
  // kSkyBindingTiles): the indirect dispatches, then a list of tileCapacity_ (the image's tiles)
  // per class, then the compose tiles' farthest depths.
  static constexpr VkDeviceSize kTileHeaderBytes = 16 * gpu::kSkyTileLists;
  vk::Owned<vk::Buffer> tiles_;
  uint32_t tileCapacity_ = 0;
  bool ownSurfacesOnly_ = false;  // of the last prepare() (SkyView::ownSurfacesOnly)
  // Of the last prepare(): the cloud pass may leave out the march in tiles whose rays all end
  // before the layer (the camera is below it, and both regions start at the image's corner).
  bool clearCloudTiles_ = false;
  // Of the last prepare(): the compose may read only the clouds' shadow in the ground's tiles
  // whose rays all end before the layer (as above, with the ground's class and inside the air).
  bool clearGroundTiles_ = false;
  // Of the last prepare(): tiles may be of the ground's classes (the depth holds only this body's
  // surfaces, or the camera is inside the air, where the classify passes check each tile).
  bool groundTiles_ = false;
  // Of the last prepare(): the camera is above the air (the aerial volume's build, aerialBuild_;
  // the camera's transmittance table, built only from inside; the ground's tiles may be near,
  // kSkyTileNear, only from inside, where the ground's class is always allowed).
  bool above_ = false;
};

}  // namespace planet
