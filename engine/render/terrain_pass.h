// The terrain of one planet (issue 3): the spherical-clipmap mesh uploaded once, the compute
// pass that gives its vertices heights and normals each frame the camera moved, the patch
// textures, and the draw. DESIGN.md "One frame" steps 1–3 for the terrain.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "planet/clipmap_culling.h"
#include "planet/clipmap_mesh.h"
#include "render/patch_textures.h"
#include "planet/clipmap_orientation.h"
#include "planet/planet_description.h"
#include "planet/planet_gpu_data.h"
#include "planet/terrain_rebase.h"
#include "camera/camera.h"
#include "reference/atmosphere_model.h"
#include "reference/eclipse.h"
#include "render/patch_layout.h"
#include "render/water_pass.h"
#include "shared/render_params.h"
#include "shared/ring_params.h"
#include "vk/buffer.h"
#include "vk/owned.h"

namespace planet::vk {
class Context;
class GpuTimer;
struct GraphicsPipelineDesc;
}  // namespace planet::vk

namespace planet {

class PatchTextures;
class ReliefCube;
class SkyTables;

// Where the vertex heights come from. Compute is the design; the others exist to measure it
// against (planet bench --compare). They draw the same land; the vertex-shader mode draws no
// water (tests/height_source_test.cpp holds both).
enum class HeightSource {
  Compute,       // terrain_heights.comp, only in frames where the camera moved
  VertexShader,  // terrain_noise.vert: every drawn vertex and its four neighbours, every draw (seed 002)
  Cpu,           // the CPU reference on all cores, uploaded into the buffers the compute pass writes
};
// "compute", "vertex_shader", "cpu".
const char* heightSourceName(HeightSource source);

struct TerrainSettings {
  // 30 levels reach θ = π·2^−30 (2 cm on Earth): deep enough that, at 2 m altitude, rings are
  // drawn down to an eighth of a pixel and the fan that closes the mesh is a few pixels wide.
  ClipmapParams mesh{30, 16, 128};
  // Rings are drawn down to a spacing of 1/subPixelRings of a pixel at the nadir; inside that a
  // fan to the pole closes the hole (its radius is about m/ln 2 ≈ 23 spacings, so 8 keeps it
  // within ~3 pixels).
  uint32_t subPixelRings = 8;
  bool limitOctaves = true;  // octave budgets per ring (off: every octave everywhere, for comparisons)
  bool patches = true;       // per-pixel detail from the patch textures
  PatchSettings patchSettings;
  // Texels per face side of the relief cube (relief_cube.h): the whole planet's heights and
  // normals where the patches do not reach (512: ~20 km on Earth, 25 MB with its mips).
  uint32_t reliefSize = 512;
  bool relief = true;  // off: shade from the vertex values where the patches end (for comparisons)
  bool wireframe = false;           // debug: triangle edges only (no patch textures, no water)
  double bandWavelengthM = 40000.0;  // largest octave of the colour noise (vegetation, frayed band edges)
  double ambient = 0.01;      // fill light, as a fraction of the sun's irradiance, added to the sky's (airless bodies)
  double sunIntensity = 1.0;  // scales the sun's irradiance (gpu::kSunIrradiance)
  bool water = true;          // draw the water sphere (planets with an ocean)
  // Draw and evaluate only the cells of the mesh that the view frustum can show
  // (clipmap_culling.h); off, every drawn ring whole (for tests that read every vertex back).
  bool frustumCulling = true;
  // At most this many patch texels written a frame (0: no limit): levels whose work does not fit
  // grow by strips over later frames, coarsest first (PatchTextures::plan). The viewer and the
  // benchmark set it (realTimePatchBudget), so that no frame builds a whole level; a single render
  // builds all.
  uint64_t patchTexelsPerFrame = 0;
  bool lights = true;         // city lights on the night side (planets whose preset has [lights])
  // Whether other bodies may hide the sun (a scene): off, the shaders leave the eclipse code out
  // (a specialization constant; the Renderer sets it from its body count).
  bool eclipses = true;
  // Leave out of each frame's ground shading what its view cannot show (TerrainShading): the
  // pictures are the same. Off, every frame shades with all the parts the planet has (to test
  // that they are).
  bool shadingPerFrame = true;
  // Draw the ground that cannot be sea floor (its triangle's lowest vertex is far enough above
  // sea level) with the early depth test, so that hidden ground is not shaded; the rest as before,
  // its depth pushed back under the sea (terrain_split.comp). Planets with a sea, the compute and
  // CPU heights. Off: all of it as before (to test the pictures against).
  bool splitSeaFloor = true;
  // Shade the ground in a compute pass (terrain_shade.comp) over a G-buffer the draw writes
  // (terrain.frag's TERRAIN_GBUFFER variant; TerrainPass::setShadingTargets), not in the draw's
  // fragment shader: each pixel is shaded once, whatever the depth test let through, and GPUs
  // whose graphics pipeline has a small part of the chip (the H100 and H200) shade on all of it.
  // The same code shades both ways, so the pictures are the same. One body only (Renderer).
  bool deferredShading = false;

  HeightSource heightSource = HeightSource::Compute;
  unsigned cpuThreads = 0;  // HeightSource::Cpu: threads (0: one per hardware thread)
};

// The optional parts of the ground's shading (terrain.frag's specialization constants). Lavapipe
// runs every side of a branch and a loop's body at least once, so each costs every pixel of every
// frame it is compiled into; a frame's fill pipeline has only those its view can show
// (TerrainPass::shadingFor), each combination built on first use.
struct TerrainShading {
  bool lights = false;        // city lights: the planet has them, they are on, and night is in view
  bool groundDetail = false;  // the detail octaves: some pixel's footprint is fine enough to show them
  bool ringShadow = false;    // the body's rings shadow it
  bool relief = false;        // the relief cube: some pixel's footprint can reach the size that takes it
  uint32_t key() const {
    return (lights ? 1u : 0u) | (groundDetail ? 2u : 0u) | (ringShadow ? 4u : 0u) | (relief ? 8u : 0u);
  }
  static constexpr uint32_t kKeys = 16;
};

// One fill draw of a frame: a run of the culled mesh's triangle list (ClipmapCull::indices, near
// to far) and the parts of the ground's shading its bands can show. A frame's bands near the
// camera take the detail octaves and its far ones the relief cube, never both at one pixel
// (TerrainPass::drawsFor): each run is drawn with a fill pipeline that has only its own parts.
struct TerrainDraw {
  uint32_t firstIndex = 0;
  uint32_t indexCount = 0;
  TerrainShading shading;
};

// Whether any ground the mesh can show (the horizon cut's cap around the camera's nadir,
// clipmap_orientation.h) has the sun below its horizon, with a 1° margin. The planet frame's
// camera position and unit sun direction.
bool nightInView(const glm::dvec3& cameraPlanet, const glm::dvec3& sunDirection, double radiusM,
                 double maxTerrainHeightM, double lowestSurfaceM);
// Whether any ground within capTheta of the unit direction `centre` (planet frame) has the sun
// below its horizon, with a 1° margin: nightInView's test for the mesh's cap, or a band of it.
bool nightWithin(const glm::dvec3& centre, const glm::dvec3& sunDirection, double capTheta);
// A lower bound on the ground footprint of any pixel (m): the distance to the nearest ground the
// highest terrain allows, times the smallest angle a pixel spans (at the image's corners). 0 when
// the camera is below the highest terrain.
double smallestFootprintM(const glm::dvec3& cameraPlanet, double radiusM, double maxTerrainHeightM, double fovYRad,
                          uint32_t width, uint32_t height);
// The same bound for the pixels that show ground at least innerTheta from the mesh's pole (the
// camera altitudeM above it; the ground between lowestSurfaceM and maxTerrainHeightM): the
// nearest such point's distance times the smallest angle a pixel spans.
double footprintBeyondM(double radiusM, double altitudeM, double innerTheta, double lowestSurfaceM,
                        double maxTerrainHeightM, double fovYRad, uint32_t width, uint32_t height);
// Whether some pixel can take the relief cube (terrain_surface.glsl: its weight needs a pixel's
// extent across the line of sight, distance × angle / radius, above an eighth of a texel's angle
// 2 / reliefSize). A pixel spans at most 1 / f radians (f: the focal length in pixels, at the
// image's centre) and lies no farther than the farthest drawn vertex: on the outermost drawn
// ring (outerTheta from the mesh's pole below the camera), at the lowest or highest surface.
bool reliefInView(double radiusM, double altitudeM, double outerTheta, double lowestSurfaceM, double maxTerrainHeightM,
                  double fovYRad, uint32_t height, uint32_t reliefSize);

// What the CPU decided for a frame.
struct TerrainFrameInfo {
  ClipmapFrame orientation;      // of the mesh (while the LOD is frozen: the frozen frame's)
  ClipmapFrame viewOrientation;  // of this camera (= orientation unless frozen): for passes around the camera (sky)
  RingRange rings;
  uint32_t heightFirstRing = 0;  // rings whose heights are computed (the drawn ones)
  uint32_t heightLastRing = 0;
  double groundHeightM = 0.0;  // CPU reference height under the camera
  double heightAboveGroundM = 0.0;
  double nearPlaneM = 0.0;
  double metresPerVertexAtNadir = 0.0;
  double poleCapRadiusM = 0.0;
  uint64_t triangles = 0;        // drawn, after culling
  uint32_t cellsKept = 0;        // of the mesh cells of the drawn rings (clipmap_culling.h)
  uint32_t cellsTotal = 0;
  uint32_t verticesEvaluated = 0;  // by the height pass this frame (0 when it was skipped; VertexShader: drawn, twice with the sea)
  double cpuHeightsMs = 0.0;       // HeightSource::Cpu: wall time of the CPU evaluation this frame
  uint32_t patchLevelsDeferred = 0;  // levels whose work waits for a later frame (patchTexelsPerFrame)
  uint32_t patchLevelsRebuilt = 0;  // levels the patch textures wrote to this frame (whole or new strips)
  uint64_t patchTexelsWritten = 0;  // texels they wrote
  bool heightsComputed = false;
  bool lodFrozen = false;   // orientation, rings, octave tables and patch layout are those of a frozen frame
  bool wireframe = false;   // drawn as triangle edges
  bool waterDrawn = false;  // the water sphere is drawn
  bool seaFloorSplit = false;  // the ground that cannot be sea floor is drawn first, with the early depth test
  TerrainShading shading;   // the parts of the ground's shading the view can show (each draw's are among them)
  std::vector<TerrainDraw> draws;  // the fill draws, near to far (none in wireframe)
  // The sun the shaders got: irradiance at the top of the atmosphere (gpu::kSunIrradiance units)
  // and the disc's angular radius.
  double sunIrradiance = 0.0;
  double sunAngularRadiusRad = 0.0;
  PatchLayout patchLayout;  // empty when the patch textures are not sampled
};

// The ground spacing of ring `ring`'s vertices on a sphere of radiusM: the larger of the radial
// step to the next ring inward and the step along the ring (metresPerVertexAtNadir of
// clipmap_orientation.h, for any ring; the innermost ring's inward neighbour is the pole). The
// pole itself (ring = ring count) gets its fan's radius. The height pass limits each ring's
// octaves to what this spacing can show (octave_budget.h).
double ringSpacingM(const ClipmapParams& params, double radiusM, uint32_t ring);

struct TerrainView {
  CameraBasis camera;                   // planet frame, double
  double fovYRad = 1.0471975511965976;  // 60°
  uint32_t width = 960;
  uint32_t height = 540;
  glm::dvec3 sunDirection{0.0, 0.0, 1.0};  // planet frame, unit
  // The sun as seen from the body (reference/sunlight.h): irradiance as a share of
  // gpu::kSunIrradiance (TerrainSettings::sunIntensity scales it further) and the disc's radius.
  double sunIrradianceScale = 1.0;
  double sunAngularRadiusRad = kSunAngularRadiusRad;
  double timeS = 0.0;  // animation time (waves, clouds)
  // Whether the sky draws the preset's clouds (SkySettings::clouds): the sea then mirrors them
  // and lies in their shadow (water.frag).
  bool clouds = true;
  // A scene's other bodies, which may hide the sun (eclipses): centres relative to the camera,
  // planet frame.
  std::vector<Occluder> occluders;
  // The near plane is 0.25 × the height above the ground, at most this: the scene renderer
  // draws several bodies into one depth buffer and gives them all the nearest body's plane.
  double maxNearPlaneM = 5.0e4;
};

class TerrainPass {
 public:
  // Timing scopes a frame records at most: "heights", "patches", "split", "terrain", "ground
  // shading" (the Renderer's, around recordShade), and the water pass's.
  static constexpr uint32_t kTimingScopes = 5 + WaterPass::kTimingScopes;
  // The deferred shading's G-buffer (TerrainSettings::deferredShading): kGBufferTargets images of
  // kGBufferFormat with colour-attachment and storage usage, drawn in this order (terrain.frag's
  // TERRAIN_GBUFFER outputs). The last one's second channel cleared to kGBufferEmpty tells the
  // pixels without ground.
  static constexpr VkFormat kGBufferFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
  static constexpr uint32_t kGBufferTargets = 4;
  static constexpr float kGBufferEmpty = -1.0f;

  // `sky` provides the transmittance table and sky irradiance the shading uses; it must outlive the pass.
  TerrainPass(vk::Context& context, const PlanetDescription& planet, const TerrainSettings& settings,
              VkFormat colorFormat, VkFormat depthFormat, const SkyTables& sky);
  ~TerrainPass();
  TerrainPass(const TerrainPass&) = delete;
  TerrainPass& operator=(const TerrainPass&) = delete;

  // CPU half of a frame: orientation (from the camera position), ring cut, octave
  // tables, patch layout, uniforms. Returns what it decided. The octave tables and uniforms go
  // into frame slot `slot`'s host-visible buffers (< vk::kFramesInFlight): call it while no
  // frame recorded for that slot is executing; a frame of the other slot may be. It builds on
  // first use what the toggles below need (the full patch textures: after waiting for the
  // device to be idle).
  const TerrainFrameInfo& prepare(const TerrainView& view, uint32_t slot = 0);
  // Compute half of the last prepared frame, with its slot's buffers: heights and normals
  // (skipped when nothing that feeds them changed since the last computed frame), then the
  // patch levels that moved. Call after prepare(), submitting in the order of the calls.
  void recordCompute(VkCommandBuffer cmd, vk::GpuTimer* timer);
  // The draws of the last prepared frame, inside a dynamic-rendering scope with the target's
  // formats: the ground, then (in the same or a later scope over the same targets) the water
  // pass over it, for planets with an ocean whose sea is drawn this frame (waterDrawn()).
  void recordDraw(VkCommandBuffer cmd, vk::GpuTimer* timer);
  void recordWaterDraw(VkCommandBuffer cmd, vk::GpuTimer* timer);
  bool waterDrawn() const { return frame_.waterDrawn; }
  // Whether the last prepared frame draws the ground into the G-buffer for recordShade (deferred
  // shading, and not the wireframe, which the draw colours itself).
  bool shadesDeferred() const { return settings_.deferredShading && !frame_.wireframe; }
  // Points the deferred shading at the G-buffer (kGBufferTargets images) and the HDR target it
  // shades into. Call before the first frame and after the targets change, while no frame that
  // uses the old ones is executing.
  void setShadingTargets(std::span<const vk::Image* const> gbuffer, const vk::Image& color);
  // Points the sea at the body's sky-view table (SkyPass::skyViewTable, in GENERAL, built before
  // the draws each frame that reads it): the sea then mirrors the sky around it, its glow toward
  // a low sun included, where before it mirrored an estimate from the sky's irradiance (still
  // used high above the ground, where the camera's table is not the sky the sea sees). Call
  // while no frame is executing.
  void setSkyView(const vk::Image& table, VkSampler sampler);
  // The weight of the sky-view table in the sea's reflection at a camera altitude (m above the
  // radius): 1 up to kSkyViewFadeStartM, 0 from kSkyViewFadeEndM (smoothstep), 0 without a table
  // or air.
  static constexpr double kSkyViewFadeStartM = 8'000.0;
  static constexpr double kSkyViewFadeEndM = 30'000.0;
  double skyViewWeight(double altitudeM) const;
  // The deferred shading of the last prepared frame, after its draw (recordDraw): every pixel of
  // the width × height targets that holds ground. The G-buffer and the HDR target in the
  // GENERAL layout, the draw's writes visible to compute shaders.
  void recordShade(VkCommandBuffer cmd, uint32_t width, uint32_t height);

  // Debug (the viewer): while frozen, prepare() keeps the orientation, rings, octave tables and
  // patch layout of the last frame prepared before freezing, and that mesh is drawn from wherever
  // the camera now is (fly away and look at the LOD from outside; frame().viewOrientation is the
  // camera's own). Unfreezing lets the LOD follow the camera again.
  void setFreezeLod(bool freeze) { freezeLod_ = freeze; }
  bool freezeLod() const { return freezeLod_; }

  // Live toggles of the TerrainSettings fields of the same names; each takes effect at the
  // next prepare(), which builds what it needs on first use (no new pass).
  // Triangle edges only: the patch textures are neither sampled nor rebuilt, no water.
  void setWireframe(bool wireframe) { settings_.wireframe = wireframe; }
  // The water sphere over the ground; only planets with an ocean have one.
  void setWaterEnabled(bool water) { settings_.water = water; }
  // Per-pixel detail from the patch textures (built on first use, after waiting for the device
  // to be idle); off, the vertex normals shade the ground (bodies a few pixels across).
  void setPatchesEnabled(bool patches) { settings_.patches = patches; }
  // TerrainSettings::patchTexelsPerFrame from the next frame on (0: no limit).
  void setPatchTexelsPerFrame(uint64_t texels) { settings_.patchTexelsPerFrame = texels; }
  // Marks every patch level stale: the next frame that samples them builds them whole.
  void invalidatePatches();
  // The body's rings, whose shadow darkens the ground and the sea (null: none). Call it before
  // the first frame: with rings the sea's pipeline is built again.
  void setRingShadow(const gpu::RingParams* ring);
  // City lights on the night side (planets with [lights]).
  void setLightsEnabled(bool lights) { settings_.lights = lights; }
  // Builds now every fill pipeline a frame may choose (TerrainShading) and the wireframe one,
  // which frames otherwise build on first use (Renderer::prepareAllPipelines).
  void prepareShadingPipelines();
  // Whether this frame's terrain draws lights: the setting and the planet has them.
  bool lightsDrawn() const { return settings_.lights && planet_.lights.enabled; }
  // Scale of the sun's irradiance (gpu::kSunIrradiance).
  void setSunIntensity(double scale) { settings_.sunIntensity = scale; }
  // Fill light, as a fraction of the sun's irradiance (airless bodies).
  void setAmbient(double fraction) { settings_.ambient = fraction; }
  // As constructed, with the toggles' current values.
  const TerrainSettings& settings() const { return settings_; }

  const ClipmapMesh& mesh() const { return mesh_; }
  const TerrainFrameInfo& frame() const { return frame_; }
  const OctaveTables& tables() const { return tables_; }
  const PlanetDescription& planet() const { return planet_; }
  // Per-vertex results of the compute passes (layouts in shaders/shared/render_params.h).
  const vk::Buffer& surfaceBuffer() const { return *surface_; }
  const vk::Buffer& normalBuffer() const { return *normals_; }
  // The last prepared frame's triangle list of the ground that cannot be sea floor (uint32
  // indices, TerrainFrameInfo::triangles of them, the others collapsed to one vertex); null
  // unless that frame split the sea floor (TerrainFrameInfo::seaFloorSplit).
  const vk::Buffer* dryTriangles() const { return frame_.seaFloorSplit ? &*splitIndices_[slot_][0] : nullptr; }
  // The maximum terrain height the horizon cut allows for (estimated once per planet).
  double maxTerrainHeightM() const { return maxTerrainHeightM_; }
  // The lowest surface a sight line can graze (m above the radius sphere): the sea level with a
  // sea (or the deepest terrain if that is higher), else the deepest terrain's estimate (<= 0).
  // The horizon cut uses it.
  double lowestSurfaceM() const { return lowestSurfaceM_; }

 private:
  // The level of detail of a frame: everything the heights depend on besides the planet. Kept
  // (with tables_) while the LOD is frozen.
  struct Lod {
    ClipmapFrame orientation;
    RingRange rings;
    uint32_t heightFirstRing = 0;
    uint32_t heightLastRing = 0;
    double metresPerVertexAtNadir = 0.0;
    double poleCapRadiusM = 0.0;
    uint64_t triangles = 0;
    double nadirPixelM = 0.0;  // ground size of a pixel at the nadir, which the patch layout follows
    PatchLayout patchLayout;   // chosen when the patch textures are first sampled for this LOD
    ClipmapCull cull;          // the cells of the rings the frame's view frustum keeps (clipmap_culling.h)
  };

  // Creates what the current toggles need and does not exist yet: the draw pipeline of the
  // polygon mode, the full-size patch textures (the pass may have started without them).
  void buildForToggles();
  // earlyDepth: the variant that writes no depth and tests it before shading (terrain.frag), which
  // planets without a sea always draw with.
  VkPipeline createDrawPipeline(bool wireframe, const TerrainShading& shading = {}, bool earlyDepth = false);
  // The deferred shading's pieces: the draw into the G-buffer (terrain.frag's TERRAIN_GBUFFER
  // variant, which takes only the relief of `shading`), and the compute pass that shades it.
  VkPipeline createGBufferPipeline(const TerrainShading& shading, bool earlyDepth);
  VkPipeline createShadePipeline(const TerrainShading& shading);
  // The ground draws' vertex stage and layout: terrain.vert over the vertex buffers, or
  // terrain_noise.vert (HeightSource::VertexShader, no vertex input) specialized with
  // `vertexSpecialization`, which must outlive the pipeline's creation.
  void setDrawVertexStage(vk::GraphicsPipelineDesc& desc, std::vector<uint32_t>& vertexSpecialization) const;
  // The ground's specialization constants for `shading` (terrain.frag, terrain_shade.comp).
  std::vector<uint32_t> shadingSpecialization(bool wireframe, const TerrainShading& shading) const;
  // The water pass, for the planet's sea (its shader with the ring shadow when ring_ is set).
  void createWater();
  // Whether the planet has clouds over its sea (clouds and air): the sea's shader then has their
  // reflection and shadow, which frames with clouds drawn (TerrainView::clouds) turn on.
  bool cloudsOverSea() const;
  // The deferred shading's compute pipeline for `shading`, built unless it exists.
  void buildShadePipeline(const TerrainShading& shading);
  // Whether this frame's fill draws are split by terrain_split.comp (TerrainSettings::splitSeaFloor).
  bool splitsSeaFloor() const;
  // The split's dispatch and its barriers (recordCompute).
  void recordSplit(VkCommandBuffer cmd, vk::GpuTimer* timer);
  // The fill pipeline of `shading` (and its early-depth variant when the sea floor is split), built
  // unless it exists; shading deferred, the G-buffer draw's.
  void buildFillPipeline(const TerrainShading& shading);
  // The parts of the ground's shading this view can show (all the planet has when
  // TerrainSettings::shadingPerFrame is off or the LOD is frozen).
  TerrainShading shadingFor(const TerrainView& view, bool lodFrozen) const;
  // Whether the detail octaves show at a pixel footprint (m) this small or smaller.
  bool detailShows(double footprintM) const;
  // The frame's fill draws over the culled mesh of lod_: the runs of bands whose shading (within
  // `shading`, the frame's) is the same; one draw of everything with `shading` unless `split`.
  std::vector<TerrainDraw> drawsFor(const TerrainView& view, const TerrainShading& shading, bool split) const;
  // Binds what both draws read (descriptor set, index buffer, the vertex-shader source's push
  // constants) with `layout`'s pipeline already bound.
  void bindDrawState(VkCommandBuffer cmd) const;
  // Culls the mesh for the view (every cell kept when `cull` is false).
  void cullFor(const glm::dmat4& viewProjection, double cameraZ, bool cull, ClipmapCull& out) const;
  // Writes a culled mesh's triangle list and vertex chunks into the slot's buffers; returns a
  // hash of the chunks.
  uint64_t writeCulledMesh(const ClipmapCull& culled);
  uint32_t drawIndexCount_ = 0;  // of the last writeCulledMesh
  uint32_t chunkCount_ = 0;
  uint32_t culledVertices_ = 0;
  // HeightSource::VertexShader: terrain_noise.vert's variant for this planet, and its
  // specialization constants for the ground (water false) or the sea.
  std::span<const uint32_t> noiseVertexSpirv() const;
  std::vector<uint32_t> noiseVertexSpecialization(bool water) const;
  // The rings, tables (uploaded) and budget figures for `orientation`, with the camera
  // heightAboveGroundM above the ground.
  Lod chooseLod(const TerrainView& view, const ClipmapFrame& orientation, double heightAboveGroundM);
  // cameraZ: the camera's height above the anchor along local z (its x and y are 0, or in the
  // view-projection while the LOD is frozen).
  void writeUniforms(const TerrainView& view, const glm::dmat4& viewProjection, double cameraZ);
  // tables_ into slot_'s buffers (every frame: the other slot's may hold another LOD's).
  void writeTables();
  gpu::TerrainComputePush heightPush() const;
  // HeightSource::Cpu: evaluates this frame's vertices on the CPU into the staging buffer and
  // records its copy into surface_, normals_ and attributes_.
  void recordCpuHeights(VkCommandBuffer cmd, uint32_t firstVertex, uint32_t vertexCount);

  vk::Context& context_;
  PlanetDescription planet_;
  TerrainSettings settings_;
  VkFormat colorFormat_ = VK_FORMAT_UNDEFINED;
  VkFormat depthFormat_ = VK_FORMAT_UNDEFINED;
  const SkyTables& sky_;
  ClipmapMesh mesh_;
  bool fullPatches_ = false;  // patches_ has settings_.patchSettings (else a minimal stand-in that is never sampled)
  double maxTerrainHeightM_ = 0.0;
  double lowestSurfaceM_ = 0.0;          // the horizon cut's grazed sphere, relative to the radius (<= 0)
  std::optional<gpu::RingParams> ring_;  // setRingShadow
  std::vector<double> ringSpacings_;     // HeightSource::Cpu: per ring and the pole (0: every octave)

  // The GPU objects, in the order of creation (destroyed in reverse).
  std::unique_ptr<PlanetGpuData> data_;
  std::unique_ptr<PatchTextures> patches_;
  std::unique_ptr<ReliefCube> relief_;
  vk::Owned<vk::Buffer> meshVertices_;
  vk::Owned<vk::Buffer> budgets_;
  vk::Owned<vk::Buffer> surface_;
  vk::Owned<vk::Buffer> normals_;
  vk::Owned<vk::Buffer> attributes_;
  // Written by the CPU per frame: one host-visible copy per frame slot.
  vk::Owned<vk::Buffer> remainders_[vk::kFramesInFlight];
  vk::Owned<vk::Buffer> shifts_[vk::kFramesInFlight];
  vk::Owned<vk::Buffer> uniforms_[vk::kFramesInFlight];
  vk::Owned<VkBufferView> uniformTexels_[vk::kFramesInFlight];  // the same, as texels (terrain_common.glsl)
  // The frame's culled mesh (clipmap_culling.h): its triangle list, and its vertices as chunks
  // (uvec2: first vertex, count) for the height pass.
  vk::Owned<vk::Buffer> drawIndices_[vk::kFramesInFlight];
  vk::Owned<vk::Buffer> chunks_[vk::kFramesInFlight];
  // HeightSource::Cpu: surface, normals, then attributes, each as the mesh's vertices.
  vk::Owned<vk::Buffer> cpuStaging_[vk::kFramesInFlight];
  vk::Owned<VkDescriptorSetLayout> setLayout_;
  vk::Owned<VkDescriptorPool> pool_;
  VkDescriptorSet sets_[vk::kFramesInFlight] = {};  // from pool_, each points at its slot's buffers
  vk::Owned<VkPipelineLayout> layout_;
  vk::Owned<VkPipeline> heightsPipeline_;
  vk::Owned<VkPipelineLayout> noiseDrawLayout_;  // HeightSource::VertexShader: push constants in the vertex stage
  // The draw as edges, on first use; filled, one per TerrainShading::key(), each on first use.
  vk::Owned<VkPipeline> wireframePipeline_;
  std::array<vk::Owned<VkPipeline>, TerrainShading::kKeys> fillPipelines_;
  // The sea floor's split (terrain_split.comp): per frame slot, the culled triangle list's ground
  // that cannot be sea floor and the rest (the same positions, the other's triangles collapsed),
  // and the early-depth fill pipelines that draw the former.
  vk::Owned<vk::Buffer> splitIndices_[vk::kFramesInFlight][2];
  vk::Owned<VkDescriptorSetLayout> splitSetLayout_;
  vk::Owned<VkDescriptorPool> splitPool_;
  VkDescriptorSet splitSets_[vk::kFramesInFlight] = {};
  vk::Owned<VkPipelineLayout> splitLayout_;
  vk::Owned<VkPipeline> splitPipeline_;
  std::array<vk::Owned<VkPipeline>, TerrainShading::kKeys> dryPipelines_;
  // Deferred shading (TerrainSettings::deferredShading): the G-buffer draws in place of the fill
  // and dry pipelines (the same key; only the relief differs between them), and the compute
  // pass, by the frame's shading key; each on first use.
  std::array<vk::Owned<VkPipeline>, TerrainShading::kKeys> gbufferPipelines_;
  std::array<vk::Owned<VkPipeline>, TerrainShading::kKeys> gbufferDryPipelines_;
  std::array<vk::Owned<VkPipeline>, TerrainShading::kKeys> shadePipelines_;
  bool shadingTargets_ = false;       // setShadingTargets was called
  bool skyViewSet_ = false;           // setSkyView was called
  std::unique_ptr<WaterPass> water_;  // planets with an ocean, except HeightSource::VertexShader

  uint32_t slot_ = 0;  // of the last prepare()
  TerrainFrameInfo frame_;
  bool freezeLod_ = false;
  std::optional<Lod> lod_;  // the last prepared frame's
  OctaveTables tables_;     // lod_'s
  gpu::FrameUniforms uniformData_{};
  PatchTextures::Plan patchPlan_;  // the last prepared frame's
  // What the last computed heights were computed for: skip the compute when it is unchanged.
  struct ComputeKey {
    glm::dvec3 camera{0.0};
    glm::dmat3 orientation{0.0};
    uint32_t firstRing = 0, lastRing = 0;
    int face = -1;
    int exponent = 0;
    int64_t originA = 0, originB = 0;
    uint64_t vertices = 0;  // a hash of the culled mesh's vertex chunks
    uint64_t patchGeneration = 0;  // patchGeneration_ of the frame
    bool operator==(const ComputeKey&) const = default;
  };
  uint64_t patchGeneration_ = 0;  // frames whose patch plan had work (the heights read the patches)
  std::optional<ComputeKey> computed_;
  ComputeKey pending_;
};

}  // namespace planet
