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

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// floor(value / step) · step for a positive step, also for negative values.
int64_t floorToMultiple(int64_t value, int64_t step) {
  int64_t quotient = value / step;
  if (value % step != 0 && value < 0) --quotient;
  return quotient * step;
}

}  // namespace

CubeFace cubeFace(int face) {
  // Each (A, B) pair is a right-handed basis of the face plane: A × B = N.
  switch (face) {
    case 0: return {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}};
    case 1: return {{0, -1, 0}, {0, 0, 1}, {-1, 0, 0}};
    case 2: return {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
    case 3: return {{0, 0, -1}, {1, 0, 0}, {0, -1, 0}};
    case 4: return {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    case 5: return {{-1, 0, 0}, {0, 1, 0}, {0, 0, -1}};
    default: throw Error(fmt::format("cube face must be in 0..{}, got {}", kCubeFaceCount - 1, face));
  }
}

int dominantCubeFace(const glm::dvec3& direction) {
  if (!isFinite(direction) || direction == glm::dvec3(0.0))
    throw Error(
        fmt::format("cube face of a zero or non-finite direction ({}, {}, {})", direction.x, direction.y, direction.z));
  // Face 2k has normal +axis k and face 2k+1 has −axis k; a strict > keeps the lower index on ties.
  int best = 0;
  double bestDot = direction.x;
  for (int face = 1; face < kCubeFaceCount; ++face) {
    const double component = direction[face / 2];
    const double dot = (face % 2 == 0) ? component : -component;
    if (dot > bestDot) {
      best = face;
      bestDot = dot;
    }
  }
  return best;
}

glm::dvec3 cubeFaceDirection(int face, double a, double b) {
  const CubeFace f = cubeFace(face);
  return glm::normalize(f.normal + a * f.axisA + b * f.axisB);
}

glm::dvec2 cubeFaceCoordinates(int face, const glm::dvec3& direction) {
  const CubeFace f = cubeFace(face);
  const double n = glm::dot(direction, f.normal);
  if (!(n > 0.0))
    throw Error(fmt::format("direction ({}, {}, {}) is not on the hemisphere of cube face {}", direction.x, direction.y,
                            direction.z, face));
  return {glm::dot(direction, f.axisA) / n, glm::dot(direction, f.axisB) / n};
}

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
