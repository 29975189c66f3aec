// What flies the viewer's camera (issue 5): over one planet a FlightCamera, moved by the keys and
// mouse or, while it plays, by a camera path (--path); in a scene of several bodies the scene's
// flight, on the scene's clock, with the autopilot to the next body (T).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "planet/planet_description.h"
#include "camera/camera_path.h"
#include "camera/flight_camera.h"
#include "camera/scene_flight.h"
#include "view/viewer.h"

namespace planet::view {

class ViewerFlight {
 public:
  // Starts where `options` say: over options.planet at options.camera (at the path's start, in
  // free flight, when there is a path; else in orbit looking down, or in free flight toward
  // the horizon), or in options.scene on body options.sceneBody at options.sceneTimeS.
  explicit ViewerFlight(const ViewOptions& options);

  FlightCamera& camera() { return scene_ ? scene_->camera() : *camera_; }
  const SceneFlight* scene() const { return scene_.get(); }  // null over one planet

  // One frame, `stepS` seconds on; `frame` (counted from 0) and `elapsedS` (wall-clock seconds
  // since the frame loop started; with a frame count, the frame places it instead) place the
  // path. Over one planet the path places the camera on `planet` (the panel's) while it plays,
  // otherwise `input` moves it; returns whether the path played. In a scene, `nextBody` starts the
  // autopilot to the body after the last one flown to, the scene's clock advances by `stepS`
  // times the time scale, and `planet` becomes the body flown at when that changes (logged).
  bool update(const FlightInput& input, double stepS, uint32_t frame, double elapsedS, bool nextBody,
              PlanetDescription& planet);
  // In a scene, the HUD's line: the body flown at and the one travelled to.
  std::string sceneStatus() const;
  // In a scene, the line printed on exit: where the camera ended, after how many changes of body.
  void printSceneSummary() const;

 private:
  std::unique_ptr<FlightCamera> camera_;  // one planet
  std::unique_ptr<SceneFlight> scene_;    // a scene (its camera is that of the body it flies at)
  std::optional<CameraPath> path_;
  uint32_t frames_ = 0;  // --frames: the path is spread over them
  double sceneTimeS_ = 0.0;
  double timeScale_ = 1.0;
};

}  // namespace planet::view
