// planet bench: the frame-time benchmark's options (cmd_bench_frames.cpp) and the benchmark
// commands; planet bench noise: throughput of the GPU noise against the CPU reference and
// libnoise; planet bench soak (cmd_bench_soak.cpp).
#include <unistd.h>

#include <cstdio>

#include <fmt/format.h>

#include "cli_common.h"
#include "core/file.h"
#include "bench/noise_bench.h"
#include "noise/noise_settings.h"

namespace planet::cli {
namespace {

constexpr size_t kMaxBenchPoints = 50'000'000;

struct BenchNoiseCommand {
  noise::NoiseBenchOptions options;
  std::string json;
};

int runBenchNoise(const GlobalOptions& global, const BenchNoiseCommand& cmd, const CLI::App& sub) {
  const noise::NoiseBenchOptions& o = cmd.options;
  if (o.points < 1 || o.points > kMaxBenchPoints)
    throw UsageError(fmt::format("--points must be in 1..{}, got {}", kMaxBenchPoints, o.points));
  if (o.octaves < noise::kMinOctaves || o.octaves > noise::kMaxOctaves)
    throw UsageError(
        fmt::format("--octaves must be in {}..{}, got {}", noise::kMinOctaves, noise::kMaxOctaves, o.octaves));
  try {
    noise::NoiseSettings s;
    s.type = noise::parseNoiseType(o.type);
    s.octaves = o.octaves;
    s.faults = o.faults;
    s.width = o.width;
    noise::validateNoiseSettings(s);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  if (o.repeats < 5 || o.repeats > 1000)
    throw UsageError(fmt::format("--repeats must be in 5..1000, got {}", o.repeats));
  if (sub.count("--json")) checkOutputFile("--json", cmd.json);  // given but empty is an error too
  auto context = openContext(global);
  const bool interactive = ::isatty(STDERR_FILENO);
  noise::NoiseBenchReport report = noise::runNoiseBench(*context, o, [&](const std::string& method) {
    std::fprintf(stderr, interactive ? "\rmeasuring %-24s" : "measuring %s\n", method.c_str());
  });
  if (interactive) std::fprintf(stderr, "\n");
  std::fputs(report.table().c_str(), stdout);
  std::fflush(stdout);
  if (!cmd.json.empty()) writeFileAtomic(cmd.json, report.toJson().dump(2) + "\n");
  return finishWithValidation(*context, 0);
}

}  // namespace

// cmd_bench_soak.cpp: `planet bench soak`, which also refuses the frame benchmark's options.
void addBenchSoakCommand(CLI::App& bench, const GlobalOptions& global, int& exitCode,
                         const std::function<void(const std::string&)>& rejectFrameOptions);

void addBenchCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
  CLI::App* bench = app.add_subcommand(
      "bench",
      "Benchmarks (print medians and spreads with the device name): with any of the options below, frame times "
      "along a camera path; or a benchmark command");
  bench->require_subcommand(0, 1);
  auto rejectFrameOptions = addFrameBenchOptions(*bench, global, exitCode);
  auto cmd = std::make_shared<BenchNoiseCommand>();
  CLI::App* sub = bench->add_subcommand(
      "noise",
      "Point-octave evaluations per second: GPU (fast and reference hash), CPU reference on 1 and all "
      "threads, libnoise Perlin and RidgedMulti, on the same points; GPU and CPU also with the analytic gradient");
  sub->add_option("--points", cmd->options.points, "Points per run")->capture_default_str();
  sub->add_option("--octaves", cmd->options.octaves, "fBm octaves (mpd, mpd_ico: levels)")->capture_default_str();
  sub->add_option("--type", cmd->options.type,
                  "Noise type of the GPU and CPU methods (any of planet noise's; libnoise stays fBm-like)")
      ->capture_default_str();
  sub->add_option("--count", cmd->options.faults, "faults: great circles per point, 1..10000")->capture_default_str();
  sub->add_option("--width", cmd->options.width, "faults: ramp half-width, radians")->capture_default_str();
  sub->add_option("--repeats", cmd->options.repeats, "Timed runs per method after one warm-up (>= 5)")
      ->capture_default_str();
  sub->add_option("--json", cmd->json, "Also write the results as JSON to FILE");
  checkNumbersAsText(*sub);
  sub->callback([&global, &exitCode, cmd, rejectFrameOptions, sub] {
    rejectFrameOptions("noise");
    exitCode = runBenchNoise(global, *cmd, *sub);
  });
  addBenchSoakCommand(*bench, global, exitCode, rejectFrameOptions);
}

}  // namespace planet::cli
