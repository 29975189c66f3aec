// The real-time viewer's camera controller: turns one frame of decoded keyboard and mouse input
// into a CameraPose (camera.h). Pure CPU, double precision, planet frame of terrain_height.h.
//
// Speed follows the height above the ground: at full input the camera covers speedPerHeight
// times its height above the ground per second, so 40,000 km up and 1.7 m up feel the same (one
// height per second), and zoom multiplies that height by a constant factor per step.
//
// Movement, in both modes, is split against the local vertical: the vertical part changes the
// altitude, the horizontal part moves the camera along the great circle through it (at its own
// radius, so a level flight keeps its altitude whatever the step). The view direction is carried
// along by the same rotation that carries the local vertical (parallel transport), so the pitch
// is unchanged by a move and the planet-frame view direction turns only by the angle the step
// subtends at the planet's centre; the heading is re-derived in the new local frame. Nothing
// divides by the distance to the pole's axis, so poles and the ±180° meridian are ordinary
// points (at a pole the heading is measured in camera.h's polar frame, as cameraBasis does).
//
// After every step the camera is kept between eyeHeightM and maxHeightM above the ground under it.
#pragma once

#include <functional>

#include <glm/glm.hpp>

#include "camera/camera.h"
#include "camera/camera_path.h"

namespace planet {

enum class FlightMode {
  Orbit,  // looks down at the planet (pitch −90, tiltable up to orbitMaxPitchDeg); moves over the ground
  Free,   // flies along the view direction; pitch in [−89.9, 89.9]
};

// One frame of user input, already decoded from keys and mouse. Non-finite values count as 0
// (speedFactor as 1).
struct FlightInput {
  double dtS = 0.0;          // seconds since the previous frame; clamped to [0, 0.25] (a hitch is not a leap)
  double forward = 0.0;      // −1..1 (W/S)
  double right = 0.0;        // −1..1 (D/A)
  double up = 0.0;           // −1..1 (E/Q or Space/Ctrl), along the local vertical in both modes
  double lookX = 0.0;        // mouse motion in pixels while the look button is held, + = right
  double lookY = 0.0;        // the same, window coordinates: + = down (looks / tilts down)
  double zoom = 0.0;         // scroll wheel steps, + = closer to the ground
  double speedFactor = 1.0;  // e.g. 4 with Shift, 0.25 with Alt; clamped to [0, 100]
};

// Each knob is checked by the constructor (planet::Error naming it).
struct FlightSettings {
  double eyeHeightM = 1.7;          // lowest height above the ground (>= 0.01 m, CameraPath's minimum)
  double maxHeightM = 1e9;          // highest height above the ground (<= 1e10 m)
  double speedPerHeight = 1.0;      // metres per second per metre above the ground, at full input
  double lookDegPerPixel = 0.15;    // mouse look sensitivity
  double zoomFactor = 0.85;         // height multiplier per zoom step toward the ground, in (0, 1)
  double orbitMaxPitchDeg = -30.0;  // how far orbit mode tilts up from straight down, in [−90, 0]
  double goToDurationS = 4.0;       // length of a goTo transition; 0 jumps
};

class FlightCamera {
 public:
  // groundHeight(direction): the surface height in metres above the sea-level sphere under a
  // unit planet-frame direction (the viewer passes the CPU reference terrain, max with the sea
  // level where there is an ocean). It must return finite values (update throws otherwise); it
  // is called about twice per update, so it may be the full-detail reference.
  using GroundHeight = std::function<double(const glm::dvec3&)>;

  // Starts in orbit mode at CameraPose{} (raised above the ground if needed). Throws
  // planet::Error for a non-positive radius, an empty groundHeight or a bad setting.
  FlightCamera(double radiusM, GroundHeight groundHeight, FlightSettings settings = {});

  // Immediate: cancels a transition; longitude wrapped to [−180, 180), heading to [0, 360),
  // pitch clamped to the mode's range, altitude to [eyeHeightM, maxHeightM] above the ground.
  // Throws planet::Error naming a latitude outside [−90, 90] or a non-finite value.
  void setPose(const CameraPose& pose);
  const CameraPose& pose() const { return pose_; }
  // cameraBasis(pose(), radiusM): what the renderer needs.
  CameraBasis basis() const;

  FlightMode mode() const { return mode_; }
  // Cancels a transition. Entering orbit mode looks straight down (pitch −90); entering free
  // mode clamps the pitch into [−89.9, 89.9]. The position and heading are kept.
  void setMode(FlightMode mode);

  // Advances one frame. While a goTo transition plays, a frame with no movement, look or zoom
  // input advances it; any such input cancels it where it is and then acts as usual (the user
  // takes over without a jump). speedFactor alone does not cancel.
  void update(const FlightInput& input);

  // A smooth transition over goToDurationS to the point at `altitudeM` above the sea-level
  // sphere (raised to eyeHeightM above the ground), keeping the current heading and pitch.
  // Throws planet::Error naming a latitude outside [−90, 90] or a non-finite value.
  void goTo(double latitudeDeg, double longitudeDeg, double altitudeM);
  // The same, arriving with target's heading and pitch (pitch clamped to the mode's range).
  void goTo(const CameraPose& target);
  bool transitioning() const { return transitioning_; }
  // The path of the current or latest transition (heights above the surface, times from 0).
  const CameraPath& transitionPath() const { return path_; }

  double groundHeightM() const { return groundM_; }  // under the camera, above the sea sphere
  double heightAboveGroundM() const { return pose_.altitudeM - groundM_; }
  // speedPerHeight · heightAboveGroundM · the last update's speedFactor: metres per second at
  // full input.
  double speedMps() const;

  double radiusM() const { return radiusM_; }
  const FlightSettings& settings() const { return settings_; }

 private:
  double minPitchDeg() const;
  double maxPitchDeg() const;
  double groundAt(const glm::dvec3& direction) const;
  // Normalises and clamps `pose` as setPose describes (without checks) and makes it current.
  void commit(CameraPose pose);
  void move(const FlightInput& input);
  void advanceTransition(double dtS);
  // The heading at a point of path_ (its time and position; the key's own heading is not used).
  double transitionHeadingDeg(const CameraKey& key) const;

  double radiusM_;
  GroundHeight groundHeight_;
  FlightSettings settings_;
  FlightMode mode_ = FlightMode::Orbit;
  CameraPose pose_;
  double groundM_ = 0.0;
  double speedFactor_ = 1.0;
  bool transitioning_ = false;
  // The goTo transition: position, height and pitch sampled from path_, the heading from the
  // track (transitionHeadingDeg).
  CameraPath path_;
  double elapsedS_ = 0.0;
  CameraPose target_;
  bool alongTrack_ = false;  // path_ travels along the great circle with normal trackNormal_
  glm::dvec3 trackNormal_{0.0};
  double startHeadingDeg_ = 0.0;
  double startOffsetDeg_ = 0.0;  // heading − bearing of the track at the start (or 0 without one)
  double offsetTurnDeg_ = 0.0;   // how that offset turns by the end, the short way round
};

}  // namespace planet
