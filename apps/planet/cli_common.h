// Pieces shared by the subcommands of `planet`: global options, opening the Vulkan context,
// and the exit codes.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "planet/clipmap_mesh.h"
#include "planet/scene_description.h"
#include "render/sky_pass.h"
#include "camera/camera.h"
#include "vk/context.h"

namespace planet {
struct PlanetDescription;
}

namespace planet::cli {

// Exit codes: 0 success, 1 failure (error, validation message, or out-of-tolerance result),
// 2 bad command line or input.
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

struct GlobalOptions {
  std::string device;       // --device NAME-SUBSTRING (else PLANET_DEVICE)
  bool validation = false;  // --validation (else PLANET_VALIDATION=1)
};

// A Vulkan context chosen by the global options and the environment.
std::unique_ptr<vk::Context> openContext(const GlobalOptions& options);

// With validation on, any validation message turns the run into a failure: prints one line
// and returns kExitFailure; else returns `exitCode`.
int finishWithValidation(const vk::Context& context, int exitCode);

// Writes each value on its own line of stdout with `format` (e.g. "{:.9g}"), in one write.
template <typename Range>
void printOnePerLine(const Range& values, std::string_view format) {
  fmt::memory_buffer out;
  for (const auto& v : values) {
    fmt::format_to(std::back_inserter(out), fmt::runtime(format), v);
    out.push_back('\n');
  }
  std::fwrite(out.data(), 1, out.size(), stdout);
}

// "WxH" in pixels for --size: width in 1..maxWidth and height in 1..maxHeight, else UsageError
// naming the text. Without bounds, a render's: both in 1..kRenderMaxSize.
void parseSize(const std::string& text, uint32_t& width, uint32_t& height, uint32_t maxWidth, uint32_t maxHeight);
void parseSize(const std::string& text, uint32_t& width, uint32_t& height);

// --fov in degrees: in (0, kRenderMaxFovDeg], else UsageError naming the value.
void checkFieldOfView(double degrees);

// --exposure (render, bench, view): "auto" (eye adaptation from the frame's luminance) or a
// fixed number in (0, kMaxExposure]; anything else is a UsageError quoting the text.
inline constexpr double kMaxExposure = 1e6;  // the message says 1e6
struct ExposureChoice {
  bool automatic = false;
  double fixed = 0.0;  // when not automatic
};
ExposureChoice parseExposure(const std::string& text);

// Makes every numeric option of `command` (CLI11 types INT, UINT and FLOAT) check its text
// first, so that '' and '-1' for an unsigned count are one UsageError naming the option and
// the text; call after the options are added.
void checkNumbersAsText(CLI::App& command);

// An output FILE named by `option` (--out, --json, --screenshot), checked before any Vulkan
// work so that a run that could not save its result fails at once: empty, a directory or
// ending in '/' is a UsageError; a missing or unwritable parent directory a planet::Error
// ("cannot write 'PATH': reason", as writing it would say).
void checkOutputFile(const std::string& option, const std::string& path);

// --seed S (render, height, export): every layer's seed becomes (seed + S) mod 2^32, another
// planet of the same kind. An S above 4294967295 is a UsageError naming it.
void applySeedOffset(PlanetDescription& planet, uint64_t seed);

// --camera with --scene: "BODY:LAT,LON,ALT_M[,HEADING,PITCH]" (throws planet::Error naming the
// bad text, an unknown body or a bad pose).
struct SceneCamera {
  size_t body = 0;
  CameraPose pose;
};
SceneCamera parseSceneCamera(const SceneDescription& scene, const std::string& text);
// With --scene: --preset and --sun are usage errors (the scene names its presets, its sun is at
// its origin).
void checkSceneExcludes(const CLI::App& command);

// The progress bar of long work on stderr (planet export, planet stats, a video of planet render):
// redrawn in place on a terminal (at most 5 times a second), else a line at most every 10 s, so
// that logs stay short and a quick run prints nothing there. `label` starts the line ("export
// heightmap 2048x1024"), `unit` names what is counted; call it as parallelFor's progress callback.
class ProgressLine {
 public:
  explicit ProgressLine(std::string label, std::string unit = "heights");
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  void operator()(size_t done, size_t total);

 private:
  std::string label_, unit_;
  bool interactive_;
  bool printed_ = false;
  std::chrono::steady_clock::time_point start_, lastLine_;
};

// A bad value the user gave (flag or input line): printed as one line, exit code 2. Control
// characters in the message (a newline inside a quoted argument) become '?', so that it stays
// one line whatever it quotes.
class UsageError : public std::runtime_error {
 public:
  explicit UsageError(const std::string& message);
};

// Registration of each subcommand; the callback runs the command and stores its exit code.
void addNoiseCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);
void addValidateCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);
void addBenchCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);
// The frame-time benchmark's options on `planet bench` itself (cmd_bench_frames.cpp): with any of
// them given and no benchmark command, `planet bench` runs it. Returns a check for the benchmark
// commands to call first: it throws UsageError when one of those options was given too.
std::function<void(const std::string& command)> addFrameBenchOptions(CLI::App& bench, const GlobalOptions& global,
                                                                     int& exitCode);
void addHeightCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);
void addExportCommand(CLI::App& app, int& exitCode);
void addStatsCommand(CLI::App& app, int& exitCode);
void addRenderCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);
void addViewCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);

// --sky tables|reference (render, bench, view): how the sky pass gets the atmosphere. Adds the
// option writing `mode`; checkSkyMode turns the text into the mode, or a UsageError naming it.
CLI::Option* addSkyModeOption(CLI::App& sub, std::string& mode);
SkyMode checkSkyMode(const std::string& mode);

// --terrain-shading forward|deferred (render, bench, view): where the ground is shaded
// (TerrainSettings::deferredShading). checkTerrainShading gives whether it is deferred, or a
// UsageError naming the text.
CLI::Option* addTerrainShadingOption(CLI::App& sub, std::string& shading);
bool checkTerrainShading(const std::string& shading);

// --mesh auto|RINGSxVERTICES (render, bench): the clipmap's density. "auto" is meshForImage's
// (the default mesh scaled to the image's pixels per radian, triangles the same size on screen);
// RINGSxVERTICES fixes the rings per level and the vertices per ring of the default's levels.
// parseMesh gives nullopt for auto, else the mesh, or a UsageError quoting the text or naming
// the count out of range; meshFor chooses the mesh of an image.
CLI::Option* addMeshOption(CLI::App& sub, std::string& text);
std::optional<ClipmapParams> parseMesh(const std::string& text);
ClipmapParams meshFor(const std::optional<ClipmapParams>& fixed, uint32_t imageHeight, double fovYDeg);

}  // namespace planet::cli
