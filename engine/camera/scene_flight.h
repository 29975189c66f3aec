// Flying through a scene of several bodies (issue 8, point 1: "the viewer can travel from one
// body's surface to another's seamlessly"). The camera is a FlightCamera in the frame of its
// reference body, so it rides along with that body's orbit and spin and the ground stays put
// under it; its speed follows the height above that body's ground. After every step the
// reference is the body whose surface is nearest relative to its radius (the Renderer's primary
// body, sceneReferenceBody); when that changes, the pose is re-expressed in the new body's
// frame at the same scene position and view direction, so the picture does not jump.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "planet/scene_description.h"
#include "camera/camera.h"
#include "camera/flight_camera.h"
#include "camera/scene_view.h"

namespace planet {

class SceneFlight {
 public:
  // Starts on `body` at `pose` (its frame) at scene time `timeS`, in free-flight mode. Throws
  // planet::Error for a body index outside the scene or a bad pose.
  SceneFlight(const SceneDescription& scene, size_t body, const CameraPose& pose, double timeS,
              FlightSettings settings = {});

  // One frame: the input moves the camera in the reference body's frame, the scene advances to
  // `timeS` (the camera riding along), then the reference body is chosen again.
  void update(const FlightInput& input, double timeS);
  // Turns the camera toward a body's centre (free mode; the position is kept).
  void lookAt(size_t body);
  // Autopilot: every update aims at the body's centre and flies ahead at kTravelSpeedFactor
  // (movement input is replaced, looking around cancels it), until the camera is that body's
  // and less than kTravelArrivalM above its ground. Throws for a bad body, as lookAt does.
  static constexpr double kTravelSpeedFactor = 4.0;
  static constexpr double kTravelArrivalM = 1000.0;
  void travelTo(size_t body);
  void cancelTravel() { travelTarget_ = std::nullopt; }
  std::optional<size_t> travelTarget() const { return travelTarget_; }

  // The frame for Renderer::prepareScene, at the last update's time.
  SceneView view() const;
  size_t referenceBody() const { return reference_; }
  FlightCamera& camera() { return *camera_; }
  const FlightCamera& camera() const { return *camera_; }
  const SceneDescription& scene() const { return scene_; }
  const std::vector<BodyState>& states() const { return states_; }
  double timeS() const { return timeS_; }
  // The camera in the scene frame.
  CameraBasis sceneCamera() const;
  // How many times the reference body changed.
  uint32_t switches() const { return switches_; }

 private:
  void makeCamera(size_t body, const CameraPose& pose, FlightMode mode);
  // Re-expresses the camera in the frame of the relatively nearest body, if that is another one.
  void rebase();

  SceneDescription scene_;
  FlightSettings settings_;
  std::vector<BodyState> states_;
  double timeS_ = 0.0;
  size_t reference_ = 0;
  std::unique_ptr<FlightCamera> camera_;
  uint32_t switches_ = 0;
  std::optional<size_t> travelTarget_;
};

}  // namespace planet
