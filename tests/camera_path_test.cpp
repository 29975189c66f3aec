// Camera paths (issue 6, point 5): strict parsing with one-line errors naming the file, line and
// value; interpolation geometric in height, along the great circle in position, the short way
// round in heading; the default benchmark path.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "planet/terrain_height.h"
#include "camera/camera_path.h"
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

// Hostile camera paths (issue 7): each case parses (to `keys` keys) or is a one-line error, of
// bounded length, that contains `says`.
TEST(CameraPath, HostileTextParsesOrGivesOneShortLineNamingTheLineAndValue) {
  const std::string first = "0 0 0 100 0 -90\n";
  const std::string second = "1 0 1 100 0 -90\n";
  std::mt19937 random(9);
  std::string binary(4096, '\0');
  for (char& c : binary) c = char(random());
  std::string manyKeys;
  for (int i = 0; i < 100000; ++i) manyKeys += std::to_string(i) + " 10 20 " + std::to_string(1 + i) + " 0 -90\n";
  struct Case {
    const char* what;
    std::string text;
    size_t keys;       // when `says` is empty
    std::string says;  // part of the error
  } cases[] = {
      {"empty", "", 0, "p.txt: a camera path needs at least 2 keys, got 0"},
      {"comments and blank lines only", "# time lat lon\n\n   \n", 0, "at least 2 keys, got 0"},
      {"a single key", "# one\n" + first, 0, "p.txt: a camera path needs at least 2 keys, got 1"},
      {"CRLF", "0 0 0 100 0 -90\r\n1 0 1 100 0 -90\r\n", 2, ""},
      {"no newline at the end", first + "1 0 1 100 0 -90", 2, ""},
      {"byte order mark", "\xef\xbb\xbf" + first + second, 2, ""},
      {"plus signs", "+0 +0 +0 +100 +0 -90\n" + second, 2, ""},
      {"100,000 keys", manyKeys, 100000, ""},
      // Found by the fuzzer: fields after the seventh were written past the six values.
      {"eight fields", first + "1 0 1 100 0 -90 7 8\n", 0, "p.txt:2: expected 6 numbers (time_s lat_deg lon_deg height_m heading_deg pitch_deg), got 8"},
      {"many fields", first + "1 0 1 100 0 -90 7 8 9 10 11 12 13 14 15 16\n", 0, "got 16"},
      {"equal times", first + "0 0 1 100 0 -90\n", 0, "p.txt:2: time_s 0 is not after the previous key's 0"},
      {"decreasing times", "5 0 0 100 0 -90\n" + second, 0, "p.txt:2: time_s 1 is not after the previous key's 5"},
      {"nan time", "nan 0 0 100 0 -90\n" + second, 0, "p.txt:1: time_s nan is not a finite number"},
      {"inf latitude", first + "1 inf 0 100 0 -90\n", 0, "p.txt:2: lat_deg inf is not a finite number"},
      {"-inf heading", first + "1 0 1 100 -inf -90\n", 0, "p.txt:2: heading_deg -inf is not a finite number"},
      {"huge time", first + "1e300 0 1 100 0 -90\n", 0, "p.txt:2: time_s 1e+300 is outside [-1000000000, 1000000000]"},
      {"times whose difference overflows", "-1.7e308 0 0 100 0 -90\n1.7e308 0 1 100 0 -90\n", 0,
       "p.txt:1: time_s -1.7e+308 is outside"},
      {"beyond double", first + "1 0 1 1e400 0 -90\n", 0, "p.txt:2: '1e400' is out of range for a double"},
      {"latitude past the pole", first + "1 90.5 0 100 0 -90\n", 0, "p.txt:2: lat_deg 90.5 is outside [-90, 90]"},
      {"longitude past a turn", first + "1 0 -361 100 0 -90\n", 0, "p.txt:2: lon_deg -361 is outside [-360, 360]"},
      {"negative height", first + "1 0 1 -5 0 -90\n", 0, "p.txt:2: height_m -5 is outside [0.01, 10000000000]"},
      {"huge height", first + "1 0 1 1e11 0 -90\n", 0, "p.txt:2: height_m 100000000000 is outside"},
      {"pitch past straight up", first + "1 0 1 100 0 90.5\n", 0, "p.txt:2: pitch_deg 90.5 is outside [-90, 90]"},
      {"antipodal keys", first + "1 0 180 100 0 -90\n", 0, "p.txt:2: position 0,180 is (nearly) antipodal"},
      {"a word", first + "1 0 1 high 0 -90\n", 0, "p.txt:2: 'high' is not a number (expected time_s"},
      {"commas", "0,0,0,100,0,-90\n" + second, 0, "p.txt:1: '0,0,0,100,0,-90' is not a number"},
      {"truncated line", first + "1 0 1 10", 0,
       "p.txt:2: expected 6 numbers (time_s lat_deg lon_deg height_m "
       "heading_deg pitch_deg), got 4"},
      {"seven numbers", first + "1 0 1 100 0 -90 3\n", 0, "p.txt:2: expected 6 numbers"},
      {"binary garbage", binary, 0, "p.txt:"},
      {"latin-1", first + "1 0 1 100 0 \xb0-90\n", 0, "p.txt:2: '?-90' is not a number"},
      {"NUL byte", first + std::string("1 0 1 100 0 \0\n", 14), 0, "p.txt:2: '?' is not a number"},
      {"vertical tab", first + "1 0\v1 100 0 -90\n", 0, "p.txt:2: '0?1' is not a number"},
      {"very long field", first + "1 0 1 " + std::string(1 << 20, '7') + " 0 -90\n", 0,
       "p.txt:2: '7777777777777777777777777777777777777777...' is out of range"},
      {"very long word", first + std::string(1 << 20, 'w') + "\n", 0,
       "p.txt:2: 'wwwwwwwwwwwwwwwwwwwwwwwwwwwwwwwwwwwwwwww...' is not a number"},
  };
  for (const Case& c : cases) {
    const auto start = std::chrono::steady_clock::now();
    std::string message;
    size_t keys = 0;
    try {
      keys = parseCameraPath(c.text, "p.txt").keys.size();
    } catch (const Error& e) {
      message = e.what();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // Not a speed claim: a bound that quadratic work on the 100,000-key case (minutes) would
    // break, loose enough for a loaded machine under ASan (1.2 s seen there).
    EXPECT_LT(seconds, 10.0) << c.what;
    if (c.says.empty()) {
      EXPECT_EQ(message, "") << c.what;
      EXPECT_EQ(keys, c.keys) << c.what;
    } else {
      EXPECT_NE(message.find(c.says), std::string::npos) << c.what << "\n got: " << message.substr(0, 300);
      EXPECT_EQ(message.find('\n'), std::string::npos) << c.what;
      EXPECT_EQ(message.find('\0'), std::string::npos) << c.what;
      EXPECT_LT(message.size(), 200u) << c.what;
    }
  }
}

// The file front door: missing, a directory, empty, over the 4 MiB limit.
TEST(CameraPath, UnreadableAndOversizedFilesAreOneLineNamingThePath) {
  const TempDir dir("camera_path_files");
  std::filesystem::create_directories(dir / "sub.path");
  const std::string missing = (dir / "missing.path").string();
  EXPECT_EQ(errorOf([&] { loadCameraPath(missing); }), "cannot read '" + missing + "': No such file or directory");
  const std::string directory = (dir / "sub.path").string();
  EXPECT_EQ(errorOf([&] { loadCameraPath(directory); }), "cannot read '" + directory + "': Is a directory");
  const std::string empty = (dir / "empty.path").string();
  std::ofstream(empty).close();
  EXPECT_EQ(errorOf([&] { loadCameraPath(empty); }), empty + ": a camera path needs at least 2 keys, got 0");
  const std::string big = (dir / "big.path").string();
  std::ofstream(big) << std::string((size_t(4) << 20) + 1, '#');
  EXPECT_EQ(errorOf([&] { loadCameraPath(big); }), big + ": larger than 4194304 bytes");
}

TEST(CameraPath, ValidationOfPathsBuiltInCodeNamesTheKey) {
  CameraPath path = twoKeys({0, 0, 0, 100, 0, -90}, {0, 0, 1, 100, 0, -90});
  EXPECT_NE(errorOf([&] { validateCameraPath(path, "mine"); }).find("mine: key 2: time_s 0 is not after"),
            std::string::npos);
  path.keys.pop_back();
  EXPECT_NE(errorOf([&] { validateCameraPath(path, "mine"); }).find("at least 2 keys, got 1"), std::string::npos);
}

TEST(CameraPath, LoadsFilesAndNamesMissingOnes) {
  const TempDir dir("camera_path_test");
  const std::filesystem::path file = dir / "path.txt";
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
  // Over the sea (20° N, 30° W is 3.7 km deep on this preset) heights count from the water.
  const CameraKey sea{0, 20.0, -30.0, 10, 0, -90};
  ASSERT_LT(terrainHeightM(planet, directionFromLatLon(20.0, -30.0)), planet.seaLevelM);
  EXPECT_DOUBLE_EQ(cameraPoseAt(sea, planet).altitudeM, planet.seaLevelM + 10.0);
}

}  // namespace
}  // namespace planet::test
