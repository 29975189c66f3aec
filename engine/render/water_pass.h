// The water pass (issue 4, point 1): the sea of a planet with an ocean, the clipmap mesh drawn
// again at sea level (shaders/water.vert) right after the ground, so that the coastline is the
// intersection of two surfaces over the same triangles. Shading (shaders/water.frag): Fresnel
// reflection of the sky, the sun's glint off a sea as rough as the wind makes it (Cox & Munk
// 1954) with small animated waves resolved near the camera, light scattered up from the water
// body, and transparency from the depth under the pixel; blended premultiplied "over" the
// ground, depth tested and written. It reads the terrain pass's descriptor set (frame uniforms,
// the vertex buffers the height pass fills, the patch textures), so the terrain pass owns it.
#pragma once

#include <cstdint>
#include <span>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "planet/clipmap_mesh.h"
#include "planet/planet_description.h"
#include "shared/render_params.h"
#include "vk/owned.h"

namespace planet::vk {
class Context;
class GpuTimer;
}  // namespace planet::vk

namespace planet {

class WaterPass {
 public:
  // Timing scopes a frame records at most: "water".
  static constexpr uint32_t kTimingScopes = 1;

  // What the sea's shader holds (specialization constants: lavapipe runs every branch's code).
  struct Features {
    bool eclipses = false;    // another body may hide the sun (a scene)
    bool ringShadow = false;  // the body's rings shadow the sea
    bool clouds = false;      // the planet's cloud layer: mirrored, and shadowing the sea
  };

  // A pipeline over the terrain pass's `layout`, for a dynamic-rendering scope of colorFormat and
  // depthFormat. The vertices come from water.vert, or from `vertexSpirv` with its
  // specialization constants (the vertex-shader height source: terrain_noise.vert).
  // `vertexStrides`: the terrain's vertex buffers (GraphicsPipelineDesc), for water.vert; with
  // `vertexSpirv` (seed 002's design) none.
  // The colour target's alpha keeps the share of the pixel that shows the ground through the sea
  // (GraphicsPipelineDesc::alphaKeepsUncovered): the sky pass darkens only that share by the
  // clouds' shadow, since the sea shades its own light under the clouds.
  WaterPass(vk::Context& context, VkPipelineLayout layout, VkFormat colorFormat, VkFormat depthFormat,
            const Features& features, std::span<const uint32_t> vertexStrides,
            std::span<const uint32_t> vertexSpirv = {}, std::span<const uint32_t> vertexSpecialization = {});

  // Records the draw of the ground's triangles (the first `indexCount` indices of the bound index
  // buffer) with the terrain's descriptor set and index buffer bound (it binds its pipeline).
  void recordDraw(VkCommandBuffer cmd, uint32_t indexCount, vk::GpuTimer* timer);
  // Binds the pipeline alone, so that the terrain pass can bind its set over it.
  void bindPipeline(VkCommandBuffer cmd) const;

 private:
  vk::Owned<VkPipeline> pipeline_;
};

// Cox & Munk (1954), from photographs of the sun's glitter: the total mean square slope of the
// sea surface (sum of the up- and cross-wind variances) in a wind of windMps at 10 m,
// 0.003 + 0.00512·U (their clean-surface fit; measured up to ~14 m/s, a straight line beyond).
double coxMunkSlopeVariance(double windMps);

// The water's values in the terrain pass's frame uniforms, for every planet (the ground's shader
// reads whether the sea is drawn): FrameUniforms::water, w the Cox–Munk slope variance.
glm::vec4 waterUniform(const WaterDescription& water, bool drawn);
// FrameUniforms::waves: deep-water waves (ω² = g k) of falling wavelength in four directions,
// with their phase at the patch reference point (face coordinates refA, refB) computed in double
// so that the pixel's float part stays small.
void writeWaves(glm::vec4 (&waves)[gpu::kWaterWaveCount], const WaterDescription& water, double radiusM, double refA,
                double refB, double timeS);

}  // namespace planet
