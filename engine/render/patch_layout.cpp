#include "render/patch_layout.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace planet {
namespace {

// Bounds of the finest exponent (patch_layout.h): 2^0 is a whole face per texel, 2^−60 about
// 5e−12 m on Earth, far below anything a double face coordinate can still resolve.
constexpr int kFinestExponentMin = -60;
constexpr int kFinestExponentMax = 0;

// floor(value / step) · step for a positive step, also for negative values.
int64_t floorToMultiple(int64_t value, int64_t step) {
  int64_t quotient = value / step;
  if (value % step != 0 && value < 0) --quotient;
  return quotient * step;
}

}  // namespace

void validatePatchSettings(const PatchSettings& settings) {
  if (settings.resolution < kPatchMinResolution || settings.resolution > kPatchMaxResolution)
    throw Error(fmt::format("patch resolution must be in [{}, {}], got {}", kPatchMinResolution, kPatchMaxResolution,
                            settings.resolution));
  if (settings.recentreDivisor < 2 || settings.recentreDivisor > settings.resolution)
    throw Error(fmt::format("patch recentre divisor must be in [2, resolution = {}], got {}", settings.resolution,
                            settings.recentreDivisor));
  if (settings.resolution % settings.recentreDivisor != 0)
    throw Error(fmt::format("patch resolution must be a multiple of the recentre divisor {}, got {}",
                            settings.recentreDivisor, settings.resolution));
  if (settings.levelCount < 1 || settings.levelCount > kPatchMaxLevels)
    throw Error(fmt::format("patch level count must be in [1, {}], got {}", kPatchMaxLevels, settings.levelCount));
  if (!std::isfinite(settings.texelsPerNadirPixel) || !(settings.texelsPerNadirPixel > 0.0))
    throw Error(
        fmt::format("patch texels per nadir pixel must be finite and > 0, got {}", settings.texelsPerNadirPixel));
}

PatchLayout choosePatchLayout(const PatchSettings& settings, double radiusM, const glm::dvec3& cameraDirection,
                              double nadirPixelM) {
  validatePatchSettings(settings);
  if (!std::isfinite(radiusM) || !(radiusM > 0.0))
    throw Error(fmt::format("patch layout radius must be finite and > 0, got {}", radiusM));
  if (!std::isfinite(nadirPixelM) || !(nadirPixelM > 0.0))
    throw Error(fmt::format("patch layout nadir pixel size must be finite and > 0, got {}", nadirPixelM));

  PatchLayout layout;
  layout.face = dominantCubeFace(cameraDirection);  // throws for a zero or non-finite direction
  layout.resolution = settings.resolution;
  const glm::dvec2 camera = cubeFaceCoordinates(layout.face, cameraDirection);

  // Largest e with radiusM · 2^e / √(1 + a² + b²) <= target, evaluated exactly as written (the
  // log2 only gives the starting guess; the loops settle rounding at the boundary).
  const double scale = std::sqrt(1.0 + camera.x * camera.x + camera.y * camera.y);
  const double target = nadirPixelM / settings.texelsPerNadirPixel;
  auto fits = [&](int e) { return radiusM * std::ldexp(1.0, e) / scale <= target; };
  const double guess = std::floor(std::log2(target * scale / radiusM));
  int finest = std::isnan(guess) ? kFinestExponentMin
                                 : int(std::clamp(guess, double(kFinestExponentMin), double(kFinestExponentMax)));
  while (finest < kFinestExponentMax && fits(finest + 1)) ++finest;
  while (finest > kFinestExponentMin && !fits(finest)) --finest;

  const int64_t half = int64_t(settings.resolution / 2);
  const int64_t step = int64_t(settings.resolution / settings.recentreDivisor);
  layout.levels.resize(settings.levelCount);
  for (uint32_t j = 0; j < settings.levelCount; ++j) {
    PatchLevel& level = layout.levels[j];
    level.exponent = finest + int(j);
    // The camera's texel index: a / Δ is exact (Δ is a power of two), so is its floor.
    const int64_t cameraA = int64_t(std::floor(std::ldexp(camera.x, -level.exponent)));
    const int64_t cameraB = int64_t(std::floor(std::ldexp(camera.y, -level.exponent)));
    level.originA = floorToMultiple(cameraA - half, step);
    level.originB = floorToMultiple(cameraB - half, step);
    const int count = int(settings.levelCount);
    level.layer = uint32_t(((level.exponent % count) + count) % count);
  }
  return layout;
}

glm::dvec2 patchTexelCoordinates(const PatchLevel& level, double x, double y) {
  const double texel = std::ldexp(1.0, level.exponent);
  return {(double(level.originA) + x + 0.5) * texel, (double(level.originB) + y + 0.5) * texel};
}

double patchTexelSpacingM(const PatchLayout& layout, const PatchLevel& level, double radiusM) {
  // The level's centre is taken at its centre texel (resolution/2, resolution/2), the texel the
  // patch textures also anchor their noise at (patch_textures.h).
  const double centre = double(layout.resolution / 2);
  const glm::dvec2 c = patchTexelCoordinates(level, centre, centre);
  return radiusM * std::ldexp(1.0, level.exponent) / std::sqrt(1.0 + c.x * c.x + c.y * c.y);
}

}  // namespace planet
