#include "render/view_quality.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/error.h"

namespace planet {
namespace {

constexpr const char* kNames[kViewQualityCount] = {"low", "medium", "high", "ultra"};

}  // namespace

const char* viewQualityName(ViewQuality quality) { return kNames[int(quality)]; }

ViewQuality parseViewQuality(std::string_view name) {
  for (int i = 0; i < kViewQualityCount; ++i)
    if (name == kNames[i]) return ViewQuality(i);
  throw Error(fmt::format("unknown quality '{}' (expected low, medium, high or ultra)", name));
}

QualityPreset qualityPreset(ViewQuality quality) {
  QualityPreset p;
  switch (quality) {
    case ViewQuality::Low:
      // Lavapipe at 960×540 on two cores: a quarter of the pixels and a quarter of the height
      // pass's vertices of High; the patch textures, whose rebuilds cost ~1 s there, are off.
      p.renderScale = 0.5;
      p.mesh = {30, 8, 64};
      p.subPixelRings = 4;
      p.atmosphereSamples = 6;
      p.patches = false;
      p.patchResolution = 256;
      p.faintestStarMagnitude = 6.0;
      break;
    case ViewQuality::Medium:
      p.renderScale = 0.75;
      p.mesh = {30, 12, 96};
      p.subPixelRings = 6;
      p.atmosphereSamples = 10;
      p.patches = true;
      p.patchResolution = 256;
      p.faintestStarMagnitude = 6.5;
      break;
    case ViewQuality::High:  // what planet render draws at its default 960x540 (meshForImage's reference)
      p.renderScale = 1.0;
      p.mesh = TerrainSettings{}.mesh;
      p.subPixelRings = TerrainSettings{}.subPixelRings;
      p.atmosphereSamples = SkySettings{}.viewSamples;
      p.patches = true;
      p.patchResolution = PatchSettings{}.resolution;
      break;
    case ViewQuality::Ultra:
      p.renderScale = 1.0;
      p.mesh = {30, 24, 256};
      p.subPixelRings = 8;
      p.atmosphereSamples = 128;
      p.patches = true;
      p.patchResolution = 1024;
      break;
  }
  return p;
}

ViewQuality defaultViewQuality(bool cpuDevice) { return cpuDevice ? ViewQuality::Low : ViewQuality::High; }

std::string describeQuality(ViewQuality quality) {
  const QualityPreset p = qualityPreset(quality);
  return fmt::format(
      "render scale {}, mesh {} levels x {} rings x {} vertices, {} atmosphere samples, {}{}", p.renderScale,
      p.mesh.levels, p.mesh.ringsPerLevel, p.mesh.numPhi, p.atmosphereSamples,
      p.patches ? fmt::format("patch textures {}^2", p.patchResolution) : "no patch textures",
      p.faintestStarMagnitude < 9.0 ? fmt::format(", stars to magnitude {}", p.faintestStarMagnitude) : "");
}

RenderSettings viewRenderSettings(const RenderSettings& base, ViewQuality quality, uint32_t windowWidth,
                                  uint32_t windowHeight) {
  const QualityPreset p = qualityPreset(quality);
  RenderSettings s = base;
  auto scaled = [&](uint32_t size) {
    return std::clamp(uint32_t(std::lround(double(size) * p.renderScale)), 16u, kRenderMaxSize);
  };
  s.width = scaled(windowWidth);
  s.height = scaled(windowHeight);
  s.terrain.mesh = p.mesh;
  s.terrain.subPixelRings = p.subPixelRings;
  s.terrain.patches = p.patches && !base.terrain.wireframe && base.terrain.patches;
  s.terrain.patchSettings.resolution = p.patchResolution;
  s.terrain.patchTexelsPerFrame = realTimePatchBudget(s.terrain.patchSettings);
  s.sky.viewSamples = p.atmosphereSamples;
  return s;
}

ClipmapParams meshForImage(const ClipmapParams& reference, uint32_t imageHeight, double fovYDeg) {
  // Pixels per radian at the image's centre, relative to the reference image's.
  auto pixelsPerRadian = [](double lines, double fovDeg) {
    return lines / (2.0 * std::tan(0.5 * fovDeg * std::numbers::pi / 180.0));
  };
  const double scale = pixelsPerRadian(double(imageHeight), fovYDeg) /
                       pixelsPerRadian(double(kMeshReferenceLines), kMeshReferenceFovDeg);
  auto scaled = [scale](uint32_t count, uint32_t lowest, uint32_t highest) {
    const double value = std::round(double(count) * scale);
    return uint32_t(std::clamp(value, double(lowest), double(highest)));
  };
  ClipmapParams mesh = reference;
  mesh.ringsPerLevel = scaled(reference.ringsPerLevel, kMeshMinRingsPerLevel, kClipmapMaxRingsPerLevel);
  mesh.numPhi = scaled(reference.numPhi, kMeshMinNumPhi, kClipmapMaxNumPhi);
  return mesh;
}

std::string describeMesh(const ClipmapParams& mesh, bool automatic, uint32_t imageHeight, double fovYDeg) {
  return fmt::format("{} rings per level x {} vertices per ring{}", mesh.ringsPerLevel, mesh.numPhi,
                     automatic ? fmt::format(" (auto for {} lines at {:g} degrees)", imageHeight, fovYDeg) : "");
}

PlanetDescription viewPlanet(const PlanetDescription& planet, ViewQuality quality) {
  PlanetDescription drawn = planet;
  drawn.stars.faintestMagnitude = std::min(drawn.stars.faintestMagnitude, qualityPreset(quality).faintestStarMagnitude);
  return drawn;
}

}  // namespace planet
