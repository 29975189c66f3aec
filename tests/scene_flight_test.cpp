// Flying from one body to another (issue 8, point 1): the camera rides along with its body, and
// the reference body changes on the way from the Moon's surface to Terra's without a jump.
#include <cmath>
#include <optional>

#include <gtest/gtest.h>

#include "core/error.h"
#include "planet/scene_description.h"
#include "camera/scene_flight.h"

namespace planet {
namespace {

TEST(SceneFlight, TheCameraRidesAlongWithItsBody) {
  const SceneDescription scene = resolveScene("system");
  CameraPose pose;
  pose.latitudeDeg = 10.0;
  pose.longitudeDeg = 20.0;
  pose.altitudeM = 5000.0;
  SceneFlight flight(scene, 2, pose, 0.0);
  ASSERT_EQ(flight.referenceBody(), 2u);
  // An hour later, with no input, the camera is where it was on the Moon, which has moved on.
  const CameraBasis before = flight.sceneCamera();
  flight.update(FlightInput{}, 3600.0);
  const CameraBasis after = flight.sceneCamera();
  EXPECT_EQ(flight.referenceBody(), 2u);
  EXPECT_NEAR(flight.camera().pose().latitudeDeg, 10.0, 1e-9);
  EXPECT_NEAR(flight.camera().pose().altitudeM, 5000.0, 1e-6);
  const glm::dvec3 moon = flight.states()[2].positionM;
  EXPECT_NEAR(glm::length(after.position - moon), scene.bodies[2].planet.radiusM + 5000.0, 1e-3);
  EXPECT_GT(glm::length(after.position - before.position), 1.0e6) << "the Moon moves ~1,000 km/h";
}

TEST(SceneFlight, FromTheMoonsSurfaceToTerrasWithoutAJump) {
  const SceneDescription scene = resolveScene("system");
  CameraPose pose;
  pose.latitudeDeg = 1.0;
  pose.longitudeDeg = 162.0;
  pose.altitudeM = -1.0e5;  // below any ground: raised to eye height
  SceneFlight flight(scene, 2, pose, 66500.0);
  ASSERT_EQ(flight.referenceBody(), 2u);
  const double start = flight.camera().heightAboveGroundM();
  EXPECT_NEAR(start, FlightSettings{}.eyeHeightM, 1e-6);
  // Travel: aim at Terra's centre every frame and fly ahead at full speed (the speed follows
  // the height above the reference body's ground, so the trip takes seconds, not days).
  FlightInput input;
  input.dtS = 0.1;
  input.forward = 1.0;
  glm::dvec3 previous = flight.sceneCamera().position;
  double largestStepM = 0.0, stepAtSwitchM = 0.0, speedAtSwitch = 0.0;
  int frames = 0;
  for (; frames < 2000 && !(flight.referenceBody() == 1 && flight.camera().heightAboveGroundM() < 50.0); ++frames) {
    if (flight.referenceBody() == 2) {
      flight.lookAt(1);
    } else if (flight.camera().heightAboveGroundM() > 1000.0) {  // in Terra's frame: on down
      CameraPose down = flight.camera().pose();
      down.pitchDeg = -90.0;
      flight.camera().setPose(down);
    }
    const double speed = flight.camera().speedMps();
    const uint32_t switches = flight.switches();
    flight.update(input, 66500.0);
    const glm::dvec3 now = flight.sceneCamera().position;
    const double step = glm::length(now - previous);
    // A step is what the speed allows (the ground-following altitude clamp adds a little).
    EXPECT_LE(step, speed * input.dtS * 1.01 + 1e-3) << "frame " << frames;
    largestStepM = std::max(largestStepM, step);
    if (flight.switches() != switches) {
      stepAtSwitchM = step;
      speedAtSwitch = speed;
    }
    previous = now;
  }
  EXPECT_EQ(flight.referenceBody(), 1u) << "Terra should be the reference body at the end";
  EXPECT_EQ(flight.switches(), 1u) << "one change of reference body, Moon to Terra";
  EXPECT_LT(flight.camera().heightAboveGroundM(), 50.0) << "after " << frames << " frames";
  EXPECT_GE(flight.camera().heightAboveGroundM(), FlightSettings{}.eyeHeightM - 1e-6);
  // The switch happens mid-way, at full speed; the camera moves there as it would anywhere.
  EXPECT_GT(speedAtSwitch, 1.0e6);
  EXPECT_LE(stepAtSwitchM, speedAtSwitch * input.dtS * 1.01);
  EXPECT_GT(largestStepM, 1.0e6);
}

TEST(SceneFlight, TravelFliesToAnotherBodyAndStopsAboveItsGround) {
  const SceneDescription scene = resolveScene("system");
  CameraPose pose;
  pose.latitudeDeg = 1.0;
  pose.longitudeDeg = 162.0;
  pose.altitudeM = 0.0;
  SceneFlight flight(scene, 2, pose, 66500.0);
  flight.travelTo(1);
  ASSERT_EQ(flight.travelTarget(), std::optional<size_t>(1));
  FlightInput input;
  input.dtS = 1.0 / 30.0;
  int frames = 0;
  double time = 66500.0;
  for (; frames < 1000 && flight.travelTarget(); ++frames) flight.update(input, time += input.dtS);
  EXPECT_FALSE(flight.travelTarget()) << "still travelling after " << frames << " frames";
  EXPECT_EQ(flight.referenceBody(), 1u);
  EXPECT_LT(flight.camera().heightAboveGroundM(), SceneFlight::kTravelArrivalM);
  EXPECT_GT(flight.camera().heightAboveGroundM(), 0.5 * SceneFlight::kTravelArrivalM);
  EXPECT_LT(frames, 400) << "a few seconds at 30 frames per second";
  // Looking around takes the controls back.
  flight.travelTo(2);
  FlightInput look;
  look.dtS = input.dtS;
  look.lookX = 5.0;
  flight.update(look, time);
  EXPECT_FALSE(flight.travelTarget());
}

TEST(SceneFlight, BadBodiesAreErrors) {
  const SceneDescription scene = resolveScene("system");
  EXPECT_THROW(SceneFlight(scene, 3, CameraPose{}, 0.0), Error);
  SceneFlight flight(scene, 1, CameraPose{}, 0.0);
  EXPECT_THROW(flight.lookAt(flight.referenceBody()), Error);
  EXPECT_THROW(flight.lookAt(7), Error);
}

}  // namespace
}  // namespace planet
