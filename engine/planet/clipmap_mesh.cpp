#include "planet/clipmap_mesh.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/error.h"

namespace planet {
namespace {

void requireRing(const ClipmapParams& params, uint32_t ring, const char* what) {
  uint32_t ringCount = clipmapRingCount(params);
  if (ring > ringCount)
    throw Error(fmt::format("{}: ring {} is out of range 0..{} ({} is the pole)", what, ring, ringCount, ringCount));
}

void requireNotNan(double theta, const char* what) {
  if (std::isnan(theta)) throw Error(fmt::format("{}: theta is NaN", what));
}

// First index of band b = 0..R (band R−1 is the pole fan; "band R" is the end of the buffer).
uint32_t bandFirstIndex(const ClipmapParams& params, uint32_t band) {
  uint32_t ringCount = clipmapRingCount(params);
  uint32_t quadBands = band < ringCount ? band : ringCount - 1;
  uint32_t first = 6 * params.numPhi * quadBands;
  if (band == ringCount) first += 3 * params.numPhi;
  return first;
}

// The continuous ring coordinate of theta, −m·log2(θ / (π/2)), before rounding and clamping.
double ringCoordinate(const ClipmapParams& params, double theta) {
  return -double(params.ringsPerLevel) * std::log2(theta / (0.5 * std::numbers::pi));
}

}  // namespace

void validateClipmapParams(const ClipmapParams& params) {
  if (params.levels < 1 || params.levels > kClipmapMaxLevels)
    throw Error(fmt::format("clipmap levels must be in 1..{}, got {}", kClipmapMaxLevels, params.levels));
  if (params.ringsPerLevel < 1 || params.ringsPerLevel > kClipmapMaxRingsPerLevel)
    throw Error(
        fmt::format("clipmap ringsPerLevel must be in 1..{}, got {}", kClipmapMaxRingsPerLevel, params.ringsPerLevel));
  if (params.numPhi < kClipmapMinNumPhi || params.numPhi > kClipmapMaxNumPhi)
    throw Error(
        fmt::format("clipmap numPhi must be in {}..{}, got {}", kClipmapMinNumPhi, kClipmapMaxNumPhi, params.numPhi));
}

uint32_t clipmapRingCount(const ClipmapParams& params) { return params.levels * params.ringsPerLevel; }

uint32_t clipmapVertexCount(const ClipmapParams& params) { return clipmapRingCount(params) * params.numPhi + 1; }

uint32_t clipmapTriangleCount(const ClipmapParams& params) {
  return (2 * clipmapRingCount(params) - 1) * params.numPhi;
}

uint32_t clipmapIndexCount(const ClipmapParams& params) { return 3 * clipmapTriangleCount(params); }

double clipmapRingTheta(const ClipmapParams& params, uint32_t ring) {
  requireRing(params, ring, "clipmapRingTheta");
  if (ring == clipmapRingCount(params)) return 0.0;
  // θ = π·2^−ℓ·2^(−j/m) (Hayes-McCoy 2010, §4.3: levelBase · 2^(−ring/numRingsPerLevel)); ldexp
  // keeps the level base exact, so ring 0 of every level is exactly π·2^−ℓ.
  uint32_t level = ring / params.ringsPerLevel + 1;
  uint32_t j = ring % params.ringsPerLevel;
  return std::ldexp(std::numbers::pi, -int(level)) * std::exp2(-double(j) / double(params.ringsPerLevel));
}

uint32_t clipmapLevelOfRing(const ClipmapParams& params, uint32_t ring) {
  requireRing(params, ring, "clipmapLevelOfRing");
  if (ring == clipmapRingCount(params)) return params.levels;
  return ring / params.ringsPerLevel + 1;
}

uint32_t clipmapInnermostRingAtOrAbove(const ClipmapParams& params, double theta) {
  requireNotNan(theta, "clipmapInnermostRingAtOrAbove");
  uint32_t ringCount = clipmapRingCount(params);
  if (theta <= 0.0) return ringCount;
  if (theta >= 0.5 * std::numbers::pi) return 0;
  // θ_k ≥ θ ⇔ k ≤ −m·log2(θ/(π/2)); the floor is only a first guess, corrected against the exact
  // ring θ values below because log2 may round across a ring.
  double estimate = std::floor(ringCoordinate(params, theta));
  uint32_t ring = estimate <= 0.0 ? 0 : estimate >= double(ringCount - 1) ? ringCount - 1 : uint32_t(estimate);
  while (ring + 1 < ringCount && clipmapRingTheta(params, ring + 1) >= theta) ++ring;
  while (ring > 0 && clipmapRingTheta(params, ring) < theta) --ring;
  return ring;
}

uint32_t clipmapOutermostRingAtOrBelow(const ClipmapParams& params, double theta) {
  requireNotNan(theta, "clipmapOutermostRingAtOrBelow");
  uint32_t ringCount = clipmapRingCount(params);
  if (theta < 0.0) return ringCount;
  if (theta >= 0.5 * std::numbers::pi) return 0;
  if (theta == 0.0) return ringCount;
  double estimate = std::ceil(ringCoordinate(params, theta));
  uint32_t ring = estimate <= 0.0 ? 0 : estimate >= double(ringCount) ? ringCount : uint32_t(estimate);
  while (ring > 0 && clipmapRingTheta(params, ring - 1) <= theta) --ring;
  while (ring < ringCount && clipmapRingTheta(params, ring) > theta) ++ring;
  return ring;
}

IndexRange clipmapRingBandRange(const ClipmapParams& params, uint32_t firstRing, uint32_t lastRing) {
  uint32_t ringCount = clipmapRingCount(params);
  if (lastRing > ringCount)
    throw Error(fmt::format("clipmapRingBandRange: lastRing {} is out of range 0..{} ({} is the pole)", lastRing,
                            ringCount, ringCount));
  if (firstRing > lastRing)
    throw Error(fmt::format("clipmapRingBandRange: firstRing {} is after lastRing {}", firstRing, lastRing));
  uint32_t first = bandFirstIndex(params, firstRing);
  return {first, bandFirstIndex(params, lastRing) - first};
}

IndexRange clipmapThetaBandRange(const ClipmapParams& params, double thetaMin, double thetaMax) {
  requireNotNan(thetaMin, "clipmapThetaBandRange");
  requireNotNan(thetaMax, "clipmapThetaBandRange");
  if (thetaMin > thetaMax)
    throw Error(fmt::format("clipmapThetaBandRange: thetaMin {} is greater than thetaMax {}", thetaMin, thetaMax));
  return clipmapRingBandRange(params, clipmapInnermostRingAtOrAbove(params, thetaMax),
                              clipmapOutermostRingAtOrBelow(params, thetaMin));
}

ClipmapMesh buildClipmapMesh(const ClipmapParams& params) {
  validateClipmapParams(params);
  ClipmapMesh mesh;
  mesh.params = params;
  const uint32_t ringCount = clipmapRingCount(params);
  const uint32_t n = params.numPhi;

  // Vertices (Hayes-McCoy 2010, §4.3 BuildVB): ring by ring from the rim inward, N per ring at
  // φ_i = 2π·i/N, then the single pole vertex. Trigonometry in double, stored as float.
  mesh.vertices.reserve(clipmapVertexCount(params));
  for (uint32_t ring = 0; ring < ringCount; ++ring) {
    double theta = clipmapRingTheta(params, ring);
    double sinTheta = std::sin(theta), cosTheta = std::cos(theta);
    uint32_t level = clipmapLevelOfRing(params, ring);
    for (uint32_t i = 0; i < n; ++i) {
      double phi = 2.0 * std::numbers::pi * double(i) / double(n);
      ClipmapVertex v;
      v.direction = glm::vec4(float(std::cos(phi) * sinTheta), float(std::sin(phi) * sinTheta), float(cosTheta), 1.0f);
      v.theta = float(theta);
      v.phi = float(phi);
      v.ring = ring;
      v.level = level;
      mesh.vertices.push_back(v);
    }
  }
  mesh.vertices.push_back({glm::vec4(0.0f, 0.0f, 1.0f, 1.0f), 0.0f, 0.0f, ringCount, params.levels});

  // Indices (§4.4 BuildIB): the quads of band b join ring b (outer) and ring b+1 (inner). The
  // φ successor wraps to index 0 so each band is a closed annulus; the dissertation patches the
  // last quad's indices after the loop for the same reason. Both triangles are counter-clockwise
  // seen from outside: going outer i → outer i+1 turns positively about +z, which is the
  // outward normal near the pole.
  mesh.indices.reserve(clipmapIndexCount(params));
  for (uint32_t band = 0; band + 1 < ringCount; ++band) {
    for (uint32_t i = 0; i < n; ++i) {
      uint32_t next = i + 1 == n ? 0 : i + 1;
      uint32_t outer0 = mesh.vertexIndex(band, i), outer1 = mesh.vertexIndex(band, next);
      uint32_t inner0 = mesh.vertexIndex(band + 1, i), inner1 = mesh.vertexIndex(band + 1, next);
      mesh.indices.insert(mesh.indices.end(), {outer0, outer1, inner1, outer0, inner1, inner0});
    }
  }
  // The pole fan closes the innermost ring (the dissertation's fan "dealt with separately").
  const uint32_t pole = mesh.poleVertex();
  for (uint32_t i = 0; i < n; ++i) {
    uint32_t next = i + 1 == n ? 0 : i + 1;
    mesh.indices.insert(mesh.indices.end(),
                        {mesh.vertexIndex(ringCount - 1, i), mesh.vertexIndex(ringCount - 1, next), pole});
  }
  return mesh;
}

}  // namespace planet
