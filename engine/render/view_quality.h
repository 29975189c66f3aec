// Quality levels of the real-time viewer (issue 5, point 7): how much of the renderer's work a
// frame does. A CPU Vulkan device (lavapipe) starts lower than a GPU, so that flying stays
// interactive there; the viewer's panel moves between the levels.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "render/renderer.h"

namespace planet {

enum class ViewQuality { Low, Medium, High, Ultra };
inline constexpr int kViewQualityCount = 4;

struct QualityPreset {
  double renderScale = 1.0;  // render target size / window size (the frame is scaled up by a blit)
  ClipmapParams mesh;        // levels, rings per level, vertices per ring
  uint32_t subPixelRings = 8;
  uint32_t atmosphereSamples = 64;  // samples along each pixel's ray of the reference sky (--sky reference)
  bool patches = true;              // per-pixel detail from the patch textures
  uint32_t patchResolution = 512;   // texels per side of each patch level
  // Stars down to this apparent magnitude at most (the preset may stop brighter): lavapipe
  // rasterises point sprites slowly, and each magnitude fainter is 10^0.5 ≈ 3.2× more stars.
  double faintestStarMagnitude = 9.0;
};

const char* viewQualityName(ViewQuality quality);
// "low", "medium", "high", "ultra"; throws planet::Error naming the bad value.
ViewQuality parseViewQuality(std::string_view name);
QualityPreset qualityPreset(ViewQuality quality);
// Low on CPU devices, High otherwise.
ViewQuality defaultViewQuality(bool cpuDevice);
// One line describing a preset ("render scale 0.5, mesh 30x6x48, 6 atmosphere samples, ...").
std::string describeQuality(ViewQuality quality);

// Render settings for a window of windowWidth × windowHeight pixels at `quality`, starting from
// `base` (its field of view, toggles and exposure are kept). The render size is at least 16×16.
RenderSettings viewRenderSettings(const RenderSettings& base, ViewQuality quality, uint32_t windowWidth,
                                  uint32_t windowHeight);
// The planet as drawn at `quality`: `planet` with its stars limited to the level's faintest
// magnitude (the viewer saves the unlimited description).
PlanetDescription viewPlanet(const PlanetDescription& planet, ViewQuality quality);

}  // namespace planet
