// `planet stats` as a user runs it: the figures of issue 10's terrain_stats.py for the same grid, a
// table on stdout with each target beside its figure, and a JSON file that parses. (Bad flags:
// cli_test.cpp's table.)
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace planet {
namespace {

namespace fs = std::filesystem;

fs::path tempDir() { return test::processTempDir("stats_cli_test"); }

test::ShellRun planetRun(const std::string& args) { return test::runShell(PLANET_EXE, args, "", tempDir()); }

// terrain_stats.py's (issue 10) height_stats() on `planet export heightmap --preset earth --size
// 256x128 --format raw` (seed 0), its figures at full precision (it prints them rounded to
// 0.001: 0.314, 974.983, 3512.525, True, 1.665, 0.973). These say that `planet stats` measures as
// the script does; terrain_statistics_test.cpp holds issue 10's targets (at 2048x1024: at this
// grid the coastline's boxes are 4 times larger and its dimension is not comparable).
constexpr double kScriptLandFraction = 0.3139266396362552;
constexpr double kScriptMeanLandM = 974.983241749816;
constexpr double kScriptMeanOceanDepthM = 3512.5249928547923;
constexpr bool kScriptBimodal = true;
constexpr double kScriptCoastlineDimension = 1.6648486891162981;
constexpr double kScriptLandInContinents = 0.9726512602303344;

TEST(StatsCli, EarthAt256x128ReproducesTheTerrainStatsScript) {
  const fs::path json = tempDir() / "earth_stats.json";
  const test::ShellRun run = planetRun("stats --preset earth --size 256x128 --json " + json.string());
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(test::readFileBytes(json));
  EXPECT_EQ(j["format"], "planet-terrain-stats");
  EXPECT_EQ(j["width"], 256);
  EXPECT_EQ(j["height"], 128);
  EXPECT_NEAR(j["land_fraction"].get<double>(), kScriptLandFraction, 1e-6 * kScriptLandFraction);
  EXPECT_NEAR(j["mean_land_m"].get<double>(), kScriptMeanLandM, 1e-6 * kScriptMeanLandM);
  EXPECT_NEAR(j["mean_ocean_depth_m"].get<double>(), kScriptMeanOceanDepthM, 1e-6 * kScriptMeanOceanDepthM);
  EXPECT_EQ(j["bimodal"].get<bool>(), kScriptBimodal);
  EXPECT_NEAR(j["coastline_dimension"].get<double>(), kScriptCoastlineDimension, 1e-3);
  EXPECT_NEAR(j["land_in_continents"].get<double>(), kScriptLandInContinents, 1e-6 * kScriptLandInContinents);
  // The extra figures are there and sensible.
  EXPECT_GT(j["highest"]["height_m"].get<double>(), 0.0);
  EXPECT_LT(j["lowest"]["height_m"].get<double>(), 0.0);
  const auto& slope = j["land_slope"];
  EXPECT_LE(slope["p10"].get<double>(), slope["p50"].get<double>());
  EXPECT_LE(slope["p50"].get<double>(), slope["p90"].get<double>());
  EXPECT_NEAR(slope["north_south_spacing_m"].get<double>(), M_PI * 6371000.0 / 128.0, 1e-6);
  EXPECT_EQ(j["hypsometry"]["area_share"].size(), 40u);
  double total = 0.0;
  for (const auto& share : j["hypsometry"]["area_share"]) total += share.get<double>();
  EXPECT_NEAR(total, 1.0, 1e-9);  // every Earth height lies within -11 .. 9 km

  // The table: each figure, with its target beside it, and nothing on stderr for a quick run.
  for (const char* text : {"land fraction                            0.314   0.25–0.35",
                           "mean land elevation                      975 m   500–1200 m",
                           "mean ocean depth                        3513 m   3000–4500 m",
                           "bimodal hypsometry                         yes   yes",
                           "coastline dimension                      1.665   1.12–1.35",
                           "land in landmasses >= 10^6 km²           0.973   >= 0.80", "highest point", "lowest point",
                           "land slope p10 / p50 / p90", "grid spacing 156368 m north-south", "hypsometry (500 m bins"})
    EXPECT_NE(run.out.find(text), std::string::npos) << text << "\n" << run.out;
  EXPECT_EQ(run.err, "");
}

TEST(StatsCli, SeedChangesTheFiguresAndTheSameRunRepeatsThem) {
  const test::ShellRun a = planetRun("stats --size 64x32");
  const test::ShellRun b = planetRun("stats --size 64x32");
  const test::ShellRun seeded = planetRun("stats --size 64x32 --seed 3");
  ASSERT_EQ(a.exitCode, 0) << a.err;
  ASSERT_EQ(seeded.exitCode, 0) << seeded.err;
  // Everything but the timing line is the same run to run.
  auto figures = [](const std::string& out) { return out.substr(0, out.rfind("heights in")); };
  EXPECT_EQ(figures(a.out), figures(b.out));
  EXPECT_NE(figures(a.out), figures(seeded.out));
  EXPECT_NE(seeded.out.find("seed 3"), std::string::npos);
}

}  // namespace
}  // namespace planet
