// Headless rendering of a planet into an offscreen target (issue 3, point 9): one frame is CPU
// preparation in double, compute (heights, normals, patch textures), then the terrain draw
// into an sRGB colour target with a reversed-Z float depth buffer, timed per pass, and read
// back as RGBA8. The viewer (later) records the same passes into its swapchain images.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/image_file.h"
#include "planet/planet_description.h"
#include "render/camera.h"
#include "render/terrain_pass.h"
#include "vk/image.h"
#include "vk/timer.h"

namespace planet::vk {
class Context;
}

namespace planet {

inline constexpr uint32_t kRenderMaxSize = 8192;  // per side
// A camera closer to the ground than this is raised to it (a person's eye height).
inline constexpr double kMinEyeHeightM = 1.7;

struct RenderSettings {
  uint32_t width = 960;
  uint32_t height = 540;
  double fovYDeg = 60.0;
  TerrainSettings terrain;
};

// Throws planet::Error naming the first bad value (size 0 or above kRenderMaxSize, field of
// view outside (0, 179] degrees).
void validateRenderSettings(const RenderSettings& settings);

struct RenderResult {
  Rgba8Image image;
  TerrainFrameInfo terrain;
  std::vector<vk::GpuTiming> timings;  // per pass, in recording order
  CameraPose camera;                   // as rendered (raised when it was below the ground)
  bool cameraRaised = false;
};

class Renderer {
 public:
  Renderer(vk::Context& context, const PlanetDescription& planet, const RenderSettings& settings);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders one frame and reads it back. Frames of one Renderer form a sequence: the clipmap
  // orientation is carried from one to the next, and unchanged heights are not recomputed.
  RenderResult render(const CameraPose& camera, const SunPose& sun);

  // The camera after the eye-height rule: an altitude below the ground (or the water) plus
  // kMinEyeHeightM is raised to it.
  CameraPose clampToGround(const CameraPose& camera, bool* raised = nullptr) const;

  TerrainPass& terrain() { return *terrain_; }
  const RenderSettings& settings() const { return settings_; }

 private:
  void release();

  vk::Context& context_;
  PlanetDescription planet_;
  RenderSettings settings_;
  std::unique_ptr<TerrainPass> terrain_;
  vk::Image color_;
  vk::Image depth_;
  vk::GpuTimer timer_;
  bool timerCreated_ = false;
};

}  // namespace planet
