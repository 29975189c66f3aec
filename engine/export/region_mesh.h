// A triangulated grid over a latitude/longitude region of a planet at the CPU reference's
// heights (terrain_height.h), for other tools; mesh_files.h writes it as glTF 2.0 or OBJ.
//
// Region: latitudes south .. north and longitudes west .. east in degrees (south < north,
// west < east, east - west <= 360; to cross 180° give east above 180, e.g. 170 .. 190).
// Vertices: N per side, index j * N + i, row j = 0 .. N-1 from north to south and column
// i = 0 .. N-1 from west to east, at
//   latitude  = (1 - t) * north + t * south,  t = j / (N - 1)
//   longitude = (1 - s) * west + s * east,    s = i / (N - 1)
// so the corner vertices lie exactly on the region's corners.
// Positions: float metres in a local frame at the region's centre (latitude (south + north) / 2,
// longitude (west + east) / 2): origin = radiusM * up, the radius-sphere point under the centre
// (planet frame, double); x = east, y = up, z = south there (right-handed and y-up as glTF
// wants; Blender's importers show x east, y north, z up). A vertex's planet-frame point is
//   origin + x * east + y * up + z * south,  and its height |point| - radiusM.
// Floats hold an offset to about 6e-8 of the region's extent (0.3 mm across 10 km).
// Normals: unit, outward, from central differences over the neighbouring vertices, with one
// grid step beyond the border evaluated too, so that tiles sharing a border agree there.
// Triangles: two per cell, counter-clockwise seen from above (glTF's front face).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/parallel_for.h"
#include "planet/planet_description.h"

namespace planet {

struct MeshRegion {
  double southDeg = 0.0, westDeg = 0.0, northDeg = 0.0, eastDeg = 0.0;
};

// Vertices per side: 2048² = 4.2 M vertices, 8.4 M triangles, ~200 MB of glTF buffer.
inline constexpr uint32_t kMeshMinResolution = 2;
inline constexpr uint32_t kMeshMaxResolution = 2048;
inline constexpr double kMeshMaxLongitudeDeg = 360.0;  // |west|, |east| at most this

// Throws planet::Error naming the bad value: non-finite, a latitude outside [-90, 90], a
// longitude outside ±360, south >= north, west >= east or east - west > 360.
void validateMeshRegion(const MeshRegion& region);

// The region's extent in metres on the radius sphere: north-south, and east-west along the
// parallel nearest the equator (its widest).
struct RegionExtentM {
  double northSouth = 0.0, eastWest = 0.0;
};
RegionExtentM regionExtentM(double radiusM, const MeshRegion& region);

struct MeshSpec {
  MeshRegion region;
  uint32_t resolution = 0;  // vertices per side
  bool filtered = false;    // octaves limited to meshSpacingM instead of full detail
};

// The octave limit of a filtered spec: the larger cell side at the region's widest,
// max(extent) / (N - 1); 0 for full detail.
double meshSpacingM(const PlanetDescription& planet, const MeshSpec& spec);
// (latitude, longitude) in degrees of vertex (i, j); i or j may be -1 or N for the border
// ring the normals use (latitude clamped to [-90, 90]).
glm::dvec2 meshVertexLatLonDeg(const MeshSpec& spec, int64_t i, int64_t j);

struct LocalFrame {
  glm::dvec3 originM{0.0};                    // planet frame
  glm::dvec3 east{0.0}, up{0.0}, south{0.0};  // x, y, z of the positions, planet frame unit vectors
};
// The frame at the region's centre; at a pole "east" is +y (as travelGreatCircle takes north).
LocalFrame regionFrame(const PlanetDescription& planet, const MeshRegion& region);

struct RegionMesh {
  MeshSpec spec;
  double spacingM = 0.0;  // the octave limit the heights were evaluated with (0: full detail)
  LocalFrame frame;
  std::vector<glm::vec3> positions;                // N * N, local frame, metres
  std::vector<glm::vec3> normals;                  // N * N, local frame, unit
  std::vector<uint32_t> indices;                   // 3 per triangle, 2 (N - 1)² triangles
  glm::vec3 positionMin{0.0f}, positionMax{0.0f};  // of positions, per axis (glTF accessor bounds)
  double minHeightM = 0.0, maxHeightM = 0.0;       // of the vertices
};

// The grid at terrainHeightM(planet, direction, spacing), on `threads` threads (0: all),
// reporting progress in heights evaluated. Throws planet::Error for a bad region or resolution.
RegionMesh computeRegionMesh(const PlanetDescription& planet, const MeshSpec& spec, unsigned threads = 0,
                             const ProgressCallback& progress = {});

}  // namespace planet
