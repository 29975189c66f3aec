// planet view: the real-time viewer in a window (issue 5). The options are checked here, before
// any window opens; the viewer itself lives in view/viewer.cpp.
#include <cmath>

#include <fmt/format.h>

#include "cli_common.h"
#include "core/error.h"
#include "camera/camera_path.h"
#include "view/viewer.h"
#include "view/viewer_ui.h"

namespace planet::cli {
namespace {

struct ViewCommand {
  std::string preset{kDefaultPresetName};
  std::string scene;
  std::string travel;
  double timeS = 0.0;
  double timeScale = 1.0;
  std::string camera;
  std::string sun;
  std::string size = "1280x720";
  std::string vsync = "on";
  std::string quality;
  double fovDeg = 60.0;
  uint32_t frames = 0;
  std::string screenshot;
  std::string path;
  bool hideUi = false;
  bool noLights = false;
  std::string exposure = "auto";
  std::string sky{skyModeName(SkySettings{}.mode)};
  std::string terrainShading = "forward";
};

constexpr uint32_t kMaxFrames = 100'000'000;

int runView(const GlobalOptions& global, const ViewCommand& cmd, const CLI::App& sub) {
  view::ViewOptions options;
  parseSize(cmd.size, options.width, options.height);
  if (cmd.vsync != "on" && cmd.vsync != "off")
    throw UsageError(fmt::format("--vsync must be 'on' or 'off', got '{}'", cmd.vsync));
  options.vsync = cmd.vsync == "on";
  checkFieldOfView(cmd.fovDeg);
  options.fovDeg = cmd.fovDeg;
  if (cmd.frames > kMaxFrames)
    throw UsageError(fmt::format("--frames must be at most {}, got {}", kMaxFrames, cmd.frames));
  options.frames = cmd.frames;
  if (sub.count("--screenshot")) checkOutputFile("--screenshot", cmd.screenshot);
  if (sub.count("--path") && cmd.path.empty()) throw UsageError("--path must name a file");
  options.screenshot = cmd.screenshot;
  options.hideUi = cmd.hideUi;
  options.lights = !cmd.noLights;
  const ExposureChoice exposure = parseExposure(cmd.exposure);
  options.autoExposure = exposure.automatic;
  if (!exposure.automatic) options.exposure = exposure.fixed;
  options.skyMode = checkSkyMode(cmd.sky);
  options.deferredShading = checkTerrainShading(cmd.terrainShading);
  options.device = global.device;
  options.validation = global.validation;
  if (!std::isfinite(cmd.timeS) || std::abs(cmd.timeS) > 1e9)
    throw UsageError(fmt::format("--time must be a number of seconds within ±1e9, got {}", cmd.timeS));
  if (!(cmd.timeScale >= 0.0 && cmd.timeScale <= 1e6))
    throw UsageError(fmt::format("--time-scale must be in [0, 1e6], got {}", cmd.timeScale));
  if (sub.count("--scene")) {
    checkSceneExcludes(sub);
    if (sub.count("--path")) throw UsageError("--path does not apply to --scene (camera paths are on one planet)");
    try {
      SceneDescription scene = resolveScene(cmd.scene);
      if (sub.count("--camera")) {
        const SceneCamera camera = parseSceneCamera(scene, cmd.camera);
        options.sceneBody = camera.body;
        options.camera = camera.pose;
      }
      if (sub.count("--travel")) {
        options.travelTo = sceneBodyIndex(scene, cmd.travel);
        if (*options.travelTo == options.sceneBody)
          throw Error(fmt::format("--travel {} names the body the camera starts on", cmd.travel));
      }
      if (sub.count("--quality")) options.quality = parseViewQuality(cmd.quality);
      options.planet = scene.bodies[options.sceneBody].planet;
      options.scene = std::move(scene);
    } catch (const Error& e) {
      throw UsageError(e.what());
    }
    options.sceneTimeS = cmd.timeS;
    options.timeScale = cmd.timeScale;
    return view::runViewer(options);
  }
  if (sub.count("--travel")) throw UsageError("--travel needs --scene (it names a body of the scene)");
  try {
    options.planet = resolvePreset(cmd.preset);  // a bad preset is reported before a window opens
    // Given but empty is an error too ("--camera ''"), not the default.
    if (sub.count("--camera")) options.camera = parseCameraPose(cmd.camera);
    if (sub.count("--sun")) options.sun = parseSunPose(cmd.sun);
    if (sub.count("--quality")) options.quality = parseViewQuality(cmd.quality);
    if (sub.count("--path")) options.path = loadCameraPath(cmd.path);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  return view::runViewer(options);
}

}  // namespace

void addViewCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
  auto cmd = std::make_shared<ViewCommand>();
  CLI::App* sub = app.add_subcommand("view", "Fly around a planet in a window (real time)");
  sub->add_option("--preset", cmd->preset, "Built-in preset (earth, moon, mars, giant, faults, mpd) or a .toml file")
      ->capture_default_str();
  sub->add_option("--scene", cmd->scene, "Fly through a scene of several bodies: built-in (system) or a .toml file");
  sub->add_option("--camera", cmd->camera,
                  "LAT,LON,ALT_M[,HEADING,PITCH]: where to start (as planet render) [default: 20,-30,2e7,0,-90]; "
                  "with --scene BODY:LAT,LON,ALT_M[,HEADING,PITCH] [default: the first body]");
  sub->add_option("--time", cmd->timeS, "With --scene: the scene time to start at, seconds")->capture_default_str();
  sub->add_option("--time-scale", cmd->timeScale, "With --scene: scene seconds per real second")->capture_default_str();
  sub->add_option("--travel", cmd->travel, "With --scene: start travelling to this body at once (as T does)");
  sub->add_option("--sun", cmd->sun,
                  "AZIMUTH,ELEVATION in degrees, seen from the start's ground point [default: 135,35]");
  sub->add_option("--size", cmd->size, "Window size WIDTHxHEIGHT in pixels")->capture_default_str();
  sub->add_option("--vsync", cmd->vsync, "on: present at the display's rate; off: as fast as possible")
      ->capture_default_str();
  sub->add_option("--quality", cmd->quality,
                  "low, medium, high or ultra [default: low on a CPU Vulkan device, else high]");
  sub->add_option("--fov", cmd->fovDeg, "Vertical field of view in degrees")->capture_default_str();
  sub->add_option("--frames", cmd->frames, "Exit after this many frames (0: when the window closes)")
      ->capture_default_str();
  sub->add_option("--screenshot", cmd->screenshot, "Save the last frame (without the panel) to this PNG on exit");
  sub->add_option("--path", cmd->path,
                  "Play a camera path file (format: planet bench --print-path); with --frames, spread over them");
  sub->add_flag("--hide-ui", cmd->hideUi, "Start with the panel hidden (F2 shows it)");
  sub->add_flag("--no-lights", cmd->noLights, "Leave out the preset's city lights on the night side (the panel turns them on)");
  sub->add_option("--exposure", cmd->exposure,
                  "HDR exposure before the tonemap: auto (adapts to the view as the eye does) or a fixed number")
      ->capture_default_str();
  addSkyModeOption(*sub, cmd->sky);
  addTerrainShadingOption(*sub, cmd->terrainShading);
  sub->footer(fmt::format("Keys:\n{}", view::viewerKeyHelp()));
  checkNumbersAsText(*sub);
  sub->callback([&global, &exitCode, cmd, sub] { exitCode = runView(global, *cmd, *sub); });
}

}  // namespace planet::cli
