#include "planet/clipmap_orientation.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/error.h"

namespace planet {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kHalfPi = 0.5 * std::numbers::pi;

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void requireRadius(double radiusM, const char* what) {
  if (!(std::isfinite(radiusM) && radiusM > 0.0))
    throw Error(fmt::format("{}: planet radius must be finite and > 0, got {}", what, radiusM));
}

void requireNotNan(double value, const char* name, const char* what) {
  if (std::isnan(value)) throw Error(fmt::format("{}: {} is NaN", what, name));
}

void requireRingParams(uint32_t levels, uint32_t ringsPerLevel, const char* what) {
  if (levels < 1 || levels > kClipmapOrientationMaxLevels)
    throw Error(fmt::format("{}: levels must be in 1..{}, got {}", what, kClipmapOrientationMaxLevels, levels));
  if (ringsPerLevel < 1 || ringsPerLevel > kClipmapOrientationMaxRingsPerLevel)
    throw Error(fmt::format("{}: ringsPerLevel must be in 1..{}, got {}", what, kClipmapOrientationMaxRingsPerLevel,
                            ringsPerLevel));
}

// θ of ring k = 0..K (K is the pole, θ = 0), the same expression as clipmapRingTheta so the two
// agree bit for bit: π·2^−ℓ·2^(−j/m) with ℓ = k/m + 1, j = k mod m (Hayes-McCoy 2010, §4.3).
double ringTheta(uint32_t levels, uint32_t ringsPerLevel, uint32_t ring) {
  if (ring >= levels * ringsPerLevel) return 0.0;
  uint32_t level = ring / ringsPerLevel + 1;
  uint32_t j = ring % ringsPerLevel;
  return std::ldexp(kPi, -int(level)) * std::exp2(-double(j) / double(ringsPerLevel));
}

// The continuous ring coordinate −m·log2(θ/(π/2)) of θ > 0; only a first guess for the searches
// below, which then correct it against the exact ring θ values (log2 may round across a ring).
double ringCoordinate(uint32_t ringsPerLevel, double theta) {
  return -double(ringsPerLevel) * std::log2(theta / kHalfPi);
}

uint32_t clampedRingGuess(double estimate, uint32_t lastRing) {
  if (!(estimate > 0.0)) return 0;
  if (estimate >= double(lastRing)) return lastRing;
  return uint32_t(estimate);
}

// The largest k in 0..K−1 with θ_k ≥ theta; K−1 when even the innermost ring is below theta.
uint32_t innermostRingAtOrAbove(uint32_t levels, uint32_t ringsPerLevel, double theta) {
  const uint32_t innermost = levels * ringsPerLevel - 1;
  if (theta <= ringTheta(levels, ringsPerLevel, innermost)) return innermost;
  uint32_t ring = clampedRingGuess(std::floor(ringCoordinate(ringsPerLevel, theta)), innermost);
  while (ring < innermost && ringTheta(levels, ringsPerLevel, ring + 1) >= theta) ++ring;
  while (ring > 0 && ringTheta(levels, ringsPerLevel, ring) < theta) --ring;
  return ring;
}

// The smallest k in 0..K−1 with θ_k ≤ theta; K−1 when no ring is that far in.
uint32_t outermostRingAtOrBelow(uint32_t levels, uint32_t ringsPerLevel, double theta) {
  const uint32_t innermost = levels * ringsPerLevel - 1;
  if (theta < ringTheta(levels, ringsPerLevel, innermost)) return innermost;
  uint32_t ring = clampedRingGuess(std::ceil(ringCoordinate(ringsPerLevel, theta)), innermost);
  while (ring > 0 && ringTheta(levels, ringsPerLevel, ring - 1) <= theta) --ring;
  while (ring < innermost && ringTheta(levels, ringsPerLevel, ring) > theta) ++ring;
  return ring;
}

// acos(r/(r+x)) for x ≥ 0, written as atan2(√(x(2r+x)), r): the angle at the centre between the
// nadir and the tangent point seen from height x. acos near 1 would lose half the digits for x ≪ r.
double tangentAngle(double radiusM, double heightM) {
  return std::atan2(std::sqrt(heightM * (2.0 * radiusM + heightM)), radiusM);
}

// Local x toward the planet's north pole (+z), projected into the tangent plane of unit pole n:
// z − n_z n, with 1 − n_z² written as n_x² + n_y² (no cancellation near a world pole) and n_x, n_y
// scaled by the larger of the two first (no underflow however close to the pole). Only the
// poles themselves (n_x = n_y = 0) fall back to world +x.
glm::dmat3 northBasis(const glm::dvec3& pole) {
  const double scale = std::max(std::abs(pole.x), std::abs(pole.y));
  glm::dvec3 x(1.0, 0.0, 0.0);
  if (scale > 0.0) {
    const double u = pole.x / scale, v = pole.y / scale;
    x = glm::normalize(glm::dvec3(-pole.z * u, -pole.z * v, scale * (u * u + v * v)));
  }
  // Against the exact pole once more, so that rounding leaves x·n at ~1e−16 at most.
  x = glm::normalize(x - glm::dot(x, pole) * pole);
  return glm::dmat3(x, glm::cross(pole, x), pole);
}

}  // namespace

ClipmapFrame orientClipmap(const glm::dvec3& cameraPositionPlanetFrame, double radiusM) {
  requireRadius(radiusM, "orientClipmap");
  if (!isFinite(cameraPositionPlanetFrame))
    throw Error(fmt::format("orientClipmap: camera position ({}, {}, {}) is not finite", cameraPositionPlanetFrame.x,
                            cameraPositionPlanetFrame.y, cameraPositionPlanetFrame.z));
  const double distance = glm::length(cameraPositionPlanetFrame);
  if (!(distance > 0.0) || !std::isfinite(distance))
    throw Error("orientClipmap: the camera is at the planet centre (no nadir direction) or too far away to measure");
  const glm::dvec3 pole = cameraPositionPlanetFrame / distance;

  ClipmapFrame frame;
  frame.localToPlanet = northBasis(pole);
  frame.cameraPlanetFrame = cameraPositionPlanetFrame;
  frame.radiusM = radiusM;
  frame.cameraDistanceM = distance;
  frame.altitudeM = distance - radiusM;
  return frame;
}

glm::dvec3 localToPlanetDirection(const ClipmapFrame& frame, double theta, double phi) {
  double sinTheta = std::sin(theta);
  glm::dvec3 local(std::cos(phi) * sinTheta, std::sin(phi) * sinTheta, std::cos(theta));
  return frame.localToPlanet * local;
}

glm::dvec2 planetToLocalThetaPhi(const ClipmapFrame& frame, const glm::dvec3& direction) {
  // The basis is orthonormal, so its transpose is its inverse.
  glm::dvec3 local = glm::transpose(frame.localToPlanet) * direction;
  double theta = std::atan2(std::hypot(local.x, local.y), local.z);
  double phi = std::atan2(local.y, local.x);
  if (phi < 0.0) phi += 2.0 * kPi;
  if (phi >= 2.0 * kPi) phi = 0.0;  // −tiny + 2π rounds to 2π, which is φ = 0
  return {theta, phi};
}

double horizonTheta(double radiusM, double altitudeM, double maxTerrainHeightM, double lowestSurfaceM) {
  requireRadius(radiusM, "horizonTheta");
  requireNotNan(altitudeM, "altitude", "horizonTheta");
  requireNotNan(maxTerrainHeightM, "max terrain height", "horizonTheta");
  requireNotNan(lowestSurfaceM, "lowest surface", "horizonTheta");
  double h = std::max(altitudeM, kClipmapMinAltitudeM);
  double terrain = std::max(maxTerrainHeightM, 0.0);
  // The sphere a sight line grazes: the radius sphere, or lower where the terrain goes below it.
  double low = std::min(lowestSurfaceM, 0.0);
  requireRadius(radiusM + low, "horizonTheta (radius plus the lowest surface)");
  // Clasen & Hege's smooth-sphere horizon plus the angle over which the grazing sight line climbs
  // back to the highest possible peak. Infinite h gives atan2(∞, r) = π/2.
  double theta = tangentAngle(radiusM + low, h - low) + tangentAngle(radiusM + low, terrain - low);
  return std::clamp(theta, kClipmapMinHorizonTheta, kHalfPi);
}

double pixelFootprintTheta(double radiusM, double altitudeM, double fovYRad, uint32_t viewportHeightPx) {
  requireRadius(radiusM, "pixelFootprintTheta");
  requireNotNan(altitudeM, "altitude", "pixelFootprintTheta");
  if (!(fovYRad > 0.0 && fovYRad < kPi))
    throw Error(fmt::format("pixelFootprintTheta: vertical field of view must be in (0, π) radians, got {}", fovYRad));
  if (viewportHeightPx == 0) throw Error("pixelFootprintTheta: viewport height is 0 pixels");
  double h = std::max(altitudeM, kClipmapMinAltitudeM);
  // s = h·tan(fov/2)/(p/2): the ground size of the central pixel at the nadir; θdiffmin = s/r.
  double pixelGroundM = h * std::tan(0.5 * fovYRad) / (0.5 * double(viewportHeightPx));
  return pixelGroundM / radiusM;
}

double minUsefulTheta(double radiusM, double altitudeM, double fovYRad, uint32_t viewportHeightPx,
                      uint32_t ringsPerLevel) {
  double pixelTheta = pixelFootprintTheta(radiusM, altitudeM, fovYRad, viewportHeightPx);
  if (ringsPerLevel < 1 || ringsPerLevel > kClipmapOrientationMaxRingsPerLevel)
    throw Error(fmt::format("minUsefulTheta: ringsPerLevel must be in 1..{}, got {}",
                            kClipmapOrientationMaxRingsPerLevel, ringsPerLevel));
  // Ring spacing at θ is θ·(1 − 2^(−1/m)), proportional to θ, so the spacing equals one pixel at
  // exactly one θ. expm1 keeps 1 − 2^(−1/m) accurate for large m.
  double spacingPerTheta = -std::expm1(-std::numbers::ln2 / double(ringsPerLevel));
  return std::clamp(pixelTheta / spacingPerTheta, 0.0, kHalfPi);
}

RingRange selectRings(uint32_t levels, uint32_t ringsPerLevel, double thetaMax, double thetaMin) {
  requireRingParams(levels, ringsPerLevel, "selectRings");
  requireNotNan(thetaMax, "thetaMax", "selectRings");
  requireNotNan(thetaMin, "thetaMin", "selectRings");
  double outer = std::clamp(thetaMax, 0.0, kHalfPi);
  double inner = std::clamp(thetaMin, 0.0, outer);
  RingRange range;
  range.firstRing = innermostRingAtOrAbove(levels, ringsPerLevel, outer);
  // θ decreases with k and θ_firstRing ≥ outer ≥ inner, so this is already ≥ firstRing; the max
  // only makes the invariant independent of that argument.
  range.lastRing = std::max(range.firstRing, outermostRingAtOrBelow(levels, ringsPerLevel, inner));
  range.includePole = true;
  return range;
}

double metresPerVertexAtNadir(double radiusM, uint32_t levels, uint32_t ringsPerLevel, uint32_t numPhi,
                              uint32_t lastRing) {
  requireRadius(radiusM, "metresPerVertexAtNadir");
  requireRingParams(levels, ringsPerLevel, "metresPerVertexAtNadir");
  if (numPhi < 3) throw Error(fmt::format("metresPerVertexAtNadir: numPhi must be ≥ 3, got {}", numPhi));
  if (lastRing >= levels * ringsPerLevel)
    throw Error(
        fmt::format("metresPerVertexAtNadir: lastRing {} is out of range 0..{}", lastRing, levels * ringsPerLevel - 1));
  // The pair (outer, inner): rings lastRing−1 and lastRing, or ring 0 and the pole.
  double outerTheta = ringTheta(levels, ringsPerLevel, lastRing == 0 ? 0 : lastRing - 1);
  double innerTheta = lastRing == 0 ? 0.0 : ringTheta(levels, ringsPerLevel, lastRing);
  double radial = radiusM * (outerTheta - innerTheta);
  double azimuthal = radiusM * std::sin(outerTheta) * 2.0 * kPi / double(numPhi);
  return std::max(radial, azimuthal);
}

double poleCapRadiusM(double radiusM, uint32_t levels, uint32_t ringsPerLevel, uint32_t lastRing) {
  requireRadius(radiusM, "poleCapRadiusM");
  requireRingParams(levels, ringsPerLevel, "poleCapRadiusM");
  if (lastRing >= levels * ringsPerLevel)
    throw Error(fmt::format("poleCapRadiusM: lastRing {} is out of range 0..{}", lastRing, levels * ringsPerLevel - 1));
  return radiusM * ringTheta(levels, ringsPerLevel, lastRing);
}

}  // namespace planet
