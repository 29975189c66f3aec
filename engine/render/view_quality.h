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
// The mesh for an image (issue 21, point 7): the clipmap keeps its triangles the same size on
// screen whatever the image's size (Clasen & Hege's rings step with the pixel; seed 002 §2.1 ties
// the finest ring to "the number of pixels per scanline"), so the rings per level and the vertices
// per ring follow the image's pixels per radian at its centre. `reference` is the mesh for
// kMeshReferenceLines lines at a kMeshReferenceFovDeg vertical field of view: the default render
// size (960×540 at 60°), where TerrainSettings{}.mesh draws what `planet render` drew before this
// rule; the viewer's low and medium presets are the same rule at their render scales. Levels are
// kept (the finest ring's size is a matter of metres, not pixels). Floors of 2 rings per level and
// 16 vertices per ring keep a thumbnail's limb round; ceilings are validateClipmapParams's.
inline constexpr uint32_t kMeshReferenceLines = 540;
inline constexpr double kMeshReferenceFovDeg = 60.0;
inline constexpr uint32_t kMeshMinRingsPerLevel = 2;
inline constexpr uint32_t kMeshMinNumPhi = 16;
ClipmapParams meshForImage(const ClipmapParams& reference, uint32_t imageHeight, double fovYDeg);
// "11 rings per level x 85 vertices per ring (auto for 360 lines at 60 degrees)": the mesh a
// render or benchmark drew, and whether meshForImage chose it (for that image height and field
// of view).
std::string describeMesh(const ClipmapParams& mesh, bool automatic, uint32_t imageHeight, double fovYDeg);

// The planet as drawn at `quality`: `planet` with its stars limited to the level's faintest
// magnitude (the viewer saves the unlimited description).
PlanetDescription viewPlanet(const PlanetDescription& planet, ViewQuality quality);

}  // namespace planet
