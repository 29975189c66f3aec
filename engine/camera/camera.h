// Camera and sun placement for the renderer, in the terms the user gives them (issue 3, point 9):
// latitude and longitude in degrees, altitude in metres above the sea-level sphere, heading in
// degrees clockwise from north, pitch in degrees above the local horizon (−90 looks straight
// down); the sun by azimuth (clockwise from north) and elevation as seen from the camera's
// ground point. All of it is double precision, in the planet frame of terrain_height.h
// (+z north pole, +x at latitude 0 / longitude 0).
#pragma once

#include <string_view>

#include <glm/glm.hpp>

namespace planet {

struct CameraPose {
  double latitudeDeg = 20.0;
  double longitudeDeg = -30.0;
  double altitudeM = 2.0e7;  // above the sea-level sphere
  double headingDeg = 0.0;   // clockwise from north
  double pitchDeg = -90.0;   // above the local horizon; −90 looks straight down
};

struct SunPose {
  double azimuthDeg = 135.0;   // clockwise from north, seen from the camera's ground point
  double elevationDeg = 35.0;  // above that point's horizon
};

// "LAT,LON,ALT_M[,HEADING,PITCH]"; throws planet::Error naming the bad text or value
// (latitude outside [−90, 90], pitch outside [−90, 90], non-finite numbers, altitude outside
// [−1e5, 1e10] m).
CameraPose parseCameraPose(std::string_view text);
// "AZIMUTH,ELEVATION"; elevation in [−90, 90]. Throws planet::Error naming the bad value.
SunPose parseSunPose(std::string_view text);

// Local east, north and up at a planet-frame direction. At a pole, north is taken along
// longitude 0 (as terrain_height.h's travelGreatCircle does).
struct LocalAxes {
  glm::dvec3 east;
  glm::dvec3 north;
  glm::dvec3 up;
};
LocalAxes localAxes(const glm::dvec3& direction);

// Where the camera is and where it looks, planet frame.
struct CameraBasis {
  glm::dvec3 position;  // metres from the planet's centre
  glm::dvec3 forward;   // unit view direction
  glm::dvec3 up;        // unit, orthogonal to forward (screen up)
};
// `seaLevelRadiusM` is the radius of the sphere altitudes are measured from.
CameraBasis cameraBasis(const CameraPose& pose, double seaLevelRadiusM);

// The pose of a basis (its inverse; position off the centre, forward and up orthonormal):
// heading and pitch follow the same rules, so cameraBasis(cameraPoseFromBasis(b, r), r) is b
// to rounding. A forward straight up or down takes its heading from the screen's up.
CameraPose cameraPoseFromBasis(const CameraBasis& basis, double seaLevelRadiusM);
// A basis at `position` looking at `target` (planet frame), screen up as near the local up as
// the view allows (the local north when looking straight up or down).
CameraBasis lookingAt(const glm::dvec3& position, const glm::dvec3& target);

// Unit direction toward the sun, planet frame.
glm::dvec3 sunDirection(const SunPose& sun, const CameraPose& camera);

// Vulkan clip space (y down, depth 0..1) with reversed Z and an infinite far plane: depth =
// near / distance, 1 at the near plane, → 0 at infinity. Float depth keeps ~7 significant
// digits of distance everywhere, which is what a 2 m-to-40,000 km scene needs. The view looks
// down −z with +y up (right-handed view space).
glm::dmat4 reversedZPerspective(double fovYRad, double aspect, double nearM);
// View matrix: `forward` and `up` (orthonormal) in some frame, camera at that frame's origin.
glm::dmat4 viewMatrix(const glm::dvec3& forward, const glm::dvec3& up);

}  // namespace planet
