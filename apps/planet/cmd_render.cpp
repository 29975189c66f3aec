// planet render: one frame of a preset or a scene, offscreen (lavapipe or GPU), written to a PNG;
// with --path, a video of a camera path (cmd_render_video.cpp).
#include <cmath>
#include <cstdio>
#include <optional>

#include <fmt/format.h>

#include "cli_common.h"
#include "cmd_render.h"
#include "core/error.h"
#include "core/image_file.h"
#include "export/video_file.h"
#include "planet/scene_description.h"
#include "planet/terrain_height.h"
#include "render/renderer.h"
#include "render/view_quality.h"
#include "vk/context.h"

namespace planet::cli {
namespace {

// With --exposure auto: what the frame was measured at, so that a picture can be reproduced with
// a fixed --exposure.
void printExposure(const RenderResult& result) {
  if (!result.exposure) return;
  const ExposureReport& e = *result.exposure;
  fmt::print("exposure: auto {:.4g} (trimmed log-average luminance {:.4g}{})\n", e.exposure, std::exp2(e.log2Luminance),
             e.exposure >= gpu::kExposureMax * 0.9999   ? ", at the largest exposure"
             : e.exposure <= gpu::kExposureMin * 1.0001 ? ", at the smallest exposure"
                                                        : "");
}

void printTimings(const RenderResult& result) {
  std::string times;
  for (const vk::GpuTiming& timing : result.timings)
    times += fmt::format(" {} {:.2f} ms", timing.name, timing.milliseconds);
  fmt::print("GPU time per pass:{}\n", times.empty() ? " (no timestamps on this device)" : times);
}

// --scene: the bodies at --time, the camera on one of them (--camera BODY:LAT,LON,ALT[,HEADING,PITCH]),
// optionally turned toward another (--look-at BODY).
int runSceneRender(const GlobalOptions& global, const RenderCommand& cmd, const CLI::App& sub,
                   const RenderSettings& settings) {
  checkSceneExcludes(sub);
  SceneDescription scene;
  size_t body = 0;
  CameraPose pose;
  std::optional<size_t> target;
  try {
    scene = resolveScene(cmd.scene);
    if (sub.count("--camera")) {
      const SceneCamera camera = parseSceneCamera(scene, cmd.camera);
      body = camera.body;
      pose = camera.pose;
    }
    if (sub.count("--look-at")) {
      target = sceneBodyIndex(scene, cmd.lookAt);
      if (*target == body) throw Error(fmt::format("--look-at {} names the camera's own body", cmd.lookAt));
    }
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  if (cmd.seed)
    for (BodyDescription& b : scene.bodies) applySeedOffset(b.planet, *cmd.seed);
  const std::vector<BodyState> states = sceneStateAt(scene, cmd.timeS);
  const BodyState& on = states[body];
  CameraBasis local = cameraBasis(pose, scene.bodies[body].planet.radiusM);
  if (target)
    local = lookingAt(local.position, glm::transpose(on.bodyToScene) * (states[*target].positionM - on.positionM));
  SceneView view;
  view.camera = cameraToScene(on.positionM, on.bodyToScene, local);
  view.bodies = sceneBodyViews(states);
  view.timeS = cmd.timeS;

  auto context = openContext(global);
  RenderResult result;
  size_t primary = 0;
  {
    Renderer renderer(*context, scene, settings);
    result = renderer.renderScene(view);
    primary = renderer.primaryBody();
  }
  if (result.cameraRaised)
    std::fprintf(stderr, "planet: warning: the camera was below the ground of %s; raised to %.2f m\n",
                 scene.bodies[primary].name.c_str(), result.camera.altitudeM);
  writePng(cmd.out, result.image);
  fmt::print("wrote {} ({}x{}, scene '{}' at t = {} s on {})\n", cmd.out, settings.width, settings.height, scene.name,
             cmd.timeS, context->info.name);
  fmt::print(
      "camera: on {} at lat {:.4f} lon {:.4f} altitude {:.2f} m ({:.2f} m above the ground), heading {:.2f} "
      "pitch {:.2f}\n",
      scene.bodies[primary].name, result.camera.latitudeDeg, result.camera.longitudeDeg, result.camera.altitudeM,
      result.terrain.heightAboveGroundM, result.camera.headingDeg, result.camera.pitchDeg);
  std::string distances;
  for (size_t i = 0; i < scene.bodies.size(); ++i)
    distances += fmt::format("{}{} {:.4g} m", i ? ", " : "", scene.bodies[i].name,
                             glm::length(states[i].positionM - view.camera.position));
  fmt::print("distance to the bodies' centres: {}\n", distances);
  // Where on the camera's body each other body stands overhead (to place a camera under it).
  std::string overhead;
  const glm::dmat3 sceneToPrimary = glm::transpose(states[primary].bodyToScene);
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    if (i == primary) continue;
    const glm::dvec3 d = glm::normalize(sceneToPrimary * (states[i].positionM - states[primary].positionM));
    overhead += fmt::format("{}{} at lat {:.4f} lon {:.4f}", overhead.empty() ? "" : ", ", scene.bodies[i].name,
                            latitudeDegOf(d), longitudeDegOf(d));
  }
  const glm::dvec3 sun = glm::normalize(sceneToPrimary * -states[primary].positionM);
  overhead += fmt::format("{}the sun at lat {:.4f} lon {:.4f}", overhead.empty() ? "" : ", ", latitudeDegOf(sun),
                          longitudeDegOf(sun));
  fmt::print("overhead on {}: {}\n", scene.bodies[primary].name, overhead);
  printExposure(result);
  printTimings(result);
  return finishWithValidation(*context, 0);
}

int runRender(const GlobalOptions& global, const RenderCommand& cmd, const CLI::App& sub) {
  RenderSettings settings;
  parseSize(cmd.size, settings.width, settings.height);
  checkFieldOfView(cmd.fovDeg);
  settings.fovYDeg = cmd.fovDeg;
  settings.terrain.wireframe = cmd.wireframe;
  settings.terrain.patches = !cmd.noPatches;
  if (!std::isfinite(cmd.timeS) || std::abs(cmd.timeS) > 1e9)
    throw UsageError(fmt::format("--time must be a number of seconds within ±1e9, got {}", cmd.timeS));
  const ExposureChoice exposure = parseExposure(cmd.exposure);
  settings.autoExposure = exposure.automatic;
  if (!exposure.automatic) settings.sky.exposure = exposure.fixed;
  settings.sky.clouds = !cmd.noClouds;
  settings.sky.mode = checkSkyMode(cmd.sky);
  settings.terrain.deferredShading = checkTerrainShading(cmd.terrainShading);
  settings.terrain.water = !cmd.noWater;
  settings.terrain.lights = !cmd.noLights;
  const std::optional<ClipmapParams> mesh = parseMesh(cmd.mesh);
  settings.terrain.mesh = meshFor(mesh, settings.height, settings.fovYDeg);
  if (sub.count("--path")) return runVideoRender(global, cmd, sub, settings);
  for (const char* option : {"--frames", "--fps", "--path-body"})
    if (sub.count(option))
      throw UsageError(fmt::format("{} needs --path (it belongs to a video of a camera path)", option));
  if (videoFormatOf(cmd.out))
    throw UsageError(fmt::format("--out {} names a video: give the camera path to fly with --path FILE", cmd.out));
  checkOutputFile("--out", cmd.out);
  if (!cmd.scene.empty() || sub.count("--scene")) return runSceneRender(global, cmd, sub, settings);
  if (sub.count("--look-at")) throw UsageError("--look-at needs --scene (it names a body of the scene)");
  PlanetDescription planet;
  CameraPose camera;
  SunPose sun;
  try {
    planet = resolvePreset(cmd.preset);
    // Given but empty is an error too ("--camera ''"), not the default.
    if (sub.count("--camera")) camera = parseCameraPose(cmd.camera);
    if (sub.count("--sun")) sun = parseSunPose(cmd.sun);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  if (cmd.seed) applySeedOffset(planet, *cmd.seed);

  auto context = openContext(global);
  RenderResult result;
  {
    Renderer renderer(*context, planet, settings);
    result = renderer.render(camera, sun, cmd.timeS);
  }
  if (result.cameraRaised)
    std::fprintf(stderr,
                 "planet: warning: camera altitude %.2f m is below the ground; raised to %.2f m (%.1f m above it)\n",
                 camera.altitudeM, result.camera.altitudeM, kMinEyeHeightM);
  writePng(cmd.out, result.image);
  const TerrainFrameInfo& t = result.terrain;
  fmt::print("wrote {} ({}x{}, {} on {})\n", cmd.out, settings.width, settings.height, planet.name, context->info.name);
  fmt::print("camera: lat {} lon {} altitude {:.2f} m ({:.2f} m above the ground), heading {} pitch {}\n",
             result.camera.latitudeDeg, result.camera.longitudeDeg, result.camera.altitudeM, t.heightAboveGroundM,
             result.camera.headingDeg, result.camera.pitchDeg);
  fmt::print("mesh: {}\n", describeMesh(settings.terrain.mesh, !mesh, settings.height, settings.fovYDeg));
  fmt::print("metres per vertex at the nadir: {:.4g}\n", t.metresPerVertexAtNadir);
  fmt::print("triangles drawn: {} (rings {}..{} of {}), vertices evaluated: {}, patch levels built: {}\n", t.triangles,
             t.rings.firstRing, t.rings.lastRing, settings.terrain.mesh.levels * settings.terrain.mesh.ringsPerLevel,
             t.verticesEvaluated, t.patchLevelsRebuilt);
  printExposure(result);
  printTimings(result);
  return finishWithValidation(*context, 0);
}

}  // namespace

void addRenderCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
  auto cmd = std::make_shared<RenderCommand>();
  CLI::App* sub = app.add_subcommand("render", "Render a planet offscreen (no window needed) and write a PNG");
  sub->add_option("--preset", cmd->preset, "Built-in preset (earth, moon, mars, giant, faults, mpd) or a .toml file")
      ->capture_default_str();
  sub->add_option("--scene", cmd->scene,
                  "A scene of several bodies instead of one preset: built-in (system) or a .toml file");
  sub->add_option("--camera", cmd->camera,
                  "LAT,LON,ALT_M[,HEADING,PITCH]: degrees, metres above sea level, heading clockwise from north, "
                  "pitch above the horizon (-90 looks down) [default: 20,-30,2e7,0,-90]; with --scene "
                  "BODY:LAT,LON,ALT_M[,HEADING,PITCH] [default: the first body]");
  sub->add_option("--look-at", cmd->lookAt, "With --scene: turn the camera toward this body's centre");
  sub->add_option("--sun", cmd->sun,
                  "AZIMUTH,ELEVATION in degrees, seen from the camera's ground point [default: 135,35]");
  sub->add_option("--size", cmd->size, "Image size WIDTHxHEIGHT in pixels")->capture_default_str();
  sub->add_option("--out", cmd->out,
                  "PNG file to write (replaced atomically); with --path a video: .mp4 (H.264), .webm (VP9) or .gif")
      ->capture_default_str();
  sub->add_option("--path", cmd->path,
                  "Render a camera path file (format: planet bench --print-path) as a video, through the ffmpeg "
                  "program; with --scene the path flies over --path-body");
  sub->add_option("--frames", cmd->frames,
                  "With --path: frames, spread evenly over the path [default: real time, the path's duration x "
                  "--fps + 1]");
  sub->add_option("--fps", cmd->fps, "With --path: frames per second of the video")->capture_default_str();
  sub->add_option("--path-body", cmd->pathBody,
                  "With --scene and --path: the body the path flies over [default: the first]");
  sub->add_option("--seed", cmd->seed, "Added to every layer's seed: another planet of the same kind");
  sub->add_option("--fov", cmd->fovDeg, "Vertical field of view in degrees")->capture_default_str();
  sub->add_flag("--wireframe", cmd->wireframe, "Draw triangle edges only (debug)");
  sub->add_flag("--no-patches", cmd->noPatches, "Shade from vertex normals only (no patch textures)");
  sub->add_option("--time", cmd->timeS,
                  "Time in seconds: cloud drift and change, waves; with --scene also the orbits and spins")
      ->capture_default_str();
  sub->add_option("--exposure", cmd->exposure,
                  "HDR exposure before the tonemap: a number, or auto (from the frame's own luminance, as the eye "
                  "adapts)")
      ->capture_default_str();
  sub->add_flag("--no-clouds", cmd->noClouds, "Leave out the preset's clouds");
  sub->add_flag("--no-water", cmd->noWater, "Leave out the water sphere (the sea floor shows)");
  sub->add_flag("--no-lights", cmd->noLights, "Leave out the preset's city lights on the night side");
  addSkyModeOption(*sub, cmd->sky);
  addTerrainShadingOption(*sub, cmd->terrainShading);
  addMeshOption(*sub, cmd->mesh);
  checkNumbersAsText(*sub);
  sub->callback([&global, &exitCode, cmd, sub] { exitCode = runRender(global, *cmd, *sub); });
}

}  // namespace planet::cli
