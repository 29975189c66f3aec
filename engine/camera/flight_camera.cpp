#include "camera/flight_camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "planet/terrain_height.h"

namespace planet {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kMaxDtS = 0.25;
constexpr double kMaxSpeedFactor = 100.0;
constexpr double kFreeMaxPitchDeg = 89.9;  // short of vertical, where the heading is undefined
// goTo: the cruise height is at least this times the ground distance, so both ends come into view.
constexpr double kApexPerDistance = 1.0;
// goTo time shares: climbing or descending by a factor e costs 1, cruising one cruise height
// along the ground costs kCruiseWeight (the same "speed per height" rule as flying by hand, with
// the cruise slowed so the ground can be followed).
constexpr double kCruiseWeight = 16.0;
constexpr double kMinSegmentWeight = 0.01;  // keeps key times strictly increasing
// goTo looks down at the cruise height in full once it climbs this factor above the lower end.
constexpr double kLookDownClimb = 100.0;

double wrapLongitudeDeg(double deg) {
  const double wrapped = std::fmod(deg + 180.0, 360.0);
  return (wrapped < 0.0 ? wrapped + 360.0 : wrapped) - 180.0;
}

double wrapHeadingDeg(double deg) {
  const double wrapped = std::fmod(deg, 360.0);
  return wrapped < 0.0 ? wrapped + 360.0 : wrapped + 0.0;  // + 0.0 turns −0 into 0
}

double finiteOr(double value, double fallback) { return std::isfinite(value) ? value : fallback; }

// Unit horizontal direction of `headingDeg` in `axes`.
glm::dvec3 levelDirection(const LocalAxes& axes, double headingDeg) {
  const double h = headingDeg * kDegree;
  return std::cos(h) * axes.north + std::sin(h) * axes.east;
}

// Rodrigues' rotation of v about the unit `axis` by `angle` radians.
glm::dvec3 rotate(const glm::dvec3& v, const glm::dvec3& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(axis, v) * s + axis * (glm::dot(axis, v) * (1.0 - c));
}

void checkPoint(const char* what, double latitudeDeg, double longitudeDeg, double altitudeM) {
  if (!std::isfinite(latitudeDeg) || latitudeDeg < -90.0 || latitudeDeg > 90.0)
    throw Error(fmt::format("{}: latitude {} is outside [-90, 90] degrees", what, latitudeDeg));
  if (!std::isfinite(longitudeDeg)) throw Error(fmt::format("{}: longitude {} is not finite", what, longitudeDeg));
  if (!std::isfinite(altitudeM)) throw Error(fmt::format("{}: altitude {} m is not finite", what, altitudeM));
}

void checkPose(const char* what, const CameraPose& pose) {
  checkPoint(what, pose.latitudeDeg, pose.longitudeDeg, pose.altitudeM);
  if (!std::isfinite(pose.headingDeg)) throw Error(fmt::format("{}: heading {} is not finite", what, pose.headingDeg));
  if (!std::isfinite(pose.pitchDeg)) throw Error(fmt::format("{}: pitch {} is not finite", what, pose.pitchDeg));
}

void checkSettings(const FlightSettings& s) {
  struct Knob {
    const char* name;
    double value, min, max;
    bool minOpen;
  } knobs[] = {
      {"eyeHeightM", s.eyeHeightM, kPathMinHeightM, kPathMaxHeightM, false},
      {"maxHeightM", s.maxHeightM, s.eyeHeightM, kPathMaxHeightM, true},
      {"speedPerHeight", s.speedPerHeight, 0.0, 1e3, true},
      {"lookDegPerPixel", s.lookDegPerPixel, 0.0, 180.0, false},
      {"zoomFactor", s.zoomFactor, 0.0, 1.0, true},
      {"orbitMaxPitchDeg", s.orbitMaxPitchDeg, -90.0, 0.0, false},
      {"goToDurationS", s.goToDurationS, 0.0, 3600.0, false},
  };
  for (const Knob& k : knobs) {
    const bool tooLow = k.minOpen ? !(k.value > k.min) : !(k.value >= k.min);
    if (!std::isfinite(k.value) || tooLow || k.value > k.max)
      throw Error(fmt::format("flight settings: {} {} is outside {}{}, {}]", k.name, k.value, k.minOpen ? "(" : "[",
                              k.min, k.max));
  }
  if (s.zoomFactor >= 1.0) throw Error(fmt::format("flight settings: zoomFactor {} is not below 1", s.zoomFactor));
}

// The heading of the great circle with unit normal `normal` at a point on it (the direction of
// travel from the start toward the target), in the local frame cameraBasis uses there.
double trackBearingDeg(const glm::dvec3& normal, double latitudeDeg, double longitudeDeg) {
  const glm::dvec3 d = directionFromLatLon(latitudeDeg, longitudeDeg);
  const LocalAxes axes = localAxes(d);
  const glm::dvec3 along = glm::cross(normal, d);
  return std::atan2(glm::dot(along, axes.east), glm::dot(along, axes.north)) / kDegree;
}

// One point of a goTo path before it gets its time: `weight` is the share of the transition that
// the segment ending here takes.
struct Waypoint {
  double latitudeDeg, longitudeDeg;
  double heightM;
  double pitchDeg;
  double weight;
};

struct GoToPlan {
  CameraPath path;
  bool alongTrack = false;  // the path travels over the ground along trackNormal's great circle
  glm::dvec3 trackNormal{0.0};
};

// Climb above the start, cruise along the great circle, descend onto the target, each part
// dropped where it has nothing to do. Interpolating position and height together across
// decades of height (a single start-to-target segment) would sweep the ground past a low
// camera at thousands of heights per second; this order keeps the sweep near the cruise rate.
// The keys' headings are set by the caller.
GoToPlan planGoTo(const CameraKey& from, const CameraKey& to, double radiusM, double maxHeightM, double lowestPitchDeg,
                  double durationS) {
  const glm::dvec3 p0 = directionFromLatLon(from.latitudeDeg, from.longitudeDeg);
  const glm::dvec3 p1 = directionFromLatLon(to.latitudeDeg, to.longitudeDeg);
  const double angle = std::atan2(glm::length(glm::cross(p0, p1)), glm::dot(p0, p1));
  const double h0 = from.heightM, h1 = to.heightM;
  const double apex = std::min(std::max({h0, h1, kApexPerDistance * angle * radiusM}), maxHeightM);
  const double lookDown = std::clamp(std::log(apex / std::min(h0, h1)) / std::log(kLookDownClimb), 0.0, 1.0);
  const double apexPitch0 = from.pitchDeg + lookDown * (lowestPitchDeg - from.pitchDeg);
  const double apexPitch1 = to.pitchDeg + lookDown * (lowestPitchDeg - to.pitchDeg);
  const bool climb = apex > h0 * (1.0 + 1e-9);
  const bool cruise = angle > 1e-12;  // below, the horizontal shift is under 10 µm: the last key makes it
  const bool descend = apex > h1 * (1.0 + 1e-9);
  const double cruiseWeight = kCruiseWeight * angle * radiusM / apex;

  GoToPlan plan;
  std::vector<Waypoint> points = {{from.latitudeDeg, from.longitudeDeg, h0, from.pitchDeg, 0.0}};
  if (climb) points.push_back({from.latitudeDeg, from.longitudeDeg, apex, apexPitch0, std::log(apex / h0)});
  double cruiseLeft = 0.0;  // the weight of the cruise still to add
  if (cruise) {
    plan.alongTrack = true;
    plan.trackNormal = glm::normalize(glm::cross(p0, p1));
    cruiseLeft = cruiseWeight;
    if (angle > 0.5 * std::numbers::pi) {
      // CameraPath segments must not be (nearly) antipodal: split the cruise at its middle. For
      // an exact antipode every great circle is one; take the one along the current heading.
      const glm::dvec3 sum = p0 + p1;
      const glm::dvec3 middle = glm::length(sum) > 1e-6
                                    ? glm::normalize(sum)
                                    : travelGreatCircle(p0, from.headingDeg, 0.5 * std::numbers::pi * radiusM, radiusM);
      plan.trackNormal = glm::normalize(glm::cross(p0, middle));  // well conditioned: 90° apart
      points.push_back(
          {latitudeDegOf(middle), longitudeDegOf(middle), apex, 0.5 * (apexPitch0 + apexPitch1), 0.5 * cruiseWeight});
      cruiseLeft = 0.5 * cruiseWeight;
    }
    if (descend) {
      points.push_back({to.latitudeDeg, to.longitudeDeg, apex, apexPitch1, cruiseLeft});
      cruiseLeft = 0.0;
    }
  }
  // The target: reached by the descent, or (already at the cruise height) by the cruise.
  points.push_back({to.latitudeDeg, to.longitudeDeg, h1, to.pitchDeg, descend ? std::log(apex / h1) : cruiseLeft});

  double total = 0.0;
  for (size_t i = 1; i < points.size(); ++i) total += std::max(points[i].weight, kMinSegmentWeight);
  double elapsed = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    if (i > 0) elapsed += std::max(points[i].weight, kMinSegmentWeight);
    const Waypoint& p = points[i];
    const double timeS = i + 1 == points.size() ? durationS : durationS * elapsed / total;
    plan.path.keys.push_back({timeS, p.latitudeDeg, p.longitudeDeg, p.heightM, 0.0, p.pitchDeg});
  }
  return plan;
}

}  // namespace

FlightCamera::FlightCamera(double radiusM, GroundHeight groundHeight, FlightSettings settings)
    : radiusM_(radiusM), groundHeight_(std::move(groundHeight)), settings_(settings) {
  if (!std::isfinite(radiusM) || !(radiusM > 0.0))
    throw Error(fmt::format("flight camera: radius {} m is not a positive number", radiusM));
  if (!groundHeight_) throw Error("flight camera: no ground height function");
  checkSettings(settings_);
  commit(CameraPose{});
}

CameraBasis FlightCamera::basis() const { return cameraBasis(pose_, radiusM_); }

double FlightCamera::minPitchDeg() const { return mode_ == FlightMode::Orbit ? -90.0 : -kFreeMaxPitchDeg; }
double FlightCamera::maxPitchDeg() const {
  return mode_ == FlightMode::Orbit ? settings_.orbitMaxPitchDeg : kFreeMaxPitchDeg;
}

double FlightCamera::groundAt(const glm::dvec3& direction) const {
  const double ground = groundHeight_(direction);
  if (!std::isfinite(ground))
    throw Error(fmt::format("flight camera: the ground height at ({}, {}, {}) is {}, not a finite number", direction.x,
                            direction.y, direction.z, ground));
  return ground;
}

void FlightCamera::commit(CameraPose pose) {
  pose.longitudeDeg = wrapLongitudeDeg(pose.longitudeDeg);
  pose.headingDeg = wrapHeadingDeg(pose.headingDeg);
  pose.pitchDeg = std::clamp(pose.pitchDeg, minPitchDeg(), maxPitchDeg());
  // The ground under the pose as the renderer will place it (the direction rebuilt from the
  // rounded angles), so "above the ground" holds for exactly what is drawn.
  groundM_ = groundAt(directionFromLatLon(pose.latitudeDeg, pose.longitudeDeg));
  pose.altitudeM = std::clamp(pose.altitudeM, groundM_ + settings_.eyeHeightM, groundM_ + settings_.maxHeightM);
  pose_ = pose;
}

void FlightCamera::setPose(const CameraPose& pose) {
  checkPose("flight camera pose", pose);
  transitioning_ = false;
  commit(pose);
}

void FlightCamera::setMode(FlightMode mode) {
  transitioning_ = false;
  mode_ = mode;
  CameraPose pose = pose_;
  if (mode == FlightMode::Orbit) pose.pitchDeg = -90.0;
  commit(pose);
}

double FlightCamera::speedMps() const { return settings_.speedPerHeight * heightAboveGroundM() * speedFactor_; }

void FlightCamera::update(const FlightInput& raw) {
  FlightInput input;
  input.dtS = std::clamp(finiteOr(raw.dtS, 0.0), 0.0, kMaxDtS);
  input.forward = std::clamp(finiteOr(raw.forward, 0.0), -1.0, 1.0);
  input.right = std::clamp(finiteOr(raw.right, 0.0), -1.0, 1.0);
  input.up = std::clamp(finiteOr(raw.up, 0.0), -1.0, 1.0);
  input.lookX = finiteOr(raw.lookX, 0.0);
  input.lookY = finiteOr(raw.lookY, 0.0);
  input.zoom = finiteOr(raw.zoom, 0.0);
  input.speedFactor = std::clamp(finiteOr(raw.speedFactor, 1.0), 0.0, kMaxSpeedFactor);
  speedFactor_ = input.speedFactor;
  const bool acts = input.forward != 0.0 || input.right != 0.0 || input.up != 0.0 || input.lookX != 0.0 ||
                    input.lookY != 0.0 || input.zoom != 0.0;
  if (transitioning_) {
    if (!acts) {
      advanceTransition(input.dtS);
      return;
    }
    transitioning_ = false;  // the user takes over from the pose the transition reached
  }
  if (acts) move(input);
}

void FlightCamera::move(const FlightInput& input) {
  const glm::dvec3 direction = directionFromLatLon(pose_.latitudeDeg, pose_.longitudeDeg);
  const LocalAxes axes = localAxes(direction);
  const glm::dvec3 level = levelDirection(axes, pose_.headingDeg);
  const glm::dvec3 right = glm::cross(level, axes.up);
  const double pitch = pose_.pitchDeg * kDegree;
  // Orbit mode moves over the ground whatever the tilt; free mode along the view.
  const glm::dvec3 ahead = mode_ == FlightMode::Free ? std::cos(pitch) * level + std::sin(pitch) * axes.up : level;

  // A diagonal is not faster than a straight line.
  glm::dvec3 stick(input.forward, input.right, input.up);
  if (glm::length(stick) > 1.0) stick = glm::normalize(stick);
  const glm::dvec3 step = speedMps() * input.dtS * (stick.x * ahead + stick.y * right + stick.z * axes.up);

  const double climb = glm::dot(step, axes.up);
  const glm::dvec3 along = step - climb * axes.up;
  const double alongM = glm::length(along);
  CameraPose pose = pose_;
  if (alongM > 0.0) {
    // The great circle through the camera toward `along`, at the camera's radius; the level
    // view direction turns with the vertical.
    const glm::dvec3 axis = glm::cross(axes.up, along) / alongM;
    const double angle = alongM / (radiusM_ + pose_.altitudeM);
    const glm::dvec3 up = rotate(axes.up, axis, angle);
    const glm::dvec3 heading = rotate(level, axis, angle);
    pose.latitudeDeg = latitudeDegOf(up);
    pose.longitudeDeg = longitudeDegOf(up);
    const LocalAxes newAxes = localAxes(directionFromLatLon(pose.latitudeDeg, pose.longitudeDeg));
    pose.headingDeg = std::atan2(glm::dot(heading, newAxes.east), glm::dot(heading, newAxes.north)) / kDegree;
  }
  pose.altitudeM += climb;
  if (input.zoom != 0.0) {
    const double ground = groundAt(directionFromLatLon(pose.latitudeDeg, pose.longitudeDeg));
    const double height = std::clamp(pose.altitudeM - ground, settings_.eyeHeightM, settings_.maxHeightM);
    pose.altitudeM = ground + height * std::pow(settings_.zoomFactor, input.zoom);
  }
  pose.headingDeg += input.lookX * settings_.lookDegPerPixel;
  pose.pitchDeg -= input.lookY * settings_.lookDegPerPixel;
  commit(pose);
}

void FlightCamera::goTo(double latitudeDeg, double longitudeDeg, double altitudeM) {
  checkPoint("goTo", latitudeDeg, longitudeDeg, altitudeM);
  goTo(CameraPose{latitudeDeg, longitudeDeg, altitudeM, pose_.headingDeg, pose_.pitchDeg});
}

void FlightCamera::goTo(const CameraPose& target) {
  checkPose("goTo", target);
  // The target as setPose would make it, computed without disturbing the current pose.
  const CameraPose start = pose_;
  const double startGround = groundM_;
  commit(target);
  target_ = pose_;
  const double targetGround = groundM_;
  pose_ = start;
  groundM_ = startGround;

  if (settings_.goToDurationS <= 0.0) {
    setPose(target_);
    return;
  }
  const CameraKey from{
      0.0, start.latitudeDeg, start.longitudeDeg, start.altitudeM - startGround, start.headingDeg, start.pitchDeg};
  const CameraKey to{settings_.goToDurationS,          target_.latitudeDeg, target_.longitudeDeg,
                     target_.altitudeM - targetGround, target_.headingDeg,  target_.pitchDeg};
  GoToPlan plan = planGoTo(from, to, radiusM_, settings_.maxHeightM, minPitchDeg(), settings_.goToDurationS);
  path_ = std::move(plan.path);
  alongTrack_ = plan.alongTrack;
  trackNormal_ = plan.trackNormal;
  startHeadingDeg_ = from.headingDeg;
  // Along a track the heading is held at an angle to the direction of travel, the angle
  // turning from the start's to the target's; without one it turns the short way round.
  startOffsetDeg_ = 0.0;
  double endOffsetDeg = to.headingDeg - from.headingDeg;
  if (alongTrack_) {
    startOffsetDeg_ = from.headingDeg - trackBearingDeg(trackNormal_, from.latitudeDeg, from.longitudeDeg);
    endOffsetDeg = to.headingDeg - trackBearingDeg(trackNormal_, to.latitudeDeg, to.longitudeDeg);
  }
  offsetTurnDeg_ = std::remainder(endOffsetDeg - startOffsetDeg_, 360.0);
  for (CameraKey& key : path_.keys) key.headingDeg = wrapHeadingDeg(transitionHeadingDeg(key));
  elapsedS_ = 0.0;
  transitioning_ = true;
}

double FlightCamera::transitionHeadingDeg(const CameraKey& key) const {
  const double offset = startOffsetDeg_ + offsetTurnDeg_ * (key.timeS - path_.startS()) / path_.durationS();
  if (!alongTrack_) return startHeadingDeg_ + offset;
  // The direction of travel is a smooth vector along the great circle, also where it passes a
  // pole and its bearing swings round: the view turns with it, not with "north".
  return trackBearingDeg(trackNormal_, key.latitudeDeg, key.longitudeDeg) + offset;
}

void FlightCamera::advanceTransition(double dtS) {
  elapsedS_ += dtS;
  // A tolerance so that duration / dt frames of a dt that does not divide it exactly still land.
  if (elapsedS_ >= path_.endS() * (1.0 - 1e-9)) {
    transitioning_ = false;
    commit(target_);  // exactly the target, not a sample rounded near it
    return;
  }
  const CameraKey key = sampleCameraPath(path_, elapsedS_);
  const double ground = groundAt(directionFromLatLon(key.latitudeDeg, key.longitudeDeg));
  commit(CameraPose{key.latitudeDeg, key.longitudeDeg, ground + key.heightM, transitionHeadingDeg(key), key.pitchDeg});
}

}  // namespace planet
