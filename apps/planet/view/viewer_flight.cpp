#include "view/viewer_flight.h"

#include <fmt/format.h>

#include "core/log.h"
#include "planet/terrain_height.h"

namespace planet::view {

ViewerFlight::ViewerFlight(const ViewOptions& options)
    : path_(options.path), frames_(options.frames), timeScale_(options.timeScale) {
  if (options.scene) {
    sceneTimeS_ = options.sceneTimeS;
    scene_ = std::make_unique<SceneFlight>(*options.scene, options.sceneBody, options.camera.value_or(CameraPose{}),
                                           sceneTimeS_);
    if (options.travelTo) scene_->travelTo(*options.travelTo);
    return;
  }
  const PlanetDescription& planet = options.planet;
  camera_ = std::make_unique<FlightCamera>(
      planet.radiusM, [planet](const glm::dvec3& direction) { return surfaceHeightM(planet, direction); });
  CameraPose start = options.camera.value_or(CameraPose{});
  if (options.path) start = cameraPoseAt(sampleCameraPath(*options.path, options.path->startS()), planet);
  // A view toward the horizon is free flight; a view down at the planet is orbit.
  if (options.path || start.pitchDeg > camera().settings().orbitMaxPitchDeg) camera().setMode(FlightMode::Free);
  camera().setPose(start);
}

bool ViewerFlight::update(const FlightInput& input, double stepS, uint32_t frame, double elapsedS, bool nextBody,
                          PlanetDescription& planet) {
  bool pathPlaying = false;
  if (path_) {
    const double t = frames_ > 0 ? frameTimeS(*path_, frame, frames_) : path_->startS() + elapsedS;
    pathPlaying = t <= path_->endS();
    if (pathPlaying) camera().setPose(cameraPoseAt(sampleCameraPath(*path_, t), planet));
  }
  if (!scene_) {
    if (!pathPlaying) camera().update(input);
    return pathPlaying;
  }
  const size_t before = scene_->referenceBody();
  if (nextBody) {
    // The next body after the one flown to last (or after the camera's own).
    const size_t count = scene_->scene().bodies.size();
    size_t next = (scene_->travelTarget().value_or(before) + 1) % count;
    if (next == before) next = (next + 1) % count;
    if (count > 1) scene_->travelTo(next);
  }
  sceneTimeS_ += stepS * timeScale_;
  scene_->update(input, sceneTimeS_);
  const SceneDescription& scene = scene_->scene();
  if (scene_->referenceBody() != before) {
    planet = scene.bodies[scene_->referenceBody()].planet;
    logInfo("now flying at {} (from {})", scene.bodies[scene_->referenceBody()].name, scene.bodies[before].name);
  }
  return pathPlaying;
}

std::string ViewerFlight::sceneStatus() const {
  const SceneDescription& scene = scene_->scene();
  const std::string& body = scene.bodies[scene_->referenceBody()].name;
  return scene_->travelTarget()
             ? fmt::format("{}: travelling to {} (T: next body)", body, scene.bodies[*scene_->travelTarget()].name)
             : fmt::format("{} (T: travel to the next body)", body);
}

void ViewerFlight::printSceneSummary() const {
  fmt::print("scene: at {} ({:.1f} m above its ground) after {} change(s) of body, scene time {:.1f} s\n",
             scene_->scene().bodies[scene_->referenceBody()].name, scene_->camera().heightAboveGroundM(),
             scene_->switches(), sceneTimeS_);
}

}  // namespace planet::view
