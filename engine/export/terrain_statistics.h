// Large-scale statistics of a whole planet's terrain from an equirectangular height grid, the
// figures issue 10 (point 3) sets targets for: land fraction, mean land
// elevation and ocean depth, hypsometry and its bimodality, coastline box-count dimension, the
// share of land in continent-sized landmasses; plus the highest and lowest point and the land's
// slope percentiles.
//
// Every issue-10 figure is defined exactly as issue 10's terrain_stats.py (shared/tools) defines it,
// so that the two give the same numbers for the same grid:
//   - the grid: W x H pixels, row-major, top row first, pixel centres at latitude
//     90 (H - 2y - 1) / H degrees (heightmap_export.h, the `planet export heightmap` grid);
//   - area weights: a pixel's area on a sphere of kStatisticsRadiusKm (6371 km, the script's
//     R_KM, whatever the planet's radius: the 10^6 km^2 threshold is Earth's), cos(lat) times
//     (2 pi R / W) (pi R / H);
//   - land: height > 0 m (the script's rule, not the planet's sea level);
//   - hypsometry: area per 500 m bin from -11000 to 9000 m (numpy.histogram: bins closed below,
//     the last one closed at 9000 too, heights outside left out); bimodal when the highest bin
//     whose centre is above -1000 m and the highest bin whose centre is below -3000 m have
//     between them (both excluded) a lowest bin of at most half the smaller peak, and the lower
//     peak holds more than 2 % of the binned area;
//   - coastline dimension: a pixel is coast when it differs in land from its left or upper
//     neighbour; within |lat| < 60 degrees, the boxes of s = 2, 4, ... 64 pixels (whole boxes
//     only, from the band's top-left) holding any coast are counted, and the dimension is minus
//     the least-squares slope of log(count) against log(s);
//   - landmasses: 8-connected land pixels, with the first and last pixel of each row joined
//     (across the 180-degree meridian, same row only, as the script); the share of land area in
//     landmasses of at least 10^6 km^2.
// Additional figures (not in the script):
//   - highest and lowest pixel (first in row-major order on ties) with its centre's latitude
//     and longitude;
//   - land slopes: at each land pixel, the gradient magnitude from forward differences to its
//     east neighbour (wrapping at 180 degrees; spacing R cos(lat) 2 pi / W) and its south
//     neighbour (the bottom row: its north one; spacing pi R / H), R the planet's radius; the
//     10th, 50th and 90th area-weighted percentiles (the smallest slope whose cumulative pixel
//     area reaches p of the land's).
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace planet {

inline constexpr double kStatisticsRadiusKm = 6371.0;  // terrain_stats.py's R_KM, for the areas
inline constexpr double kHypsometryMinM = -11000.0;
inline constexpr double kHypsometryBinM = 500.0;
inline constexpr int kHypsometryBins = 40;  // -11000 .. 9000 m
inline constexpr double kContinentMinKm2 = 1e6;
inline constexpr int kCoastBoxSizes = 6;  // 2, 4, 8, 16, 32, 64 pixels
inline constexpr double kMountainBaseM = 1000.0;

struct GridPoint {
  double heightM = 0.0;
  double latitudeDeg = 0.0, longitudeDeg = 0.0;  // the pixel's centre
};

struct TerrainStatistics {
  uint32_t width = 0, height = 0;
  double landFraction = 0.0;     // area-weighted share of pixels with height > 0
  double meanLandM = 0.0;        // area-weighted mean height of land pixels (NaN without land)
  double meanOceanDepthM = 0.0;  // minus the area-weighted mean height of the others (NaN without any)

  // Share of the whole grid's area in each 500 m bin, bin i covering [-11000 + 500 i, + 500).
  std::array<double, kHypsometryBins> hypsometry{};
  double upperPeakM = 0.0;   // centre of the largest bin centred above -1000 m
  double lowerPeakM = 0.0;   // centre of the largest bin centred below -3000 m
  double troughShare = 0.0;  // the smallest bin strictly between them (the smaller peak if none)
  bool bimodal = false;

  std::array<uint64_t, kCoastBoxSizes> coastBoxCounts{};  // boxes of 2 .. 64 pixels holding coast
  double coastlineDimension = 0.0;  // NaN when a box size finds no coast (or the band is too small)

  double landInContinents = 0.0;  // share of land area in landmasses >= 10^6 km^2 (0 without land)
  uint64_t landmassCount = 0;     // landmasses of any size
  uint64_t continentCount = 0;    // of those, the ones of at least 10^6 km^2

  // Mountains in belts, not everywhere (issue 10): the share of the land's area that holds half
  // of its height above kMountainBaseM (area-weighted, the highest pixels first). Small when the
  // relief stands in ranges, about half when it is spread evenly over the land. NaN without
  // land above kMountainBaseM.
  double mountainConcentration = 0.0;

  GridPoint highest, lowest;

  double northSouthSpacingM = 0.0;                        // pi R / H, R the planet's radius
  double eastWestSpacingEquatorM = 0.0;                   // 2 pi R / W (times cos(lat) elsewhere)
  double slopeP10 = 0.0, slopeP50 = 0.0, slopeP90 = 0.0;  // rise over run (NaN without land)
};

// The figures above of a width x height grid of heights in metres (`heightsM`: row-major, top row
// first, width * height values), `planetRadiusM` giving the slopes' spacings. Throws
// planet::Error for an empty grid or a size that does not match.
TerrainStatistics computeTerrainStatistics(std::span<const float> heightsM, uint32_t width, uint32_t height,
                                           double planetRadiusM);

// Issue 10's targets for an Earth-like planet (point 3), for reports next to the figures.
struct TerrainTargets {
  double landFractionMin = 0.25, landFractionMax = 0.35;
  double meanLandMinM = 500.0, meanLandMaxM = 1200.0;
  double meanOceanDepthMinM = 3000.0, meanOceanDepthMaxM = 4500.0;
  double coastlineDimensionMin = 1.12, coastlineDimensionMax = 1.35;
  double landInContinentsMin = 0.80;
  double mountainConcentrationMax = 0.10;  // this project's bound (the earth preset before issue 10: 0.12)
};
inline constexpr TerrainTargets kEarthTerrainTargets{};

}  // namespace planet
