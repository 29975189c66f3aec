// The relief cube (issue 20, point 2: crisp from orbit): the planet's heights and normals over
// the whole sphere, one cube map at a fixed spacing (~20 km on Earth at the default 512 texels a
// face side), built once per planet with a full mip chain. The terrain and water shaders
// (terrain_surface.glsl, surfaceDetail) shade from it wherever the camera's patch textures do
// not reach and the mesh's vertices are coarser than its texels: beyond the camera's cube face
// from orbit, toward the horizon, and everywhere at quality `low` (no patches). There a
// coastline followed the mesh's triangles (blocks and polygons many pixels wide); now it
// follows the texels, interpolated and minified like any texture.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "vk/image.h"
#include "vk/owned.h"
#include "vk/pipeline.h"

namespace planet::vk {
class Context;
}  // namespace planet::vk

namespace planet {

class PlanetGpuData;

// The size of a cube the shaders never sample (gpu::kReliefStandInSize): bound when the relief is off.
inline constexpr uint32_t kReliefStandInSize = 8;

inline constexpr uint32_t kReliefDefaultSize = 512;
inline constexpr uint32_t kReliefMinSize = 16;
inline constexpr uint32_t kReliefMaxSize = 4096;

class ReliefCube {
 public:
  // Builds the cube (blocking: one submission, ~1 s on lavapipe at 512). `size`: texels per face
  // side, kReliefMinSize..kReliefMaxSize and a multiple of 8, or kReliefStandInSize; throws
  // planet::Error otherwise.
  ReliefCube(vk::Context& context, const PlanetGpuData& data, uint32_t size = kReliefDefaultSize);

  VkImageView view() const { return image_->cubeView; }  // SHADER_READ_ONLY_OPTIMAL, every level
  vk::Image& image() { return *image_; }                  // for readback (tests)
  VkSampler sampler() const { return sampler_.get(); }
  uint32_t size() const { return image_->extent.width; }
  // The angle (radians) a texel spans at a face's centre, where texels are smallest.
  double texelAngleRad() const;

 private:
  void build(vk::Context& context, const PlanetGpuData& data);

  // In the order of creation (destroyed in reverse).
  vk::Owned<vk::Image> image_;
  vk::Owned<VkSampler> sampler_;
};

}  // namespace planet
