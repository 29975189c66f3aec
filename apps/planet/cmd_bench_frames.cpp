// planet bench [options]: frame times of the headless renderer along a camera path (issue 6).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <functional>

#include <fmt/format.h>

#include "cli_common.h"
#include "core/error.h"
#include "core/file.h"
#include "frame_plot.h"
#include "bench/frame_bench.h"
#include "render/sky_pass.h"
#include "vk/buffer.h"

namespace planet::cli {
namespace {

struct FrameBenchCommand {
  std::string preset{kDefaultPresetName};
  std::string size = "640x360";
  int64_t frames = 120;
  int64_t warmup = 5;
  double fovDeg = 60.0;
  double flightFps = 60.0;
  int64_t inFlight = 1;
  std::string sun;
  std::string exposure = fmt::format("{:g}", SkySettings{}.exposure);
  std::string path;
  std::string json;
  std::string csv;
  std::string plot;
  bool compare = false;
  bool noPatches = false;
  bool noLights = false;
  bool printPath = false;
  std::string sky{skyModeName(SkySettings{}.mode)};
  std::string terrainShading = "forward";
  std::string mesh = "auto";
  std::vector<CLI::Option*> options;      // every option above: given any, `planet bench` runs the benchmark
  std::vector<CLI::Option*> fileOptions;  // --path, --json, --csv, --plot
};

// The progress line on stderr: rewritten in place on a terminal, else a line when a mode or
// phase starts and then at most every 10 s (logs of CI runs stay short).
class Progress {
 public:
  Progress() : interactive_(::isatty(STDERR_FILENO)) {}
  ~Progress() {
    if (interactive_ && printed_) std::fputs("\n", stderr);
  }
  void operator()(const std::string& mode, bool warmup, uint32_t frame, uint32_t count, double lastMs) {
    const auto now = std::chrono::steady_clock::now();
    const bool phaseStart = frame == 0;
    if (!interactive_ && !phaseStart && now - lastLine_ < std::chrono::seconds(10)) return;
    lastLine_ = now;
    printed_ = true;
    const std::string last = lastMs > 0.0 && !phaseStart ? fmt::format(", last {:.1f} ms", lastMs) : "";
    std::fprintf(stderr, interactive_ ? "\rbench: %s, %s frame %u of %u%s   " : "bench: %s, %s frame %u of %u%s\n",
                 mode.c_str(), warmup ? "warm-up" : "timed", frame + 1, count, last.c_str());
    std::fflush(stderr);
  }

 private:
  bool interactive_;
  bool printed_ = false;
  std::chrono::steady_clock::time_point lastLine_{};
};

int runFrameBench(const GlobalOptions& global, const FrameBenchCommand& cmd, const CLI::App& bench) {
  FrameBenchOptions o;
  parseSize(cmd.size, o.width, o.height);
  if (cmd.frames < 1 || cmd.frames > kBenchMaxFrames)
    throw UsageError(fmt::format("--frames must be in 1..{}, got {}", kBenchMaxFrames, cmd.frames));
  if (cmd.warmup < 0 || cmd.warmup > kBenchMaxWarmup)
    throw UsageError(fmt::format("--warmup must be in 0..{}, got {}", kBenchMaxWarmup, cmd.warmup));
  checkFieldOfView(cmd.fovDeg);
  if (!(cmd.flightFps == 0.0 || (cmd.flightFps >= 1.0 && cmd.flightFps <= kBenchMaxFlightFps)))
    throw UsageError(fmt::format("--flight-fps must be 0 or in 1..{}, got {}", kBenchMaxFlightFps, cmd.flightFps));
  o.flightFps = cmd.flightFps;
  if (cmd.inFlight != 1 && cmd.inFlight != int64_t(vk::kFramesInFlight))
    throw UsageError(fmt::format("--in-flight must be 1 or {}, got {}", vk::kFramesInFlight, cmd.inFlight));
  if (cmd.inFlight > 1 && cmd.flightFps == 0.0)
    throw UsageError("--in-flight 2 times each frame behind a real-time one: it needs --flight-fps above 0");
  o.framesInFlight = uint32_t(cmd.inFlight);
  o.frames = uint32_t(cmd.frames);
  o.warmup = uint32_t(cmd.warmup);
  o.fovYDeg = cmd.fovDeg;
  o.compare = cmd.compare;
  o.patches = !cmd.noPatches;
  o.lights = !cmd.noLights;
  const ExposureChoice exposure = parseExposure(cmd.exposure);
  o.autoExposure = exposure.automatic;
  if (!exposure.automatic) o.exposure = exposure.fixed;
  o.skyMode = checkSkyMode(cmd.sky);
  o.deferredShading = checkTerrainShading(cmd.terrainShading);
  const std::optional<ClipmapParams> mesh = parseMesh(cmd.mesh);
  o.mesh = meshFor(mesh, o.height, o.fovYDeg);
  o.meshAuto = !mesh;
  for (const CLI::Option* option : cmd.fileOptions)
    if (option->count() && option->as<std::string>().empty())
      throw UsageError(option->get_name() + " must name a file");
  // Outputs are checked before the run, not found unwritable after minutes of it.
  for (const auto& [name, file] : {std::pair{"--json", &cmd.json}, {"--csv", &cmd.csv}, {"--plot", &cmd.plot}})
    if (!file->empty()) checkOutputFile(name, *file);
  PlanetDescription planet;
  CameraPath path;
  const std::string pathSource = cmd.path.empty() ? "default" : cmd.path;
  try {
    planet = resolvePreset(cmd.preset);
    if (bench.count("--sun")) o.sun = parseSunPose(cmd.sun);  // --sun '' is an error, not the default
    path = cmd.path.empty() ? defaultCameraPath(planet.radiusM) : loadCameraPath(cmd.path);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  if (cmd.printPath) {
    std::fputs(formatCameraPath(path).c_str(), stdout);
    return 0;
  }
  // Before the benchmark, not after minutes of it.
  const std::string python = cmd.plot.empty() ? "" : findPlotPython();

  auto context = openContext(global);
  FrameBenchReport report;
  {
    Progress progress;
    report = runFrameBench(*context, planet, cmd.preset, path, pathSource, o, std::ref(progress));
  }
  std::fputs(report.table().c_str(), stdout);
  std::fflush(stdout);
  if (!cmd.json.empty()) writeFileAtomic(cmd.json, report.toJson().dump(2) + "\n");
  const std::string csv = report.csv();
  if (!cmd.csv.empty()) writeFileAtomic(cmd.csv, csv);
  if (!cmd.plot.empty())
    writeFramePlot(python, csv, cmd.plot,
                   fmt::format("planet bench, {} {}x{} on {}", cmd.preset, o.width, o.height, report.device));
  return finishWithValidation(*context, 0);
}

}  // namespace

std::function<void(const std::string& command)> addFrameBenchOptions(CLI::App& bench, const GlobalOptions& global,
                                                                     int& exitCode) {
  auto cmd = std::make_shared<FrameBenchCommand>();
  auto add = [&](CLI::Option* option) { cmd->options.push_back(option); };
  auto addFile = [&](CLI::Option* option) {
    add(option);
    cmd->fileOptions.push_back(option);
  };
  add(bench.add_option("--preset", cmd->preset, "Built-in preset (earth, moon, mars, giant, faults, mpd) or a .toml file")
          ->capture_default_str());
  add(bench.add_option("--size", cmd->size, "Image size WIDTHxHEIGHT in pixels")->capture_default_str());
  add(bench.add_option("--frames", cmd->frames, "Timed frames, spread evenly over the path")->capture_default_str());
  add(bench.add_option("--warmup", cmd->warmup, "Untimed frames before them, spread over the path the same way")
          ->capture_default_str());
  add(bench.add_option("--fov", cmd->fovDeg, "Vertical field of view in degrees")->capture_default_str());
  add(bench
          .add_option("--flight-fps", cmd->flightFps,
                      "Time each frame after an untimed one 1/RATE s of flight earlier, as in a real-time flight at "
                      "RATE frames per second (0: the timed frames only, each 1/(frames-1) of the path apart)")
          ->capture_default_str());
  add(bench
          .add_option("--in-flight", cmd->inFlight,
                      "Frames in flight: 1 (each frame's CPU work, then its GPU work, timed on the wall clock) or 2 "
                      "(as the viewer: each frame prepared while the one before executes, timed from that one's end "
                      "to its own on the GPU's clock)")
          ->capture_default_str());
  add(bench.add_option("--sun", cmd->sun,
                       "AZIMUTH,ELEVATION in degrees, seen from the camera's ground point [default: 135,35]"));
  add(bench
          .add_option("--exposure", cmd->exposure,
                      "HDR exposure before the tonemap: a number, or auto (each frame from its own luminance; the "
                      "luminance pass is timed)")
          ->capture_default_str());
  addFile(bench.add_option("--path", cmd->path,
                           "Camera path file: lines 'time_s lat lon height_m heading pitch' (height above the ground), "
                           "# comments [default: a descent from 40,000 km to 2 m, then a traverse at 300 m/s]"));
  addFile(bench.add_option("--json", cmd->json, "Write the summary and every frame as JSON to FILE"));
  addFile(bench.add_option("--csv", cmd->csv, "Write one row per frame to FILE"));
  addFile(
      bench.add_option("--plot", cmd->plot, "Write a PNG of frame time along the path, per pass (needs matplotlib)"));
  add(bench.add_flag("--compare", cmd->compare,
                     "Also fly the path with vertex-shader heights, CPU heights and octave limiting off; report each "
                     "as a ratio of median terrain time to the default's"));
  add(bench.add_flag("--no-patches", cmd->noPatches, "Shade from vertex normals only (no patch textures)"));
  add(bench.add_flag("--no-lights", cmd->noLights, "Leave out the preset's city lights on the night side"));
  add(addSkyModeOption(bench, cmd->sky));
  add(addTerrainShadingOption(bench, cmd->terrainShading));
  add(addMeshOption(bench, cmd->mesh));
  add(bench.add_flag("--print-path", cmd->printPath, "Print the camera path in the --path format and exit"));
  auto givenOption = [cmd] {
    for (const CLI::Option* option : cmd->options)
      if (option->count()) return option->get_name();
    return std::string();
  };
  checkNumbersAsText(bench);
  bench.callback([&global, &exitCode, cmd, &bench, givenOption] {
    // Without options of its own, or with a benchmark command, there is nothing to do here (main
    // reports a missing command; the command rejects these options itself).
    if (givenOption().empty() || !bench.get_subcommands().empty()) return;
    exitCode = runFrameBench(global, *cmd, bench);
  });
  return [givenOption](const std::string& command) {
    const std::string given = givenOption();
    if (!given.empty())
      throw UsageError(
          fmt::format("{} belongs to the frame benchmark ('planet bench {} ...'), not to 'planet bench {}'", given,
                      given, command));
  };
}

}  // namespace planet::cli
