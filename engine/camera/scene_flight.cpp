#include "camera/scene_flight.h"

#include <fmt/format.h>

#include "core/error.h"
#include "planet/terrain_height.h"

namespace planet {

SceneFlight::SceneFlight(const SceneDescription& scene, size_t body, const CameraPose& pose, double timeS,
                         FlightSettings settings)
    : scene_(scene), settings_(settings), timeS_(timeS) {
  if (body >= scene_.bodies.size())
    throw Error(fmt::format("scene flight body {} is outside 0..{}", body, scene_.bodies.size() - 1));
  states_ = sceneStateAt(scene_, timeS_);
  makeCamera(body, pose, FlightMode::Free);
  rebase();
}

void SceneFlight::makeCamera(size_t body, const CameraPose& pose, FlightMode mode) {
  const PlanetDescription& planet = scene_.bodies[body].planet;
  auto ground = [planet](const glm::dvec3& direction) { return surfaceHeightM(planet, direction); };
  auto camera = std::make_unique<FlightCamera>(planet.radiusM, ground, settings_);
  camera->setMode(mode);
  camera->setPose(pose);
  camera_ = std::move(camera);
  reference_ = body;
}

CameraBasis SceneFlight::sceneCamera() const {
  const BodyState& on = states_[reference_];
  return cameraToScene(on.positionM, on.bodyToScene, camera_->basis());
}

void SceneFlight::rebase() {
  const CameraBasis world = sceneCamera();
  const size_t nearest = sceneReferenceBody(scene_, states_, world.position);
  if (nearest == reference_) return;
  const BodyState& to = states_[nearest];
  const CameraBasis local = cameraToBody(to.positionM, to.bodyToScene, world);
  makeCamera(nearest, cameraPoseFromBasis(local, scene_.bodies[nearest].planet.radiusM), camera_->mode());
  ++switches_;
}

void SceneFlight::travelTo(size_t body) {
  lookAt(body);
  travelTarget_ = body;
}

void SceneFlight::update(const FlightInput& userInput, double timeS) {
  FlightInput input = userInput;
  if (travelTarget_ && (input.lookX != 0.0 || input.lookY != 0.0)) travelTarget_ = std::nullopt;
  if (travelTarget_) {
    // Once in the target's frame, the end of the last update aimed the camera down at it.
    if (*travelTarget_ != reference_) lookAt(*travelTarget_);
    input.forward = 1.0;
    input.right = input.up = input.zoom = 0.0;
    input.speedFactor = kTravelSpeedFactor;
  }
  camera_->update(input);
  timeS_ = timeS;
  states_ = sceneStateAt(scene_, timeS_);
  rebase();
  if (travelTarget_ && *travelTarget_ == reference_) {
    if (camera_->heightAboveGroundM() < kTravelArrivalM) {
      travelTarget_ = std::nullopt;
    } else {
      // Arrived in the target's frame: on down toward its centre (free mode's steepest pitch).
      CameraPose pose = camera_->pose();
      pose.pitchDeg = -90.0;
      camera_->setPose(pose);
    }
  }
}

void SceneFlight::lookAt(size_t body) {
  if (body >= scene_.bodies.size() || body == reference_)
    throw Error(fmt::format("scene flight can look at bodies 0..{} other than its own ({}), got {}",
                            scene_.bodies.size() - 1, reference_, body));
  const BodyState& on = states_[reference_];
  const glm::dvec3 target = glm::transpose(on.bodyToScene) * (states_[body].positionM - on.positionM);
  camera_->setMode(FlightMode::Free);
  const CameraBasis basis = lookingAt(camera_->basis().position, target);
  camera_->setPose(cameraPoseFromBasis(basis, scene_.bodies[reference_].planet.radiusM));
}

SceneView SceneFlight::view() const {
  SceneView view;
  view.camera = sceneCamera();
  view.bodies = sceneBodyViews(states_);
  view.timeS = timeS_;
  return view;
}

}  // namespace planet
