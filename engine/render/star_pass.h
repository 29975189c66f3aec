// The star pass (issue 4, point 4): a catalogue of stars generated once on the GPU from a seed
// (shaders/stars.comp; the model in shaders/common/stars.glsl), drawn each frame as additive
// point sprites at infinity into the HDR colour target, first in the frame (the terrain and
// everything nearer overwrites them). Fading by the sky's brightness belongs to the sky pass
// (sky_pass.h), which knows which pixels are background.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "reference/star_catalogue.h"
#include "shared/star_params.h"
#include "vk/buffer.h"
#include "vk/owned.h"

namespace planet::vk {
class Context;
class GpuTimer;
}  // namespace planet::vk

namespace planet {

// Sprite diameters (1–3 px) are meant for views up to this height; taller views scale them up
// so that the sky looks the same at any resolution.
inline constexpr float kStarReferenceHeightPx = 1080.0f;
// Tiles are culled against the view's four side planes widened by this angle (1°), so that
// float rounding in either test never drops a star the rasteriser would draw.
inline constexpr double kStarCullMarginRad = 0.017453292519943295;

class StarPass {
 public:
  // Timing scopes a frame records at most: "star catalogue" (the first frame), "stars".
  static constexpr uint32_t kTimingScopes = 2;

  // Validates the settings (validateStarSettings), creates the catalogue buffer and both
  // pipelines; the draw pipeline is compatible with a dynamic-rendering scope of colorFormat and
  // depthFormat (VK_FORMAT_UNDEFINED: none), neither tests nor writes depth, and adds to colour.
  StarPass(vk::Context& context, const StarSettings& settings, VkFormat colorFormat, VkFormat depthFormat);

  // Records the catalogue's generation and the barrier that makes it visible to the vertex
  // shader (and to transfers and the host, for readCatalogue). Outside a rendering scope. The
  // first call records and sets generated(); later calls record nothing. The flag is set when
  // recording, so the command buffer must be submitted before (or with) the first draw's.
  // `timer` (optional) gets a scope "star catalogue".
  void recordGenerate(VkCommandBuffer cmd, vk::GpuTimer* timer = nullptr);
  // Records the draw, inside an active dynamic-rendering scope with viewport and scissor set.
  // `directionToClip` maps a planet-frame direction (w = 0) to clip space: projection · view
  // rotation, with the camera's translation irrelevant. `viewportHeightPx` scales the sprites
  // of views taller than kStarReferenceHeightPx. Only the sky tiles whose caps reach into the
  // view (with kStarCullMarginRad to spare) are drawn, unless settings.cullTiles is off; a star
  // outside the view is clipped either way, so culling changes no pixel. `timer` (optional)
  // gets a scope "stars".
  // Throws planet::Error before recordGenerate or for a height that is not finite and positive.
  void recordDraw(VkCommandBuffer cmd, const glm::mat4& directionToClip, float viewportHeightPx, vk::GpuTimer* timer);

  // Reads the catalogue back (blocking). Throws planet::Error before recordGenerate; the
  // generating command buffer must have completed.
  std::vector<gpu::StarRecord> readCatalogue();

  bool generated() const { return generated_; }
  // Stars the last recordDraw drew (all of them when culling is off).
  uint32_t drawnStarCount() const { return drawnStars_; }
  const StarSettings& settings() const { return settings_; }
  const vk::Buffer& catalogueBuffer() const { return *catalogue_; }
  // The largest point the device draws (a sprite is its star's diameter + kStarSpriteMargin):
  // 1 px without the largePoints feature, and then every star is a single plain pixel.
  float maxPointSize() const { return maxPointSize_; }

 private:
  vk::Context& context_;
  StarSettings settings_;
  float maxPointSize_ = 1.0f;
  bool generated_ = false;
  uint32_t drawnStars_ = 0;
  std::vector<StarTileCap> caps_;    // per sky tile
  std::vector<uint32_t> tileFirst_;  // kStarTileCount + 1 catalogue indices

  // In the order of creation (destroyed in reverse).
  vk::Owned<vk::Buffer> catalogue_;
  vk::Owned<VkDescriptorSetLayout> setLayout_;
  vk::Owned<VkDescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;  // from pool_
  vk::Owned<VkPipelineLayout> layout_;
  vk::Owned<VkPipeline> generatePipeline_;
  vk::Owned<VkPipeline> drawPipeline_;
};

// Which stars the eye sees against the sky in front of them (shaders/common/star_visibility.glsl,
// as the sky's compose applies it): the faintest magnitude seen against a sky of HDR luminance
// `sky` (the frame's units: the sun's irradiance above the air is 1), and the share of a star's
// light that shows, from its relative flux 10^(−0.4 m) as it reaches the eye.
double starLimitingMagnitude(double sky);
double starVisibleShare(double relativeFlux, double sky);

}  // namespace planet
