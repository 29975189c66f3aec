// planet stats: the large-scale terrain statistics of issue 10 (engine/export/terrain_statistics.h)
// from the CPU reference's equirect height grid, the one `planet export heightmap` writes (no
// Vulkan), with issue 10's targets beside each figure.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "core/error.h"
#include "core/file.h"
#include "export/heightmap_export.h"
#include "export/terrain_statistics.h"

namespace planet::cli {
namespace {

// The landmass labelling holds a few words a pixel: 8192x4096 (33 M pixels) is about 1 GiB.
constexpr uint32_t kStatsMaxWidth = 8192;
constexpr uint32_t kStatsMaxHeight = 4096;

struct StatsCommand {
  std::string preset{kDefaultPresetName};
  std::optional<uint64_t> seed;
  std::string size = "2048x1024";
  std::string json;
};

HeightmapSpec parseStatsSize(const std::string& text) {
  uint32_t width = 0, height = 0;
  parseSize(text, width, height, kStatsMaxWidth, kStatsMaxHeight);
  return equirectSpec(width, height);
}

// A figure that may be NaN (no land, no ocean, no coast): "n/a" in the table, null in JSON.
std::string fixed(double value, int digits) {
  return std::isfinite(value) ? fmt::format("{:.{}f}", value, digits) : std::string("n/a");
}

std::string metres(double value) { return std::isfinite(value) ? fmt::format("{:.0f} m", value) : "n/a"; }

nlohmann::ordered_json number(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

std::string latLonText(const GridPoint& p) {
  return fmt::format("{:.2f}° {}, {:.2f}° {}", std::abs(p.latitudeDeg), p.latitudeDeg < 0.0 ? 'S' : 'N',
                     std::abs(p.longitudeDeg), p.longitudeDeg < 0.0 ? 'W' : 'E');
}

double slopeDeg(double riseOverRun) { return std::atan(riseOverRun) * 180.0 / std::numbers::pi; }

void printTable(const PlanetDescription& planet, const std::string& preset, uint64_t seed, const TerrainStatistics& s) {
  const TerrainTargets& t = kEarthTerrainTargets;
  fmt::memory_buffer out;
  // No blank lines (a README example block ends at one) and no trailing blanks (an empty bar or target).
  auto line = [&out](std::string_view text) {
    const size_t end = text.find_last_not_of(' ');
    fmt::format_to(std::back_inserter(out), "{}\n", text.substr(0, end == std::string_view::npos ? 0 : end + 1));
  };
  auto row = [&](std::string_view name, const std::string& value, const std::string& target) {
    line(fmt::format("{:<34}{:>12}   {}", name, value, target));
  };
  line(fmt::format("{} (preset {}, seed {}): {}x{} equirect heights from the CPU reference, full detail", planet.name,
                   preset, seed, s.width, s.height));
  line(fmt::format(
      "land: height > 0 m (as issue 10's terrain_stats.py; sea level {:.0f} m); areas on a {:.0f} km sphere",
      planet.seaLevelM, kStatisticsRadiusKm));
  line(fmt::format("{:<34}{:>12}   {}", "figure", "value", "issue 10 target (Earth)"));
  row("land fraction", fixed(s.landFraction, 3),
      fmt::format("{:.2f}–{:.2f} (0.29)", t.landFractionMin, t.landFractionMax));
  row("mean land elevation", metres(s.meanLandM),
      fmt::format("{:.0f}–{:.0f} m (≈ 840 m)", t.meanLandMinM, t.meanLandMaxM));
  row("mean ocean depth", metres(s.meanOceanDepthM),
      fmt::format("{:.0f}–{:.0f} m (≈ 3680 m)", t.meanOceanDepthMinM, t.meanOceanDepthMaxM));
  row("bimodal hypsometry", s.bimodal ? "yes" : "no", "yes");
  row("  peak above -1 km", fmt::format("{:.0f} m", s.upperPeakM), "near 0–1 km");
  row("  peak below -3 km", fmt::format("{:.0f} m", s.lowerPeakM), "near -4 to -5 km");
  row("coastline dimension", fixed(s.coastlineDimension, 3),
      fmt::format("{:.2f}–{:.2f} (1.23)", t.coastlineDimensionMin, t.coastlineDimensionMax));
  row("land in landmasses >= 10^6 km²", fixed(s.landInContinents, 3),
      fmt::format(">= {:.2f} (0.95)", t.landInContinentsMin));
  row("  landmasses, of those >= 10^6 km²", fmt::format("{}, {}", s.landmassCount, s.continentCount), "");
  row("land holding half the height > 1 km", fixed(s.mountainConcentration, 3),
      fmt::format("<= {:.2f} (belts)", t.mountainConcentrationMax));
  line(fmt::format("highest point {:.1f} m at {}", s.highest.heightM, latLonText(s.highest)));
  line(fmt::format("lowest point {:.1f} m at {}", s.lowest.heightM, latLonText(s.lowest)));
  line(
      fmt::format("land slope p10 / p50 / p90: {}° / {}° / {}° (grid spacing {:.0f} m north-south, {:.0f} m "
                  "east-west at the equator)",
                  fixed(slopeDeg(s.slopeP10), 2), fixed(slopeDeg(s.slopeP50), 2), fixed(slopeDeg(s.slopeP90), 2),
                  s.northSouthSpacingM, s.eastWestSpacingEquatorM));
  line("hypsometry (500 m bins, share of the area):");
  int first = kHypsometryBins, last = -1;
  for (int i = 0; i < kHypsometryBins; ++i)
    if (s.hypsometry[size_t(i)] > 0.0) first = std::min(first, i), last = i;
  for (int i = first; i <= last; ++i) {
    const double share = s.hypsometry[size_t(i)];
    const double bottom = kHypsometryMinM + kHypsometryBinM * i;
    line(fmt::format("  {:>6.0f} .. {:>6.0f} m  {:5.3f}  {}", bottom, bottom + kHypsometryBinM, share,
                     std::string(size_t(std::lround(share * 200.0)), '#')));
  }
  std::fwrite(out.data(), 1, out.size(), stdout);
}

nlohmann::ordered_json statsJson(const PlanetDescription& planet, const ExportSource& source,
                                 const TerrainStatistics& s) {
  const TerrainTargets& t = kEarthTerrainTargets;
  nlohmann::ordered_json j;
  j["format"] = "planet-terrain-stats";
  j["version"] = 1;
  j["generator"] = "planet stats";
  j["source"] = exportProvenance(planet, source, 0.0);
  j["projection"] = "equirect";
  j["width"] = s.width;
  j["height"] = s.height;
  j["definitions"] = "issue 10's terrain_stats.py: land is height > 0 m, areas on a 6371 km sphere";
  j["land_fraction"] = number(s.landFraction);
  j["mean_land_m"] = number(s.meanLandM);
  j["mean_ocean_depth_m"] = number(s.meanOceanDepthM);
  j["bimodal"] = s.bimodal;
  j["upper_peak_m"] = s.upperPeakM;
  j["lower_peak_m"] = s.lowerPeakM;
  j["trough_share"] = s.troughShare;
  j["hypsometry"] = {{"min_m", kHypsometryMinM},
                     {"bin_m", kHypsometryBinM},
                     {"area_share", std::vector<double>(s.hypsometry.begin(), s.hypsometry.end())}};
  j["coastline_dimension"] = number(s.coastlineDimension);
  j["coast_box_sizes_px"] = {2, 4, 8, 16, 32, 64};
  j["coast_box_counts"] = std::vector<uint64_t>(s.coastBoxCounts.begin(), s.coastBoxCounts.end());
  j["land_in_continents"] = number(s.landInContinents);
  j["landmass_count"] = s.landmassCount;
  j["continent_count"] = s.continentCount;
  j["mountain_concentration"] = number(s.mountainConcentration);
  for (auto [name, p] : {std::pair{"highest", &s.highest}, std::pair{"lowest", &s.lowest}})
    j[name] = {{"height_m", p->heightM}, {"latitude_deg", p->latitudeDeg}, {"longitude_deg", p->longitudeDeg}};
  j["land_slope"] = {{"north_south_spacing_m", s.northSouthSpacingM},
                     {"east_west_spacing_equator_m", s.eastWestSpacingEquatorM},
                     {"p10", number(s.slopeP10)},
                     {"p50", number(s.slopeP50)},
                     {"p90", number(s.slopeP90)},
                     {"p10_deg", number(slopeDeg(s.slopeP10))},
                     {"p50_deg", number(slopeDeg(s.slopeP50))},
                     {"p90_deg", number(slopeDeg(s.slopeP90))}};
  j["targets"] = {{"land_fraction", {t.landFractionMin, t.landFractionMax}},
                  {"mean_land_m", {t.meanLandMinM, t.meanLandMaxM}},
                  {"mean_ocean_depth_m", {t.meanOceanDepthMinM, t.meanOceanDepthMaxM}},
                  {"bimodal", true},
                  {"coastline_dimension", {t.coastlineDimensionMin, t.coastlineDimensionMax}},
                  {"land_in_continents_min", t.landInContinentsMin},
                  {"mountain_concentration_max", t.mountainConcentrationMax}};
  return j;
}

int runStats(const StatsCommand& cmd, bool jsonGiven) {
  const HeightmapSpec spec = parseStatsSize(cmd.size);
  if (jsonGiven) checkOutputFile("--json", cmd.json);
  PlanetDescription planet;
  try {
    planet = resolvePreset(cmd.preset);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  if (cmd.seed) applySeedOffset(planet, *cmd.seed);
  const ExportSource source{cmd.preset, cmd.seed.value_or(0)};

  const auto start = std::chrono::steady_clock::now();
  Heightmap map;
  {
    ProgressLine progress(fmt::format("stats heightmap {}x{}", spec.width, spec.height));
    map = computeHeightmap(planet, spec, 0, std::ref(progress));
  }
  const TerrainStatistics stats = computeTerrainStatistics(map.heightsM, spec.width, spec.height, planet.radiusM);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!cmd.json.empty()) writeFileAtomic(cmd.json, statsJson(planet, source, stats).dump(2) + "\n");
  printTable(planet, cmd.preset, source.seedOffset, stats);
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  fmt::print("{} heights in {:.2f} s on {} thread{}{}\n", map.heightsM.size(), seconds, threads,
             threads == 1 ? "" : "s", cmd.json.empty() ? "" : fmt::format("; wrote {}", cmd.json));
  return 0;
}

}  // namespace

void addStatsCommand(CLI::App& app, int& exitCode) {
  auto cmd = std::make_shared<StatsCommand>();
  CLI::App* sub = app.add_subcommand(
      "stats",
      "Terrain statistics of issue 10 from the CPU reference's equirect heights (no GPU): land fraction, mean land "
      "elevation and ocean depth, hypsometry and its bimodality, coastline dimension, land in continents, highest "
      "and lowest point, land slopes; each beside its target");
  sub->add_option("--preset", cmd->preset, "Built-in preset (earth, moon, mars, giant, faults, mpd) or a .toml file")
      ->capture_default_str();
  sub->add_option("--seed", cmd->seed, "Added to every layer's seed, as in planet render and planet export");
  sub->add_option("--size", cmd->size,
                  fmt::format("Grid WxH in pixels, the planet export heightmap grid (at most {}x{})", kStatsMaxWidth,
                              kStatsMaxHeight))
      ->capture_default_str();
  sub->add_option("--json", cmd->json, "Also write every figure to this JSON file (replaced atomically)");
  checkNumbersAsText(*sub);
  sub->callback([&exitCode, cmd, sub] { exitCode = runStats(*cmd, sub->count("--json") > 0); });
}

}  // namespace planet::cli
