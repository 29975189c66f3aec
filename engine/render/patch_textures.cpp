#include "render/patch_textures.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <span>

#include <fmt/format.h>

#include "core/error.h"
#include "core/log.h"
#include "planet/octave_budget.h"
#include "planet/planet_gpu_data.h"
#include "planet/terrain_rebase.h"
#include "shared/patch_params.h"
#include "spv/patch_height.comp.h"
#include "spv/patch_height_no_craters.comp.h"
#include "spv/patch_normal.comp.h"
#include "vk/commands.h"
#include "vk/context.h"

namespace planet {
namespace {

// Set 0 of both passes (shaders/shared/patch_params.h); each pass uses a subset.
constexpr VkDescriptorType kBindings[] = {
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,        // kPatchBindingLevel
    VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER,  // kPatchBindingRemainders (why texels: patch_height.comp)
    VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER,  // kPatchBindingShifts
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,        // kPatchBindingHeights
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,        // kPatchBindingLayers
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,        // kPatchBindingPermutations
    VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,         // kPatchBindingImage
};
static_assert(std::size(kBindings) == gpu::kPatchBindingCount && gpu::kPatchBindingImage == 6);
// The level buffer's std430 block: PatchLevelParams, then the runtime array of tiles.
static_assert(sizeof(gpu::PatchLevelParams) % 16 == 0);

// Exponents whose texel size 2^e, and the squares of small multiples of it, stay normal floats.
constexpr int kMaxAbsExponent = 60;

uint32_t groupsFor(uint32_t count) { return (count + gpu::kPatchWorkgroupSize - 1) / gpu::kPatchWorkgroupSize; }

// floor(value / step) for a positive step.
int64_t floorDiv(int64_t value, int64_t step) {
  int64_t quotient = value / step;
  return (value % step != 0 && value < 0) ? quotient - 1 : quotient;
}

}  // namespace

PatchTextures::PatchTextures(vk::Context& context, const PlanetGpuData& data, const PatchSettings& settings)
    : context_(context), data_(data), settings_(settings) {
  validatePatchSettings(settings_);
  VkFormatProperties properties{};
  vkGetPhysicalDeviceFormatProperties(context_.physicalDevice, kFormat, &properties);
  const VkFormatFeatureFlags features = properties.optimalTilingFeatures;
  const VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
  if ((features & needed) != needed)
    throw Error(
        fmt::format("device '{}' cannot use R32G32B32A32_SFLOAT as a storage and sampled image (optimal "
                    "tiling features {:#x}), which the patch textures need",
                    context_.info.name, features));
  const bool linear = (features & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;
  if (!linear)
    logWarning("device '{}' cannot filter R32G32B32A32_SFLOAT linearly: the patch textures are sampled nearest",
               context_.info.name);

  const uint32_t res = settings_.resolution;
  // Tiles are whole workgroups: the height pass takes a workgroup's tile from its id.
  const uint32_t group = gpu::kPatchWorkgroupSize;
  tileSize_ = group * std::max(1u, res / (gpu::kPatchTileDivisor * group));
  // Height-buffer columns 0..res+1 start anywhere in a tile: at most this many tiles per side.
  maxTilesPerSide_ = (tileSize_ - 1 + res + 2 + tileSize_ - 1) / tileSize_;
  const VkDeviceSize tiles = VkDeviceSize(maxTilesPerSide_) * maxTilesPerSide_;
  const VkDeviceSize tableRows = tiles * gpu::kTerrainMaxLayers * gpu::kNoiseMaxOctaves;
  if (tableRows > context_.properties.limits.maxTexelBufferElements)
    throw Error(fmt::format("patch textures of {} texels need {} octave-table texels, more than the device's {}", res,
                            tableRows, context_.properties.limits.maxTexelBufferElements));
  const VkDeviceSize side = res + 2;
  image_ = {context_, vk::createImage2DArray(context_, {res, res}, settings_.levelCount, kFormat,
                                             VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT)};
  vk::submitAndWait(context_, [&](VkCommandBuffer cmd) {
    // Undefined contents to GENERAL, the only layout the image is used in; the fence wait
    // orders this before everything update() records later.
    vk::transitionImage(cmd, *image_, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, 0,
                        VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                        VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
  });

  VkSamplerCreateInfo samplerInfo{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  samplerInfo.magFilter = linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  samplerInfo.minFilter = samplerInfo.magFilter;
  samplerInfo.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  // Toroidal storage: a level's texels wrap around its layer, and so does filtering across
  // the seam (the texels either side of it are neighbours on the face). The array layer is
  // chosen by an integer coordinate, which addressing does not touch.
  samplerInfo.addressModeU = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  samplerInfo.addressModeV = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  samplerInfo.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  samplerInfo.minLod = 0.0f;
  samplerInfo.maxLod = 0.0f;
  sampler_ = {context_, vk::createSampler(context_, samplerInfo)};

  regions_.resize(size_t(settings_.levelCount) * kRegionsPerLevel);
  contents_.resize(settings_.levelCount);
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  for (RegionResources& layer : regions_) {
    const VkDeviceSize levelBytes = sizeof(gpu::PatchLevelParams) + tiles * sizeof(gpu::PatchTile);
    for (uint32_t slot = 0; slot < vk::kFramesInFlight; ++slot) {
      layer.level[slot] = {context_, vk::createBuffer(context_, levelBytes, storage, vk::MemoryUsage::Upload)};
      const VkBufferUsageFlags texels = VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
      layer.remainders[slot] = {
          context_, vk::createBuffer(context_, tableRows * sizeof(glm::vec4), texels, vk::MemoryUsage::Upload)};
      layer.shifts[slot] = {
          context_, vk::createBuffer(context_, tableRows * sizeof(glm::uvec4), texels, vk::MemoryUsage::Upload)};
      layer.remainderTexels[slot] = {
          context_, vk::createBufferView(context_, *layer.remainders[slot], VK_FORMAT_R32G32B32A32_SFLOAT)};
      layer.shiftTexels[slot] = {context_,
                                 vk::createBufferView(context_, *layer.shifts[slot], VK_FORMAT_R32G32B32A32_UINT)};
    }
    layer.heights = {context_,
                     vk::createBuffer(context_, side * side * sizeof(float), storage, vk::MemoryUsage::DeviceLocal)};
  }
  createPipelines();
}

void PatchTextures::createPipelines() {
  // The old pipelines (and the sets from their pools) go before the new ones are made.
  normalPipeline_.reset();
  heightPipeline_.reset();
  specialization_ = layerSpecialization(data_.planet());
  const uint32_t sets = uint32_t(regions_.size()) * vk::kFramesInFlight;
  // Without the crater and erosion code unless a layer needs it (planet_gpu_data.h,
  // needsFullNoiseShaders); the specialization holds the types, so a change of variant also shows
  // as a change of it.
  const std::span<const uint32_t> height = needsFullNoiseShaders(data_.planet())
                                               ? std::span<const uint32_t>(kSpv_patch_height_comp)
                                               : kSpv_patch_height_no_craters_comp;
  heightPipeline_ = {context_, vk::createComputePipeline(context_, height, kBindings, 0, specialization_, sets)};
  normalPipeline_ = {context_, vk::createComputePipeline(context_, kSpv_patch_normal_comp, kBindings, 0, {}, sets)};
  const VkDescriptorType buffer = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  for (RegionResources& layer : regions_) {
    for (uint32_t slot = 0; slot < vk::kFramesInFlight; ++slot) {
      for (const vk::ComputePipeline* pipeline : {&heightPipeline_.get(), &normalPipeline_.get()}) {
        VkDescriptorSet set = vk::allocateSet(context_, pipeline->descriptorPool, pipeline->setLayout);
        vk::writeBufferDescriptor(context_, set, gpu::kPatchBindingLevel, buffer, *layer.level[slot]);
        vk::writeTexelBufferDescriptor(context_, set, gpu::kPatchBindingRemainders, layer.remainderTexels[slot].get());
        vk::writeTexelBufferDescriptor(context_, set, gpu::kPatchBindingShifts, layer.shiftTexels[slot].get());
        vk::writeBufferDescriptor(context_, set, gpu::kPatchBindingHeights, buffer, *layer.heights);
        vk::writeBufferDescriptor(context_, set, gpu::kPatchBindingLayers, buffer, data_.layers());
        vk::writeBufferDescriptor(context_, set, gpu::kPatchBindingPermutations, buffer, data_.permutations());
        vk::writeImageDescriptor(context_, set, gpu::kPatchBindingImage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, image_->view,
                                 VK_IMAGE_LAYOUT_GENERAL);
        (pipeline == &heightPipeline_.get() ? layer.heightSet : layer.normalSet)[slot] = set;
      }
    }
  }
}

void PatchTextures::invalidate() {
  for (LayerContent& content : contents_) content.held = {};
}

glm::uvec2 PatchTextures::storedTexel(const PatchLevel& level, uint32_t resolution, int64_t x, int64_t y) {
  const int64_t res = resolution;
  const int64_t a = level.originA + x, b = level.originB + y;
  return {uint32_t(a - floorDiv(a, res) * res), uint32_t(b - floorDiv(b, res) * res)};
}

glm::vec2 PatchTextures::storageOffset(const PatchLevel& level, uint32_t resolution) {
  const glm::uvec2 first = storedTexel(level, resolution, 0, 0);
  return glm::vec2(first) / float(resolution);
}

PatchTextures::Region PatchTextures::heldOf(int face, const PatchLevel& level) const {
  const LayerContent& content = contents_[level.layer];
  if (content.held.empty() || content.face != face || content.exponent != level.exponent) return {};
  const int64_t res = settings_.resolution;
  const Region& h = content.held;
  const int64_t a0 = std::max(h.originA, level.originA), a1 = std::min(h.originA + h.width, level.originA + res);
  const int64_t b0 = std::max(h.originB, level.originB), b1 = std::min(h.originB + h.height, level.originB + res);
  if (a1 <= a0 || b1 <= b0) return {};
  return {a0, b0, uint32_t(a1 - a0), uint32_t(b1 - b0)};
}

void PatchTextures::writeRegion(const PatchLayout& layout, const PatchLevel& level, const Region& region,
                                RegionResources& resources, uint32_t slot) {
  const PlanetDescription& planet = data_.planet();
  const CubeFace face = cubeFace(layout.face);
  const double texel = std::ldexp(1.0, level.exponent);
  const int64_t size = tileSize_;

  gpu::PatchLevelParams params{};
  params.axisA = glm::vec4(glm::vec3(face.axisA), 0.0f);
  params.axisB = glm::vec4(glm::vec3(face.axisB), 0.0f);
  params.texelSize = float(texel);
  params.radiusM = float(planet.radiusM);
  params.baseHeightM = float(planet.baseHeightM);
  params.heightScale = float(planet.heightScale);
  // Height-buffer column 0 is face index originA − 1; tiles start at multiples of the tile size.
  const int64_t firstA = region.originA - 1, firstB = region.originB - 1;
  const int64_t tileA = floorDiv(firstA, size), tileB = floorDiv(firstB, size);
  params.shiftA = int32_t(firstA - tileA * size);
  params.shiftB = int32_t(firstB - tileB * size);
  params.tileSize = tileSize_;
  const int64_t spanA = int64_t(region.width) + 2, spanB = int64_t(region.height) + 2;
  const uint32_t tilesA = uint32_t((params.shiftA + spanA + size - 1) / size);
  const uint32_t tilesB = uint32_t((params.shiftB + spanB + size - 1) / size);
  params.tilesPerSide = std::max(tilesA, tilesB);
  params.resolution = layout.resolution;
  params.regionWidth = region.width;
  params.regionHeight = region.height;
  const int64_t res = layout.resolution;
  params.storeOffsetA = uint32_t(region.originA - floorDiv(region.originA, res) * res);
  params.storeOffsetB = uint32_t(region.originB - floorDiv(region.originB, res) * res);
  params.layerCount = uint32_t(planet.layers.size());
  params.imageLayer = level.layer;
  params.firstGroupA = uint32_t(params.shiftA) / gpu::kPatchWorkgroupSize;
  params.firstGroupB = uint32_t(params.shiftB) / gpu::kPatchWorkgroupSize;
  resources.heightGroupsA = groupsFor(uint32_t(params.shiftA + spanA)) - params.firstGroupA;
  resources.heightGroupsB = groupsFor(uint32_t(params.shiftB + spanB)) - params.firstGroupB;
  resources.normalGroupsA = groupsFor(region.width);
  resources.normalGroupsB = groupsFor(region.height);
  const double spacingM = patchTexelSpacingM(layout, level, planet.radiusM);
  for (size_t l = 0; l < planet.layers.size(); ++l) {
    const OctaveBudget budget = octaveBudget(planet.layers[l], spacingM);
    params.budgets[l] = {budget.octaves, budget.lastOctaveWeight, 0u, 0u};
  }
  char* levelData = static_cast<char*>(resources.level[slot]->mapped());
  std::memcpy(levelData, &params, sizeof(params));

  // Each tile's anchor, its centre texel (face index k·T + T/2), in double; then its tables.
  auto* tiles = reinterpret_cast<gpu::PatchTile*>(levelData + sizeof(params));
  auto* remainders = static_cast<glm::vec4*>(resources.remainders[slot]->mapped());
  auto* shifts = static_cast<glm::uvec4*>(resources.shifts[slot]->mapped());
  const size_t rowsPerTile = planet.layers.size() * gpu::kNoiseMaxOctaves;
  for (uint32_t ty = 0; ty < tilesB; ++ty) {
    for (uint32_t tx = 0; tx < tilesA; ++tx) {
      const double a = (double((tileA + tx) * size + size / 2) + 0.5) * texel;
      const double b = (double((tileB + ty) * size + size / 2) + 0.5) * texel;
      const glm::dvec3 g = face.normal + a * face.axisA + b * face.axisB;
      const double s = glm::length(g);
      const glm::dvec3 c = g / s;
      const uint32_t index = ty * params.tilesPerSide + tx;
      tiles[index] = {glm::vec4(glm::vec3(c), float(s)), glm::vec4(float(a), float(b), 0.0f, 0.0f)};
      const OctaveTables tables = buildOctaveTables(planet, planet.radiusM * c);
      std::copy(tables.remainders.begin(), tables.remainders.end(), remainders + index * rowsPerTile);
      std::copy(tables.shifts.begin(), tables.shifts.end(), shifts + index * rowsPerTile);
    }
  }
  context_.allocator.flush(resources.level[slot]->allocation);
  context_.allocator.flush(resources.remainders[slot]->allocation);
  context_.allocator.flush(resources.shifts[slot]->allocation);
}

namespace {

// A level's window less what its layer holds, `held` (a rectangle inside it that shares a corner
// with it, or none): at most one strip along a (all rows) and one along b (the held columns),
// else the whole window.
std::vector<PatchTextures::Region> missingRegions(const PatchTextures::Region& window, const PatchTextures::Region& held) {
  using Region = PatchTextures::Region;
  if (held.empty()) return {window};
  if (held == window) return {};
  const int64_t a1 = window.originA + window.width, b1 = window.originB + window.height;
  const int64_t heldA1 = held.originA + held.width, heldB1 = held.originB + held.height;
  const bool cornerA = held.originA == window.originA || heldA1 == a1;
  const bool cornerB = held.originB == window.originB || heldB1 == b1;
  if (!cornerA || !cornerB) return {window};
  std::vector<Region> regions;
  if (held.width != window.width) {
    const int64_t first = held.originA == window.originA ? heldA1 : window.originA;
    regions.push_back({first, window.originB, window.width - held.width, window.height});
  }
  if (held.height != window.height) {
    const int64_t first = held.originB == window.originB ? heldB1 : window.originB;
    regions.push_back({held.originA, first, held.width, window.height - held.height});
  }
  return regions;
}

// Grows `held` (inside `window`) by one strip along its side farthest from the window's edge, at
// most `texels` texels and at least `minThickness` thick (less only where less is missing).
// Returns the strip (empty when nothing is missing or it would be thinner).
PatchTextures::Region growHeld(const PatchTextures::Region& window, PatchTextures::Region& held, uint64_t texels,
                               uint32_t minThickness) {
  const int64_t gaps[4] = {held.originA - window.originA,
                           (window.originA + window.width) - (held.originA + held.width),
                           held.originB - window.originB,
                           (window.originB + window.height) - (held.originB + held.height)};
  const int side = int(std::max_element(std::begin(gaps), std::end(gaps)) - std::begin(gaps));
  const int64_t gap = gaps[side];
  if (gap <= 0) return {};
  const bool alongA = side < 2;  // a strip of columns (it spans held's rows), else of rows
  const int64_t extent = alongA ? held.height : held.width;
  const int64_t thickness = std::min<int64_t>(gap, int64_t(texels / uint64_t(extent)));
  if (thickness < std::min<int64_t>(gap, minThickness)) return {};
  PatchTextures::Region strip;
  if (alongA) {
    strip = {side == 0 ? held.originA - thickness : held.originA + held.width, held.originB, uint32_t(thickness),
             held.height};
    held.originA = std::min(held.originA, strip.originA);
    held.width += uint32_t(thickness);
  } else {
    strip = {held.originA, side == 2 ? held.originB - thickness : held.originB + held.height, held.width,
             uint32_t(thickness)};
    held.originB = std::min(held.originB, strip.originB);
    held.height += uint32_t(thickness);
  }
  return strip;
}

}  // namespace

PatchTextures::Plan PatchTextures::plan(const PatchLayout& desired, uint64_t texelBudget) const {
  Plan plan;
  plan.layout = desired;
  const size_t count = desired.levels.size();
  plan.usable.assign(count, false);
  plan.held.assign(count, Region{});
  plan.work.assign(count, {});
  const int64_t res = settings_.resolution;
  uint64_t spent = 0;
  // Nothing held anywhere (the first frame, or after invalidate()): a load, built whole.
  if (std::all_of(contents_.begin(), contents_.end(), [](const LayerContent& c) { return c.held.empty(); }))
    texelBudget = 0;
  // Coarsest first: a coarse level stands in for every finer one that waits.
  for (size_t j = count; j-- > 0;) {
    const PatchLevel& level = desired.levels[j];
    if (level.layer >= contents_.size()) continue;  // update() reports the bad layer
    const Region window{level.originA, level.originB, uint32_t(res), uint32_t(res)};
    Region held = heldOf(desired.face, level);
    std::vector<Region>& work = plan.work[j];
    if (texelBudget == 0) {
      work = missingRegions(window, held);
      held = window;
    } else if (held.empty()) {
      // A square at the window's centre, as large as the budget left allows (in steps of the
      // workgroup), at least kMinStripTexels wide for the first level with work.
      const uint64_t left = texelBudget > spent ? texelBudget - spent : 0;
      uint32_t side = std::min<uint32_t>(uint32_t(res), uint32_t(std::sqrt(double(left))));
      side -= side % gpu::kPatchWorkgroupSize;
      if (side < kMinStripTexels && spent == 0) side = std::min<uint32_t>(uint32_t(res), kMinStripTexels);
      if (side >= std::min<uint32_t>(uint32_t(res), kMinStripTexels)) {
        const int64_t offset = (res - side) / 2;
        held = {level.originA + offset, level.originB + offset, side, side};
        work.push_back(held);
        spent += held.texels();
      }
    } else {
      for (uint32_t r = 0; r < kRegionsPerLevel; ++r) {
        const uint64_t left = texelBudget > spent ? texelBudget - spent : 0;
        // The first strip of a frame is never refused for the budget: every frame makes progress.
        const uint64_t allowed = spent == 0 ? std::max<uint64_t>(left, uint64_t(kMinStripTexels) * res) : left;
        const Region strip = growHeld(window, held, allowed, kMinStripTexels);
        if (strip.empty()) break;
        work.push_back(strip);
        spent += strip.texels();
      }
    }
    plan.usable[j] = !held.empty();
    plan.held[j] = held;
    if (held != window) ++plan.deferred;
  }
  return plan;
}

void PatchTextures::checkLayout(const PatchLayout& layout) const {
  if (layout.resolution != settings_.resolution)
    throw Error(fmt::format("patch layout resolution {} differs from the patch textures' {}", layout.resolution,
                            settings_.resolution));
  if (layout.levels.size() != settings_.levelCount)
    throw Error(
        fmt::format("patch layout has {} levels, the patch textures {}", layout.levels.size(), settings_.levelCount));
  cubeFace(layout.face);  // throws for a bad face
  std::vector<bool> used(settings_.levelCount, false);
  for (const PatchLevel& level : layout.levels) {
    if (level.layer >= settings_.levelCount || used[level.layer])
      throw Error(
          fmt::format("patch level layer {} is outside 0..{} or used twice", level.layer, settings_.levelCount - 1));
    used[level.layer] = true;
    if (level.exponent < -kMaxAbsExponent || level.exponent > kMaxAbsExponent)
      throw Error(fmt::format("patch level exponent must be in [{}, {}], got {}", -kMaxAbsExponent, kMaxAbsExponent,
                              level.exponent));
  }
}

uint32_t PatchTextures::update(VkCommandBuffer cmd, const PatchLayout& layout, uint32_t slot) {
  vk::checkFrameSlot(slot);
  checkLayout(layout);
  return update(cmd, plan(layout, 0), slot);
}

uint32_t PatchTextures::update(VkCommandBuffer cmd, const Plan& planned, uint32_t slot) {
  vk::checkFrameSlot(slot);
  const size_t count = planned.layout.levels.size();
  if (planned.usable.size() != count || planned.held.size() != count || planned.work.size() != count)
    throw Error(fmt::format("patch plan has {} levels and {} usable flags, {} held regions, {} work lists", count,
                            planned.usable.size(), planned.held.size(), planned.work.size()));
  checkLayout(planned.layout);
  // The planet's layer types or hashes changed: the height pipeline is specialized on them.
  // A frame of the other slot may still use the old pipelines and sets: wait for it (rare).
  // Every level is then built whole, which holds at least what the plan said it would.
  const Plan* plan = &planned;
  Plan whole;
  if (layerSpecialization(data_.planet()) != specialization_) {
    VK_CHECK(vkDeviceWaitIdle(context_.device));
    createPipelines();
    invalidate();
    whole = this->plan(planned.layout, 0);
    plan = &whole;
  }
  const PatchLayout& layout = plan->layout;

  struct Work {
    const PatchLevel* level;
    Region region;
    RegionResources* resources;
  };
  std::vector<Work> work;
  uint32_t levelsTouched = 0;
  lastUpdateTexels_ = 0;
  for (size_t j = 0; j < count; ++j) {
    const std::vector<Region>& regions = plan->work[j];
    if (regions.size() > kRegionsPerLevel)
      throw Error(fmt::format("patch plan has {} regions for level {}, at most {}", regions.size(), j,
                              kRegionsPerLevel));
    const PatchLevel& level = layout.levels[j];
    levelsTouched += regions.empty() ? 0 : 1;
    for (size_t r = 0; r < regions.size(); ++r) {
      work.push_back({&level, regions[r], &regions_[size_t(level.layer) * kRegionsPerLevel + r]});
      lastUpdateTexels_ += regions[r].texels();
    }
  }
  if (work.empty()) return 0;

  for (const Work& w : work) writeRegion(layout, *w.level, w.region, *w.resources, slot);

  // Earlier frames' terrain may still sample these layers and an earlier update's passes used
  // the height buffers: both finish before the new writes (write-after-read).
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                             VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, heightPipeline_->pipeline);
  for (const Work& w : work) {
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, heightPipeline_->layout, 0, 1,
                            &w.resources->heightSet[slot], 0, nullptr);
    vkCmdDispatch(cmd, w.resources->heightGroupsA, w.resources->heightGroupsB, 1);
  }
  // The normal pass reads the heights (with their border) that the height pass wrote.
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, normalPipeline_->pipeline);
  for (const Work& w : work) {
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, normalPipeline_->layout, 0, 1,
                            &w.resources->normalSet[slot], 0, nullptr);
    vkCmdDispatch(cmd, w.resources->normalGroupsA, w.resources->normalGroupsB, 1);
  }
  // The terrain samples the new texels: its heights pass, its vertex shader (the vertex-shader
  // height source) and its fragment shader.
  vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                        VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);

  for (size_t j = 0; j < count; ++j) {
    const PatchLevel& level = layout.levels[j];
    if (!plan->work[j].empty()) contents_[level.layer] = {layout.face, level.exponent, plan->held[j]};
  }
  return levelsTouched;
}

}  // namespace planet
