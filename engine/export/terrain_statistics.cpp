// The definitions follow issue 10's terrain_stats.py step by step (see the header); where numpy's
// behaviour matters (histogram edges, argmax ties, polyfit) the comment says which.
#include "export/terrain_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "export/heightmap_export.h"

namespace planet {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = std::numbers::pi;

// The pixel-centre latitude of row y, as the script computes it (the exporter's formula).
double rowLatitudeDeg(uint32_t y, uint32_t height) { return equirectPixelCentreDeg(0, y, 1, height).x; }

// numpy.histogram's bin of `v` for the edges -11000, -10500, ... 9000: [e_i, e_i+1), the last bin
// also holding 9000; -1 outside. The estimate from the division is checked against the exact
// edges, so that a height a rounding away from an edge lands where numpy puts it.
int hypsometryBin(double v) {
  const double top = kHypsometryMinM + kHypsometryBinM * kHypsometryBins;
  if (!(v >= kHypsometryMinM && v <= top)) return -1;
  if (v == top) return kHypsometryBins - 1;
  int i = std::clamp(int(std::floor((v - kHypsometryMinM) / kHypsometryBinM)), 0, kHypsometryBins - 1);
  if (v < kHypsometryMinM + kHypsometryBinM * i) --i;
  if (i + 1 < kHypsometryBins && v >= kHypsometryMinM + kHypsometryBinM * (i + 1)) ++i;
  return i;
}

double binCentreM(int i) { return kHypsometryMinM + kHypsometryBinM * i + 0.5 * kHypsometryBinM; }

// The script's bimodality rule on bin areas `hist` (km^2).
void hypsometryVerdict(const std::array<double, kHypsometryBins>& hist, TerrainStatistics& s) {
  // argmax: the first of equal maxima.
  int hiAt = -1, loAt = -1;
  for (int i = 0; i < kHypsometryBins; ++i) {
    if (binCentreM(i) > -1000.0 && (hiAt < 0 || hist[size_t(i)] > hist[size_t(hiAt)])) hiAt = i;
    if (binCentreM(i) < -3000.0 && (loAt < 0 || hist[size_t(i)] > hist[size_t(loAt)])) loAt = i;
  }
  const double hi = hist[size_t(hiAt)], lo = hist[size_t(loAt)];
  double trough = kNaN;
  for (int i = loAt + 1; i < hiAt; ++i)
    trough = std::isnan(trough) ? hist[size_t(i)] : std::min(trough, hist[size_t(i)]);
  if (std::isnan(trough)) trough = std::min(hi, lo);
  const double binned = std::accumulate(hist.begin(), hist.end(), 0.0);
  s.upperPeakM = binCentreM(hiAt);
  s.lowerPeakM = binCentreM(loAt);
  s.bimodal = trough <= 0.5 * std::min(hi, lo) && lo > 0.02 * binned;
  s.troughShare = trough;  // in km^2 here; the caller scales it with the bins
}

// Box counting of the coast within 60 degrees of the equator.
void coastlineDimension(const std::vector<uint8_t>& land, uint32_t w, uint32_t h, TerrainStatistics& s) {
  std::vector<uint8_t> edge(land.size(), 0);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      edge[i] = (x > 0 && land[i] != land[i - 1]) || (y > 0 && land[i] != land[i - w]);
    }
  uint32_t bandTop = h, bandRows = 0;  // the rows with |lat| < 60: one run, symmetric about the equator
  for (uint32_t y = 0; y < h; ++y)
    if (std::abs(rowLatitudeDeg(y, h)) < 60.0) {
      bandTop = std::min(bandTop, y);
      ++bandRows;
    }
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  bool empty = false;
  for (int k = 0; k < kCoastBoxSizes; ++k) {
    const uint32_t box = 2u << k;
    const uint32_t rows = bandRows / box, cols = w / box;
    uint64_t count = 0;
    for (uint32_t by = 0; by < rows; ++by)
      for (uint32_t bx = 0; bx < cols; ++bx) {
        bool any = false;
        for (uint32_t y = bandTop + by * box; y < bandTop + (by + 1) * box && !any; ++y)
          for (uint32_t x = bx * box; x < (bx + 1) * box && !any; ++x) any = edge[size_t(y) * w + x] != 0;
        count += any;
      }
    s.coastBoxCounts[size_t(k)] = count;
    if (count == 0) empty = true;
    const double lx = std::log(double(box)), ly = std::log(double(count));
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  // numpy.polyfit(log s, log count, 1)[0]: the least-squares slope.
  const double n = kCoastBoxSizes;
  s.coastlineDimension = empty ? kNaN : -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// Union-find over pixel indices, for the landmasses.
struct Components {
  std::vector<uint32_t> parent;
  explicit Components(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t find(uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void join(uint32_t a, uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

void landmasses(const std::vector<uint8_t>& land, const std::vector<double>& rowAreaKm2, uint32_t w, uint32_t h,
                TerrainStatistics& s) {
  Components c(land.size());
  auto index = [w](uint32_t x, uint32_t y) { return uint32_t(size_t(y) * w + x); };
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      if (!land[index(x, y)]) continue;
      // 8-connected (scipy.ndimage.label with a 3x3 structure): the neighbours already visited.
      if (x > 0 && land[index(x - 1, y)]) c.join(index(x, y), index(x - 1, y));
      if (y > 0) {
        if (land[index(x, y - 1)]) c.join(index(x, y), index(x, y - 1));
        if (x > 0 && land[index(x - 1, y - 1)]) c.join(index(x, y), index(x - 1, y - 1));
        if (x + 1 < w && land[index(x + 1, y - 1)]) c.join(index(x, y), index(x + 1, y - 1));
      }
    }
  // Across the 180-degree meridian: the script joins a row's first and last pixel only.
  for (uint32_t y = 0; y < h && w > 1; ++y)
    if (land[index(0, y)] && land[index(w - 1, y)]) c.join(index(0, y), index(w - 1, y));
  std::vector<double> areaKm2(land.size(), 0.0);
  double total = 0.0;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      if (land[index(x, y)]) {
        areaKm2[c.find(index(x, y))] += rowAreaKm2[y];
        total += rowAreaKm2[y];
      }
  double big = 0.0;
  for (size_t i = 0; i < land.size(); ++i)
    if (land[i] && c.parent[i] == i) {
      ++s.landmassCount;
      if (areaKm2[i] >= kContinentMinKm2) {
        ++s.continentCount;
        big += areaKm2[i];
      }
    }
  s.landInContinents = big / std::max(total, 1e-9);
}

// The share of the land's area holding half of its height above kMountainBaseM.
void mountainConcentration(std::span<const float> heights, const std::vector<double>& rowAreaKm2, uint32_t w,
                           uint32_t h, TerrainStatistics& s) {
  std::vector<std::pair<double, double>> above;  // (height above the base, area) of land pixels above it
  double landArea = 0.0, volume = 0.0;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const double v = heights[size_t(y) * w + x];
      if (!(v > 0.0)) continue;
      landArea += rowAreaKm2[y];
      if (v <= kMountainBaseM) continue;
      above.push_back({v - kMountainBaseM, rowAreaKm2[y]});
      volume += (v - kMountainBaseM) * rowAreaKm2[y];
    }
  if (!(volume > 0.0)) {
    s.mountainConcentration = kNaN;
    return;
  }
  std::sort(above.begin(), above.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  double area = 0.0, held = 0.0;
  for (const auto& [excess, pixelArea] : above) {
    if (held >= 0.5 * volume) break;
    held += excess * pixelArea;
    area += pixelArea;
  }
  s.mountainConcentration = area / landArea;
}

// The land's slopes and their area-weighted percentiles.
void landSlopes(std::span<const float> heights, const std::vector<uint8_t>& land, uint32_t w, uint32_t h,
                double radiusM, TerrainStatistics& s) {
  s.northSouthSpacingM = kPi * radiusM / h;
  s.eastWestSpacingEquatorM = 2.0 * kPi * radiusM / w;
  std::vector<std::pair<double, double>> slopeAndArea;  // (rise over run, cos(lat))
  for (uint32_t y = 0; y < h; ++y) {
    const double cosLat = std::cos(rowLatitudeDeg(y, h) * kPi / 180.0);
    const double eastWestM = s.eastWestSpacingEquatorM * cosLat;
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      if (!land[i]) continue;
      const double here = heights[i];
      const double east = heights[size_t(y) * w + (x + 1) % w];
      const double gx = (east - here) / eastWestM;
      double gy = 0.0;
      if (h > 1) gy = (double(heights[y + 1 < h ? i + w : i - w]) - here) / s.northSouthSpacingM;
      slopeAndArea.emplace_back(std::sqrt(gx * gx + gy * gy), cosLat);
    }
  }
  if (slopeAndArea.empty()) {
    s.slopeP10 = s.slopeP50 = s.slopeP90 = kNaN;
    return;
  }
  std::sort(slopeAndArea.begin(), slopeAndArea.end());
  double total = 0.0;
  for (const auto& [slope, area] : slopeAndArea) total += area;
  const double ps[3] = {0.1, 0.5, 0.9};
  double* out[3] = {&s.slopeP10, &s.slopeP50, &s.slopeP90};
  double cumulative = 0.0;
  size_t k = 0;
  for (const auto& [slope, area] : slopeAndArea) {
    cumulative += area;
    while (k < 3 && cumulative >= ps[k] * total) *out[k++] = slope;
  }
  while (k < 3) *out[k++] = slopeAndArea.back().first;  // rounding left the top short
}

}  // namespace

TerrainStatistics computeTerrainStatistics(std::span<const float> heightsM, uint32_t width, uint32_t height,
                                           double planetRadiusM) {
  if (width == 0 || height == 0 || heightsM.size() != size_t(width) * height)
    throw Error(fmt::format("terrain statistics need a {}x{} grid of {} heights, got {}", width, height,
                            size_t(width) * height, heightsM.size()));
  TerrainStatistics s;
  s.width = width;
  s.height = height;
  const uint32_t w = width, h = height;
  // A pixel's area in km^2 depends on its row only: cos(lat) (2 pi R / W) (pi R / H).
  std::vector<double> rowAreaKm2(h);
  for (uint32_t y = 0; y < h; ++y)
    rowAreaKm2[y] = std::cos(rowLatitudeDeg(y, h) * (kPi / 180.0)) * (2.0 * kPi * kStatisticsRadiusKm / w) *
                    (kPi * kStatisticsRadiusKm / h);

  std::vector<uint8_t> land(heightsM.size());
  std::array<double, kHypsometryBins> hist{};
  double area = 0.0, landArea = 0.0, landSum = 0.0, oceanArea = 0.0, oceanSum = 0.0;
  size_t highest = 0, lowest = 0;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const double v = heightsM[i], a = rowAreaKm2[y];
      land[i] = v > 0.0;
      area += a;
      if (land[i]) {
        landArea += a;
        landSum += v * a;
      } else {
        oceanArea += a;
        oceanSum += v * a;
      }
      if (const int bin = hypsometryBin(v); bin >= 0) hist[size_t(bin)] += a;
      if (heightsM[i] > heightsM[highest]) highest = i;
      if (heightsM[i] < heightsM[lowest]) lowest = i;
    }
  s.landFraction = landArea / area;
  s.meanLandM = landArea > 0.0 ? landSum / landArea : kNaN;
  s.meanOceanDepthM = oceanArea > 0.0 ? -oceanSum / oceanArea : kNaN;

  hypsometryVerdict(hist, s);
  s.troughShare /= area;
  for (int i = 0; i < kHypsometryBins; ++i) s.hypsometry[size_t(i)] = hist[size_t(i)] / area;

  coastlineDimension(land, w, h, s);
  landmasses(land, rowAreaKm2, w, h, s);
  mountainConcentration(heightsM, rowAreaKm2, w, h, s);

  for (auto [index, point] : {std::pair{highest, &s.highest}, std::pair{lowest, &s.lowest}}) {
    const glm::dvec2 latLon = equirectPixelCentreDeg(uint32_t(index % w), uint32_t(index / w), w, h);
    *point = {heightsM[index], latLon.x, latLon.y};
  }
  landSlopes(heightsM, land, w, h, planetRadiusM, s);
  return s;
}

}  // namespace planet
