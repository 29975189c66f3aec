// World-anchored patch textures (issue 3, "Patch textures by compute"): the levels of a
// PatchLayout (patch_layout.h) rendered by compute into one 2D-array image, texel = (unit outward
// surface normal in the planet frame, terrain height in metres above the radius sphere).
//
// Precision and stability (DESIGN.md, "Earth-scale precision"): no float position of size R is
// ever formed. The texels are grouped into tiles fixed on the cube face (shared/patch_params.h);
// each tile's anchor (its centre texel) and octave tables (terrain_rebase.h) are computed in
// double on the CPU, and each texel is evaluated from its exact face-coordinate offset to its
// tile's anchor. So a texel's value depends only on where it lies on the face and on its level's
// octave budget, octaveBudget(layer, patchTexelSpacingM(...)): a level that moves by whole
// recentre steps reproduces the texels it keeps (up to the budget's change with the level's
// centre, at most an ulp of the height).
//
// Storage is toroidal (shared/patch_params.h): a texel lives at its face index mod resolution in
// its layer, so a level that moved by fewer texels than its resolution, on the same face and at
// the same exponent, keeps every texel it still covers in place and computes only the one or two
// strips it newly covers (one recentre step: an eighth of the level). A level is rebuilt whole
// when its face or exponent changed, it moved by a whole level or more, or after invalidate().
// Under a per-frame budget (plan()) a layer may hold only a rectangle of its level, grown by
// strips over frames; the terrain samples it there only (FrameUniforms::patchBounds).
// Samplers wrap (VK_SAMPLER_ADDRESS_MODE_REPEAT) and the terrain adds each level's storage
// offset (FrameUniforms::patchWrap).
//
// Two compute passes per region written: patch_height.comp evaluates heights for the region plus
// a one-texel border into a per-region buffer; patch_normal.comp takes central differences of
// the surface points (R + h)·p of the four neighbours and writes (normal, height).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include <vulkan/vulkan.h>

#include "render/patch_layout.h"
#include "vk/buffer.h"
#include "vk/image.h"
#include "vk/owned.h"
#include "vk/pipeline.h"

namespace planet::vk {
class Context;
}

namespace planet {

class PlanetGpuData;

class PatchTextures {
 public:
  // The image format: 32-bit float, because heights of thousands of metres must keep
  // millimetres (a half float steps by 2 m between 2 and 4 km).
  static constexpr VkFormat kFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

  // Validates `settings` (validatePatchSettings) and that the device can store to and sample the
  // format; without linear filtering of it the sampler falls back to nearest (logged). `data`
  // must outlive this object. The image starts in VK_IMAGE_LAYOUT_GENERAL with every level
  // marked stale (one blocking submission here).
  PatchTextures(vk::Context& context, const PlanetGpuData& data, const PatchSettings& settings);

  // Records into `cmd` the compute work that brings every level of `layout` up to date: a level
  // whose layer does not already hold exactly (face, exponent, originA, originB) for this planet
  // gets the strips it newly covers (or all of it, see above). Returns how many levels it
  // recorded work for (0: nothing recorded, not even a barrier); lastUpdateTexels() says how
  // many texels that work wrote. The rebuilt levels' parameters and octave tables
  // are written now into host-visible buffers owned per layer and frame slot (`slot` <
  // vk::kFramesInFlight), so update() may be called while a command buffer recorded for another
  // slot still executes, but not while one recorded for the same slot does (wait for its fence).
  // The caller must submit `cmd`, in the order of the update() calls: the levels count as up to
  // date from this call on. The image stays in VK_IMAGE_LAYOUT_GENERAL;
  // the recorded work ends with a barrier that makes it visible to the terrain's sampling (its
  // heights pass, vertex and fragment shaders).
  // The height pass is specialized on the planet's layer count, types and hashes; should those
  // differ from the last call's, both pipelines are recreated here (after waiting for the device
  // to be idle: a frame in flight may still use them) and every level rebuilt.
  // Throws planet::Error if layout.resolution or the number of levels differs from the
  // settings, for a bad face, a layer outside 0..levelCount−1 or used twice, an exponent
  // outside [−60, 60], or a bad slot; then nothing was recorded or marked up to date.
  uint32_t update(VkCommandBuffer cmd, const PatchLayout& layout, uint32_t slot = 0);

  // A rectangle of a level's texels by face index: [originA, originA + width) × [originB,
  // originB + height), within the level's window.
  struct Region {
    int64_t originA = 0;
    int64_t originB = 0;
    uint32_t width = 0;
    uint32_t height = 0;
    bool empty() const { return width == 0 || height == 0; }
    uint64_t texels() const { return uint64_t(width) * height; }
    bool operator==(const Region&) const = default;
  };

  // A frame's share of the work toward `desired` (issue 12, point 5: patch work spread over
  // frames so that no frame pays for a whole level). What a layer holds is a rectangle of its
  // level's window; a frame extends it by strips, so a level is usable, over what it holds, from
  // its first strip on: the terrain samples each level only inside its held rectangle and hands
  // the rest of its weight to coarser levels. Levels are taken coarsest first (a coarse level
  // stands in for every finer one that waits) while their strips fit in `texelBudget`:
  //  - 0, no limit: every level is brought up to date (what it newly covers, or all of it);
  //  - else a level held nowhere starts with a square at its centre (the camera's ground), and
  //    one held in part grows by at most kRegionsPerLevel strips, each along the side farthest
  //    from the window's edge, as thick as the budget left allows. The first level with work
  //    always gets at least a strip kMinStripTexels thick, so every frame makes progress.
  // While no layer holds anything (the first frame, or after invalidate()) the budget does not
  // apply: that frame is a load, and everything is built whole.
  struct Plan {
    PatchLayout layout;                     // the desired placement of every level
    std::vector<bool> usable;               // per level: it holds some texels after this frame's work
    std::vector<Region> held;               // per level: what its layer holds after this frame's work
    std::vector<std::vector<Region>> work;  // per level: the strips this frame computes
    uint32_t deferred = 0;                  // levels not whole after this frame's work
  };
  // Strips thinner than this are left for a later frame (the height pass computes a one-texel
  // border around each, and a frame's fixed costs are per strip).
  static constexpr uint32_t kMinStripTexels = 16;
  // A level's update writes at most two regions (the strip along a and the one along b).
  static constexpr uint32_t kRegionsPerLevel = 2;
  Plan plan(const PatchLayout& desired, uint64_t texelBudget) const;
  // Records the plan's work (see update() above for the rest). The plan must be the last one
  // made, for this PatchTextures, with no update() since.
  uint32_t update(VkCommandBuffer cmd, const Plan& plan, uint32_t slot = 0);

  // Marks every level stale, e.g. after the planet's parameters changed.
  void invalidate();

  // Texels the last update() wrote (0 when it found nothing to do).
  uint64_t lastUpdateTexels() const { return lastUpdateTexels_; }

  // Where level texel (x, y) of `level` is stored in its layer: the face index mod resolution.
  static glm::uvec2 storedTexel(const PatchLevel& level, uint32_t resolution, int64_t x, int64_t y);
  // The storage offset of a level as the terrain samples it: (originA mod resolution,
  // originB mod resolution) / resolution (exact in float for a power-of-two resolution).
  static glm::vec2 storageOffset(const PatchLevel& level, uint32_t resolution);

  // 2D array of settings().levelCount layers of resolution² texels, format kFormat, always in
  // VK_IMAGE_LAYOUT_GENERAL (between update()s), usage sampled + storage (+ transfer).
  const vk::Image& image() const { return *image_; }
  // Linear filtering (nearest where the device cannot filter kFormat), clamp to edge, no mips.
  VkSampler sampler() const { return sampler_.get(); }
  const PatchSettings& settings() const { return settings_; }

 private:
  // What a layer holds: a rectangle of one level's texels (empty after construction and
  // invalidate()).
  struct LayerContent {
    int face = 0;
    int exponent = 0;
    Region held;
  };
  // The host-visible buffers and the descriptor sets that point at them, one per frame slot.
  struct RegionResources {
    vk::Owned<vk::Buffer> level[vk::kFramesInFlight];       // gpu::PatchLevelParams, then gpu::PatchTile per tile
    vk::Owned<vk::Buffer> remainders[vk::kFramesInFlight];  // each tile's octave remainders
    vk::Owned<vk::Buffer> shifts[vk::kFramesInFlight];      // each tile's octave lattice shifts
    vk::Owned<VkBufferView> remainderTexels[vk::kFramesInFlight];  // the two as texel buffers
    vk::Owned<VkBufferView> shiftTexels[vk::kFramesInFlight];
    vk::Owned<vk::Buffer> heights;  // device-local: (resolution + 2)² floats, GPU-written
    // From the pools of heightPipeline_ and normalPipeline_.
    VkDescriptorSet heightSet[vk::kFramesInFlight] = {};
    VkDescriptorSet normalSet[vk::kFramesInFlight] = {};
    uint32_t heightGroupsA = 0;  // the height pass's dispatch for the region last written
    uint32_t heightGroupsB = 0;
    uint32_t normalGroupsA = 0;  // the normal pass's
    uint32_t normalGroupsB = 0;
  };

  // (Re)creates both pipelines, the height one specialized for the planet's current layers,
  // and points each region's descriptor sets at its resources.
  void createPipelines();
  // What `level`'s layer holds of the level's window (empty if it holds another level).
  Region heldOf(int face, const PatchLevel& level) const;
  // Throws for a layout that does not fit the settings (see update()).
  void checkLayout(const PatchLayout& layout) const;
  void writeRegion(const PatchLayout& layout, const PatchLevel& level, const Region& region,
                   RegionResources& resources, uint32_t slot);

  vk::Context& context_;
  const PlanetGpuData& data_;
  PatchSettings settings_;
  uint32_t tileSize_ = 1;  // texels per tile side
  uint32_t maxTilesPerSide_ = 1;
  std::vector<uint32_t> specialization_;  // of the height pipeline (layerSpecialization)
  std::vector<LayerContent> contents_;
  // In the order of creation (destroyed in reverse).
  vk::Owned<vk::Image> image_;
  vk::Owned<VkSampler> sampler_;
  std::vector<RegionResources> regions_;  // kRegionsPerLevel per layer
  vk::Owned<vk::ComputePipeline> heightPipeline_;
  vk::Owned<vk::ComputePipeline> normalPipeline_;
  uint64_t lastUpdateTexels_ = 0;
};

}  // namespace planet
