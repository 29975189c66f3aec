// Terrain height of a planet description at a point, evaluated by the CPU double-precision
// reference of the shared noise (engine/noise/noise_kernel.h). This is the reference the GPU
// terrain is checked against, and what `planet height` prints.
#pragma once

#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "planet/planet_description.h"

namespace planet {

// Planet frame: +z is the north pole, +x points at latitude 0 / longitude 0, +y at longitude
// 90° east. Angles in degrees; throws planet::Error for a latitude outside [-90, 90] or a
// non-finite value.
glm::dvec3 directionFromLatLon(double latitudeDeg, double longitudeDeg);
// Its inverse for any non-zero direction (not necessarily unit): degrees, longitude in [−180, 180].
double latitudeDegOf(const glm::dvec3& direction);
double longitudeDegOf(const glm::dvec3& direction);

// The direction reached from `start` after travelling `distanceM` along the great circle with
// initial `bearingDeg` (clockwise from north) on a sphere of radius `radiusM`.
glm::dvec3 travelGreatCircle(const glm::dvec3& start, double bearingDeg, double distanceM, double radiusM);

// Height in metres above the radius sphere at unit direction `direction`:
//   heightScale * (baseHeightM + sum over layers of amplitudeM * noise(radiusM * direction * frequency)).
// spacingM <= 0: every octave of every layer is evaluated (no octave limit), the full-detail
// surface. spacingM > 0: each layer is limited to octaveBudget(layer, spacingM), as the renderer
// limits a vertex or texel that far from its neighbours (octave_budget.h).
double terrainHeightM(const PlanetDescription& planet, const glm::dvec3& direction, double spacingM = 0.0);

// What a camera stands on at `direction`: the full-detail terrain height, or the sea level
// where the planet has an ocean above it (metres above the radius sphere).
double surfaceHeightM(const PlanetDescription& planet, const glm::dvec3& direction);

// Estimates of the lowest and highest terrain of the planet, for the horizon cut, the culling
// hulls and the per-frame shading bounds: the extremes over 4096 directions spread evenly over
// the sphere (a Fibonacci lattice) at ~200 km spacing, widened by what the octaves finer than
// that and the points between the samples may add (the summed amplitude of every layer's omitted
// octaves, bounded generously, plus 10 %), and narrowed to exactTerrainHeightBounds where that
// exists. minM is at most 0 and maxM at least 0 (the radius sphere is always inside the bounds).
struct TerrainHeightBounds {
  double minM = 0.0;
  double maxM = 0.0;
};
TerrainHeightBounds estimateTerrainHeightBounds(const PlanetDescription& planet);

// Bounds that hold everywhere, from each layer's range: a curve's values (it is clamped at its
// ends and monotone between its knots), or for a simplex or fBm layer without one its octaves'
// weights times the largest simplex value; masks multiply ranges, amplitudes scale them. None
// when some layer has neither (the other fractals). Without sampling, so they may be wider
// than the terrain ever reaches, but never narrower (Earth's preset: about -6.4 to 7.2 km).
std::optional<TerrainHeightBounds> exactTerrainHeightBounds(const PlanetDescription& planet);

// Heights along a great circle: `count` samples `stepM` apart, starting at `start`.
std::vector<double> terrainHeightsAlong(const PlanetDescription& planet, const glm::dvec3& start, double bearingDeg,
                                        double stepM, size_t count);

}  // namespace planet
