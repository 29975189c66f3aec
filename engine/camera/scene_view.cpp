#include "camera/scene_view.h"

namespace planet {

std::vector<SceneBodyView> sceneBodyViews(const std::vector<BodyState>& states) {
  std::vector<SceneBodyView> views;
  for (const BodyState& state : states) {
    const double distance = glm::length(state.positionM);
    // A body at the sun's centre (no orbit reaches it: scene_description.h) keeps the defaults.
    views.push_back({state.positionM, state.bodyToScene,
                     distance > 0.0 ? -state.positionM / distance : glm::dvec3(0.0, 0.0, 1.0),
                     distance > 0.0 ? distance : kAstronomicalUnitM});
  }
  return views;
}

CameraBasis cameraToScene(const glm::dvec3& positionM, const glm::dmat3& bodyToScene, const CameraBasis& local) {
  return {positionM + bodyToScene * local.position, bodyToScene * local.forward, bodyToScene * local.up};
}

CameraBasis cameraToBody(const glm::dvec3& positionM, const glm::dmat3& bodyToScene, const CameraBasis& scene) {
  const glm::dmat3 sceneToBody = glm::transpose(bodyToScene);
  return {sceneToBody * (scene.position - positionM), sceneToBody * scene.forward, sceneToBody * scene.up};
}

}  // namespace planet
