// Views of a scene of several bodies (issue 8) and the transforms that carry a camera between
// a body's frame and the scene's, in double. The Renderer draws a SceneView; the scene flight
// and the render command build one.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "camera/camera.h"
#include "planet/scene_description.h"

namespace planet {

// A frame of a scene of several bodies (issue 8): everything in the scene frame, double.
struct SceneBodyView {
  glm::dvec3 positionM{0.0};       // the body's centre
  glm::dmat3 bodyToScene{1.0};     // rotation of its planet frame
  glm::dvec3 sunDirection{0.0, 0.0, 1.0};  // unit, from the body toward the sun
  double sunDistanceM = kAstronomicalUnitM;  // of its centre from the sun's: sets its sunlight (reference/sunlight.h)
};
struct SceneView {
  CameraBasis camera;  // scene frame
  std::vector<SceneBodyView> bodies;  // one per body of the Renderer, in its order
  double timeS = 0.0;                 // animation phase (clouds, waves)
};
// The bodies' views at their scene positions, lit by a sun at the scene's origin (each at its own
// distance from it).
std::vector<SceneBodyView> sceneBodyViews(const std::vector<BodyState>& states);
// A camera between a body's frame and the scene frame (the body's centre at positionM, its
// frame turned by bodyToScene), in double.
CameraBasis cameraToScene(const glm::dvec3& positionM, const glm::dmat3& bodyToScene, const CameraBasis& local);
CameraBasis cameraToBody(const glm::dvec3& positionM, const glm::dmat3& bodyToScene, const CameraBasis& scene);

}  // namespace planet
