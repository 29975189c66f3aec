// planet noise: evaluates one noise function (or it and its gradient) at points read from stdin.
#include <cstdio>
#include <iostream>
#include <iterator>
#include <vector>

#include <fmt/format.h>

#include "cli_common.h"
#include "core/error.h"
#include "noise/noise_cpu.h"
#include "noise/noise_gpu.h"
#include "noise/point_reader.h"

namespace planet::cli {
namespace {

struct NoiseCommand {
  std::string type;
  std::string hash = "fast";
  std::string backend = "cpu";
  noise::NoiseSettings settings;
  double offset = 0.0;
  double gain = 0.0;
  int levels = 0;
  bool gradient = false;  // print value dx dy dz per line
};

// `value dx dy dz` per point, each %.9g (enough to round-trip a float).
void printGradients(const std::vector<glm::vec4>& gradients) {
  fmt::memory_buffer out;
  for (const glm::vec4& g : gradients)
    fmt::format_to(std::back_inserter(out), "{:.9g} {:.9g} {:.9g} {:.9g}\n", g.x, g.y, g.z, g.w);
  std::fwrite(out.data(), 1, out.size(), stdout);
}

int runNoise(const GlobalOptions& global, NoiseCommand& cmd, const CLI::App& sub) {
  noise::NoiseSettings& s = cmd.settings;
  std::vector<glm::vec3> points;
  try {
    s.type = noise::parseNoiseType(cmd.type);
    s.hash = noise::parseNoiseHash(cmd.hash);
    if (sub.count("--offset")) s.offset = cmd.offset;
    if (sub.count("--gain")) s.gain = cmd.gain;
    const bool faults = s.type == noise::NoiseType::Faults;
    const bool mpd = noise::isMpd(s.type);
    if (!faults && (sub.count("--count") || sub.count("--width")))
      throw Error(fmt::format("--count and --width apply to --type faults only, not to {}", cmd.type));
    if (!mpd && (sub.count("--levels") || sub.count("--multifractal")))
      throw Error(fmt::format("--levels and --multifractal apply to --type mpd and mpd_ico only, not to {}", cmd.type));
    if (mpd && sub.count("--octaves")) throw Error("--octaves does not apply to mpd or mpd_ico: give --levels");
    if (sub.count("--levels")) s.octaves = cmd.levels;
    noise::validateNoiseSettings(s);
    if (cmd.backend != "cpu" && cmd.backend != "gpu")
      throw Error("unknown backend '" + cmd.backend + "' (expected cpu or gpu)");
    points = noise::readPoints(std::cin);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }

  std::vector<float> values(cmd.gradient ? 0 : points.size());
  std::vector<glm::vec4> gradients(cmd.gradient ? points.size() : 0);
  int exitCode = 0;
  if (!points.empty()) {
    if (cmd.backend == "gpu") {
      auto context = openContext(global);
      {
        noise::GpuNoise gpu(*context);
        if (cmd.gradient)
          gpu.evaluateGradient(s, points, gradients);
        else
          gpu.evaluate(s, points, values);
      }
      exitCode = finishWithValidation(*context, 0);
    } else if (cmd.gradient) {
      noise::evaluateCpuGradient(s, points, gradients, 0);
    } else {
      noise::evaluateCpu(s, points, values, 0);
    }
  }
  if (cmd.gradient)
    printGradients(gradients);
  else
    printOnePerLine(values, "{:.9g}");  // as printf %.9g
  return exitCode;
}

}  // namespace

void addNoiseCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
  auto cmd = std::make_shared<NoiseCommand>();
  CLI::App* sub = app.add_subcommand(
      "noise",
      "Evaluate a noise function at points 'x y z' read from stdin, one value per line (%.9g), or with --gradient "
      "'value dx dy dz'");
  sub->add_option("--type", cmd->type,
                  "simplex | fbm | ridged | hybrid | hetero | cascade | craters | damped | eroded | faults | mpd | "
                  "mpd_ico")
      ->required();
  sub->add_option("--octaves", cmd->settings.octaves, "Octaves, 1..32")->capture_default_str();
  sub->add_option("--lacunarity", cmd->settings.lacunarity, "Frequency ratio between octaves, in (1, 8]")
      ->capture_default_str();
  sub->add_option("--H", cmd->settings.H,
                  "Octave i is weighted by lacunarity^(-i*H) (mpd: level l's offsets by 2^(-l*H)), in [0, 4]")
      ->capture_default_str();
  sub->add_option("--offset", cmd->offset,
                  "Offset of ridged (default 1), hybrid (0.7), hetero (0.7) and cascade (0.8); rim perturbation of "
                  "craters, in [0, 0.5] (0.25); octaves of plain fBm under eroded's gullies (3, rounded down, at "
                  "least 1)");
  sub->add_option("--gain", cmd->gain,
                  "Ridged feedback gain; damped: how much steep ground smooths the finer octaves (0: fBm); eroded: "
                  "gully depth; mpd --multifractal: k (default 2, in [0, 16])");
  sub->add_option("--count", cmd->settings.faults, "faults: number of random great circles, 1..10000")
      ->capture_default_str();
  sub->add_option("--width", cmd->settings.width,
                  "faults: half-width of each step's smooth transition, radians in [0, 1.5] (0: sharp steps)")
      ->capture_default_str();
  sub->add_option("--levels", cmd->levels, "mpd, mpd_ico: subdivision levels, 1..24 (default 8)");
  sub->add_flag("--multifractal", cmd->settings.multifractal,
                "mpd, mpd_ico: scale each offset by gain x the mean of its parents (seed 000's MPD multifractal)");
  sub->add_option("--seed", cmd->settings.seed, "Seed, 0..4294967295")->capture_default_str();
  sub->add_option("--hash", cmd->hash, "Lattice hash: fast (ALU only) | reference (Perlin's table)")
      ->capture_default_str();
  sub->add_option("--backend", cmd->backend, "cpu (reference) | gpu (compute shader)")->capture_default_str();
  sub->add_flag("--gradient", cmd->gradient,
                "Print the value and its analytic gradient with respect to x, y, z: 'value dx dy dz' per line (every "
                "type; at a kink such as ridged's |N|, the derivative on the side the value takes)");
  checkNumbersAsText(*sub);
  sub->callback([&global, &exitCode, cmd, sub] { exitCode = runNoise(global, *cmd, *sub); });
}

}  // namespace planet::cli
