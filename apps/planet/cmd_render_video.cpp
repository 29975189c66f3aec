// planet render --path FILE --out flight.mp4: a camera path (the format of planet bench) flown
// frame by frame, each frame piped to ffmpeg as it is read back (issue 23, point 5). Frames are
// placed by index, never by wall time (camera_path.h), so a video is the same every run.
#include <chrono>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "camera/camera_path.h"
#include "camera/scene_view.h"
#include "cli_common.h"
#include "cmd_render.h"
#include "core/error.h"
#include "export/video_file.h"
#include "planet/scene_description.h"

namespace planet::cli {
namespace {

// What the flight needs, checked before any Vulkan work: the path, the bodies and the sun.
struct Flight {
  CameraPath path;
  std::optional<SceneDescription> scene;  // with --scene
  PlanetDescription planet;               // without: the preset
  size_t body = 0;                        // with --scene: the body the path flies over
  SunPose sun;                            // without --scene
  uint32_t frames = 0;
};

uint32_t frameCount(const RenderCommand& cmd, const CLI::App& sub, const CameraPath& path) {
  if (sub.count("--frames")) return uint32_t(cmd.frames);  // range checked by the caller
  // Real time: one frame every 1/fps s of the path, both ends included.
  const double frames = std::floor(path.durationS() * cmd.fps + 1e-9) + 1.0;
  if (frames > double(kVideoMaxFrames))
    throw UsageError(fmt::format("--path {} lasts {} s: at {} fps that is over {} frames; give fewer with --frames",
                                 cmd.path, path.durationS(), cmd.fps, kVideoMaxFrames));
  return uint32_t(frames);
}

Flight loadFlight(const RenderCommand& cmd, const CLI::App& sub) {
  Flight flight;
  try {
    flight.path = loadCameraPath(cmd.path);
    if (sub.count("--scene")) {
      flight.scene = resolveScene(cmd.scene);
      if (sub.count("--path-body")) flight.body = sceneBodyIndex(*flight.scene, cmd.pathBody);
      if (cmd.seed)
        for (BodyDescription& b : flight.scene->bodies) applySeedOffset(b.planet, *cmd.seed);
    } else {
      flight.planet = resolvePreset(cmd.preset);
      if (sub.count("--sun")) flight.sun = parseSunPose(cmd.sun);
      if (cmd.seed) applySeedOffset(flight.planet, *cmd.seed);
    }
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  flight.frames = frameCount(cmd, sub, flight.path);
  return flight;
}

// The frame at path time `pathS`: the camera from the path, on the preset's planet (the sun fixed
// in its frame) or on the path's body of the scene as it stands at that time.
SceneView frameView(const Flight& flight, double pathS, double startS, const glm::dvec3& sunPlanet) {
  const CameraKey key = sampleCameraPath(flight.path, pathS);
  SceneView view;
  view.timeS = startS + (pathS - flight.path.startS());
  if (!flight.scene) {
    const CameraPose pose = cameraPoseAt(key, flight.planet);
    view.camera = cameraBasis(pose, flight.planet.radiusM);
    view.bodies = {SceneBodyView{glm::dvec3(0.0), glm::dmat3(1.0), sunPlanet}};
    return view;
  }
  const PlanetDescription& planet = flight.scene->bodies[flight.body].planet;
  const std::vector<BodyState> states = sceneStateAt(*flight.scene, view.timeS);
  const BodyState& on = states[flight.body];
  view.camera = cameraToScene(on.positionM, on.bodyToScene, cameraBasis(cameraPoseAt(key, planet), planet.radiusM));
  view.bodies = sceneBodyViews(states);
  return view;
}

}  // namespace

int runVideoRender(const GlobalOptions& global, const RenderCommand& cmd, const CLI::App& sub,
                   const RenderSettings& settings) {
  if (cmd.path.empty()) throw UsageError("--path must name a file");
  const std::optional<VideoFormat> format = videoFormatOf(cmd.out);
  if (!format) throw UsageError(fmt::format("--out with --path must end in .mp4, .webm or .gif, got '{}'", cmd.out));
  if (sub.count("--camera")) throw UsageError("--camera and --path exclude each other: the path places the camera");
  if (sub.count("--look-at")) throw UsageError("--look-at and --path exclude each other: the path aims the camera");
  if (sub.count("--scene"))
    checkSceneExcludes(sub);
  else if (sub.count("--path-body"))
    throw UsageError("--path-body needs --scene (it names a body of the scene)");
  if (sub.count("--frames") && (cmd.frames < 1 || cmd.frames > kVideoMaxFrames))
    throw UsageError(fmt::format("--frames must be in 1..{}, got {}", kVideoMaxFrames, cmd.frames));
  if (!(cmd.fps >= kVideoMinFps && cmd.fps <= kVideoMaxFps))
    throw UsageError(fmt::format("--fps must be in {}..{}, got {}", kVideoMinFps, kVideoMaxFps, cmd.fps));
  if (videoNeedsEvenSize(*format) && (settings.width % 2 || settings.height % 2))
    throw UsageError(fmt::format("--size {}x{}: a {} video needs an even width and height (4:2:0 chroma)",
                                 settings.width, settings.height, videoExtension(*format)));
  checkOutputFile("--out", cmd.out);
  const Flight flight = loadFlight(cmd, sub);
  const std::string ffmpeg = findFfmpeg(*format);  // before the renderer is built, not after its frames

  auto context = openContext(global);
  const std::string& name = flight.scene ? flight.scene->name : flight.planet.name;
  const auto started = std::chrono::steady_clock::now();
  uint32_t raised = 0;
  {
    VideoWriter video(ffmpeg, cmd.out, {settings.width, settings.height, cmd.fps, *format});
    std::unique_ptr<Renderer> renderer = flight.scene ? std::make_unique<Renderer>(*context, *flight.scene, settings)
                                                      : std::make_unique<Renderer>(*context, flight.planet, settings);
    // As in the viewer: --sun places the sun for the first frame's camera, then it stays fixed in
    // the planet frame while the camera moves.
    const glm::dvec3 sunPlanet =
        flight.scene ? glm::dvec3(0.0)
                     : sunDirection(flight.sun,
                                    cameraPoseAt(sampleCameraPath(flight.path, flight.path.startS()), flight.planet));
    ProgressLine progress(fmt::format("render {} {}x{}", cmd.out, settings.width, settings.height), "frames");
    for (uint32_t i = 0; i < flight.frames; ++i) {
      const double pathS = frameTimeS(flight.path, i, flight.frames);
      const RenderResult result = renderer->renderScene(frameView(flight, pathS, cmd.timeS, sunPlanet));
      raised += result.cameraRaised ? 1 : 0;
      video.addFrame(result.image);
      progress(i + 1, flight.frames);
    }
    video.finish();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (raised > 0)
    std::fprintf(stderr,
                 "planet: warning: the camera was below the ground in %u of %u frames; raised to %.1f m above it\n",
                 raised, flight.frames, kMinEyeHeightM);
  fmt::print("wrote {} ({} frames, {}x{} at {} fps: {:.2f} s of video; {} over {:.4g} s of path '{}', on {})\n",
             cmd.out, flight.frames, settings.width, settings.height, cmd.fps, flight.frames / cmd.fps, name,
             flight.path.durationS(), cmd.path, context->info.name);
  if (flight.scene) fmt::print("the path flies over {}\n", flight.scene->bodies[flight.body].name);
  fmt::print("rendered and encoded in {:.1f} s ({:.0f} ms per frame)\n", seconds, 1000.0 * seconds / flight.frames);
  return finishWithValidation(*context, 0);
}

}  // namespace planet::cli
