// Compiled with -ffp-contract=off (the project-wide rule, top CMakeLists.txt): the reference must round exactly like
// the GLSL it is compiled from.
#include "reference/star_catalogue.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/error.h"
#include "reference/star_kernel.h"

namespace planet {

uint32_t realisticStarCount(float faintestMagnitude) {
  return uint32_t(std::lround(9000.0 * std::pow(10.0, 0.5 * (double(faintestMagnitude) - 6.5))));
}

void validateStarSettings(const StarSettings& settings) {
  if (settings.count == 0 || settings.count > gpu::kStarMaxCount)
    throw Error(fmt::format("star count {} is outside 1..{}", settings.count, gpu::kStarMaxCount));
  if (!(settings.faintestMagnitude >= kStarMinFaintestMagnitude &&
        settings.faintestMagnitude <= kStarMaxFaintestMagnitude))
    throw Error(fmt::format("faintest star magnitude {} is outside [{}, {}]", settings.faintestMagnitude,
                            kStarMinFaintestMagnitude, kStarMaxFaintestMagnitude));
  if (!(settings.brightness > 0.0f && settings.brightness <= kStarMaxBrightness))
    throw Error(fmt::format("star brightness {} is outside (0, {}]", settings.brightness, kStarMaxBrightness));
}

std::vector<gpu::StarRecord> starCatalogueCpu(const StarSettings& settings) {
  validateStarSettings(settings);
  std::vector<gpu::StarRecord> catalogue(settings.count);
  stars::StarKernel kernel;
  for (uint32_t i = 0; i < settings.count; ++i)
    catalogue[i] = kernel.starGenerate(i, settings.count, settings.seed, settings.faintestMagnitude);
  return catalogue;
}

uint32_t starTileFirstIndex(uint32_t tile, uint32_t count) {
  // The smallest i with i · kStarTileCount ≥ tile · count (stars.glsl, starTileOf).
  return uint32_t((uint64_t(tile) * count + gpu::kStarTileCount - 1) / gpu::kStarTileCount);
}

StarTileCap starTileCap(uint32_t tile) {
  if (tile >= gpu::kStarTileCount)
    throw Error(fmt::format("sky tile {} is outside 0..{}", tile, gpu::kStarTileCount - 1));
  const uint32_t band = tile / gpu::kStarTileSectors, sector = tile % gpu::kStarTileSectors;
  const double z0 = 1.0 - 2.0 * band / gpu::kStarTileBands, z1 = 1.0 - 2.0 * (band + 1) / gpu::kStarTileBands;
  const double phi0 = 2.0 * std::numbers::pi * sector / gpu::kStarTileSectors;
  const double phi1 = 2.0 * std::numbers::pi * (sector + 1) / gpu::kStarTileSectors;
  auto point = [&](double u, double v) {
    const double z = z0 + (z1 - z0) * u, phi = phi0 + (phi1 - phi0) * v;
    const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
    return glm::dvec3(rho * std::cos(phi), rho * std::sin(phi), z);
  };
  // Axis: the tile's centre direction; radius: the farthest of a fine grid over the tile (the
  // farthest point lies on the boundary, which the grid samples every 1/64 of a side), plus a
  // margin for what lies between samples (≤ 0.2° for tiles at most 40° across).
  StarTileCap cap;
  cap.axis = glm::normalize(point(0.5, 0.5));
  constexpr int kSamples = 64;
  double minCos = 1.0;
  for (int i = 0; i <= kSamples; ++i)
    for (int j = 0; j <= kSamples; ++j)
      minCos = std::min(minCos, glm::dot(cap.axis, point(double(i) / kSamples, double(j) / kSamples)));
  cap.radiusRad = std::acos(std::clamp(minCos, -1.0, 1.0)) + 0.2 * std::numbers::pi / 180.0;
  return cap;
}

}  // namespace planet
