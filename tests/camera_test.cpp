// Camera and sun placement from the user's terms (latitude, longitude, altitude, heading, pitch).
#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/gtc/matrix_access.hpp>
#include <gtest/gtest.h>

#include "core/error.h"
#include "planet/terrain_height.h"
#include "camera/camera.h"
#include "test_support.h"

namespace planet::test {
namespace {

constexpr double kRadius = 6371000.0;

TEST(Camera, ParsesThreeOrFiveNumbers) {
  CameraPose a = parseCameraPose("10.5,-20,1500");
  EXPECT_EQ(a.latitudeDeg, 10.5);
  EXPECT_EQ(a.longitudeDeg, -20.0);
  EXPECT_EQ(a.altitudeM, 1500.0);
  EXPECT_EQ(a.pitchDeg, -90.0);  // default: looking straight down
  CameraPose b = parseCameraPose("0,0,2,45,-10");
  EXPECT_EQ(b.headingDeg, 45.0);
  EXPECT_EQ(b.pitchDeg, -10.0);
  SunPose sun = parseSunPose("270,5.5");
  EXPECT_EQ(sun.azimuthDeg, 270.0);
  EXPECT_EQ(sun.elevationDeg, 5.5);
}

TEST(Camera, BadTextNamesTheValue) {
  EXPECT_NE(errorOf([] { parseCameraPose("10,20"); }).find("expected 3 or 5 numbers"), std::string::npos);
  EXPECT_NE(errorOf([] { parseCameraPose("10,20,30,40"); }).find("HEADING and PITCH together"), std::string::npos);
  EXPECT_NE(errorOf([] { parseCameraPose("10,abc,30"); }).find("'abc'"), std::string::npos);
  EXPECT_NE(errorOf([] { parseCameraPose("10,nan,30"); }).find("'nan'"), std::string::npos);
  EXPECT_NE(errorOf([] { parseCameraPose("10,,30"); }).find("''"), std::string::npos);
  EXPECT_NE(errorOf([] { parseCameraPose("91,0,30"); }).find("latitude 91"), std::string::npos);
  EXPECT_NE(errorOf([] { parseCameraPose("0,0,30,0,-91"); }).find("pitch -91"), std::string::npos);
  EXPECT_NE(errorOf([] { parseCameraPose("0,0,1e12"); }).find("altitude 1000000000000"), std::string::npos);
  EXPECT_NE(errorOf([] { parseSunPose("10"); }).find("expected 2 numbers"), std::string::npos);
  EXPECT_NE(errorOf([] { parseSunPose("10,95"); }).find("elevation 95"), std::string::npos);
  EXPECT_NE(errorOf([] { parseSunPose(""); }).find("sun ''"), std::string::npos);
}

TEST(Camera, HeadingAndPitchFollowTheLocalHorizon) {
  // At latitude 0, longitude 0: up = +x, north = +z, east = +y.
  CameraPose pose{0.0, 0.0, 100.0, 0.0, 0.0};
  CameraBasis north = cameraBasis(pose, kRadius);
  EXPECT_NEAR(glm::distance(north.position, glm::dvec3(kRadius + 100.0, 0.0, 0.0)), 0.0, 1e-6);
  EXPECT_NEAR(glm::distance(north.forward, glm::dvec3(0.0, 0.0, 1.0)), 0.0, 1e-12);
  EXPECT_NEAR(glm::distance(north.up, glm::dvec3(1.0, 0.0, 0.0)), 0.0, 1e-12);
  pose.headingDeg = 90.0;
  EXPECT_NEAR(glm::distance(cameraBasis(pose, kRadius).forward, glm::dvec3(0.0, 1.0, 0.0)), 0.0, 1e-12);
  pose.pitchDeg = -90.0;  // straight down; the top of the picture points east (the heading)
  CameraBasis down = cameraBasis(pose, kRadius);
  EXPECT_NEAR(glm::distance(down.forward, glm::dvec3(-1.0, 0.0, 0.0)), 0.0, 1e-12);
  EXPECT_NEAR(glm::distance(down.up, glm::dvec3(0.0, 1.0, 0.0)), 0.0, 1e-12);
}

TEST(Camera, BasisIsOrthonormalEverywhereIncludingThePoles) {
  for (double lat : {-90.0, -45.0, 0.0, 30.0, 89.9999, 90.0})
    for (double heading : {0.0, 123.0, 270.0})
      for (double pitch : {-90.0, -30.0, 0.0, 60.0, 90.0}) {
        CameraBasis b = cameraBasis({lat, 17.0, 10.0, heading, pitch}, kRadius);
        EXPECT_NEAR(glm::length(b.forward), 1.0, 1e-12);
        EXPECT_NEAR(glm::length(b.up), 1.0, 1e-12);
        EXPECT_NEAR(glm::dot(b.forward, b.up), 0.0, 1e-12) << lat << " " << heading << " " << pitch;
        // Pitch is the elevation of the view above the local horizon.
        const double elevation = std::asin(std::clamp(glm::dot(b.forward, glm::normalize(b.position)), -1.0, 1.0)) *
                                 180.0 / std::numbers::pi;
        EXPECT_NEAR(elevation, pitch, 1e-6);
      }
}

TEST(Camera, SunElevationIsSeenFromTheCameraGroundPoint) {
  CameraPose camera{40.0, -100.0, 5000.0, 0.0, -90.0};
  const glm::dvec3 up = directionFromLatLon(40.0, -100.0);
  for (double elevation : {-10.0, 0.0, 5.0, 45.0, 90.0}) {
    glm::dvec3 sun = sunDirection({200.0, elevation}, camera);
    EXPECT_NEAR(std::asin(glm::dot(sun, up)) * 180.0 / std::numbers::pi, elevation, 1e-9);
  }
  // Azimuth 90 is east: the sun's horizontal part points along increasing longitude.
  glm::dvec3 east = sunDirection({90.0, 0.0}, camera);
  const glm::dvec3 fartherEast = directionFromLatLon(40.0, -99.9) - directionFromLatLon(40.0, -100.0);
  EXPECT_GT(glm::dot(east, glm::normalize(fartherEast)), 0.999);
}

TEST(Camera, ReversedZMapsNearToOneAndFarTowardZero) {
  const glm::dmat4 p = reversedZPerspective(std::numbers::pi / 3.0, 16.0 / 9.0, 0.5);
  auto depth = [&](double distance) {
    glm::dvec4 clip = p * glm::dvec4(0.0, 0.0, -distance, 1.0);
    return clip.z / clip.w;
  };
  EXPECT_NEAR(depth(0.5), 1.0, 1e-15);
  EXPECT_NEAR(depth(1.0), 0.5, 1e-15);
  EXPECT_NEAR(depth(4.0e7), 0.5 / 4.0e7, 1e-20);
  EXPECT_GT(depth(1.0e3), depth(1.0e3 + 1.0));  // nearer is larger (depth test GREATER)
  // +y in view space is up on screen: Vulkan's clip y points down.
  glm::dvec4 top = p * glm::dvec4(0.0, 1.0, -10.0, 1.0);
  EXPECT_LT(top.y / top.w, 0.0);
}

}  // namespace
}  // namespace planet::test
