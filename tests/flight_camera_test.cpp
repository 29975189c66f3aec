// The viewer's camera controller: speed proportional to the height above the ground, never
// below the ground, free flight along the view, orbit over the ground with geometric zoom, no
// singularity at the poles or the ±180° meridian, and smooth goTo transitions.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "planet/terrain_height.h"
#include "camera/flight_camera.h"
#include "test_support.h"

namespace planet::test {
namespace {

constexpr double kRadius = 6371000.0;
constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kFrameS = 1.0 / 60.0;

FlightCamera::GroundHeight flatGround(double heightM) {
  return [heightM](const glm::dvec3&) { return heightM; };
}

// Ridges 2 km high and ~630 m apart: slopes up to ~20:1.
double steepGround(const glm::dvec3& d) { return 1000.0 + 2000.0 * std::sin(d.x * kRadius / 100.0); }

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

glm::dvec3 directionOf(const CameraPose& pose) { return directionFromLatLon(pose.latitudeDeg, pose.longitudeDeg); }

FlightInput frame(double forward = 0.0, double right = 0.0, double up = 0.0) {
  FlightInput input;
  input.dtS = kFrameS;
  input.forward = forward;
  input.right = right;
  input.up = up;
  return input;
}

bool finite(const CameraPose& p) {
  return std::isfinite(p.latitudeDeg) && std::isfinite(p.longitudeDeg) && std::isfinite(p.altitudeM) &&
         std::isfinite(p.headingDeg) && std::isfinite(p.pitchDeg);
}

TEST(FlightCamera, SpeedScalesWithHeightAboveGround) {
  // One second of full forward input covers one height, 40,000 km up as 2 m up; measured along
  // the camera's own path (at 40,000 km the ground point moves R / (R + h) of that: a ground
  // point sweeping 40,000 km a second would lap the planet).
  for (FlightMode mode : {FlightMode::Orbit, FlightMode::Free}) {
    for (double height : {4e7, 2.0}) {
      SCOPED_TRACE(fmt::format("mode {} height {}", int(mode), height));
      FlightCamera camera(kRadius, flatGround(0.0));
      camera.setMode(mode);
      camera.setPose({10.0, 20.0, height, 70.0, mode == FlightMode::Free ? 0.0 : -90.0});
      EXPECT_NEAR(camera.speedMps(), height, 1e-9 * height);
      const glm::dvec3 start = camera.basis().position;
      double pathM = 0.0;
      for (int i = 0; i < 60; ++i) {
        const glm::dvec3 before = camera.basis().position;
        camera.update(frame(1.0));
        pathM += glm::length(camera.basis().position - before);
      }
      EXPECT_NEAR(pathM, height, 0.01 * height);
      EXPECT_NEAR(camera.heightAboveGroundM(), height, 1e-6 * height);  // level: the height is kept
      const double groundM = angleBetween(start, camera.basis().position) * kRadius;
      if (height < 10.0) {
        EXPECT_NEAR(groundM, height, 0.01 * height);
      }
    }
  }
  // speedFactor scales it, and the speed follows the height above the ground, not the altitude.
  FlightCamera camera(kRadius, flatGround(1000.0));
  camera.setPose({0.0, 0.0, 1010.0, 0.0, -90.0});
  FlightInput shift;
  shift.speedFactor = 4.0;
  camera.update(shift);
  EXPECT_NEAR(camera.speedMps(), 40.0, 1e-9);
}

TEST(FlightCamera, NeverBelowTheGround) {
  FlightCamera flat(kRadius, flatGround(1000.0));
  flat.setPose({0.0, 0.0, 0.0, 0.0, -90.0});
  EXPECT_DOUBLE_EQ(flat.pose().altitudeM, 1000.0 + 1.7);  // setPose below the ground is raised
  EXPECT_NEAR(flat.heightAboveGroundM(), 1.7, 1e-9);

  std::mt19937 random(7);
  std::uniform_real_distribution<double> stick(-1.0, 1.0);
  for (FlightMode mode : {FlightMode::Orbit, FlightMode::Free}) {
    FlightCamera steep(kRadius, steepGround);
    steep.setMode(mode);
    steep.setPose({0.0, 0.3, 3000.0, 90.0, -80.0});
    FlightCamera* cameras[] = {&flat, &steep};
    for (FlightCamera* camera : cameras) {
      auto check = [&](int step) {
        const CameraPose& p = camera->pose();
        ASSERT_TRUE(finite(p)) << step;
        const double ground = camera == &flat ? 1000.0 : steepGround(directionOf(p));
        ASSERT_GE(p.altitudeM, ground + 1.7 - 1e-9) << "step " << step;
      };
      // Full down and forward, large hitches, Shift held hard: 100 s of it.
      for (int i = 0; i < 400; ++i) {
        FlightInput input = frame(1.0, 0.0, -1.0);
        input.dtS = 10.0;  // clamped to 0.25 s
        input.speedFactor = 100.0;
        input.lookY = 50.0;  // looking (or tilting) down
        camera->update(input);
        check(i);
      }
      // Random sticks, mouse and zoom over the ridges.
      for (int i = 0; i < 3000; ++i) {
        FlightInput input = frame(stick(random), stick(random), stick(random));
        input.dtS = 0.25 * std::abs(stick(random));
        input.lookX = 20.0 * stick(random);
        input.lookY = 20.0 * stick(random);
        input.zoom = i % 7 == 0 ? 3.0 : 0.0;
        input.speedFactor = 4.0;
        camera->update(input);
        check(i);
      }
    }
  }
}

TEST(FlightCamera, FreeFlightMovesAlongTheViewDirection) {
  FlightCamera camera(kRadius, flatGround(0.0));
  camera.setMode(FlightMode::Free);
  camera.setPose({45.0, 10.0, 1000.0, 30.0, -30.0});
  const CameraBasis before = camera.basis();
  camera.update({.dtS = 0.01, .forward = 1.0});
  const CameraBasis after = camera.basis();
  // 10 m along the 3D view vector (the arc differs from the chord by ~1e-5 m).
  EXPECT_LT(glm::length(after.position - (before.position + 10.0 * before.forward)), 1e-3);
  EXPECT_NEAR(camera.pose().altitudeM, 1000.0 - 10.0 * std::sin(30.0 * kDegree), 1e-3);  // looking down descends
  EXPECT_NEAR(camera.pose().pitchDeg, -30.0, 1e-9);  // carried with the vertical: level stays level
  EXPECT_LT(angleBetween(before.forward, after.forward), 2.0 * 10.0 / kRadius);

  // Looking up climbs; level flight keeps the altitude; right and up move as named.
  camera.setPose({0.0, 0.0, 1000.0, 0.0, 20.0});
  camera.update({.dtS = 0.01, .forward = 1.0});
  EXPECT_NEAR(camera.pose().altitudeM, 1000.0 + 10.0 * std::sin(20.0 * kDegree), 1e-3);
  camera.setPose({0.0, 0.0, 1000.0, 0.0, 0.0});
  camera.update({.dtS = 0.01, .right = 1.0});
  EXPECT_NEAR(camera.pose().altitudeM, 1000.0, 1e-6);
  EXPECT_NEAR(camera.pose().longitudeDeg, 10.0 / (kRadius + 1000.0) / kDegree, 1e-12);  // heading 0: right = east
  EXPECT_NEAR(camera.pose().latitudeDeg, 0.0, 1e-12);
  camera.update({.dtS = 0.01, .up = 1.0});
  EXPECT_NEAR(camera.pose().altitudeM, 1010.0, 1e-3);
}

TEST(FlightCamera, MouseLookTurnsAndClampsPitchInFreeFlight) {
  FlightCamera camera(kRadius, flatGround(0.0));
  camera.setMode(FlightMode::Free);
  EXPECT_DOUBLE_EQ(camera.pose().pitchDeg, -89.9);  // entering free mode leaves the vertical
  camera.setPose({0.0, 0.0, 100.0, 350.0, 0.0});
  camera.update({.dtS = kFrameS, .lookX = 100.0, .lookY = -100.0});  // right and up
  EXPECT_NEAR(camera.pose().headingDeg, 5.0, 1e-9);                  // 350 + 15, wrapped
  EXPECT_NEAR(camera.pose().pitchDeg, 15.0, 1e-9);
  camera.update({.dtS = kFrameS, .lookY = -1e6});
  EXPECT_DOUBLE_EQ(camera.pose().pitchDeg, 89.9);
  camera.update({.dtS = kFrameS, .lookY = 1e6});
  EXPECT_DOUBLE_EQ(camera.pose().pitchDeg, -89.9);
  EXPECT_NEAR(camera.pose().altitudeM, 100.0, 1e-9);  // looking moves nothing
}

TEST(FlightCamera, OrbitLooksDownAndMovesTheGroundPoint) {
  FlightCamera camera(kRadius, flatGround(500.0));
  EXPECT_EQ(camera.mode(), FlightMode::Orbit);
  camera.setMode(FlightMode::Free);
  camera.setPose({10.0, 20.0, 10500.0, 0.0, 0.0});
  camera.setMode(FlightMode::Orbit);
  EXPECT_DOUBLE_EQ(camera.pose().pitchDeg, -90.0);
  EXPECT_NEAR(camera.basis().forward.z, -std::sin(10.0 * kDegree), 1e-12);  // at the nadir

  // Heading 0: forward goes north at 10 km/s (height 10 km), right goes east; the height stays.
  camera.update({.dtS = 0.1, .forward = 1.0});
  EXPECT_NEAR(camera.pose().latitudeDeg, 10.0 + 1000.0 / (kRadius + 10500.0) / kDegree, 1e-9);
  EXPECT_NEAR(camera.pose().longitudeDeg, 20.0, 1e-9);
  EXPECT_NEAR(camera.heightAboveGroundM(), 10000.0, 1e-6);
  const double lat = camera.pose().latitudeDeg;
  camera.update({.dtS = 0.1, .right = 1.0});
  EXPECT_GT(camera.pose().longitudeDeg, 20.0 + 0.5 * 1000.0 / kRadius / kDegree);
  EXPECT_NEAR(camera.pose().latitudeDeg, lat, 1e-6);
  EXPECT_DOUBLE_EQ(camera.pose().pitchDeg, -90.0);

  // Look rotates the heading and tilts within [-90, orbitMaxPitchDeg].
  camera.update({.dtS = kFrameS, .lookX = 200.0});
  EXPECT_NEAR(camera.pose().headingDeg, 30.0, 0.01);  // plus the track's turn moving east
  camera.update({.dtS = kFrameS, .lookY = -100.0});
  EXPECT_NEAR(camera.pose().pitchDeg, -75.0, 1e-9);
  camera.update({.dtS = kFrameS, .lookY = -1e6});
  EXPECT_DOUBLE_EQ(camera.pose().pitchDeg, -30.0);
  camera.update({.dtS = kFrameS, .lookY = 1e6});
  EXPECT_DOUBLE_EQ(camera.pose().pitchDeg, -90.0);
}

TEST(FlightCamera, ZoomMultipliesTheHeightAboveGround) {
  FlightCamera camera(kRadius, flatGround(500.0));
  camera.setPose({10.0, 20.0, 10500.0, 0.0, -90.0});
  camera.update({.zoom = 1.0});  // zoom acts whatever dt
  EXPECT_NEAR(camera.heightAboveGroundM(), 10000.0 * 0.85, 1e-6);
  camera.update({.dtS = kFrameS, .zoom = -3.0});
  EXPECT_NEAR(camera.heightAboveGroundM(), 10000.0 / (0.85 * 0.85), 1e-6);
  EXPECT_NEAR(camera.pose().latitudeDeg, 10.0, 1e-12);
  for (int i = 0; i < 1000; ++i) camera.update({.dtS = kFrameS, .zoom = 10.0});
  EXPECT_NEAR(camera.heightAboveGroundM(), 1.7, 1e-9);
  for (int i = 0; i < 1000; ++i) camera.update({.dtS = kFrameS, .zoom = -10.0});
  EXPECT_NEAR(camera.heightAboveGroundM(), 1e9, 1e-3);
}

TEST(FlightCamera, FlyingOverTheNorthPoleIsContinuous) {
  FlightCamera camera(kRadius, flatGround(0.0));
  camera.setMode(FlightMode::Free);
  camera.setPose({89.5, 30.0, 10000.0, 0.0, 0.0});
  glm::dvec3 forward = camera.basis().forward;
  double highest = -90.0;
  for (int i = 0; i < 1500; ++i) {  // 10 km/s, 25 s: about 1 degree past the pole
    camera.update(frame(1.0));
    ASSERT_TRUE(finite(camera.pose())) << i;
    const glm::dvec3 next = camera.basis().forward;
    ASSERT_LT(angleBetween(forward, next), 0.01 * kDegree) << "frame " << i;
    forward = next;
    highest = std::max(highest, camera.pose().latitudeDeg);
  }
  EXPECT_GT(highest, 89.99);                             // it went over the pole
  EXPECT_LT(camera.pose().latitudeDeg, 89.5);            // and down the other side
  EXPECT_NEAR(camera.pose().longitudeDeg, -150.0, 0.1);  // on the opposite meridian
  EXPECT_NEAR(camera.pose().headingDeg, 180.0, 0.1);     // now heading south
}

TEST(FlightCamera, OrbitOverTheSouthPoleKeepsTheScreenUpContinuous) {
  FlightCamera camera(kRadius, flatGround(0.0));
  camera.setPose({-89.0, -100.0, 5e4, 180.0, -90.0});
  CameraBasis basis = camera.basis();
  for (int i = 0; i < 600; ++i) {  // 50 km/s, 10 s: 500 km, over the pole
    camera.update(frame(1.0));
    ASSERT_TRUE(finite(camera.pose())) << i;
    const CameraBasis next = camera.basis();
    ASSERT_LT(angleBetween(basis.forward, next.forward), 0.02 * kDegree) << "frame " << i;
    ASSERT_LT(angleBetween(basis.up, next.up), 0.02 * kDegree) << "frame " << i;
    basis = next;
  }
  EXPECT_NEAR(camera.pose().latitudeDeg, -89.0 + (500e3 / (kRadius + 5e4) / kDegree - 2.0), 0.01);
  EXPECT_NEAR(camera.pose().longitudeDeg, 80.0, 0.01);
}

TEST(FlightCamera, SittingExactlyAtAPoleIsStable) {
  for (double lat : {90.0, -90.0}) {
    for (FlightMode mode : {FlightMode::Orbit, FlightMode::Free}) {
      FlightCamera camera(kRadius, flatGround(0.0));
      camera.setMode(mode);
      const CameraPose start{lat, 0.0, 100.0, 45.0, mode == FlightMode::Free ? -10.0 : -90.0};
      camera.setPose(start);
      for (int i = 0; i < 100; ++i) camera.update({.dtS = 1e-300});  // zero input, tiny dt
      EXPECT_EQ(camera.pose().latitudeDeg, lat);
      EXPECT_EQ(camera.pose().headingDeg, 45.0);
      EXPECT_EQ(camera.pose().altitudeM, 100.0);
      // Leaving in every direction: finite, and the view turns only by the step's angle.
      for (double heading = 0.0; heading < 360.0; heading += 30.0) {
        CameraPose pose = start;
        pose.headingDeg = heading;
        camera.setPose(pose);
        const CameraBasis before = camera.basis();
        for (auto input : {frame(1.0), frame(0.0, 1.0), frame(-1.0, -1.0, 1.0)}) {
          camera.setPose(pose);
          camera.update(input);
          ASSERT_TRUE(finite(camera.pose()));
          EXPECT_LT(angleBetween(before.forward, camera.basis().forward), 1e-5);
          EXPECT_LT(angleBetween(before.up, camera.basis().up), 1e-5);
          EXPECT_GT(glm::length(camera.basis().position - before.position), 1.0);
        }
      }
    }
  }
}

TEST(FlightCamera, CrossingTheAntimeridianIsContinuous) {
  FlightCamera camera(kRadius, flatGround(0.0));
  camera.setMode(FlightMode::Free);
  camera.setPose({0.0, 179.99, 1000.0, 90.0, 0.0});
  CameraBasis basis = camera.basis();
  for (int i = 0; i < 240; ++i) {  // 1 km/s east for 4 s: 0.036 degrees
    camera.update(frame(1.0));
    const CameraBasis next = camera.basis();
    ASSERT_LT(glm::length(next.position - basis.position), 20.0) << i;
    ASSERT_LT(angleBetween(basis.forward, next.forward), 1e-5) << i;
    ASSERT_GE(camera.pose().longitudeDeg, -180.0);
    ASSERT_LT(camera.pose().longitudeDeg, 180.0);
    basis = next;
  }
  EXPECT_NEAR(camera.pose().longitudeDeg, -180.0 + 0.026, 1e-3);
  EXPECT_NEAR(camera.pose().headingDeg, 90.0, 1e-6);
}

TEST(FlightCamera, BadInputIsIgnored) {
  FlightCamera camera(kRadius, flatGround(0.0));
  const CameraPose start = camera.pose();
  const double nan = std::nan("");
  camera.update({.dtS = nan, .forward = 1.0});
  camera.update({.dtS = -1.0, .forward = 1.0});
  camera.update({.dtS = kFrameS, .forward = nan, .right = INFINITY, .lookX = nan, .zoom = nan});
  camera.update({.dtS = kFrameS, .forward = 1.0, .speedFactor = nan});  // as 1
  EXPECT_TRUE(finite(camera.pose()));
  EXPECT_EQ(camera.pose().longitudeDeg, start.longitudeDeg);
  EXPECT_NEAR(camera.pose().latitudeDeg, start.latitudeDeg + 2e7 * kFrameS / (kRadius + 2e7) / kDegree, 1e-9);
}

TEST(FlightCamera, GoToArrivesSmoothlyAtTheTarget) {
  struct Case {
    CameraPose from;
    double lat, lon, alt;
  } cases[] = {
      {{33.8, -90.0, 2.0, 60.0, -8.0}, -10.0, 170.0, 2.0},      // ground to ground, far
      {{20.0, -30.0, 2e7, 0.0, -60.0}, 33.8, -90.0, 2.0},       // high orbit down to the ground
      {{45.0, 5.0, 1000.0, 90.0, -20.0}, 45.001, 5.0, 1200.0},  // close: no climb
      {{10.0, 20.0, 100.0, 0.0, -10.0}, -10.0, -160.0, 100.0},  // the exact antipode
      {{0.0, 179.0, 100.0, 0.0, -10.0}, 90.0, 0.0, 50.0},       // onto the pole
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(fmt::format("to {},{},{}", c.lat, c.lon, c.alt));
    FlightCamera camera(kRadius, flatGround(0.0));
    camera.setMode(FlightMode::Free);
    camera.setPose(c.from);
    camera.goTo(c.lat, c.lon, c.alt);
    EXPECT_TRUE(camera.transitioning());
    const double startHeight = camera.heightAboveGroundM();
    double highest = 0.0;
    CameraBasis basis = camera.basis();
    const int frames = int(std::lround(camera.settings().goToDurationS / kFrameS));
    for (int i = 0; i < frames; ++i) {
      const double height = camera.heightAboveGroundM();
      camera.update({.dtS = kFrameS});
      ASSERT_TRUE(finite(camera.pose())) << i;
      const CameraBasis next = camera.basis();
      // No jumps: under half the height above the ground per 1/60 s, a few degrees of turn.
      ASSERT_LT(glm::length(next.position - basis.position), 0.5 * std::min(height, camera.heightAboveGroundM()))
          << "frame " << i;
      ASSERT_LT(angleBetween(basis.forward, next.forward), 3.0 * kDegree) << "frame " << i;
      ASSERT_LT(angleBetween(basis.up, next.up), 3.0 * kDegree) << "frame " << i;  // the picture does not spin
      basis = next;
      highest = std::max(highest, camera.heightAboveGroundM());
      if (i + 1 < frames) {
        ASSERT_TRUE(camera.transitioning()) << i;
      }
    }
    EXPECT_FALSE(camera.transitioning());
    EXPECT_NEAR(camera.pose().latitudeDeg, c.lat, 1e-6);
    if (c.lat != 90.0) {
      EXPECT_NEAR(camera.pose().longitudeDeg, c.lon, 1e-6);
    }
    EXPECT_NEAR(camera.pose().altitudeM, c.alt, 1e-3 * c.alt);
    EXPECT_NEAR(camera.pose().headingDeg, c.from.headingDeg, 1e-9);  // arrives as it left
    EXPECT_NEAR(camera.pose().pitchDeg, c.from.pitchDeg, 1e-9);
    const double distance = angleBetween(directionOf(c.from), directionFromLatLon(c.lat, c.lon)) * kRadius;
    if (distance > 10.0 * std::max(startHeight, c.alt)) {
      EXPECT_GT(highest, 0.9 * distance);  // climbs high enough to see both ends
    } else {
      EXPECT_LE(highest, std::max({startHeight, c.alt, distance}) * (1.0 + 1e-9));
    }
  }
}

TEST(FlightCamera, GoToUsesACameraPathOfHeightsAboveTheSurface) {
  FlightCamera camera(kRadius, flatGround(300.0));
  camera.setPose({0.0, 0.0, 302.0, 0.0, -90.0});
  camera.goTo(0.0, 1.0, 1300.0);
  const CameraPath& path = camera.transitionPath();
  ASSERT_GE(path.keys.size(), 3u);
  EXPECT_NO_THROW(validateCameraPath(path, "goTo"));
  EXPECT_NEAR(path.keys.front().heightM, 2.0, 1e-9);
  EXPECT_NEAR(path.keys.back().heightM, 1000.0, 1e-9);
  EXPECT_DOUBLE_EQ(path.durationS(), 4.0);
  // Halfway it is the path's sample, placed on the ground by the camera's ground function.
  for (int i = 0; i < 120; ++i) camera.update({.dtS = kFrameS});
  const CameraKey key = sampleCameraPath(path, 120 * kFrameS);
  EXPECT_NEAR(camera.pose().latitudeDeg, key.latitudeDeg, 1e-9);
  EXPECT_NEAR(camera.pose().longitudeDeg, key.longitudeDeg, 1e-9);
  EXPECT_NEAR(camera.pose().altitudeM, 300.0 + key.heightM, 1e-6);
}

TEST(FlightCamera, InputCancelsGoToWhereItIs) {
  FlightCamera camera(kRadius, flatGround(0.0));
  camera.setPose({0.0, 0.0, 1000.0, 0.0, -90.0});
  camera.goTo(40.0, 40.0, 1000.0);
  for (int i = 0; i < 60; ++i) camera.update({.dtS = kFrameS, .speedFactor = 4.0});  // speed alone: no
  EXPECT_TRUE(camera.transitioning());
  const CameraBasis before = camera.basis();
  const double height = camera.heightAboveGroundM();
  camera.update({.dtS = kFrameS, .forward = 1.0});
  EXPECT_FALSE(camera.transitioning());
  // It moves on from where the transition had got to, at the hand-flying speed.
  EXPECT_LT(glm::length(camera.basis().position - before.position), 1.1 * 4.0 * height * kFrameS);
  for (int i = 0; i < 600; ++i) camera.update({.dtS = kFrameS});
  EXPECT_FALSE(camera.transitioning());
  EXPECT_LT(camera.pose().latitudeDeg, 39.0);

  camera.goTo(10.0, 10.0, 100.0);
  camera.update({.dtS = kFrameS});
  camera.setMode(FlightMode::Free);  // setMode and setPose cancel too
  EXPECT_FALSE(camera.transitioning());
  camera.goTo(10.0, 10.0, 100.0);
  camera.setPose({0.0, 0.0, 100.0, 0.0, 0.0});
  EXPECT_FALSE(camera.transitioning());
}

TEST(FlightCamera, GoToRejectsBadValuesNamingThem) {
  FlightCamera camera(kRadius, flatGround(0.0));
  const CameraPose start = camera.pose();
  EXPECT_NE(errorOf([&] { camera.goTo(91.0, 0.0, 100.0); }).find("latitude 91"), std::string::npos);
  EXPECT_NE(errorOf([&] { camera.goTo(-90.5, 0.0, 100.0); }).find("latitude -90.5"), std::string::npos);
  EXPECT_NE(errorOf([&] { camera.goTo(std::nan(""), 0.0, 100.0); }).find("latitude nan"), std::string::npos);
  EXPECT_NE(errorOf([&] { camera.goTo(0.0, INFINITY, 100.0); }).find("longitude inf"), std::string::npos);
  EXPECT_NE(errorOf([&] { camera.goTo(0.0, 0.0, std::nan("")); }).find("altitude nan"), std::string::npos);
  EXPECT_NE(errorOf([&] { camera.setPose({95.0, 0.0, 100.0, 0.0, 0.0}); }).find("latitude 95"), std::string::npos);
  EXPECT_FALSE(camera.transitioning());
  EXPECT_EQ(camera.pose().latitudeDeg, start.latitudeDeg);
  // The ground function and the settings are checked too.
  EXPECT_NE(errorOf([] { FlightCamera c(kRadius, nullptr); }).find("ground height"), std::string::npos);
  EXPECT_NE(errorOf([] { FlightCamera c(kRadius, flatGround(0.0), {.eyeHeightM = 0.0}); }).find("eyeHeightM 0"),
            std::string::npos);
  EXPECT_NE(errorOf([] { FlightCamera c(kRadius, flatGround(0.0), {.zoomFactor = 1.5}); }).find("zoomFactor 1.5"),
            std::string::npos);
  FlightCamera broken(kRadius, [](const glm::dvec3& d) { return d.z > 0.5 ? std::nan("") : 0.0; });
  EXPECT_NE(errorOf([&] {
              broken.setPose({60.0, 0.0, 100.0, 0.0, -90.0});
            }).find("not a finite number"),
            std::string::npos);
}

TEST(FlightCamera, GoToWithAZeroDurationJumps) {
  FlightCamera camera(kRadius, flatGround(0.0), {.goToDurationS = 0.0});
  camera.goTo({5.0, 370.0, 50.0, -30.0, -90.0});
  EXPECT_FALSE(camera.transitioning());
  EXPECT_DOUBLE_EQ(camera.pose().longitudeDeg, 10.0);  // wrapped
  EXPECT_DOUBLE_EQ(camera.pose().headingDeg, 330.0);
  EXPECT_DOUBLE_EQ(camera.pose().altitudeM, 50.0);
}

}  // namespace
}  // namespace planet::test
