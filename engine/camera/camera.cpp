#include "camera/camera.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "planet/terrain_height.h"

namespace planet {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Splits "a,b,c" and parses each as a finite double; `what` names the option in messages.
std::vector<double> parseNumbers(std::string_view text, std::string_view what, size_t minCount, size_t maxCount) {
  std::vector<double> values;
  size_t start = 0;
  while (true) {
    const size_t comma = text.find(',', start);
    const std::string_view field = text.substr(start, comma == std::string_view::npos ? text.npos : comma - start);
    double value = 0.0;
    const char* end = field.data() + field.size();
    auto [ptr, ec] = std::from_chars(field.data(), end, value);
    if (field.empty() || ec != std::errc() || ptr != end || !std::isfinite(value))
      throw Error(fmt::format("{} '{}': '{}' is not a finite number", what, text, field));
    values.push_back(value);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (values.size() < minCount || values.size() > maxCount)
    throw Error(fmt::format(
        "{} '{}': expected {} numbers separated by commas, got {}", what, text,
        minCount == maxCount ? std::to_string(minCount) : fmt::format("{} or {}", minCount, maxCount), values.size()));
  return values;
}

}  // namespace

CameraPose parseCameraPose(std::string_view text) {
  const std::vector<double> v = parseNumbers(text, "camera", 3, 5);
  if (v.size() == 4) throw Error(fmt::format("camera '{}': give HEADING and PITCH together", text));
  CameraPose pose;
  pose.latitudeDeg = v[0];
  pose.longitudeDeg = v[1];
  pose.altitudeM = v[2];
  if (v.size() == 5) {
    pose.headingDeg = v[3];
    pose.pitchDeg = v[4];
  }
  if (pose.latitudeDeg < -90.0 || pose.latitudeDeg > 90.0)
    throw Error(fmt::format("camera latitude {} is outside [-90, 90] degrees", pose.latitudeDeg));
  if (pose.altitudeM < -1e5 || pose.altitudeM > 1e10)
    throw Error(fmt::format("camera altitude {} m is outside [-1e5, 1e10] m", pose.altitudeM));
  if (pose.pitchDeg < -90.0 || pose.pitchDeg > 90.0)
    throw Error(fmt::format("camera pitch {} is outside [-90, 90] degrees", pose.pitchDeg));
  return pose;
}

SunPose parseSunPose(std::string_view text) {
  const std::vector<double> v = parseNumbers(text, "sun", 2, 2);
  if (v[1] < -90.0 || v[1] > 90.0) throw Error(fmt::format("sun elevation {} is outside [-90, 90] degrees", v[1]));
  return {v[0], v[1]};
}

LocalAxes localAxes(const glm::dvec3& direction) {
  LocalAxes axes;
  axes.up = glm::normalize(direction);
  glm::dvec3 east = glm::cross(glm::dvec3(0.0, 0.0, 1.0), axes.up);
  axes.east = glm::length(east) < 1e-12 ? glm::dvec3(0.0, 1.0, 0.0) : glm::normalize(east);
  axes.north = glm::cross(axes.up, axes.east);
  return axes;
}

CameraBasis cameraBasis(const CameraPose& pose, double seaLevelRadiusM) {
  const glm::dvec3 direction = directionFromLatLon(pose.latitudeDeg, pose.longitudeDeg);
  const LocalAxes axes = localAxes(direction);
  const double heading = pose.headingDeg * kDegree;
  const double pitch = pose.pitchDeg * kDegree;
  const glm::dvec3 level = std::cos(heading) * axes.north + std::sin(heading) * axes.east;
  CameraBasis basis;
  basis.position = (seaLevelRadiusM + pose.altitudeM) * direction;
  basis.forward = glm::normalize(std::cos(pitch) * level + std::sin(pitch) * axes.up);
  // Screen up: the level heading direction tilted back, so looking straight down the top of
  // the picture points along the heading.
  basis.up = glm::normalize(-std::sin(pitch) * level + std::cos(pitch) * axes.up);
  return basis;
}

CameraPose cameraPoseFromBasis(const CameraBasis& basis, double seaLevelRadiusM) {
  const double distance = glm::length(basis.position);
  const glm::dvec3 direction = basis.position / distance;
  const LocalAxes axes = localAxes(direction);
  CameraPose pose;
  pose.latitudeDeg = latitudeDegOf(direction);
  pose.longitudeDeg = longitudeDegOf(direction);
  pose.altitudeM = distance - seaLevelRadiusM;
  const double sinPitch = std::clamp(glm::dot(basis.forward, axes.up), -1.0, 1.0);
  const double pitch = std::asin(sinPitch);
  // forward = cos p · level + sin p · up and screenUp = −sin p · level + cos p · up, so
  // level = cos p · forward − sin p · screenUp.
  const glm::dvec3 level = std::cos(pitch) * basis.forward - sinPitch * basis.up;
  pose.headingDeg = std::atan2(glm::dot(level, axes.east), glm::dot(level, axes.north)) / kDegree;
  pose.pitchDeg = pitch / kDegree;
  return pose;
}

CameraBasis lookingAt(const glm::dvec3& position, const glm::dvec3& target) {
  CameraBasis basis;
  basis.position = position;
  basis.forward = glm::normalize(target - position);
  const LocalAxes axes = localAxes(position);
  glm::dvec3 up = axes.up - glm::dot(axes.up, basis.forward) * basis.forward;
  if (glm::length(up) < 1e-9) up = axes.north - glm::dot(axes.north, basis.forward) * basis.forward;
  basis.up = glm::normalize(up);
  return basis;
}

glm::dvec3 sunDirection(const SunPose& sun, const CameraPose& camera) {
  const LocalAxes axes = localAxes(directionFromLatLon(camera.latitudeDeg, camera.longitudeDeg));
  const double azimuth = sun.azimuthDeg * kDegree;
  const double elevation = sun.elevationDeg * kDegree;
  return glm::normalize(std::cos(elevation) * (std::cos(azimuth) * axes.north + std::sin(azimuth) * axes.east) +
                        std::sin(elevation) * axes.up);
}

glm::dmat4 reversedZPerspective(double fovYRad, double aspect, double nearM) {
  const double f = 1.0 / std::tan(0.5 * fovYRad);
  glm::dmat4 m(0.0);
  m[0][0] = f / aspect;
  m[1][1] = -f;     // Vulkan's clip-space y points down
  m[2][3] = -1.0;   // w = −z_view (distance in front of the camera)
  m[3][2] = nearM;  // z = near, so depth = near / distance
  return m;
}

glm::dmat4 viewMatrix(const glm::dvec3& forward, const glm::dvec3& up) {
  const glm::dvec3 right = glm::normalize(glm::cross(forward, up));
  const glm::dvec3 trueUp = glm::cross(right, forward);
  glm::dmat4 m(1.0);
  // Rows are the camera axes: x = right, y = up, z = −forward.
  for (int i = 0; i < 3; ++i) {
    m[i][0] = right[i];
    m[i][1] = trueUp[i];
    m[i][2] = -forward[i];
  }
  return m;
}

}  // namespace planet
