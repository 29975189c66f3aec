// Camera paths (issue 6, point 5): strict parsing with one-line errors naming the file, line and
// value; interpolation geometric in height, along the great circle in position, the short way
// round in heading; the default benchmark path.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "planet/terrain_height.h"
#include "render/camera_path.h"
#include "test_support.h"

namespace planet::test {
namespace {

constexpr double kRadius = 6371000.0;

// The parse error for `text` as file "p.txt", or "" when it parses.
std::string parseError(const std::string& text) {
  return errorOf([&] { parseCameraPath(text, "p.txt"); });
}

CameraPath twoKeys(const CameraKey& a, const CameraKey& b) {
  CameraPath path;
  path.keys = {a, b};
  return path;
}

TEST(CameraPath, ParsesKeysWithCommentsBlankLinesAndTabs) {
  const CameraPath path = parseCameraPath(
      "# time lat lon height heading pitch\n"
      "\n"
      "0 33.8 -90 4e7 0 -90   # from orbit\n"
      "  12.5\t-10\t170.25\t2\t350\t-5\r\n",
      "p.txt");
  ASSERT_EQ(path.keys.size(), 2u);
  EXPECT_EQ(path.keys[0].heightM, 4e7);
  EXPECT_EQ(path.keys[0].pitchDeg, -90.0);
  EXPECT_EQ(path.keys[1].timeS, 12.5);
  EXPECT_EQ(path.keys[1].latitudeDeg, -10.0);
  EXPECT_EQ(path.keys[1].longitudeDeg, 170.25);
  EXPECT_EQ(path.keys[1].heightM, 2.0);
  EXPECT_EQ(path.keys[1].headingDeg, 350.0);
  EXPECT_EQ(path.startS(), 0.0);
  EXPECT_EQ(path.durationS(), 12.5);
}

TEST(CameraPath, ErrorsNameTheFileTheLineAndTheValue) {
  const std::string first = "0 0 0 100 0 -90\n";
  struct Case {
    std::string text, message;
  } cases[] = {
      {first + "1 0 0 100 0 x\n", "p.txt:2: 'x' is not a number"},
      {first + "1 0 0 100 0\n",
       "p.txt:2: expected 6 numbers (time_s lat_deg lon_deg height_m heading_deg pitch_deg), got 5"},
      {first + "1 0 0 100 0 -90 7\n", "p.txt:2: expected 6 numbers"},
      {first + "1 0 0 nan 0 -90\n", "p.txt:2: height_m nan is not a finite number"},
      {first + "inf 0 0 100 0 -90\n", "p.txt:2: time_s inf is not a finite number"},
      {first + "1 91 0 100 0 -90\n", "p.txt:2: lat_deg 91 is outside [-90, 90]"},
      {first + "1 0 400 100 0 -90\n", "p.txt:2: lon_deg 400 is outside [-360, 360]"},
      {first + "1 0 0 0 0 -90\n", "p.txt:2: height_m 0 is outside [0.01, 10000000000]"},
      {first + "1 0 0 100 0 -91\n", "p.txt:2: pitch_deg -91 is outside [-90, 90]"},
      {first + "0 0 1 100 0 -90\n", "p.txt:2: time_s 0 is not after the previous key's 0"},
      {"\n# only one\n" + first, "p.txt: a camera path needs at least 2 keys, got 1"},
      {"", "p.txt: a camera path needs at least 2 keys, got 0"},
      {first + "1 0 180 100 0 -90\n", "p.txt:2: position 0,180 is (nearly) antipodal to the previous key's 0,0"},
  };
  for (const Case& c : cases) {
    const std::string error = parseError(c.text);
    EXPECT_NE(error.find(c.message), std::string::npos) << c.text << "\ngot: " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
  }
  EXPECT_EQ(parseError(first + "1 0 179 100 0 -90\n"), "");  // 179° apart is still defined
}

TEST(CameraPath, ValidationOfPathsBuiltInCodeNamesTheKey) {
  CameraPath path = twoKeys({0, 0, 0, 100, 0, -90}, {0, 0, 1, 100, 0, -90});
  EXPECT_NE(errorOf([&] { validateCameraPath(path, "mine"); }).find("mine: key 2: time_s 0 is not after"),
            std::string::npos);
  path.keys.pop_back();
  EXPECT_NE(errorOf([&] { validateCameraPath(path, "mine"); }).find("at least 2 keys, got 1"), std::string::npos);
}

TEST(CameraPath, LoadsFilesAndNamesMissingOnes) {
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "planet_camera_path_test.txt";
  std::ofstream(file) << "0 1 2 3 4 5\n10 1 2 30 4 5\n";
  EXPECT_EQ(loadCameraPath(file.string()).keys.size(), 2u);
  std::ofstream(file) << "0 1 2 3 4 5\nten 1 2 30 4 5\n";
  EXPECT_NE(errorOf([&] { loadCameraPath(file.string()); }).find(file.string() + ":2: 'ten' is not a number"),
            std::string::npos);
  std::filesystem::remove(file);
  EXPECT_NE(errorOf([&] { loadCameraPath(file.string()); }).find("cannot read '" + file.string() + "'"),
            std::string::npos);
}

TEST(CameraPath, FormatRoundTrips) {
  const CameraPath path = defaultCameraPath(kRadius);
  const CameraPath again = parseCameraPath(formatCameraPath(path), "formatted");
  ASSERT_EQ(again.keys.size(), path.keys.size());
  for (size_t i = 0; i < path.keys.size(); ++i) {
    EXPECT_EQ(again.keys[i].timeS, path.keys[i].timeS);
    EXPECT_EQ(again.keys[i].latitudeDeg, path.keys[i].latitudeDeg);
    EXPECT_EQ(again.keys[i].longitudeDeg, path.keys[i].longitudeDeg);
    EXPECT_EQ(again.keys[i].heightM, path.keys[i].heightM);
    EXPECT_EQ(again.keys[i].headingDeg, path.keys[i].headingDeg);
    EXPECT_EQ(again.keys[i].pitchDeg, path.keys[i].pitchDeg);
  }
}

TEST(CameraPath, HeightIsGeometricSoEveryFactorOfTenTakesEqualTime) {
  const CameraPath path = twoKeys({0, 10, 20, 4e7, 0, -90}, {7, 10, 20, 4, 0, -90});  // 7 decades in 7 s
  for (int second = 0; second <= 7; ++second)
    EXPECT_NEAR(std::log10(sampleCameraPath(path, second).heightM), 7.0 - second + std::log10(4.0), 1e-12) << second;
  EXPECT_NEAR(sampleCameraPath(path, 3.5).heightM, std::sqrt(4e7 * 4.0), 1e-6);
  // A vertical segment keeps the key's exact coordinates.
  EXPECT_EQ(sampleCameraPath(path, 2.2).latitudeDeg, 10.0);
  EXPECT_EQ(sampleCameraPath(path, 2.2).longitudeDeg, 20.0);
}

TEST(CameraPath, PositionFollowsTheGreatCircleAtConstantSpeed) {
  // From (0°, 0°) to (0°, 90°): along the equator.
  const CameraPath equator = twoKeys({0, 0, 0, 10, 0, 0}, {9, 0, 90, 10, 0, 0});
  const CameraKey third = sampleCameraPath(equator, 3.0);
  EXPECT_NEAR(third.latitudeDeg, 0.0, 1e-12);
  EXPECT_NEAR(third.longitudeDeg, 30.0, 1e-12);
  // A general pair: every sample lies on the plane of the great circle, at an angle from the
  // start proportional to time.
  const CameraKey a{0, 40, -100, 10, 0, 0}, b{5, -20, 60, 10, 0, 0};
  const CameraPath path = twoKeys(a, b);
  const glm::dvec3 p = directionFromLatLon(a.latitudeDeg, a.longitudeDeg);
  const glm::dvec3 q = directionFromLatLon(b.latitudeDeg, b.longitudeDeg);
  const glm::dvec3 normal = glm::normalize(glm::cross(p, q));
  const double total = std::acos(glm::dot(p, q));
  for (double t : {0.5, 1.7, 2.5, 4.9}) {
    const CameraKey k = sampleCameraPath(path, t);
    const glm::dvec3 d = directionFromLatLon(k.latitudeDeg, k.longitudeDeg);
    EXPECT_NEAR(glm::dot(d, normal), 0.0, 1e-12) << t;
    EXPECT_NEAR(std::acos(std::clamp(glm::dot(p, d), -1.0, 1.0)), total * t / 5.0, 1e-9) << t;
  }
}

TEST(CameraPath, HeadingTurnsTheShortWayAndPitchIsLinear) {
  const CameraPath path = twoKeys({0, 0, 0, 10, 350, -90}, {4, 0, 0, 10, 10, -10});
  EXPECT_NEAR(std::fmod(sampleCameraPath(path, 2.0).headingDeg + 360.0, 360.0), 0.0, 1e-9);
  EXPECT_NEAR(sampleCameraPath(path, 1.0).headingDeg, 355.0, 1e-9);
  EXPECT_NEAR(sampleCameraPath(path, 1.0).pitchDeg, -70.0, 1e-9);
}

TEST(CameraPath, SamplesOutsideThePathGiveTheEndKeysAndFramesSpanThePath) {
  const CameraPath path = twoKeys({2, 1, 2, 3, 4, 5}, {6, 6, 7, 8, 9, 10});
  EXPECT_EQ(sampleCameraPath(path, -100.0).latitudeDeg, 1.0);
  EXPECT_EQ(sampleCameraPath(path, 2.0).heightM, 3.0);
  EXPECT_EQ(sampleCameraPath(path, 6.0).heightM, 8.0);
  EXPECT_EQ(sampleCameraPath(path, 1e9).pitchDeg, 10.0);
  EXPECT_EQ(frameTimeS(path, 0, 5), 2.0);
  EXPECT_EQ(frameTimeS(path, 2, 5), 4.0);
  EXPECT_EQ(frameTimeS(path, 4, 5), 6.0);
  EXPECT_EQ(frameTimeS(path, 0, 1), 2.0);
}

TEST(CameraPath, DefaultPathDescendsThroughEveryScaleThenTraversesAt300MetresPerSecond) {
  const CameraPath path = defaultCameraPath(kRadius);
  EXPECT_NO_THROW(validateCameraPath(path, "default"));
  EXPECT_EQ(path.keys.front().heightM, 4e7);
  for (double h : {4e5, 1e4, 1e3, 100.0, 2.0}) {
    bool found = false;
    for (const CameraKey& k : path.keys) found = found || k.heightM == h;
    EXPECT_TRUE(found) << h;
  }
  // The last two keys: a traverse at constant height and 300 m/s.
  const CameraKey& a = path.keys[path.keys.size() - 2];
  const CameraKey& b = path.keys.back();
  EXPECT_EQ(a.heightM, b.heightM);
  const glm::dvec3 p = directionFromLatLon(a.latitudeDeg, a.longitudeDeg);
  const glm::dvec3 q = directionFromLatLon(b.latitudeDeg, b.longitudeDeg);
  EXPECT_NEAR(std::acos(glm::dot(p, q)) * kRadius / (b.timeS - a.timeS), 300.0, 0.01);
  // Down to the last metres the height keeps changing by a steady factor per second (100 m at
  // 22 s, 2 m at 29 s).
  const double h27 = sampleCameraPath(path, 27.0).heightM, h28 = sampleCameraPath(path, 28.0).heightM;
  EXPECT_NEAR(h27 / h28, sampleCameraPath(path, 28.0).heightM / 2.0, 1e-9);
}

TEST(CameraPath, PosesStandOnTheSurfaceBelowTheCamera) {
  const PlanetDescription planet = resolvePreset("earth");
  const CameraKey land{0, 33.8, -90, 2, 60, -8};
  const double ground = terrainHeightM(planet, directionFromLatLon(33.8, -90.0));
  ASSERT_GT(ground, planet.seaLevelM) << "the default path starts over land";
  const CameraPose pose = cameraPoseAt(land, planet);
  EXPECT_DOUBLE_EQ(pose.altitudeM, ground + 2.0);
  EXPECT_EQ(pose.headingDeg, 60.0);
  EXPECT_EQ(pose.pitchDeg, -8.0);
  // Over the sea (37.2° N, 118.6° W is 4 km deep on this preset) heights count from the water.
  const CameraKey sea{0, 37.2, -118.6, 10, 0, -90};
  ASSERT_LT(terrainHeightM(planet, directionFromLatLon(37.2, -118.6)), planet.seaLevelM);
  EXPECT_DOUBLE_EQ(cameraPoseAt(sea, planet).altitudeM, planet.seaLevelM + 10.0);
}

}  // namespace
}  // namespace planet::test
