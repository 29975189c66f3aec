// planet bench soak: thousands of frames of the real-time path with camera motion and live
// parameter changes; memory flat after the warm-up, the last image equal to a fresh render's,
// no validation message (issue 7, point 6; bench/soak.h).
#include <unistd.h>

#include <chrono>
#include <cstdio>

#include <fmt/format.h>

#include "cli_common.h"
#include "core/error.h"
#include "core/file.h"
#include "core/log.h"
#include "bench/soak.h"

namespace planet::cli {
namespace {

struct BenchSoakCommand {
  std::string preset{kDefaultPresetName};
  std::string size = "160x90";
  int64_t frames = 10'000;
  int64_t warmup = kSoakLoopFrames;
  std::string quality = "low";
  double fovDeg = 60.0;
  std::string json;
};

// The progress line on stderr: rewritten in place on a terminal, else one line every 30 s.
class SoakProgressLine {
 public:
  SoakProgressLine() : interactive_(::isatty(STDERR_FILENO)) {}
  ~SoakProgressLine() {
    if (interactive_ && printed_) std::fputs("\n", stderr);
  }
  void operator()(uint32_t frame, uint32_t count, double lastMs, int64_t rssKiB) {
    const auto now = std::chrono::steady_clock::now();
    const auto every = interactive_ ? std::chrono::milliseconds(200) : std::chrono::milliseconds(30'000);
    if (frame != 0 && now - lastLine_ < every) return;
    lastLine_ = now;
    printed_ = true;
    const std::string last = frame > 0 ? fmt::format(", last {:.1f} ms", lastMs) : "";
    const std::string line =
        fmt::format("soak: frame {} of {}{}, RSS {:.1f} MiB", frame + 1, count, last, double(rssKiB) / 1024.0);
    std::fprintf(stderr, interactive_ ? "\r%s   " : "%s\n", line.c_str());
    std::fflush(stderr);
  }

 private:
  bool interactive_;
  bool printed_ = false;
  std::chrono::steady_clock::time_point lastLine_{};
};

int runBenchSoak(const GlobalOptions& global, const BenchSoakCommand& cmd) {
  SoakOptions o;
  parseSize(cmd.size, o.width, o.height);
  if (cmd.frames < 1 || cmd.frames > kSoakMaxFrames)
    throw UsageError(fmt::format("--frames must be in 1..{}, got {}", kSoakMaxFrames, cmd.frames));
  if (cmd.warmup < 0 || cmd.warmup >= cmd.frames)
    throw UsageError(
        fmt::format("--warmup must be in 0..{} (fewer than --frames), got {}", cmd.frames - 1, cmd.warmup));
  checkFieldOfView(cmd.fovDeg);
  o.frames = uint32_t(cmd.frames);
  o.warmup = uint32_t(cmd.warmup);
  o.fovYDeg = cmd.fovDeg;
  PlanetDescription planet;
  try {
    o.quality = parseViewQuality(cmd.quality);
    planet = resolvePreset(cmd.preset);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }

  auto context = openContext(global);
  SoakReport report;
  {
    SoakProgressLine progress;
    report = runSoak(*context, planet, cmd.preset, o, std::ref(progress));
  }
  std::fputs(report.table().c_str(), stdout);
  std::fflush(stdout);
  if (!cmd.json.empty()) writeFileAtomic(cmd.json, report.toJson().dump(2) + "\n");
  if (!report.passed()) {
    logError("soak failed: {}", report.failure());
    return kExitFailure;
  }
  return finishWithValidation(*context, 0);
}

}  // namespace

void addBenchSoakCommand(CLI::App& bench, const GlobalOptions& global, int& exitCode,
                         const std::function<void(const std::string&)>& rejectFrameOptions) {
  auto cmd = std::make_shared<BenchSoakCommand>();
  CLI::App* sub = bench.add_subcommand(
      "soak",
      "Many frames with two in flight, the camera looping orbit -> ground -> orbit and the viewer's live settings "
      "changed on a schedule: allocator and resident memory flat after the warm-up, the last image equal to a fresh "
      "renderer's, no validation message (else exit 1)");
  sub->add_option("--preset", cmd->preset, "Built-in preset (earth, moon, mars, giant, faults, mpd) or a .toml file")
      ->capture_default_str();
  sub->add_option("--size", cmd->size, "Render size WIDTHxHEIGHT in pixels")->capture_default_str();
  sub->add_option("--frames", cmd->frames, "Frames in all")->capture_default_str();
  sub->add_option("--warmup", cmd->warmup,
                  "Frames before memory must stay flat (fewer than --frames; default one loop of the schedule)")
      ->capture_default_str();
  sub->add_option("--quality", cmd->quality, "The viewer's quality level: low, medium, high or ultra")
      ->capture_default_str();
  sub->add_option("--fov", cmd->fovDeg, "Vertical field of view in degrees")->capture_default_str();
  sub->add_option("--json", cmd->json, "Also write the summary and every memory sample as JSON to FILE");
  checkNumbersAsText(*sub);
  sub->callback([&global, &exitCode, cmd, sub, rejectFrameOptions] {
    rejectFrameOptions("soak");
    // Checked before minutes of frames, not after them.
    if (sub->count("--json")) checkOutputFile("--json", cmd->json);
    exitCode = runBenchSoak(global, *cmd);
  });
}

}  // namespace planet::cli
