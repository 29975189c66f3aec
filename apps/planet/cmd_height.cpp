// planet height: terrain heights of a preset along a great circle (CPU double reference).
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>

#include <fmt/format.h>

#include "cli_common.h"
#include "core/error.h"
#include "planet/terrain_height.h"
#include "planet/terrain_points_gpu.h"
#include "planet/terrain_rebase.h"

namespace planet::cli {
namespace {

constexpr size_t kMaxHeightSamples = 1'000'000;

struct HeightCommand {
  std::string preset{kDefaultPresetName};
  std::optional<uint64_t> seed;
  std::string at;
  double bearingDeg = 0.0;
  double stepM = 1.0;
  size_t count = 1;
  std::string backend = "cpu";
};

// "LAT,LON" in degrees.
glm::dvec2 parseLatLon(const std::string& text) {
  size_t comma = text.find(',');
  double values[2];
  std::string_view parts[2] = {std::string_view(text).substr(0, comma), comma == std::string::npos
                                                                            ? std::string_view()
                                                                            : std::string_view(text).substr(comma + 1)};
  for (int i = 0; i < 2; ++i) {
    auto [ptr, ec] = std::from_chars(parts[i].data(), parts[i].data() + parts[i].size(), values[i]);
    if (comma == std::string::npos || ec != std::errc() || ptr != parts[i].data() + parts[i].size() ||
        !std::isfinite(values[i]))
      throw UsageError("--at expects LAT,LON in degrees, got '" + text + "'");
  }
  return {values[0], values[1]};
}

// The GPU path: float offsets from the first sample, octave tables rebased there in double.
std::vector<double> gpuHeights(const GlobalOptions& global, const PlanetDescription& planet, const glm::dvec3& start,
                               const HeightCommand& cmd, int& exitCode) {
  const glm::dvec3 anchor = planet.radiusM * start;
  std::vector<glm::vec3> offsets(cmd.count);
  for (size_t i = 0; i < cmd.count; ++i)
    offsets[i] = glm::vec3(
        planet.radiusM * travelGreatCircle(start, cmd.bearingDeg, double(i) * cmd.stepM, planet.radiusM) - anchor);
  auto context = openContext(global);
  std::vector<float> heights;
  {
    GpuTerrainPoints terrain(*context, planet);
    heights = terrain.evaluate(buildOctaveTables(planet, anchor), offsets);
  }
  exitCode = finishWithValidation(*context, 0);
  return std::vector<double>(heights.begin(), heights.end());
}

int runHeight(const GlobalOptions& global, const HeightCommand& cmd) {
  if (cmd.count < 1 || cmd.count > kMaxHeightSamples)
    throw UsageError(fmt::format("--count must be in 1..{}, got {}", kMaxHeightSamples, cmd.count));
  if (!std::isfinite(cmd.stepM) || cmd.stepM < 0.0 || cmd.stepM > 1e8)
    throw UsageError(fmt::format("--step-m must be in [0, 1e8], got {}", cmd.stepM));
  if (!std::isfinite(cmd.bearingDeg)) throw UsageError(fmt::format("--bearing must be finite, got {}", cmd.bearingDeg));
  if (cmd.backend != "cpu" && cmd.backend != "gpu")
    throw UsageError("unknown backend '" + cmd.backend + "' (expected cpu or gpu)");
  glm::dvec2 latLon = parseLatLon(cmd.at);
  glm::dvec3 start;
  PlanetDescription planet;
  try {
    start = directionFromLatLon(latLon.x, latLon.y);
    planet = resolvePreset(cmd.preset);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  if (cmd.seed) applySeedOffset(planet, *cmd.seed);
  int exitCode = 0;
  std::vector<double> heights = cmd.backend == "gpu"
                                    ? gpuHeights(global, planet, start, cmd, exitCode)
                                    : terrainHeightsAlong(planet, start, cmd.bearingDeg, cmd.stepM, cmd.count);
  printOnePerLine(heights, "{:.4f}");
  return exitCode;
}

}  // namespace

void addHeightCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
  auto cmd = std::make_shared<HeightCommand>();
  CLI::App* sub = app.add_subcommand(
      "height", "Terrain heights in metres above the radius sphere, one per line, along a great circle from --at");
  sub->add_option("--preset", cmd->preset, "Built-in preset (earth, moon, mars, giant, faults, mpd) or a .toml file")
      ->capture_default_str();
  sub->add_option("--seed", cmd->seed, "Added to every layer's seed, as in planet render and planet export");
  sub->add_option("--at", cmd->at, "Start point LAT,LON in degrees")->required();
  sub->add_option("--bearing", cmd->bearingDeg, "Direction of the line, degrees clockwise from north")
      ->capture_default_str();
  sub->add_option("--step-m", cmd->stepM, "Distance between samples in metres")->capture_default_str();
  sub->add_option("--count", cmd->count, "Number of samples")->capture_default_str();
  sub->add_option(
         "--backend", cmd->backend,
         "cpu (double reference) | gpu (compute shader, float offsets from the first sample, rebased in double)")
      ->capture_default_str();
  checkNumbersAsText(*sub);
  sub->callback([&global, &exitCode, cmd] { exitCode = runHeight(global, *cmd); });
}

}  // namespace planet::cli
