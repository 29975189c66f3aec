#include "render/terrain_pass.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <numbers>
#include <span>
#include <vector>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "planet/clipmap_culling.h"
#include "planet/octave_budget.h"
#include "planet/planet_gpu_data.h"
#include "planet/terrain_height.h"
#include "planet/terrain_rebase.h"
#include "render/patch_textures.h"
#include "render/relief_cube.h"
#include "render/sky_tables.h"
#include "reference/city_lights_cpu.h"
#include "reference/color_schemes_cpu.h"
#include "reference/terrain_surface_cpu.h"
#include "spv/terrain.frag.h"
#include "spv/terrain_early_depth.frag.h"
#include "spv/terrain_gbuffer.frag.h"
#include "spv/terrain_gbuffer_early_depth.frag.h"
#include "spv/terrain_shade.comp.h"
#include "spv/terrain.vert.h"
#include "spv/terrain_noise.vert.h"
#include "spv/terrain_noise_no_craters.vert.h"
#include "spv/terrain_heights.comp.h"
#include "spv/terrain_heights_no_craters.comp.h"
#include "spv/terrain_split.comp.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/graphics_pipeline.h"
#include "vk/pipeline.h"
#include "vk/timer.h"

namespace planet {
namespace {

// The per-pixel ground noise's octave i (terrain_detail.glsl): the biome octaves continue the
// band noise (largest wavelength bandWavelengthM) by factors of 4 from a sixteenth of it; the
// detail octaves run from 4 m by factors of 3.
double groundOctaveFrequency(uint32_t i, double bandWavelengthM) {
  return i < gpu::kGroundBiomeOctavesGpu ? std::ldexp(16.0 / bandWavelengthM, int(2 * i))
                                         : std::pow(3.0, double(i - gpu::kGroundBiomeOctavesGpu)) / 4.0;
}

constexpr VkDescriptorType kBindingTypes[gpu::kRenderBindingCount] = {
    VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,          // frame
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,          // mesh
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,          // surface
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,          // normals
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,          // attributes
    VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,          // layers (why uniform: shaders/terrain_vertex_surface.glsl)
    VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,          // remainders (why uniform: shaders/terrain_vertex_surface.glsl)
    VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,          // shifts
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,          // permutations
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,          // budgets
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // patches
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // transmittance
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // relief
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,          // chunks
    VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER,    // frame texels (the frame's uniforms again)
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // the cloud cover (the sea's reflection and shadow)
    // The deferred shading (written by setShadingTargets): the G-buffer's four images, the HDR target.
    VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
    VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,  // the sky-view table (setSkyView), which the sea mirrors
};
static_assert(gpu::kRenderBindingLatitudeFootprint - gpu::kRenderBindingNormalHeight + 1 ==
              TerrainPass::kGBufferTargets);
// terrain_split.comp: the culled triangle list and the vertices' surface in, the two lists out.
constexpr VkDescriptorType kSplitBindingTypes[4] = {
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
struct SplitPush {  // terrain_split.comp's push constants
  uint32_t triangleCount;
  float seaLevelM;
  float slope;
  float marginM;
};
// How far a pixel's height may lie below its triangle's lowest vertex (terrain_split.comp): a rise
// of 3 per metre of the longest edge (72°, steeper than the presets' slopes at any octave the
// vertices leave out) plus 20 m.
constexpr float kSplitSlope = 3.0f;
constexpr float kSplitMarginM = 20.0f;

// Where the shaders find FrameUniforms's indexed arrays among its texels.
constexpr bool frameTexelAt(size_t offset, uint32_t texel) { return offset == texel * sizeof(glm::vec4); }
static_assert(frameTexelAt(offsetof(gpu::FrameUniforms, patchLevels), gpu::kFrameTexelPatchLevels));
static_assert(frameTexelAt(offsetof(gpu::FrameUniforms, patchWrap), gpu::kFrameTexelPatchWrap));
static_assert(frameTexelAt(offsetof(gpu::FrameUniforms, patchBounds), gpu::kFrameTexelPatchBounds));
static_assert(frameTexelAt(offsetof(gpu::FrameUniforms, skyIrradiance), gpu::kFrameTexelSkyIrradiance));
static_assert(frameTexelAt(offsetof(gpu::FrameUniforms, waves), gpu::kFrameTexelWaves));
static_assert(frameTexelAt(offsetof(gpu::FrameUniforms, groundOctaves), gpu::kFrameTexelGroundOctaves));
static_assert(frameTexelAt(offsetof(gpu::FrameUniforms, groundShifts), gpu::kFrameTexelGroundShifts));
static_assert(sizeof(gpu::FrameUniforms) % sizeof(glm::vec4) == 0, "the texel view covers the whole struct");
constexpr VkDeviceSize kTableRows = VkDeviceSize(gpu::kTerrainMaxLayers) * gpu::kNoiseMaxOctaves;

// The draws' vertex buffers (terrain.vert, water.vert), bound in this order by bindDrawState: the
// surface, the mesh vertex's direction, the normal, the attributes. The draws take them as vertex
// input, not from the storage buffers the compute pass writes: lavapipe's vertex fetch loads each
// vec4 as one vector, where a storage buffer read at gl_VertexIndex is a bounds-checked scalar
// load per lane and component (with the frame texels of terrain_common.glsl: terrain pass 53 →
// 43 ms, water 8.7 → 5.2 ms, best of four runs on a static view at 640×360; docs/benchmarks.md).
constexpr uint32_t kVertexStrides[] = {sizeof(glm::vec4), sizeof(ClipmapVertex), sizeof(glm::vec4), sizeof(glm::vec4)};

glm::vec4 toVec4(const glm::vec3& v, float w = 0.0f) { return glm::vec4(v, w); }

// terrain.frag's colour constants (shaders/terrain_colors.glsl, in its order), appended to its
// specialization as the bits of their floats.
void appendColorSpecialization(std::vector<uint32_t>& values, const PlanetColors& c, const MaterialDescription& m) {
  const glm::vec3 colors[] = {c.deepWater, c.shallowWater, c.beach, c.lowland,  c.highland, c.cliff,  c.snow,
                              m.conifer,   m.forest,       m.grass, m.dryGrass, m.desert,   m.tundra, m.scree};
  static_assert(std::size(colors) == gpu::kTerrainFragColorCount);
  for (const glm::vec3& color : colors)
    for (int i = 0; i < 3; ++i) values.push_back(std::bit_cast<uint32_t>(color[i]));
}

// The ground materials' uniforms (shaders/terrain_material.glsl) and the per-pixel ground noise's
// octaves rebased at `anchorM` (the mesh's anchor, planet frame; shaders/terrain_detail.glsl):
// the coarse ones continue the band noise's four octaves (bandWavelengthM / 2^(4 + 2i): a
// lacunarity of 4, as fraying needs fewer of them than relief), the fine ones are 4 m / 3^i
// (each octave costs every near pixel a noise evaluation: 3 covers 4 m .. 1.6 cm in 6).
// As for the terrain's octave tables, anchor · frequency is split in double by splitLatticeAnchor
// (planet/terrain_rebase.h); the shift is kept modulo 2^22, the fast hash's lattice period.
void writeMaterials(gpu::FrameUniforms& u, const MaterialDescription& m, double bandWavelengthM,
                    const glm::dvec3& anchorM) {
  auto slope = [](double degrees) { return float(1.0 - std::cos(degrees * std::numbers::pi / 180.0)); };
  u.climate = glm::vec4(float(m.equatorTemperatureC), float(m.poleTemperatureDropC), float(m.lapseRateKPerKm * 1e-3),
                        float(m.snowTemperatureC));
  u.moisture = glm::vec4(float(m.moisture), float(m.moistureNoise), float(m.coastalHeightM), float(m.dryBelt));
  u.slopes = glm::vec4(slope(m.rockSlopeDeg), slope(m.snowSlopeDeg), float(m.detailRelief), float(m.detailContrast));
  for (uint32_t i = 0; i < gpu::kGroundOctavesGpu; ++i) {
    const double frequency = groundOctaveFrequency(i, bandWavelengthM);
    u.groundOctaves[i].w = float(frequency);
    glm::uvec4 shift;
    splitLatticeAnchor(anchorM * frequency, u.groundOctaves[i], shift);
    // Modulo 2^22 (kLatticeMask of shaders/common/noise.glsl), which a float holds exactly.
    u.groundShifts[i] = glm::vec4(glm::vec3(shift & glm::uvec4(0x3fffffu)), 0.0f);
  }
}

}  // namespace

bool nightInView(const glm::dvec3& cameraPlanet, const glm::dvec3& sunDirection, double radiusM,
                 double maxTerrainHeightM, double lowestSurfaceM) {
  const double distance = glm::length(cameraPlanet);
  if (!(distance > 0.0)) return true;
  const double cap = horizonTheta(radiusM, distance - radiusM, maxTerrainHeightM, lowestSurfaceM);
  return nightWithin(cameraPlanet / distance, sunDirection, cap);
}

bool nightWithin(const glm::dvec3& centre, const glm::dvec3& sunDirection, double capTheta) {
  const double sunFromCentre = std::acos(std::clamp(glm::dot(centre, sunDirection), -1.0, 1.0));
  // The interpolated vertex normals and float directions stray far less than the margin.
  constexpr double kMarginRad = std::numbers::pi / 180.0;
  return sunFromCentre + capTheta > 0.5 * std::numbers::pi - kMarginRad;
}

namespace {

// The smallest angle a pixel spans (radians). A pixel at distance rho from the image's centre
// (focal length f, in pixels) spans f / (f² + rho²) radians across the radius and
// 1 / sqrt(f² + rho²) along it: the least, at the corners, the former. A derivative over one
// pixel on the ground is at least the distance times that (the ground tilted away only
// lengthens it).
double smallestPixelAngle(double fovYRad, uint32_t width, uint32_t height) {
  const double f = 0.5 * double(height) / std::tan(0.5 * fovYRad);
  const double rho2 = 0.25 * (double(width) * double(width) + double(height) * double(height));
  return f / (f * f + rho2);
}

}  // namespace

double smallestFootprintM(const glm::dvec3& cameraPlanet, double radiusM, double maxTerrainHeightM, double fovYRad,
                          uint32_t width, uint32_t height) {
  const double nearest = glm::length(cameraPlanet) - (radiusM + std::max(maxTerrainHeightM, 0.0));
  if (!(nearest > 0.0) || width == 0 || height == 0) return 0.0;
  return nearest * smallestPixelAngle(fovYRad, width, height);
}

double footprintBeyondM(double radiusM, double altitudeM, double innerTheta, double lowestSurfaceM,
                        double maxTerrainHeightM, double fovYRad, uint32_t width, uint32_t height) {
  if (width == 0 || height == 0) return 0.0;
  // The distance from the camera (on the pole's axis, at radius c) to the point at angle θ and
  // radius r: d² = r² + c² − 2 r c cos θ, least at r = c cos θ (clamped to the ground's radii)
  // and growing with θ.
  const double camera = radiusM + altitudeM;
  const double c = std::cos(innerTheta);
  const double r =
      std::clamp(camera * c, radiusM + lowestSurfaceM, radiusM + std::max(maxTerrainHeightM, lowestSurfaceM));
  const double nearest = std::sqrt(std::max(r * r + camera * camera - 2.0 * r * camera * c, 0.0));
  return nearest * smallestPixelAngle(fovYRad, width, height);
}

bool reliefInView(double radiusM, double altitudeM, double outerTheta, double lowestSurfaceM, double maxTerrainHeightM,
                  double fovYRad, uint32_t height, uint32_t reliefSize) {
  if (reliefSize <= kReliefStandInSize) return false;
  if (height == 0 || !(radiusM > 0.0)) return true;
  // The distance from the camera grows with θ and is convex in the height: the farthest drawn
  // point is a vertex of the outer ring at one of the two heights.
  const double camera = radiusM + altitudeM;
  double farthest = 0.0;
  for (double h : {lowestSurfaceM, maxTerrainHeightM}) {
    const double r = radiusM + h;
    farthest =
        std::max(farthest, std::sqrt(std::max(r * r + camera * camera - 2.0 * r * camera * std::cos(outerTheta), 0.0)));
  }
  const double f = 0.5 * double(height) / std::tan(0.5 * fovYRad);
  // 5 % of margin for the shader's float derivatives.
  return 1.05 * farthest / (f * radiusM) >= (2.0 / double(reliefSize)) / 8.0;
}

const char* heightSourceName(HeightSource source) {
  switch (source) {
    case HeightSource::Compute: return "compute";
    case HeightSource::VertexShader: return "vertex_shader";
    case HeightSource::Cpu: return "cpu";
  }
  return "?";
}

double ringSpacingM(const ClipmapParams& params, double radiusM, uint32_t ring) {
  const uint32_t rings = clipmapRingCount(params);
  if (ring >= rings) return radiusM * clipmapRingTheta(params, rings - 1);  // the pole: its fan's radius
  const double theta = clipmapRingTheta(params, ring);
  const double inner = clipmapRingTheta(params, ring + 1);
  const double along = std::sin(theta) * 2.0 * std::numbers::pi / double(params.numPhi);
  return radiusM * std::max(theta - inner, along);
}

TerrainPass::TerrainPass(vk::Context& context, const PlanetDescription& planet, const TerrainSettings& settings,
                         VkFormat colorFormat, VkFormat depthFormat, const SkyTables& sky)
    : context_(context),
      planet_(planet),
      settings_(settings),
      colorFormat_(colorFormat),
      depthFormat_(depthFormat),
      sky_(sky) {
  if (settings.subPixelRings == 0 || settings.subPixelRings > 64)
    throw Error(fmt::format("sub-pixel ring factor {} is outside 1..64", settings.subPixelRings));
  mesh_ = buildClipmapMesh(settings.mesh);
  const TerrainHeightBounds bounds = estimateTerrainHeightBounds(planet);
  maxTerrainHeightM_ = bounds.maxM;
  // A sea hides what lies below its surface; without one the deepest basin is the lowest sight line.
  lowestSurfaceM_ = planet.hasOcean ? std::max(bounds.minM, planet.seaLevelM) : bounds.minM;
  data_ = std::make_unique<PlanetGpuData>(context, planet);
  // Wireframe draws edges only, so full patch textures would be built for nothing (yet).
  fullPatches_ = settings.patches && !settings.wireframe;
  PatchSettings patchSettings = settings.patchSettings;
  if (!fullPatches_) patchSettings = PatchSettings{kPatchMinResolution, 1, 1.0, 2};  // bound, never sampled
  patches_ = std::make_unique<PatchTextures>(context, *data_, patchSettings);
  // Without the relief a stand-in of kReliefStandInSize texels is bound, which the shaders skip.
  relief_ = std::make_unique<ReliefCube>(context, *data_, settings.relief ? settings.reliefSize : kReliefStandInSize);

  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  const VkBufferUsageFlags vertexStorage = storage | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
  const VkDeviceSize vertexCount = mesh_.vertexCount();
  // Static data, uploaded once (the mesh is never rebuilt per frame).
  meshVertices_ = {context, vk::createBuffer(context, vertexCount * sizeof(ClipmapVertex), vertexStorage,
                                             vk::MemoryUsage::DeviceLocal)};
  vk::uploadBuffer(context, *meshVertices_, mesh_.vertices.data(), vertexCount * sizeof(ClipmapVertex));
  const uint32_t rings = mesh_.ringCount();
  const uint32_t n = settings.mesh.numPhi;

  // Octave budgets per ring (and the pole), from the ring spacing: constant for a mesh.
  std::vector<gpu::RingBudget> budgets(rings + 1, gpu::RingBudget{});
  for (uint32_t ring = 0; ring <= rings; ++ring) {
    const double spacing = settings.limitOctaves ? ringSpacingM(settings.mesh, planet.radiusM, ring) : 0.0;
    if (settings.heightSource == HeightSource::Cpu) ringSpacings_.push_back(spacing);
    for (size_t l = 0; l < planet.layers.size(); ++l) {
      const OctaveBudget budget = octaveBudget(planet.layers[l], spacing);
      budgets[ring].octaves[l] = budget.octaves;
      budgets[ring].lastOctaveWeight[l] = budget.lastOctaveWeight;
    }
  }
  budgets_ = {context, vk::createBuffer(context, budgets.size() * sizeof(gpu::RingBudget), storage,
                                        vk::MemoryUsage::DeviceLocal)};
  vk::uploadBuffer(context, *budgets_, budgets.data(), budgets.size() * sizeof(gpu::RingBudget));

  const VkDeviceSize vertexBytes = vertexCount * sizeof(glm::vec4);
  // The sea floor's split needs the heights before the draw (TerrainSettings::splitSeaFloor).
  const bool split = planet.hasOcean && settings.splitSeaFloor && settings.heightSource != HeightSource::VertexShader;
  surface_ = {context, vk::createBuffer(context, vertexBytes, vertexStorage, vk::MemoryUsage::DeviceLocal)};
  normals_ = {context, vk::createBuffer(context, vertexBytes, vertexStorage, vk::MemoryUsage::DeviceLocal)};
  attributes_ = {context, vk::createBuffer(context, vertexBytes, vertexStorage, vk::MemoryUsage::DeviceLocal)};
  // Per-frame data the CPU writes: host-visible, one copy per frame slot.
  for (uint32_t slot = 0; slot < vk::kFramesInFlight; ++slot) {
    remainders_[slot] = {context, vk::createBuffer(context, kTableRows * sizeof(glm::vec4),
                                                   VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, vk::MemoryUsage::Upload)};
    shifts_[slot] = {context, vk::createBuffer(context, kTableRows * sizeof(glm::uvec4),
                                               VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, vk::MemoryUsage::Upload)};
    uniforms_[slot] = {context,
                       vk::createBuffer(context, sizeof(gpu::FrameUniforms),
                                        VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                                        vk::MemoryUsage::Upload)};
    uniformTexels_[slot] = {context, vk::createBufferView(context, *uniforms_[slot], VK_FORMAT_R32G32B32A32_SFLOAT)};
    // Room for every band and the fan, and for a chunk per sector and per workgroup of every ring.
    const VkDeviceSize maxIndices = VkDeviceSize(6) * n * (rings - 1) + VkDeviceSize(3) * n;
    const VkDeviceSize maxChunks =
        VkDeviceSize(rings) * (std::min(kCullSectors, n) + n / gpu::kTerrainComputeWorkgroupSize + 1) + 1;
    drawIndices_[slot] = {
        context, vk::createBuffer(context, maxIndices * sizeof(uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT | storage,
                                  vk::MemoryUsage::Upload)};
    if (split)
      for (vk::Owned<vk::Buffer>& list : splitIndices_[slot])
        list = {context, vk::createBuffer(context, maxIndices * sizeof(uint32_t),
                                          VK_BUFFER_USAGE_INDEX_BUFFER_BIT | storage, vk::MemoryUsage::DeviceLocal)};
    chunks_[slot] = {context, vk::createBuffer(context, maxChunks * sizeof(glm::uvec2), storage, vk::MemoryUsage::Upload)};
    if (settings.heightSource == HeightSource::Cpu)
      cpuStaging_[slot] = {context, vk::createBuffer(context, 3 * vertexBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                                     vk::MemoryUsage::Upload)};
  }

  const VkShaderStageFlags stages =
      VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  setLayout_ = {context, vk::createSetLayout(context, kBindingTypes, stages)};
  pool_ = {context, vk::createDescriptorPool(context, kBindingTypes, vk::kFramesInFlight)};
  for (uint32_t slot = 0; slot < vk::kFramesInFlight; ++slot) {
    VkDescriptorSet set = sets_[slot] = vk::allocateSet(context, pool_.get(), setLayout_.get());
    const vk::Buffer* buffers[] = {&*uniforms_[slot],      &*meshVertices_,  &*surface_,          &*normals_,
                                   &*attributes_,          &data_->layers(), &*remainders_[slot], &*shifts_[slot],
                                   &data_->permutations(), &*budgets_};
    for (uint32_t b = 0; b < gpu::kRenderBindingPatches; ++b)
      vk::writeBufferDescriptor(context, set, b, kBindingTypes[b], *buffers[b]);
    vk::writeBufferDescriptor(context, set, gpu::kRenderBindingChunks, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                              *chunks_[slot]);
    vk::writeTexelBufferDescriptor(context, set, gpu::kRenderBindingFrameTexels, uniformTexels_[slot].get());
    vk::writeImageDescriptor(context, set, gpu::kRenderBindingPatches, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                             patches_->image().view, VK_IMAGE_LAYOUT_GENERAL, patches_->sampler());
    vk::writeImageDescriptor(context, set, gpu::kRenderBindingTransmittance, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                             sky.transmittanceView(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sky.sampler());
    vk::writeImageDescriptor(context, set, gpu::kRenderBindingRelief, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                             relief_->view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, relief_->sampler());
    // Built with the sky tables, before any frame's terrain (Renderer::record).
    vk::writeImageDescriptor(context, set, gpu::kRenderBindingClouds, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                             sky.clouds().view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sky.clouds().sampler());
    // A valid image until setSkyView names the table; the sea reads it only after (FrameUniforms::skyView).
    vk::writeImageDescriptor(context, set, gpu::kRenderBindingSkyView, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                             sky.transmittanceView(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sky.sampler());
  }

  layout_ = {context, vk::createPipelineLayout(context, setLayout_.get(), sizeof(gpu::TerrainComputePush),
                                               VK_SHADER_STAGE_COMPUTE_BIT)};
  // Specialized on the planet's layers: lavapipe would otherwise run every fractal type and hash.
  // Without the crater and erosion code unless a layer needs it (planet_gpu_data.h,
  // needsFullNoiseShaders).
  const std::span<const uint32_t> heights = needsFullNoiseShaders(planet)
                                                ? std::span<const uint32_t>(kSpv_terrain_heights_comp)
                                                : kSpv_terrain_heights_no_craters_comp;
  heightsPipeline_ = {
      context, vk::createComputePipelineWithLayout(context, heights, layout_.get(), layerSpecialization(planet))};
  if (settings.heightSource == HeightSource::VertexShader)
    noiseDrawLayout_ = {context, vk::createPipelineLayout(context, setLayout_.get(), sizeof(gpu::TerrainComputePush),
                                                          VK_SHADER_STAGE_VERTEX_BIT)};
  if (split) {
    splitSetLayout_ = {context, vk::createSetLayout(context, kSplitBindingTypes, VK_SHADER_STAGE_COMPUTE_BIT)};
    splitPool_ = {context, vk::createDescriptorPool(context, kSplitBindingTypes, vk::kFramesInFlight)};
    for (uint32_t slot = 0; slot < vk::kFramesInFlight; ++slot) {
      splitSets_[slot] = vk::allocateSet(context, splitPool_.get(), splitSetLayout_.get());
      const vk::Buffer* buffers[] = {&*drawIndices_[slot], &*surface_, &*splitIndices_[slot][0],
                                     &*splitIndices_[slot][1]};
      for (uint32_t b = 0; b < std::size(buffers); ++b)
        vk::writeBufferDescriptor(context, splitSets_[slot], b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, *buffers[b]);
    }
    splitLayout_ = {context, vk::createPipelineLayout(context, splitSetLayout_.get(), sizeof(SplitPush),
                                                      VK_SHADER_STAGE_COMPUTE_BIT)};
    splitPipeline_ = {context,
                      vk::createComputePipelineWithLayout(context, kSpv_terrain_split_comp, splitLayout_.get())};
  }
  // The fill pipelines are built on first use, per shading (prepare()).
  if (settings.wireframe) wireframePipeline_ = {context, createDrawPipeline(true)};
  if (planet.hasOcean) createWater();
}

void TerrainPass::createWater() {
  // The sea reads the vertex buffers the compute (or CPU) heights fill; in seed 002's design
  // (heights in the vertex shader) its vertices evaluate the noise again.
  WaterPass::Features features;
  features.eclipses = settings_.eclipses;
  features.ringShadow = ring_.has_value();
  features.clouds = cloudsOverSea();
  if (noiseDrawLayout_.get()) {
    const std::vector<uint32_t> specialization = noiseVertexSpecialization(true);
    water_ = std::make_unique<WaterPass>(context_, noiseDrawLayout_.get(), colorFormat_, depthFormat_, features,
                                         std::span<const uint32_t>(), noiseVertexSpirv(), specialization);
  } else {
    water_ = std::make_unique<WaterPass>(context_, layout_.get(), colorFormat_, depthFormat_, features, kVertexStrides);
  }
}

void TerrainPass::setRingShadow(const gpu::RingParams* ring) {
  const bool had = ring_.has_value();
  ring_ = ring ? std::optional<gpu::RingParams>(*ring) : std::nullopt;
  // The sea's shader has the shadow's code only with rings (a specialization constant).
  if (water_ && had != ring_.has_value()) createWater();
}

bool TerrainPass::cloudsOverSea() const { return planet_.clouds.enabled && planet_.atmosphere.enabled; }

TerrainPass::~TerrainPass() = default;

std::span<const uint32_t> TerrainPass::noiseVertexSpirv() const {
  // As the height pass's variants: without the crater and erosion code unless a layer needs it.
  return needsFullNoiseShaders(planet_) ? std::span<const uint32_t>(kSpv_terrain_noise_vert)
                                        : kSpv_terrain_noise_no_craters_vert;
}

std::vector<uint32_t> TerrainPass::noiseVertexSpecialization(bool water) const {
  // The layers' constants as the height pass gets them, then kNoiseVertexWater (terrain_noise.vert).
  std::vector<uint32_t> values = layerSpecialization(planet_);
  values.resize(gpu::kTerrainSpecCount, 0u);
  values.push_back(water ? 1u : 0u);
  return values;
}

std::vector<uint32_t> TerrainPass::shadingSpecialization(bool wireframe, const TerrainShading& shading) const {
  // The colour scheme, the polar caps, the eclipses and the frame's shading (TerrainShading) as
  // specialization constants (terrain.frag): lavapipe runs every side of a branch, and the seed
  // schemes' per-pixel noise (or the lights') would cost every planet. Then the planet's colours.
  const uint32_t parts[] = {uint32_t(planet_.colors.scheme),
                            planet_.colors.polarCaps ? 1u : 0u,
                            !wireframe && shading.lights ? 1u : 0u,
                            settings_.eclipses ? 1u : 0u,
                            !wireframe && shading.groundDetail ? 1u : 0u,
                            !wireframe && shading.ringShadow ? 1u : 0u,
                            !wireframe && shading.relief ? 1u : 0u};
  static_assert(std::size(parts) == gpu::kTerrainFragSpecColors);
  std::vector<uint32_t> specialization(std::begin(parts), std::end(parts));
  appendColorSpecialization(specialization, planet_.colors, planet_.materials);
  return specialization;
}

void TerrainPass::setDrawVertexStage(vk::GraphicsPipelineDesc& desc,
                                     std::vector<uint32_t>& vertexSpecialization) const {
  if (noiseDrawLayout_.get()) {  // HeightSource::VertexShader: no vertex input
    vertexSpecialization = noiseVertexSpecialization(false);
    desc.vertexSpirv = noiseVertexSpirv();
    desc.vertexSpecialization = vertexSpecialization;
    desc.layout = noiseDrawLayout_.get();
  } else {
    desc.vertexSpirv = kSpv_terrain_vert;
    desc.vertexStrides = kVertexStrides;
    desc.layout = layout_.get();
  }
}

VkPipeline TerrainPass::createDrawPipeline(bool wireframe, const TerrainShading& shading, bool earlyDepth) {
  vk::GraphicsPipelineDesc desc;
  // Without a sea the shader writes no depth, and its variant tests the depth before shading
  // (terrain.frag): the pixels of ground hidden behind nearer ground are not shaded.
  // With one, the ground that cannot be sea floor gets that variant too (splitsSeaFloor).
  desc.fragmentSpirv =
      planet_.hasOcean && !earlyDepth ? std::span<const uint32_t>(kSpv_terrain_frag) : kSpv_terrain_early_depth_frag;
  const std::vector<uint32_t> specialization = shadingSpecialization(wireframe, shading);
  desc.fragmentSpecialization = specialization;
  std::vector<uint32_t> vertexSpecialization;
  setDrawVertexStage(desc, vertexSpecialization);
  desc.colorFormat = colorFormat_;
  desc.depthFormat = depthFormat_;
  desc.polygonMode = wireframe ? VK_POLYGON_MODE_LINE : VK_POLYGON_MODE_FILL;
  // The mesh's triangles are counter-clockwise seen from outside. The projection's y flip and
  // Vulkan's y-down framebuffer cancel, so they stay counter-clockwise on screen.
  desc.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  desc.cullMode = wireframe ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT;
  return vk::createGraphicsPipeline(context_, desc);
}

VkPipeline TerrainPass::createGBufferPipeline(const TerrainShading& shading, bool earlyDepth) {
  // The draw's surface takes only the relief of the shading (terrain_surface.glsl): the others
  // cleared, so that the pipeline store shares one pipeline between the keys that differ in them.
  TerrainShading surface;
  surface.relief = shading.relief;
  vk::GraphicsPipelineDesc desc;
  desc.fragmentSpirv = planet_.hasOcean && !earlyDepth ? std::span<const uint32_t>(kSpv_terrain_gbuffer_frag)
                                                       : kSpv_terrain_gbuffer_early_depth_frag;
  const std::vector<uint32_t> specialization = shadingSpecialization(false, surface);
  desc.fragmentSpecialization = specialization;
  std::vector<uint32_t> vertexSpecialization;
  setDrawVertexStage(desc, vertexSpecialization);
  desc.colorFormat = kGBufferFormat;
  desc.colorAttachments = kGBufferTargets;
  desc.depthFormat = depthFormat_;
  desc.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;  // as createDrawPipeline's
  desc.cullMode = VK_CULL_MODE_BACK_BIT;
  return vk::createGraphicsPipeline(context_, desc);
}

VkPipeline TerrainPass::createShadePipeline(const TerrainShading& shading) {
  // The relief is the draw's (createGBufferPipeline): cleared, as above.
  TerrainShading shade = shading;
  shade.relief = false;
  return vk::createComputePipelineWithLayout(context_, kSpv_terrain_shade_comp, layout_.get(),
                                             shadingSpecialization(false, shade));
}

void TerrainPass::setShadingTargets(std::span<const vk::Image* const> gbuffer, const vk::Image& color) {
  if (gbuffer.size() != kGBufferTargets)
    throw Error(
        fmt::format("TerrainPass::setShadingTargets: {} G-buffer images, not {}", gbuffer.size(), kGBufferTargets));
  for (VkDescriptorSet set : sets_) {
    for (uint32_t i = 0; i < kGBufferTargets; ++i)
      vk::writeImageDescriptor(context_, set, gpu::kRenderBindingNormalHeight + i, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                               gbuffer[i]->view, VK_IMAGE_LAYOUT_GENERAL);
    vk::writeImageDescriptor(context_, set, gpu::kRenderBindingShadedColor, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                             color.view, VK_IMAGE_LAYOUT_GENERAL);
  }
  shadingTargets_ = true;
}

void TerrainPass::setSkyView(const vk::Image& table, VkSampler sampler) {
  for (VkDescriptorSet set : sets_)
    vk::writeImageDescriptor(context_, set, gpu::kRenderBindingSkyView, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                             table.view, VK_IMAGE_LAYOUT_GENERAL, sampler);
  skyViewSet_ = true;
}

double TerrainPass::skyViewWeight(double altitudeM) const {
  if (!skyViewSet_ || !planet_.atmosphere.enabled) return 0.0;
  const double x = std::clamp((altitudeM - kSkyViewFadeStartM) / (kSkyViewFadeEndM - kSkyViewFadeStartM), 0.0, 1.0);
  return 1.0 - x * x * (3.0 - 2.0 * x);
}

void TerrainPass::recordShade(VkCommandBuffer cmd, uint32_t width, uint32_t height) {
  if (!shadesDeferred()) throw Error("TerrainPass::recordShade in a frame that does not shade deferred");
  if (!shadingTargets_) throw Error("TerrainPass::recordShade before setShadingTargets");
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, shadePipelines_[frame_.shading.key()].get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &sets_[slot_], 0, nullptr);
  const uint32_t size = gpu::kTerrainShadeWorkgroupSize;
  vkCmdDispatch(cmd, (width + size - 1) / size, (height + size - 1) / size, 1);
}

TerrainShading TerrainPass::shadingFor(const TerrainView& view, bool lodFrozen) const {
  TerrainShading shading;
  shading.lights = lightsDrawn();
  shading.groundDetail = true;
  shading.ringShadow = ring_.has_value();
  shading.relief = relief_->size() > kReliefStandInSize;
  // A frozen mesh is seen from anywhere: all of it.
  if (!settings_.shadingPerFrame || lodFrozen || !lod_) return shading;
  const glm::dvec3& camera = view.camera.position;
  const double radius = planet_.radiusM;
  shading.lights =
      shading.lights && nightInView(camera, view.sunDirection, radius, maxTerrainHeightM_, lowestSurfaceM_);
  shading.groundDetail =
      detailShows(smallestFootprintM(camera, radius, maxTerrainHeightM_, view.fovYRad, view.width, view.height));
  shading.relief = reliefInView(radius, lod_->orientation.altitudeM, mesh_.ringTheta(lod_->rings.firstRing),
                                lowestSurfaceM_, maxTerrainHeightM_, view.fovYRad, view.height, relief_->size());
  return shading;
}

bool TerrainPass::detailShows(double footprintM) const {
  // terrain_detail.glsl: octave i fades out where the footprint reaches half its wavelength; a
  // tenth of margin for the derivatives' float error.
  const double longestDetailM = 1.0 / groundOctaveFrequency(gpu::kGroundBiomeOctavesGpu, settings_.bandWavelengthM);
  return 0.9 * footprintM < 0.5 * longestDetailM;
}

std::vector<TerrainDraw> TerrainPass::drawsFor(const TerrainView& view, const TerrainShading& shading,
                                               bool split) const {
  const ClipmapCull& cull = lod_->cull;
  const uint32_t total = uint32_t(cull.indices.size());
  std::vector<TerrainDraw> draws;
  const auto add = [&](uint32_t begin, uint32_t end, const TerrainShading& run) {
    if (end <= begin) return;
    if (!draws.empty() && draws.back().shading.key() == run.key())
      draws.back().indexCount += end - begin;
    else
      draws.push_back({begin, end - begin, run});
  };
  if (!split) {
    add(0, total, shading);
    return draws;
  }
  // As shadingFor, per band: the detail octaves where its nearest ground can have a pixel fine
  // enough (the bands near the camera), the relief cube where its farthest can have one wide
  // enough (the far ones), the city lights where its outer ring reaches the night (from orbit,
  // the bands toward the terminator).
  const double radius = planet_.radiusM;
  const double altitude = lod_->orientation.altitudeM;
  const uint32_t first = lod_->rings.firstRing, last = lod_->rings.lastRing;
  // k = last is the pole fan (θ from 0 to ring last's), k < last band k (between rings k + 1 and k).
  for (uint32_t k = last + 1; k-- > first;) {
    const uint32_t begin = k == last ? 0u : cull.bandFirstIndex[k - first];
    const uint32_t end = k > first ? cull.bandFirstIndex[k - 1 - first] : total;
    const double inner = k == last ? 0.0 : mesh_.ringTheta(k + 1);
    TerrainShading run = shading;
    run.groundDetail = shading.groundDetail &&
                       detailShows(footprintBeyondM(radius, altitude, inner, lowestSurfaceM_, maxTerrainHeightM_,
                                                    view.fovYRad, view.width, view.height));
    run.lights =
        shading.lights && nightWithin(lod_->orientation.nadirDirection(), view.sunDirection, mesh_.ringTheta(k));
    run.relief = shading.relief && reliefInView(radius, altitude, mesh_.ringTheta(k), lowestSurfaceM_,
                                                maxTerrainHeightM_, view.fovYRad, view.height, relief_->size());
    add(begin, end, run);
  }
  return draws;
}

void TerrainPass::prepareShadingPipelines() {
  if (!wireframePipeline_.get()) wireframePipeline_ = {context_, createDrawPipeline(true)};
  for (bool lights : {false, lightsDrawn()})
    for (bool detail : {false, true})
      for (bool relief : {false, relief_->size() > kReliefStandInSize}) {
        TerrainShading shading;
        shading.lights = lights;
        shading.groundDetail = detail;
        shading.ringShadow = ring_.has_value();
        shading.relief = relief;
        buildFillPipeline(shading);
        if (settings_.deferredShading) buildShadePipeline(shading);
      }
}

void TerrainPass::buildFillPipeline(const TerrainShading& shading) {
  // Shading deferred, the G-buffer draws stand in for the shading ones (buildShadePipeline).
  const bool deferred = settings_.deferredShading;
  const auto create = [&](bool earlyDepth) {
    return deferred ? createGBufferPipeline(shading, earlyDepth) : createDrawPipeline(false, shading, earlyDepth);
  };
  vk::Owned<VkPipeline>& fill = (deferred ? gbufferPipelines_ : fillPipelines_)[shading.key()];
  if (!fill.get()) fill = {context_, create(false)};
  vk::Owned<VkPipeline>& dry = (deferred ? gbufferDryPipelines_ : dryPipelines_)[shading.key()];
  if (splitPipeline_.get() && !dry.get()) dry = {context_, create(true)};
}

void TerrainPass::buildShadePipeline(const TerrainShading& shading) {
  vk::Owned<VkPipeline>& shade = shadePipelines_[shading.key()];
  if (!shade.get()) shade = {context_, createShadePipeline(shading)};
}

bool TerrainPass::splitsSeaFloor() const { return splitPipeline_.get() && !settings_.wireframe; }

void TerrainPass::buildForToggles() {
  if (settings_.wireframe && !wireframePipeline_.get()) wireframePipeline_ = {context_, createDrawPipeline(true)};
  if (settings_.patches && !settings_.wireframe && !fullPatches_) {
    // The pass started in wireframe with a stand-in. A frame of the other slot may still use
    // the old textures and the descriptor sets: wait for every frame (once per pass).
    VK_CHECK(vkDeviceWaitIdle(context_.device));
    auto patches = std::make_unique<PatchTextures>(context_, *data_, settings_.patchSettings);
    for (VkDescriptorSet set : sets_)
      vk::writeImageDescriptor(context_, set, gpu::kRenderBindingPatches, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                               patches->image().view, VK_IMAGE_LAYOUT_GENERAL, patches->sampler());
    patches_ = std::move(patches);
    fullPatches_ = true;
    if (lod_) lod_->patchLayout = PatchLayout{};  // chosen for the new textures' settings
  }
}

TerrainPass::Lod TerrainPass::chooseLod(const TerrainView& view, const ClipmapFrame& orientation,
                                        double heightAboveGroundM) {
  const double radius = planet_.radiusM;
  const ClipmapParams& params = settings_.mesh;
  Lod lod;
  lod.orientation = orientation;
  // Cuts: horizon from the height above the radius sphere (with the terrain's maximum as margin
  // and its lowest sight line), pixel cut from the height above the ground actually below the camera.
  const double thetaMax = horizonTheta(radius, orientation.altitudeM, maxTerrainHeightM_, lowestSurfaceM_);
  const double thetaMin = minUsefulTheta(radius, std::max(heightAboveGroundM, kClipmapMinAltitudeM), view.fovYRad,
                                         view.height * settings_.subPixelRings, params.ringsPerLevel);
  lod.rings = selectRings(params.levels, params.ringsPerLevel, thetaMax, thetaMin);
  const uint32_t rings = mesh_.ringCount();
  // Heights of the drawn rings only: each vertex's normal comes from its own gradient (issue 19),
  // where differences of neighbours took one more ring on each side.
  lod.heightFirstRing = lod.rings.firstRing;
  lod.heightLastRing = std::min(lod.rings.lastRing, rings - 1);
  lod.metresPerVertexAtNadir =
      metresPerVertexAtNadir(radius, params.levels, params.ringsPerLevel, params.numPhi, lod.rings.lastRing);
  lod.poleCapRadiusM = poleCapRadiusM(radius, params.levels, params.ringsPerLevel, lod.rings.lastRing);
  lod.triangles = uint64_t(lod.rings.lastRing - lod.rings.firstRing) * 2 * params.numPhi + params.numPhi;
  // Patch layout (when sampled) from the ground footprint of a pixel at the nadir.
  lod.nadirPixelM = radius * pixelFootprintTheta(radius, std::max(heightAboveGroundM, 0.01), view.fovYRad, view.height);

  // Octave tables around the anchor, the sea-sphere point below the camera.
  tables_ = buildOctaveTables(planet_, radius * orientation.nadirDirection());
  return lod;
}

void TerrainPass::writeTables() {
  // Host-visible: plain copies, no submission (the slot's previous frame has completed).
  vk::uploadBuffer(context_, *remainders_[slot_], tables_.remainders.data(),
                   tables_.remainders.size() * sizeof(glm::vec4));
  vk::uploadBuffer(context_, *shifts_[slot_], tables_.shifts.data(), tables_.shifts.size() * sizeof(glm::uvec4));
}

const TerrainFrameInfo& TerrainPass::prepare(const TerrainView& view, uint32_t slot) {
  vk::checkFrameSlot(slot);
  slot_ = slot;
  const double radius = planet_.radiusM;
  buildForToggles();
  TerrainFrameInfo info;
  // This camera's orientation, from its position alone (clipmap_orientation.h): the same pose
  // gets the same frame bit for bit however the camera got there.
  info.viewOrientation = orientClipmap(view.camera.position, radius);

  // The ground below the camera (for the pixel cut and the near plane).
  info.groundHeightM = terrainHeightM(planet_, info.viewOrientation.nadirDirection());
  const double ground = planet_.hasOcean ? std::max(info.groundHeightM, planet_.seaLevelM) : info.groundHeightM;
  info.heightAboveGroundM = std::max(info.viewOrientation.altitudeM - ground, kClipmapMinAltitudeM * 0.01);
  info.nearPlaneM = std::min(std::clamp(0.25 * info.heightAboveGroundM, 0.01, 5.0e4), std::max(view.maxNearPlaneM, 0.01));

  info.lodFrozen = freezeLod_ && lod_;
  if (!info.lodFrozen) {
    // The cull's vectors go to the new LOD for their capacity (cullClipmap refills them).
    ClipmapCull culled = lod_ ? std::move(lod_->cull) : ClipmapCull{};
    lod_ = chooseLod(view, info.viewOrientation, info.heightAboveGroundM);
    lod_->cull = std::move(culled);
  }
  writeTables();
  Lod& lod = *lod_;
  const bool patches = settings_.patches && !settings_.wireframe;
  if (patches && lod.patchLayout.levels.empty())
    lod.patchLayout =
        choosePatchLayout(patches_->settings(), radius, lod.orientation.nadirDirection(), lod.nadirPixelM);
  info.orientation = lod.orientation;
  info.rings = lod.rings;
  info.heightFirstRing = lod.heightFirstRing;
  info.heightLastRing = lod.heightLastRing;
  info.metresPerVertexAtNadir = lod.metresPerVertexAtNadir;
  info.poleCapRadiusM = lod.poleCapRadiusM;
  info.triangles = lod.triangles;
  if (patches) info.patchLayout = lod.patchLayout;
  info.wireframe = settings_.wireframe;
  info.waterDrawn = water_ && settings_.water && !settings_.wireframe;
  info.seaFloorSplit = splitsSeaFloor();

  // View: the mesh's local frame with the camera at its origin. The mesh's positions are offsets
  // from its anchor (radius · its nadir), and the camera it was chosen for sits at (0, 0,
  // altitude) from it. A frozen mesh's camera has moved since by `moved` (local frame): the
  // shaders take its z part with the altitude, the view matrix the rest.
  const glm::dmat3 planetToLocal = glm::transpose(lod.orientation.localToPlanet);
  glm::dmat4 viewM = viewMatrix(planetToLocal * view.camera.forward, planetToLocal * view.camera.up);
  double cameraZ = lod.orientation.altitudeM;
  if (info.lodFrozen) {
    const glm::dvec3 moved = planetToLocal * (view.camera.position - lod.orientation.cameraPlanetFrame);
    viewM = viewM * glm::translate(glm::dmat4(1.0), -glm::dvec3(moved.x, moved.y, 0.0));
    cameraZ += moved.z;
  }
  const glm::dmat4 projection =
      reversedZPerspective(view.fovYRad, double(view.width) / double(view.height), info.nearPlaneM);
  info.shading = shadingFor(view, info.lodFrozen);
  frame_ = info;
  // This frame's share of the patch levels' work (all of it without a budget).
  patchPlan_ = patches ? patches_->plan(info.patchLayout, settings_.patchTexelsPerFrame) : PatchTextures::Plan{};
  frame_.patchLevelsDeferred = patchPlan_.deferred;
  writeUniforms(view, projection * viewM, cameraZ);
  // A frozen mesh keeps the cells its own frame kept, so that it can be looked at from elsewhere.
  if (!info.lodFrozen) cullFor(projection * viewM, cameraZ, settings_.frustumCulling, lod.cull);
  const uint64_t vertices = writeCulledMesh(lod.cull);
  if (!info.wireframe) {
    frame_.draws = drawsFor(view, info.shading, settings_.shadingPerFrame && !info.lodFrozen);
    for (const TerrainDraw& draw : frame_.draws) buildFillPipeline(draw.shading);
    if (shadesDeferred()) buildShadePipeline(info.shading);
  }

  // What the heights depend on: unchanged while frozen (unless a toggle changes the patch layout).
  pending_ = ComputeKey{};
  pending_.camera = lod.orientation.cameraPlanetFrame;
  pending_.orientation = lod.orientation.localToPlanet;
  pending_.firstRing = lod.rings.firstRing;
  pending_.lastRing = lod.rings.lastRing;
  pending_.vertices = vertices;
  // New patch texels change the heights of the vertices they hold.
  if (std::any_of(patchPlan_.work.begin(), patchPlan_.work.end(),
                  [](const std::vector<PatchTextures::Region>& w) { return !w.empty(); }))
    ++patchGeneration_;
  pending_.patchGeneration = patchGeneration_;
  if (patches) {
    pending_.face = info.patchLayout.face;
    pending_.exponent = info.patchLayout.levels[0].exponent;
    pending_.originA = info.patchLayout.levels[0].originA;
    pending_.originB = info.patchLayout.levels[0].originB;
  }
  return frame_;
}

void TerrainPass::cullFor(const glm::dmat4& viewProjection, double cameraZ, bool cull, ClipmapCull& out) const {
  ClipmapCullView view;
  view.viewProjection = viewProjection;
  view.radiusM = planet_.radiusM;
  view.cameraZ = cameraZ;
  view.minHeightM = lowestSurfaceM_;
  view.maxHeightM = maxTerrainHeightM_;
  cullClipmap(mesh_, frame_.rings.firstRing, frame_.rings.lastRing, view, gpu::kTerrainComputeWorkgroupSize, cull, out);
}

uint64_t TerrainPass::writeCulledMesh(const ClipmapCull& culled) {
  // Host-visible: plain copies (the slot's previous frame has completed).
  vk::uploadBuffer(context_, *drawIndices_[slot_], culled.indices.data(), culled.indices.size() * sizeof(uint32_t));
  std::vector<glm::uvec2> chunks;
  uint64_t hash = 1469598103934665603ull;  // FNV-1a over the chunks
  for (const ClipmapCull::Chunk& c : culled.chunks) {
    chunks.emplace_back(c.firstVertex, c.count);
    for (uint32_t word : {c.firstVertex, c.count}) hash = (hash ^ word) * 1099511628211ull;
  }
  vk::uploadBuffer(context_, *chunks_[slot_], chunks.data(), chunks.size() * sizeof(glm::uvec2));
  drawIndexCount_ = uint32_t(culled.indices.size());
  chunkCount_ = uint32_t(chunks.size());
  frame_.triangles = drawIndexCount_ / 3;
  frame_.cellsKept = culled.cellsKept;
  frame_.cellsTotal = culled.cellsTotal;
  culledVertices_ = culled.vertexCount();
  return hash;
}

void TerrainPass::writeUniforms(const TerrainView& view, const glm::dmat4& viewProjection, double cameraZ) {
  const ClipmapFrame& o = frame_.orientation;
  gpu::FrameUniforms& u = uniformData_;
  u = gpu::FrameUniforms{};
  u.viewProjection = glm::mat4(viewProjection);
  u.localToPlanet = glm::mat4(glm::mat3(o.localToPlanet));
  u.planetToLocal = glm::mat4(glm::mat3(glm::transpose(o.localToPlanet)));
  u.camera = glm::vec4(float(cameraZ), float(planet_.radiusM), float(view.timeS), float(planet_.water.waveSlope));
  const PlanetColors& c = planet_.colors;
  u.planet =
      glm::vec4(float(planet_.seaLevelM), planet_.hasOcean ? 1.0f : 0.0f, float(c.beachHeightM), float(c.snowLineM));
  u.shading = glm::vec4(float(std::sin(c.iceCapLatitudeDeg * std::numbers::pi / 180.0)), float(int(c.scheme)),
                        frame_.wireframe ? 1.0f : 0.0f, float(settings_.ambient));
  const glm::dvec3 sunLocal = glm::transpose(o.localToPlanet) * view.sunDirection;
  // The sun at the body's distance (reference/sunlight.h): its direct light, the sky light it
  // feeds (linear in it), and the disc's size for the horizon fade and the ring's penumbra.
  const double scale = view.sunIrradianceScale;
  frame_.sunIrradiance = gpu::kSunIrradiance * settings_.sunIntensity * scale;
  frame_.sunAngularRadiusRad = view.sunAngularRadiusRad;
  u.sunLocal = glm::vec4(glm::vec3(sunLocal), float(frame_.sunIrradiance));
  u.water = waterUniform(planet_.water, frame_.waterDrawn);
  if (view.clouds && cloudsOverSea()) {
    const CloudCover::Layer layer = sky_.clouds().layerAt(view.timeS);
    u.clouds = layer.clouds;
    u.cloudShape = glm::vec4(layer.shape.x, layer.shape.y, 1.0f, 0.0f);
    u.cloudMotion = layer.motion;
  }
  // The sky the sea mirrors: the sky-view table near the ground (its ground sphere as the sky
  // pass's: the radius sphere under a sea, and only a planet with a sea draws water).
  u.skyView = glm::vec4(float(skyViewWeight(cameraZ)), 0.0f, 0.0f, 0.0f);
  if (ring_) {
    u.cameraPlanet = glm::vec4(glm::vec3(view.camera.position), 1.0f);
    u.ring = *ring_;
    u.ring.variation.w = float(view.sunAngularRadiusRad);
  }
  u.eclipse = eclipseGpuParams(view.occluders, glm::transpose(o.localToPlanet), view.sunAngularRadiusRad);
  u.atmosphere = sky_.atmosphere();
  u.atmosphere.radii.z = float(view.sunAngularRadiusRad);
  u.atmosphere.ozoneSun.y *= float(scale);
  for (int i = 0; i < kSkyIrradianceSamples; ++i) u.skyIrradiance[i] = sky_.skyIrradiance()[size_t(i)] * float(scale);
  u.colorDeepWater = toVec4(c.deepWater);
  u.colorShallowWater = toVec4(c.shallowWater);
  u.colorSnow = toVec4(c.snow);
  writeMaterials(u, planet_.materials, settings_.bandWavelengthM, o.nadirDirection() * planet_.radiusM);
  u.scheme = schemeGpuParams(c, planet_.radiusM, planet_.materials.rockSlopeDeg);
  if (lightsDrawn()) u.lights = lightsGpuParams(planet_.lights, planet_.radiusM);

  const PatchLayout& layout = frame_.patchLayout;
  if (!layout.levels.empty()) {
    // The reference point: the finest level's texel-grid corner. Per-vertex face offsets are
    // measured from it in float; everything large is subtracted here in double.
    const PatchLevel& finest = layout.levels[0];
    const double refA = std::ldexp(double(finest.originA), finest.exponent);
    const double refB = std::ldexp(double(finest.originB), finest.exponent);
    const glm::dvec3 ref = cubeFaceDirection(layout.face, refA, refB);
    const CubeFace face = cubeFace(layout.face);
    u.faceAxisA = glm::vec4(glm::vec3(face.axisA), float(glm::dot(ref, face.axisA)));
    u.faceAxisB = glm::vec4(glm::vec3(face.axisB), float(glm::dot(ref, face.axisB)));
    u.faceNormal = glm::vec4(glm::vec3(face.normal), float(glm::dot(ref, face.normal)));
    u.refMinusNadir = glm::vec4(glm::vec3(ref - o.nadirDirection()), float(layout.levels.size()));
    // Each level as the textures will hold it this frame (PatchTextures::plan): a level whose
    // work is spread over frames is sampled only over the rectangle its layer holds, and not at
    // all (layer −1) while it holds nothing.
    const double res = double(layout.resolution);
    for (size_t j = 0; j < layout.levels.size(); ++j) {
      const PatchLevel& level = patchPlan_.layout.levels[j];
      const double texel = std::ldexp(1.0, level.exponent);
      u.patchLevels[j] = glm::vec4(patchPlan_.usable[j] ? float(level.layer) : -1.0f,
                                   float(1.0 / (texel * layout.resolution)),
                                   float(refA - double(level.originA) * texel), float(refB - double(level.originB) * texel));
      const PatchTextures::Region& held = patchPlan_.held[j];
      u.patchBounds[j] = glm::vec4(float(double(held.originA - level.originA) / res),
                                   float(double(held.originB - level.originB) / res),
                                   float(double(held.originA + held.width - level.originA) / res),
                                   float(double(held.originB + held.height - level.originB) / res));
      const glm::vec2 wrap = PatchTextures::storageOffset(level, layout.resolution);
      if (j % 2 == 0) {
        u.patchWrap[j / 2].x = wrap.x;
        u.patchWrap[j / 2].y = wrap.y;
      } else {
        u.patchWrap[j / 2].z = wrap.x;
        u.patchWrap[j / 2].w = wrap.y;
      }
    }
    // The water's waves are phased at the same reference point.
    writeWaves(u.waves, planet_.water, planet_.radiusM, refA, refB, view.timeS);
  }
  vk::uploadBuffer(context_, *uniforms_[slot_], &u, sizeof(u));
}

gpu::TerrainComputePush TerrainPass::heightPush() const {
  gpu::TerrainComputePush push{};
  push.numPhi = settings_.mesh.numPhi;
  push.ringCount = mesh_.ringCount();
  push.layerCount = uint32_t(planet_.layers.size());
  push.baseHeightM = float(planet_.baseHeightM);
  push.heightScale = float(planet_.heightScale);
  push.bandFrequency = float(1.0 / settings_.bandWavelengthM);
  push.regionalWeight = float(planet_.materials.regionalNoise);
  push.firstRing = frame_.heightFirstRing;
  push.lastRing = frame_.heightLastRing;
  push.poleNeighbourRing = frame_.rings.lastRing;
  return push;
}

void TerrainPass::recordCpuHeights(VkCommandBuffer cmd, uint32_t firstVertex, uint32_t vertexCount) {
  CpuSurfaceJob job;
  job.planet = &planet_;
  job.tables = &tables_;
  job.mesh = &mesh_;
  job.frame = &uniformData_;
  job.ringSpacingM = ringSpacings_;
  job.bandFrequency = float(1.0 / settings_.bandWavelengthM);
  job.regionalWeight = float(planet_.materials.regionalNoise);
  job.firstVertex = firstVertex;
  job.vertexCount = vertexCount;
  const VkDeviceSize vertices = mesh_.vertexCount();
  const vk::Buffer& stagingBuffer = *cpuStaging_[slot_];
  glm::vec4* staging = static_cast<glm::vec4*>(stagingBuffer.mapped());
  const auto start = std::chrono::steady_clock::now();
  // The slot's previous copy out of this staging buffer has finished: its fence was waited for.
  computeSurfaceCpu(job, settings_.cpuThreads, staging, staging + vertices, staging + 2 * vertices);
  frame_.cpuHeightsMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const VkDeviceSize v4 = sizeof(glm::vec4);
  const VkDeviceSize pole = mesh_.poleVertex();
  const VkBufferCopy surface[2] = {{firstVertex * v4, firstVertex * v4, vertexCount * v4}, {pole * v4, pole * v4, v4}};
  const VkBufferCopy normals[2] = {{(vertices + firstVertex) * v4, firstVertex * v4, vertexCount * v4},
                                   {(vertices + pole) * v4, pole * v4, v4}};
  const VkBufferCopy attributes[2] = {{(2 * vertices + firstVertex) * v4, firstVertex * v4, vertexCount * v4},
                                      {(2 * vertices + pole) * v4, pole * v4, v4}};
  context_.allocator.flush(stagingBuffer.allocation);
  vkCmdCopyBuffer(cmd, stagingBuffer.buffer, surface_->buffer, 2, surface);
  vkCmdCopyBuffer(cmd, stagingBuffer.buffer, normals_->buffer, 2, normals);
  vkCmdCopyBuffer(cmd, stagingBuffer.buffer, attributes_->buffer, 2, attributes);
}

void TerrainPass::recordCompute(VkCommandBuffer cmd, vk::GpuTimer* timer) {
  // The patch levels first: the heights take the vertices they hold from them
  // (terrain_vertex_surface.glsl, vertexSurface), as does the vertex-shader source.
  frame_.patchLevelsRebuilt = 0;
  frame_.patchTexelsWritten = 0;
  if (!frame_.patchLayout.levels.empty()) {
    if (timer) timer->begin(cmd, "patches");
    frame_.patchLevelsRebuilt = patches_->update(cmd, patchPlan_, slot_);
    frame_.patchTexelsWritten = patches_->lastUpdateTexels();
    if (timer) timer->end(cmd);
  }
  frame_.heightsComputed = !(computed_ && *computed_ == pending_);
  frame_.verticesEvaluated = 0;
  frame_.cpuHeightsMs = 0.0;
  const uint32_t n = settings_.mesh.numPhi;
  if (settings_.heightSource == HeightSource::VertexShader) {
    // The draws evaluate every vertex they draw, every frame, the sea's again: nothing to
    // compute ahead.
    frame_.heightsComputed = true;
    frame_.verticesEvaluated = culledVertices_ * (frame_.waterDrawn ? 2 : 1);
  } else if (frame_.heightsComputed) {
    if (timer) timer->begin(cmd, "heights");
    // The previous frame's draws read these buffers; the rewrite must wait for them.
    vk::memoryBarrier(cmd,
                      VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                          VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT, 0);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &sets_[slot_], 0, nullptr);
    const gpu::TerrainComputePush push = heightPush();
    // Heights and normals together (their analytic gradient), on the GPU or uploaded from the CPU.
    if (settings_.heightSource == HeightSource::Cpu) {
      // The CPU reference evaluates the drawn rings whole (a comparison mode: it stays simple).
      const uint32_t first = frame_.heightFirstRing * n;
      const uint32_t count = (frame_.heightLastRing - frame_.heightFirstRing + 1) * n;
      frame_.verticesEvaluated = count + 1;
      recordCpuHeights(cmd, first, count);
    } else {
      // One workgroup per chunk of the culled mesh's vertices.
      frame_.verticesEvaluated = culledVertices_;
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, heightsPipeline_.get());
      vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
      vkCmdDispatch(cmd, chunkCount_, 1, 1);
    }
    // The draws read positions, normals and attributes as vertex input.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                      VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
    if (timer) timer->end(cmd);
    computed_ = pending_;
  }
  if (frame_.seaFloorSplit) recordSplit(cmd, timer);
}

void TerrainPass::recordSplit(VkCommandBuffer cmd, vk::GpuTimer* timer) {
  const uint32_t triangles = drawIndexCount_ / 3;
  if (triangles == 0) return;
  if (timer) timer->begin(cmd, "split");
  // After the heights (or their upload) and the previous draws from these lists.
  vk::memoryBarrier(
      cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT,
      VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
      VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, splitPipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, splitLayout_.get(), 0, 1, &splitSets_[slot_], 0,
                          nullptr);
  const SplitPush push{triangles, float(planet_.seaLevelM), kSplitSlope, kSplitMarginM};
  vkCmdPushConstants(cmd, splitLayout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  vkCmdDispatch(cmd, (triangles + 63) / 64, 1, 1);
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT, VK_ACCESS_2_INDEX_READ_BIT);
  if (timer) timer->end(cmd);
}

void TerrainPass::invalidatePatches() {
  if (patches_) patches_->invalidate();
}

void TerrainPass::bindDrawState(VkCommandBuffer cmd) const {
  const VkPipelineLayout drawLayout = noiseDrawLayout_.get() ? noiseDrawLayout_.get() : layout_.get();
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, drawLayout, 0, 1, &sets_[slot_], 0, nullptr);
  if (noiseDrawLayout_.get()) {
    const gpu::TerrainComputePush push = heightPush();
    vkCmdPushConstants(cmd, drawLayout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), &push);
  }
  vkCmdBindIndexBuffer(cmd, drawIndices_[slot_]->buffer, 0, VK_INDEX_TYPE_UINT32);
  if (!noiseDrawLayout_.get()) {
    const VkBuffer vertexBuffers[] = {surface_->buffer, meshVertices_->buffer, normals_->buffer, attributes_->buffer};
    const VkDeviceSize offsets[std::size(vertexBuffers)] = {};
    static_assert(std::size(vertexBuffers) == std::size(kVertexStrides));
    vkCmdBindVertexBuffers(cmd, 0, uint32_t(std::size(vertexBuffers)), vertexBuffers, offsets);
  }
}

void TerrainPass::recordDraw(VkCommandBuffer cmd, vk::GpuTimer* timer) {
  if (timer) timer->begin(cmd, "terrain");
  // The culled mesh, near to far (clipmap_culling.h): the fan that closes the innermost drawn ring
  // at the pole, then the kept quads of the drawn bands inside out, so that the early depth test
  // of planets without a sea (terrain.frag) skips most hidden ground before shading it.
  if (frame_.wireframe) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, wireframePipeline_.get());
    bindDrawState(cmd);
    vkCmdDrawIndexed(cmd, drawIndexCount_, 1, 0, 0, 0);
  } else {
    // Each run of bands with its own fill pipeline (the bound state stays: one layout). With the
    // sea floor split, the runs twice: the ground that cannot be sea floor first, by the pipelines
    // that test depth before shading; then the rest, whose depth the shader may push back. Both
    // lists keep the runs' positions.
    bindDrawState(cmd);
    const int lists = frame_.seaFloorSplit ? 2 : 1;
    for (int list = 0; list < lists; ++list) {
      if (frame_.seaFloorSplit) vkCmdBindIndexBuffer(cmd, splitIndices_[slot_][list]->buffer, 0, VK_INDEX_TYPE_UINT32);
      const bool dryList = frame_.seaFloorSplit && list == 0;
      const auto& pipelines = shadesDeferred() ? (dryList ? gbufferDryPipelines_ : gbufferPipelines_)
                                               : (dryList ? dryPipelines_ : fillPipelines_);
      for (const TerrainDraw& draw : frame_.draws) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines[draw.shading.key()].get());
        vkCmdDrawIndexed(cmd, draw.indexCount, 1, draw.firstIndex, 0, 0);
      }
    }
  }
  if (timer) timer->end(cmd);
}

void TerrainPass::recordWaterDraw(VkCommandBuffer cmd, vk::GpuTimer* timer) {
  if (!frame_.waterDrawn) return;
  // The sea over the ground, over the same ranges; the water pipeline shares the ground's layout.
  // With the sea floor split, only over the triangles that can be sea floor: over the rest the
  // ground stands above sea level at every pixel, so a ray to the sea there crosses the ground
  // first (the mesh is one surface) and the depth test would hide all of it. On lavapipe the
  // draw's vertices and triangles cost time all the same (1.2 ms of the water's 2.8 ms 50 m over
  // land at 640×360).
  water_->bindPipeline(cmd);
  bindDrawState(cmd);
  if (frame_.seaFloorSplit) vkCmdBindIndexBuffer(cmd, splitIndices_[slot_][1]->buffer, 0, VK_INDEX_TYPE_UINT32);
  water_->recordDraw(cmd, drawIndexCount_, timer);
}

}  // namespace planet
