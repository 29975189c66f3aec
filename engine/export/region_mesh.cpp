#include "export/region_mesh.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/error.h"
#include "planet/terrain_height.h"

namespace planet {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

double lerp(double from, double to, double t) { return (1.0 - t) * from + t * to; }

}  // namespace

void validateMeshRegion(const MeshRegion& region) {
  const double values[] = {region.southDeg, region.westDeg, region.northDeg, region.eastDeg};
  for (double v : values)
    if (!std::isfinite(v)) throw Error(fmt::format("region coordinates must be finite, got {}", v));
  for (double latitude : {region.southDeg, region.northDeg})
    if (latitude < -90.0 || latitude > 90.0)
      throw Error(fmt::format("region latitude {} is outside [-90, 90] degrees", latitude));
  for (double longitude : {region.westDeg, region.eastDeg})
    if (std::abs(longitude) > kMeshMaxLongitudeDeg)
      throw Error(fmt::format("region longitude {} is outside [-{}, {}] degrees", longitude, kMeshMaxLongitudeDeg,
                              kMeshMaxLongitudeDeg));
  if (!(region.southDeg < region.northDeg))
    throw Error(
        fmt::format("region south latitude {} must be less than north latitude {}", region.southDeg, region.northDeg));
  if (!(region.westDeg < region.eastDeg))
    throw Error(
        fmt::format("region west longitude {} must be less than east longitude {} (to cross 180 degrees "
                    "give an east longitude above 180)",
                    region.westDeg, region.eastDeg));
  if (region.eastDeg - region.westDeg > 360.0)
    throw Error(fmt::format("region spans {} degrees of longitude, at most 360", region.eastDeg - region.westDeg));
}

RegionExtentM regionExtentM(double radiusM, const MeshRegion& region) {
  // The parallel nearest the equator: 0 when the region straddles it.
  const double widest = region.southDeg <= 0.0 && region.northDeg >= 0.0
                            ? 0.0
                            : std::min(std::abs(region.southDeg), std::abs(region.northDeg));
  return {radiusM * (region.northDeg - region.southDeg) * kDegToRad,
          radiusM * std::cos(widest * kDegToRad) * (region.eastDeg - region.westDeg) * kDegToRad};
}

double meshSpacingM(const PlanetDescription& planet, const MeshSpec& spec) {
  if (!spec.filtered) return 0.0;
  const RegionExtentM extent = regionExtentM(planet.radiusM, spec.region);
  return std::max(extent.northSouth, extent.eastWest) / double(spec.resolution - 1);
}

glm::dvec2 meshVertexLatLonDeg(const MeshSpec& spec, int64_t i, int64_t j) {
  const double steps = double(spec.resolution - 1);
  const double latitude = std::clamp(lerp(spec.region.northDeg, spec.region.southDeg, double(j) / steps), -90.0, 90.0);
  return {latitude, lerp(spec.region.westDeg, spec.region.eastDeg, double(i) / steps)};
}

LocalFrame regionFrame(const PlanetDescription& planet, const MeshRegion& region) {
  LocalFrame frame;
  frame.up = directionFromLatLon(0.5 * (region.southDeg + region.northDeg), 0.5 * (region.westDeg + region.eastDeg));
  frame.originM = planet.radiusM * frame.up;
  const glm::dvec3 east = glm::cross(glm::dvec3(0.0, 0.0, 1.0), frame.up);
  frame.east = glm::length(east) < 1e-12 ? glm::dvec3(0.0, 1.0, 0.0) : glm::normalize(east);
  // east x up = -north: the third axis of a right-handed (east, up, south) frame.
  frame.south = glm::cross(frame.east, frame.up);
  return frame;
}

RegionMesh computeRegionMesh(const PlanetDescription& planet, const MeshSpec& spec, unsigned threads,
                             const ProgressCallback& progress) {
  validateMeshRegion(spec.region);
  if (spec.resolution < kMeshMinResolution || spec.resolution > kMeshMaxResolution)
    throw Error(fmt::format("mesh resolution must be in {}..{} vertices per side, got {}", kMeshMinResolution,
                            kMeshMaxResolution, spec.resolution));
  const size_t n = spec.resolution;
  const size_t side = n + 2;  // with the border ring at i, j = -1 and N
  RegionMesh mesh;
  mesh.spec = spec;
  mesh.spacingM = meshSpacingM(planet, spec);
  mesh.frame = regionFrame(planet, spec.region);

  // Planet-frame surface points of the bordered grid, in double.
  std::vector<glm::dvec3> points(side * side);
  std::vector<double> heights(side * side);
  parallelFor(
      side, 1, threads,
      [&](size_t begin, size_t end) {
        for (size_t row = begin; row < end; ++row)
          for (size_t column = 0; column < side; ++column) {
            const glm::dvec2 latLon = meshVertexLatLonDeg(spec, int64_t(column) - 1, int64_t(row) - 1);
            const glm::dvec3 direction = directionFromLatLon(latLon.x, latLon.y);
            const double h = terrainHeightM(planet, direction, mesh.spacingM);
            heights[row * side + column] = h;
            points[row * side + column] = (planet.radiusM + h) * direction;
          }
      },
      progress ? ProgressCallback([&](size_t done, size_t total) { progress(done * side, total * side); })
               : ProgressCallback());

  const LocalFrame& f = mesh.frame;
  auto toLocal = [&](const glm::dvec3& v) {
    return glm::vec3(float(glm::dot(v, f.east)), float(glm::dot(v, f.up)), float(glm::dot(v, f.south)));
  };
  // Vertex (i, j) of the bordered grid: i and j may be -1 or N.
  auto at = [&](int64_t i, int64_t j) { return points[size_t(j + 1) * side + size_t(i + 1)]; };
  mesh.positions.resize(n * n);
  mesh.normals.resize(n * n);
  mesh.minHeightM = 1e300;
  mesh.maxHeightM = -1e300;
  for (int64_t j = 0; j < int64_t(n); ++j)
    for (int64_t i = 0; i < int64_t(n); ++i) {
      const size_t index = size_t(j) * n + size_t(i);
      const glm::dvec3 p = at(i, j);
      mesh.positions[index] = toLocal(p - f.originM);
      const double h = heights[size_t(j + 1) * side + size_t(i + 1)];
      mesh.minHeightM = std::min(mesh.minHeightM, h);
      mesh.maxHeightM = std::max(mesh.maxHeightM, h);
      // east x north = up; j grows southward.
      const glm::dvec3 towardEast = at(i + 1, j) - at(i - 1, j);
      const glm::dvec3 towardNorth = at(i, j - 1) - at(i, j + 1);
      glm::dvec3 normal = glm::cross(towardEast, towardNorth);
      const glm::dvec3 radial = glm::normalize(p);
      const double length = glm::length(normal);
      // A pole row (every vertex the same direction, up to rounding) has no east-west extent:
      // there the radial direction. Judged by the directions, not the points: heights at one
      // direction may differ by metres between longitudes (the reference's seam at the pole).
      const double eastSpan = glm::length(glm::normalize(at(i + 1, j)) - glm::normalize(at(i - 1, j)));
      const double northSpan = glm::length(glm::normalize(at(i, j - 1)) - glm::normalize(at(i, j + 1)));
      const bool degenerate = !(eastSpan > 1e-9 * northSpan) || !(length > 0.0);
      normal = degenerate ? radial : normal / length;
      if (glm::dot(normal, radial) < 0.0) normal = -normal;
      mesh.normals[index] = glm::normalize(toLocal(normal));
    }
  mesh.positionMin = mesh.positionMax = mesh.positions[0];
  for (const glm::vec3& p : mesh.positions) {
    mesh.positionMin = glm::min(mesh.positionMin, p);
    mesh.positionMax = glm::max(mesh.positionMax, p);
  }

  mesh.indices.reserve(6 * (n - 1) * (n - 1));
  for (size_t j = 0; j + 1 < n; ++j)
    for (size_t i = 0; i + 1 < n; ++i) {
      const uint32_t northWest = uint32_t(j * n + i), northEast = northWest + 1;
      const uint32_t southWest = uint32_t((j + 1) * n + i), southEast = southWest + 1;
      mesh.indices.insert(mesh.indices.end(), {northWest, southWest, southEast, northWest, southEast, northEast});
    }
  return mesh;
}

}  // namespace planet
