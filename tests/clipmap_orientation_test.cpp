// Per-frame placement of the spherical-clipmap hemisphere (Clasen & Hege 2006; Hayes-McCoy 2010
// §2.4, §4.5): the pole-to-camera basis (orthonormal everywhere, stable across world poles,
// deterministic), the (θ, φ) mapping, the horizon and pixel cuts, and the ring range they select.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "planet/clipmap_orientation.h"

namespace planet {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kEarthRadiusM = 6371000.0;
constexpr double kEverestM = 8848.0;
constexpr double kFovY = kPi / 3.0;  // 60°
constexpr uint32_t kViewportPx = 1080;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A direction rotated by `angle` away from unit `axis`, toward world axis towardAxis (or the next
// one when that is nearly parallel to `axis`).
glm::dvec3 tiltedAway(const glm::dvec3& axis, double angle, int towardAxis) {
  glm::dvec3 toward(0.0);
  toward[towardAxis] = 1.0;
  glm::dvec3 tangent = toward - glm::dot(toward, axis) * axis;
  if (glm::length(tangent) < 0.1) {
    toward = glm::dvec3(0.0);
    toward[(towardAxis + 1) % 3] = 1.0;
    tangent = toward - glm::dot(toward, axis) * axis;
  }
  tangent = glm::normalize(tangent);
  return std::cos(angle) * axis + std::sin(angle) * tangent;
}

// Dense directions: a Fibonacci sphere, the six world axes, the cube diagonals, directions on the
// coordinate planes (ties between two smallest components), and each world axis tilted by 1e−9 and
// 1e−6 rad toward each of the other axes and diagonally.
std::vector<glm::dvec3> testDirections() {
  std::vector<glm::dvec3> dirs;
  const int count = 4000;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    double z = 1.0 - 2.0 * (i + 0.5) / count;
    double rho = std::sqrt(1.0 - z * z);
    dirs.push_back({rho * std::cos(golden * i), rho * std::sin(golden * i), z});
  }
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {1.0, -1.0}) {
      glm::dvec3 a(0.0);
      a[axis] = sign;
      dirs.push_back(a);
      for (double tilt : {1e-9, 1e-6}) {
        for (int toward = 0; toward < 3; ++toward)
          if (toward != axis) dirs.push_back(tiltedAway(a, tilt, toward));
        glm::dvec3 diagonal(1.0);
        diagonal[axis] = 0.0;
        glm::dvec3 tangent = glm::normalize(diagonal);
        dirs.push_back(std::cos(tilt) * a + std::sin(tilt) * tangent);
        dirs.push_back(std::cos(tilt) * a - std::sin(tilt) * tangent);
      }
    }
  }
  for (double sx : {1.0, -1.0})
    for (double sy : {1.0, -1.0})
      for (double sz : {1.0, -1.0}) {
        dirs.push_back(glm::normalize(glm::dvec3(sx, sy, sz)));
        dirs.push_back(glm::normalize(glm::dvec3(sx, sy, 0.0)));
        dirs.push_back(glm::normalize(glm::dvec3(0.0, sy, sz)));
        dirs.push_back(glm::normalize(glm::dvec3(sx, 0.0, sz)));
      }
  return dirs;
}

// Largest deviation of the basis from orthonormality, and its determinant.
double orthonormalityError(const glm::dmat3& m) {
  glm::dmat3 gram = glm::transpose(m) * m;
  double error = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) error = std::max(error, std::abs(gram[i][j] - (i == j ? 1.0 : 0.0)));
  return error;
}

bool allFinite(const glm::dmat3& m) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!std::isfinite(m[i][j])) return false;
  return true;
}

void expectValidBasis(const ClipmapFrame& frame, const glm::dvec3& cameraDirection, const std::string& what) {
  const glm::dmat3& m = frame.localToPlanet;
  ASSERT_TRUE(allFinite(m)) << what;
  EXPECT_LT(orthonormalityError(m), 1e-12) << what;
  EXPECT_NEAR(glm::determinant(m), 1.0, 1e-12) << what;
  EXPECT_LT(glm::length(m[2] - cameraDirection), 1e-12) << what;
}

std::string describe(const glm::dvec3& v) { return fmt::format("({}, {}, {})", v.x, v.y, v.z); }

// Distance between two angles on the circle, in [0, π].
double circularDistance(double a, double b) {
  double d = std::fmod(std::abs(a - b), 2.0 * kPi);
  return std::min(d, 2.0 * kPi - d);
}

// Ring θ from the clean formula (π/2)·2^(−k/m), independent of the library's ldexp form.
double ringThetaFormula(uint32_t ringsPerLevel, uint32_t ring) {
  return 0.5 * kPi * std::exp2(-double(ring) / double(ringsPerLevel));
}

// ---------------------------------------------------------------------------------------------
// Basis

TEST(ClipmapOrientation, BasisIsOrthonormalAndPointsAtCameraForEveryDirection) {
  for (const glm::dvec3& dir : testDirections()) {
    for (double distance : {1.0, kEarthRadiusM + 1.7, kEarthRadiusM + 4e7}) {
      ClipmapFrame frame = orientClipmap(dir * distance, kEarthRadiusM);
      expectValidBasis(frame, dir, "direction " + describe(dir) + " distance " + std::to_string(distance));
    }
  }
}

// The spin is chosen from the pose alone: local x is the local north (the planet's +z projected
// into the tangent plane), so it lies in the plane of +z and the pole, on the side of +z.
TEST(ClipmapOrientation, LocalXPointsNorthEverywhereButAtTheWorldPoles) {
  const glm::dvec3 north(0.0, 0.0, 1.0);
  for (const glm::dvec3& dir : testDirections()) {
    if (std::hypot(dir.x, dir.y) == 0.0) continue;  // the world poles: see CameraAtWorldPole...
    ClipmapFrame frame = orientClipmap(dir * (kEarthRadiusM + 10.0), kEarthRadiusM);
    const glm::dvec3 x = frame.localToPlanet[0];
    EXPECT_GT(x.z, 0.0) << describe(dir);
    EXPECT_LT(std::abs(glm::dot(x, glm::normalize(glm::cross(north, dir)))), 1e-12) << describe(dir);
  }
}

TEST(ClipmapOrientation, CameraAtWorldPoleGetsAFiniteRightHandedBasis) {
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {1.0, -1.0}) {
      glm::dvec3 camera(0.0);
      camera[axis] = sign * (kEarthRadiusM + 100.0);
      ClipmapFrame frame = orientClipmap(camera, kEarthRadiusM);
      glm::dvec3 dir = camera / std::abs(camera[axis]);
      expectValidBasis(frame, dir, "world axis " + describe(dir));
      // Right-handed with the pole as z: x × y = z exactly as the columns say.
      EXPECT_LT(glm::length(glm::cross(frame.localToPlanet[0], frame.localToPlanet[1]) - dir), 1e-15);
    }
  }
}

TEST(ClipmapOrientation, FrameRecordsAltitudeAndDistance) {
  glm::dvec3 camera = glm::normalize(glm::dvec3(1.0, -2.0, 3.0)) * (kEarthRadiusM + 1234.5);
  ClipmapFrame frame = orientClipmap(camera, kEarthRadiusM);
  EXPECT_NEAR(frame.altitudeM, 1234.5, 1e-6);
  EXPECT_NEAR(frame.cameraDistanceM, kEarthRadiusM + 1234.5, 1e-6);
  EXPECT_EQ(frame.radiusM, kEarthRadiusM);
  EXPECT_EQ(frame.cameraPlanetFrame, camera);
  EXPECT_EQ(frame.nadirDirection(), frame.localToPlanet[2]);
  // Below sea level (a valley or the sea floor) is still a valid camera.
  ClipmapFrame below = orientClipmap(glm::dvec3(0.0, 0.0, kEarthRadiusM - 400.0), kEarthRadiusM);
  EXPECT_NEAR(below.altitudeM, -400.0, 1e-9);
}

// Chord between two unit axes modulo a half turn: min(|a − b|, |a + b|). A half turn about the
// pole maps an even-N mesh onto itself (vertex i onto i + N/2), so a spin change of π is no change.
double chordModuloHalfTurn(const glm::dvec3& a, const glm::dvec3& b) {
  return std::min(glm::length(a - b), glm::length(a + b));
}

// The camera walks full great circles in 0.01° steps, through a world pole or 1e−9 rad past it.
// Away from the poles the axes turn smoothly, by at most the step times (1 + 1/sin colatitude)
// (parallel transport plus the turn of the north direction about the pole). Through a pole the
// north frame turns by exactly π, a symmetry of an even-N mesh: modulo that, consecutive frames
// differ by no more than the bound (on a meridian, by just the step), so nothing pops there.
TEST(ClipmapOrientation, BasisTurnsSmoothlyAndThroughWorldPolesOnlyByASymmetry) {
  const double step = 0.01 * kPi / 180.0;
  const int steps = 36000;
  struct Circle {
    glm::dvec3 pole, across;  // the circle is cos t·pole + sin t·across
    bool meridian;            // through the planet's axis
  };
  const std::vector<Circle> circles = {
      {{0, 0, 1}, {1, 0, 0}, true},
      {{0, 0, 1}, {0, 1, 0}, true},
      {{0, 0, 1}, glm::normalize(glm::dvec3(1, 1, 0)), true},
      {{0, 0, -1}, glm::normalize(glm::dvec3(-3, 1, 0)), true},
      {{1, 0, 0}, {0, 1, 0}, false},  // the equator
      {{0, 1, 0}, glm::normalize(glm::dvec3(1, 0, 1)), false},
      // 1e−9 rad off the pole: passes it at a grazing distance.
      {glm::normalize(glm::dvec3(1e-9, 0, 1)), glm::normalize(glm::dvec3(0, 1, 0)), false},
  };
  for (const Circle& circle : circles) {
    ClipmapFrame previous = orientClipmap(circle.pole * (kEarthRadiusM + 500.0), kEarthRadiusM);
    double worstMeridianRatio = 0.0;
    for (int i = 1; i <= steps; ++i) {
      const double t = i * step;
      const glm::dvec3 dir = std::cos(t) * circle.pole + std::sin(t) * circle.across;
      ClipmapFrame frame = orientClipmap(dir * (kEarthRadiusM + 500.0), kEarthRadiusM);
      ASSERT_LT(orthonormalityError(frame.localToPlanet), 1e-12) << "step " << i;
      const double sinColatitude =
          std::min(std::hypot(dir.x, dir.y), std::hypot(previous.localToPlanet[2].x, previous.localToPlanet[2].y));
      // A sample exactly on a pole (world +x there) is not compared.
      for (int axis = 0; axis < 2 && sinColatitude > 0.0; ++axis) {
        const double bound = 1.01 * step * (1.0 + 1.0 / sinColatitude) + 1e-12;
        const double change = chordModuloHalfTurn(frame.localToPlanet[axis], previous.localToPlanet[axis]);
        ASSERT_LE(change, bound) << "axis " << axis << " at step " << i << " on the circle through "
                                 << describe(circle.pole);
        if (circle.meridian) worstMeridianRatio = std::max(worstMeridianRatio, change / step);
      }
      previous = frame;
    }
    // North along a meridian is its own parallel transport: the axes turn by just the step.
    if (circle.meridian) {
      EXPECT_NEAR(worstMeridianRatio, 1.0, 1e-3) << describe(circle.across);
    }
  }
}

// Issue 20, point 8: the frame depends on the pose only, so a loop that returns to its start
// gives back the start's frame bit for bit (parallel transport came back turned by the loop's
// solid angle, and the picture after a flight differed from a fresh render).
TEST(ClipmapOrientation, ClosedLoopReturnsTheSameBasisBitForBit) {
  const double colatitude = kPi / 4.0;
  const int steps = 3600;
  auto dirAt = [&](int i) {
    double lon = 2.0 * kPi * (i % steps) / steps;
    return glm::dvec3(std::sin(colatitude) * std::cos(lon), std::sin(colatitude) * std::sin(lon), std::cos(colatitude));
  };
  ClipmapFrame start = orientClipmap(dirAt(0) * 7e6, kEarthRadiusM);
  ClipmapFrame frame = start;
  for (int i = 1; i <= steps; ++i) frame = orientClipmap(dirAt(i) * 7e6, kEarthRadiusM);
  EXPECT_EQ(std::memcmp(&frame.localToPlanet, &start.localToPlanet, sizeof(glm::dmat3)), 0);
}

TEST(ClipmapOrientation, SameInputsGiveBitIdenticalBases) {
  for (const glm::dvec3& dir : testDirections()) {
    glm::dvec3 camera = dir * (kEarthRadiusM + 321.0);
    ClipmapFrame a = orientClipmap(camera, kEarthRadiusM);
    ClipmapFrame b = orientClipmap(camera, kEarthRadiusM);
    ASSERT_EQ(std::memcmp(&a.localToPlanet, &b.localToPlanet, sizeof(glm::dmat3)), 0) << describe(dir);
  }
}

TEST(ClipmapOrientation, RejectsBadRadiusAndCamera) {
  glm::dvec3 camera(0.0, 0.0, 7e6);
  for (double radius : {kNan, -1.0, 0.0, kInf}) EXPECT_THROW(orientClipmap(camera, radius), Error) << radius;
  EXPECT_THROW(orientClipmap(glm::dvec3(0.0), kEarthRadiusM), Error);
  EXPECT_THROW(orientClipmap(glm::dvec3(kNan, 0.0, 1.0), kEarthRadiusM), Error);
  EXPECT_THROW(orientClipmap(glm::dvec3(kInf, 0.0, 1.0), kEarthRadiusM), Error);
}

// ---------------------------------------------------------------------------------------------
// (θ, φ) mapping

TEST(ClipmapOrientation, PoleAndPhiZeroFollowTheBasisColumns) {
  ClipmapFrame frame = orientClipmap(glm::dvec3(-2e6, 5e6, 3e6), kEarthRadiusM);
  EXPECT_LT(glm::length(localToPlanetDirection(frame, 0.0, 1.234) - frame.localToPlanet[2]), 1e-15);
  EXPECT_LT(glm::length(localToPlanetDirection(frame, kPi / 2, 0.0) - frame.localToPlanet[0]), 1e-15);
  EXPECT_LT(glm::length(localToPlanetDirection(frame, kPi / 2, kPi / 2) - frame.localToPlanet[1]), 1e-15);
}

TEST(ClipmapOrientation, DirectionAndThetaPhiRoundTrip) {
  std::vector<glm::dvec3> cameras = {{0, 0, 7e6}, {0, 0, -7e6}, {3e6, -4e6, 5e6}, {7e6, 1e-3, 0}};
  for (const glm::dvec3& camera : cameras) {
    ClipmapFrame frame = orientClipmap(camera, kEarthRadiusM);
    // direction → (θ, φ) → direction, over the whole sphere, the world poles included.
    for (const glm::dvec3& dir : testDirections()) {
      glm::dvec2 tp = planetToLocalThetaPhi(frame, dir);
      ASSERT_GE(tp.x, 0.0);
      ASSERT_LE(tp.x, kPi);
      ASSERT_GE(tp.y, 0.0);
      ASSERT_LT(tp.y, 2.0 * kPi);
      ASSERT_LT(glm::length(localToPlanetDirection(frame, tp.x, tp.y) - dir), 1e-12) << describe(dir);
      // Scale does not matter.
      glm::dvec2 scaled = planetToLocalThetaPhi(frame, dir * 6.4e6);
      ASSERT_LT(glm::length(localToPlanetDirection(frame, scaled.x, scaled.y) - dir), 1e-12) << describe(dir);
    }
    // (θ, φ) → direction → (θ, φ), away from the pole where φ is defined; ring θ values down to the
    // finest the mesh has, where φ is still well conditioned to 1e−12.
    for (double theta : {1e-3, 0.01, 0.3, 1.0, kPi / 2, 2.5, kPi - 1e-3}) {
      for (int i = 0; i < 64; ++i) {
        double phi = 2.0 * kPi * i / 64.0 + 1e-3;
        glm::dvec2 tp = planetToLocalThetaPhi(frame, localToPlanetDirection(frame, theta, phi));
        ASSERT_NEAR(tp.x, theta, 1e-12);
        ASSERT_LT(circularDistance(tp.y, phi), 1e-12) << "theta " << theta << " phi " << phi;
      }
    }
    // θ stays accurate right at the pole (atan2, not acos).
    glm::dvec2 nearPole = planetToLocalThetaPhi(frame, localToPlanetDirection(frame, 1e-10, 0.5));
    EXPECT_NEAR(nearPole.x, 1e-10, 1e-15);
    // The pole itself: x·n and y·n of the rounded basis are ~1e−17, not always 0.
    glm::dvec2 pole = planetToLocalThetaPhi(frame, frame.localToPlanet[2]);
    EXPECT_LT(pole.x, 1e-15);
  }
}

// ---------------------------------------------------------------------------------------------
// Horizon cut

TEST(ClipmapOrientation, HorizonAtTenKilometresMatchesSmoothSphere) {
  const double h = 10000.0;
  double theta = horizonTheta(kEarthRadiusM, h, 0.0);
  EXPECT_NEAR(theta, std::acos(kEarthRadiusM / (kEarthRadiusM + h)), 1e-12);
  EXPECT_NEAR(theta, 0.0560, 5e-4);
  EXPECT_NEAR(theta * kEarthRadiusM, 357000.0, 1000.0);  // ~357 km of ground to the horizon
}

TEST(ClipmapOrientation, HorizonMarginAddsTheTangentAngleOfTheHighestPeak) {
  for (double h : {2.0, 100.0, 10000.0, 4e5}) {
    double smooth = horizonTheta(kEarthRadiusM, h, 0.0);
    double withPeaks = horizonTheta(kEarthRadiusM, h, kEverestM);
    EXPECT_NEAR(withPeaks - smooth, std::acos(kEarthRadiusM / (kEarthRadiusM + kEverestM)), 1e-12) << h;
    EXPECT_NEAR(withPeaks - smooth, 0.0527, 5e-4) << h;
  }
  // Terrain entirely below sea level is hidden by the water sphere: no margin.
  EXPECT_EQ(horizonTheta(kEarthRadiusM, 1000.0, -500.0), horizonTheta(kEarthRadiusM, 1000.0, 0.0));
}

// Terrain below the radius sphere (a planet without a sea): the grazed sphere is r + L.
TEST(ClipmapOrientation, HorizonReachesPastTheRadiusSphereOverLowerTerrain) {
  const double r = 3.3895e6, h = 2.0, high = 8000.0, low = -4000.0;
  const double theta = horizonTheta(r, h, high, low);
  EXPECT_NEAR(theta, std::acos((r + low) / (r + h)) + std::acos((r + low) / (r + high)), 1e-9);
  EXPECT_GT(theta, horizonTheta(r, h, high) + 0.02);  // the radius sphere's horizon cut much nearer
  // Above the radius sphere a lowest surface changes nothing (a sea at 0 hides what lies below).
  EXPECT_EQ(horizonTheta(r, h, high, 500.0), horizonTheta(r, h, high));
  EXPECT_EQ(horizonTheta(r, h, high, 0.0), horizonTheta(r, h, high));
  EXPECT_THROW(horizonTheta(r, h, high, std::nan("")), Error);
  EXPECT_THROW(horizonTheta(r, h, high, -2.0 * r), Error);
}

TEST(ClipmapOrientation, HorizonGrowsWithAltitudeUpToTheRim) {
  double last = 0.0;
  for (double h = 0.01; h < 1e13; h *= 1.1) {
    double theta = horizonTheta(kEarthRadiusM, h, kEverestM);
    ASSERT_GE(theta, last) << h;
    ASSERT_LE(theta, kPi / 2) << h;
    ASSERT_GE(theta, kClipmapMinHorizonTheta) << h;
    last = theta;
  }
  // Without terrain the horizon only approaches the rim (π/2 − r/h); infinity reaches it.
  EXPECT_NEAR(horizonTheta(kEarthRadiusM, 1e13, 0.0), kPi / 2, 1e-6);
  EXPECT_EQ(horizonTheta(kEarthRadiusM, kInf, 0.0), kPi / 2);
  EXPECT_EQ(horizonTheta(kEarthRadiusM, 1e9, kEverestM), kPi / 2);
  // Still below the rim at a geostationary-like distance without terrain.
  EXPECT_LT(horizonTheta(kEarthRadiusM, 3.6e7, 0.0), kPi / 2);
}

TEST(ClipmapOrientation, HorizonUsesOneMetreFloorAtOrBelowSeaLevel) {
  double floor = horizonTheta(kEarthRadiusM, kClipmapMinAltitudeM, kEverestM);
  EXPECT_EQ(horizonTheta(kEarthRadiusM, 0.0, kEverestM), floor);
  EXPECT_EQ(horizonTheta(kEarthRadiusM, -300.0, kEverestM), floor);
  EXPECT_GT(horizonTheta(kEarthRadiusM, 0.0, 0.0), 0.0);
  EXPECT_NEAR(horizonTheta(kEarthRadiusM, -1.0, 0.0), std::sqrt(2.0 / kEarthRadiusM), 1e-9);
}

TEST(ClipmapOrientation, HorizonRejectsBadInputs) {
  for (double radius : {kNan, -1.0, 0.0, kInf}) EXPECT_THROW(horizonTheta(radius, 100.0, 0.0), Error) << radius;
  EXPECT_THROW(horizonTheta(kEarthRadiusM, kNan, 0.0), Error);
  EXPECT_THROW(horizonTheta(kEarthRadiusM, 100.0, kNan), Error);
}

// ---------------------------------------------------------------------------------------------
// Pixel cut

TEST(ClipmapOrientation, MinUsefulThetaScalesLinearlyWithAltitudeAndPixelSize) {
  const uint32_t m = 16;
  double base = minUsefulTheta(kEarthRadiusM, 1000.0, kFovY, kViewportPx, m);
  EXPECT_NEAR(minUsefulTheta(kEarthRadiusM, 2000.0, kFovY, kViewportPx, m) / base, 2.0, 1e-12);
  EXPECT_NEAR(minUsefulTheta(kEarthRadiusM, 10.0, kFovY, kViewportPx, m) / base, 0.01, 1e-12);
  // Half the pixels on the same field of view: each pixel twice as large.
  EXPECT_NEAR(minUsefulTheta(kEarthRadiusM, 1000.0, kFovY, kViewportPx / 2, m) / base, 2.0, 1e-12);
  // tan(fov/2) doubled: pixels twice as large.
  double fov2 = 2.0 * std::atan(2.0 * std::tan(kFovY / 2.0));
  EXPECT_NEAR(minUsefulTheta(kEarthRadiusM, 1000.0, fov2, kViewportPx, m) / base, 2.0, 1e-12);
  // The absolute value: s = h·tan(30°)/540, θ = s/r/(1 − 2^(−1/16)).
  double s = 1000.0 * std::tan(kPi / 6.0) / 540.0;
  EXPECT_NEAR(pixelFootprintTheta(kEarthRadiusM, 1000.0, kFovY, kViewportPx), s / kEarthRadiusM, 1e-20);
  EXPECT_NEAR(base, s / kEarthRadiusM / (1.0 - std::exp2(-1.0 / 16.0)), 1e-18);
}

TEST(ClipmapOrientation, RingSpacingAtMinUsefulThetaIsOnePixel) {
  for (uint32_t m : {1u, 4u, 16u, 64u}) {
    double theta = minUsefulTheta(kEarthRadiusM, 500.0, kFovY, kViewportPx, m);
    double spacing = theta * (1.0 - std::exp2(-1.0 / double(m)));
    EXPECT_NEAR(spacing / pixelFootprintTheta(kEarthRadiusM, 500.0, kFovY, kViewportPx), 1.0, 1e-12) << m;
  }
}

TEST(ClipmapOrientation, MinUsefulThetaClampsAndRejectsBadInputs) {
  EXPECT_EQ(minUsefulTheta(kEarthRadiusM, 1e12, kFovY, kViewportPx, 16), kPi / 2);
  EXPECT_EQ(minUsefulTheta(kEarthRadiusM, -5.0, kFovY, kViewportPx, 16),
            minUsefulTheta(kEarthRadiusM, kClipmapMinAltitudeM, kFovY, kViewportPx, 16));
  EXPECT_THROW(minUsefulTheta(kNan, 100.0, kFovY, kViewportPx, 16), Error);
  EXPECT_THROW(minUsefulTheta(-1.0, 100.0, kFovY, kViewportPx, 16), Error);
  EXPECT_THROW(minUsefulTheta(kEarthRadiusM, kNan, kFovY, kViewportPx, 16), Error);
  EXPECT_THROW(minUsefulTheta(kEarthRadiusM, 100.0, 0.0, kViewportPx, 16), Error);
  EXPECT_THROW(minUsefulTheta(kEarthRadiusM, 100.0, kPi, kViewportPx, 16), Error);
  EXPECT_THROW(minUsefulTheta(kEarthRadiusM, 100.0, kNan, kViewportPx, 16), Error);
  EXPECT_THROW(minUsefulTheta(kEarthRadiusM, 100.0, kFovY, 0, 16), Error);
  EXPECT_THROW(minUsefulTheta(kEarthRadiusM, 100.0, kFovY, kViewportPx, 0), Error);
}

// ---------------------------------------------------------------------------------------------
// Ring selection

void expectRangeCovers(uint32_t levels, uint32_t m, double thetaMax, double thetaMin, const std::string& what) {
  const uint32_t ringCount = levels * m;
  RingRange range = selectRings(levels, m, thetaMax, thetaMin);
  double outer = std::min(thetaMax, kPi / 2);
  double inner = std::min(thetaMin, outer);
  const double tol = 1e-15;  // the library's ldexp form and the test's exp2 form differ by an ulp
  ASSERT_LE(range.firstRing, range.lastRing) << what;
  ASSERT_LT(range.lastRing, ringCount) << what;
  ASSERT_TRUE(range.includePole) << what;
  // Outer edge reaches the horizon; one ring further in would not.
  EXPECT_GE(ringThetaFormula(m, range.firstRing) * (1.0 + tol), outer) << what;
  if (range.firstRing + 1 < ringCount) {
    EXPECT_LT(ringThetaFormula(m, range.firstRing + 1) * (1.0 - tol), outer) << what;
  }
  // Inner edge reaches thetaMin (the fan covers the rest), unless the mesh has no finer ring...
  if (range.lastRing + 1 < ringCount) {
    EXPECT_LE(ringThetaFormula(m, range.lastRing) * (1.0 - tol), inner) << what;
  }
  // ...and no further in than needed: every drawn quad band is at least thetaMin's ring spacing
  // (a pixel, when thetaMin is minUsefulTheta).
  if (range.lastRing > range.firstRing) {
    EXPECT_GT(ringThetaFormula(m, range.lastRing - 1) * (1.0 + tol), inner) << what;
  }
}

TEST(ClipmapOrientation, SelectedRingsCoverHorizonToPixelCutFromOrbitToGround) {
  struct Mesh {
    uint32_t levels, m;
  };
  for (Mesh mesh : {Mesh{20, 16}, Mesh{18, 16}, Mesh{21, 8}, Mesh{3, 1}, Mesh{40, 2}, Mesh{12, 64}}) {
    for (double h = 4e7; h >= 1.7; h /= 1.3) {
      double thetaMax = horizonTheta(kEarthRadiusM, h, kEverestM);
      double thetaMin = minUsefulTheta(kEarthRadiusM, h, kFovY, kViewportPx, mesh.m);
      expectRangeCovers(
          mesh.levels, mesh.m, thetaMax, thetaMin,
          "L=" + std::to_string(mesh.levels) + " m=" + std::to_string(mesh.m) + " h=" + std::to_string(h));
    }
    expectRangeCovers(mesh.levels, mesh.m, horizonTheta(kEarthRadiusM, 1.7, 0.0),
                      minUsefulTheta(kEarthRadiusM, 1.7, kFovY, kViewportPx, mesh.m), "h=1.7 exactly");
  }
}

TEST(ClipmapOrientation, SelectedRingsCoverArbitraryAndEdgeAngles) {
  const uint32_t levels = 10, m = 4, ringCount = levels * m;
  std::vector<double> angles = {0.0, 1e-300, 1e-9, kPi / 2, 2.0, kInf, -1.0};
  for (uint32_t k = 0; k < ringCount; ++k) {
    double t = ringThetaFormula(m, k);
    angles.insert(angles.end(), {t, std::nextafter(t, 0.0), std::nextafter(t, 10.0), t * 0.999, t * 1.001});
  }
  for (double a : angles)
    for (double b : angles) {
      std::string what = "thetaMax " + std::to_string(a) + " thetaMin " + std::to_string(b);
      expectRangeCovers(levels, m, a, b, what);
    }
}

TEST(ClipmapOrientation, SelectRingsHandlesTheExtremes) {
  // Everything: rim to innermost ring.
  RingRange all = selectRings(18, 16, kPi / 2, 0.0);
  EXPECT_EQ(all.firstRing, 0u);
  EXPECT_EQ(all.lastRing, 18u * 16u - 1u);
  // A horizon inside the innermost ring: only the pole fan.
  RingRange tiny = selectRings(18, 16, 1e-12, 0.0);
  EXPECT_EQ(tiny.firstRing, 18u * 16u - 1u);
  EXPECT_EQ(tiny.lastRing, 18u * 16u - 1u);
  // A fine cut beyond the horizon: at most the one band around thetaMax, closed by the fan.
  RingRange inverted = selectRings(18, 16, 0.1, 1.0);
  EXPECT_EQ(inverted.lastRing, inverted.firstRing + 1);
  EXPECT_GE(ringThetaFormula(16, inverted.firstRing), 0.1);
  EXPECT_LE(ringThetaFormula(16, inverted.lastRing), 0.1);
  // ...and exactly at a ring (ring 32 = level 3's first, θ = π/8 exactly): that ring alone,
  // closed by the fan.
  RingRange atRing = selectRings(18, 16, kPi / 8, 2.0);
  EXPECT_EQ(atRing.firstRing, 32u);
  EXPECT_EQ(atRing.lastRing, 32u);
  // One ring in the whole mesh.
  RingRange single = selectRings(1, 1, 0.3, 0.1);
  EXPECT_EQ(single.firstRing, 0u);
  EXPECT_EQ(single.lastRing, 0u);
  EXPECT_TRUE(single.includePole);
}

TEST(ClipmapOrientation, SelectRingsRejectsBadInputs) {
  EXPECT_THROW(selectRings(0, 16, 1.0, 0.1), Error);
  EXPECT_THROW(selectRings(18, 0, 1.0, 0.1), Error);
  EXPECT_THROW(selectRings(kClipmapOrientationMaxLevels + 1, 16, 1.0, 0.1), Error);
  EXPECT_THROW(selectRings(18, kClipmapOrientationMaxRingsPerLevel + 1, 1.0, 0.1), Error);
  EXPECT_THROW(selectRings(18, 16, kNan, 0.1), Error);
  EXPECT_THROW(selectRings(18, 16, 1.0, kNan), Error);
}

TEST(ClipmapOrientation, SelectedRingsShrinkAsTheCameraClimbs) {
  // Higher camera: the horizon moves out (firstRing ≤) and the pixel cut moves out (lastRing ≤).
  RingRange last = selectRings(20, 16, horizonTheta(kEarthRadiusM, 1.7, kEverestM),
                               minUsefulTheta(kEarthRadiusM, 1.7, kFovY, kViewportPx, 16));
  for (double h = 2.0; h < 4e7; h *= 1.5) {
    RingRange range = selectRings(20, 16, horizonTheta(kEarthRadiusM, h, kEverestM),
                                  minUsefulTheta(kEarthRadiusM, h, kFovY, kViewportPx, 16));
    EXPECT_LE(range.firstRing, last.firstRing) << h;
    EXPECT_LE(range.lastRing, last.lastRing) << h;
    last = range;
  }
  // From 40,000 km the fine cut removes most rings of an Earth-scale mesh.
  EXPECT_LT(last.lastRing, 60u);
}

// ---------------------------------------------------------------------------------------------
// Metres per vertex

TEST(ClipmapOrientation, TwentyLevelsReachSubHalfMetreSpacingOnEarthAtTwoMetres) {
  // m = 16 rings per level and N = 148 ≈ 2π/(1 − 2^(−1/16)) vertices per ring (square quads).
  const uint32_t m = 16, numPhi = 148;
  const double h = 2.0;
  auto spacingFor = [&](uint32_t levels) {
    RingRange range = selectRings(levels, m, horizonTheta(kEarthRadiusM, h, kEverestM),
                                  minUsefulTheta(kEarthRadiusM, h, kFovY, kViewportPx, m));
    // At 2 m the pixel cut lies far inside the innermost ring: everything down to it is drawn.
    EXPECT_EQ(range.lastRing, levels * m - 1) << levels;
    return metresPerVertexAtNadir(kEarthRadiusM, levels, m, numPhi, range.lastRing);
  };
  double at20 = spacingFor(20), at19 = spacingFor(19);
  EXPECT_LT(at20, 0.5);
  EXPECT_GT(at19, 0.5);  // so 20 levels is the least that does it
  EXPECT_NEAR(at20, 0.442, 0.002);
  // The radial edge alone, (π/2)·r·2^(−(K−2)/m)·(1 − 2^(−1/m)), from the clean formula.
  double radial = 0.5 * kPi * kEarthRadiusM * std::exp2(-(20.0 * m - 2.0) / m) * (1.0 - std::exp2(-1.0 / m));
  EXPECT_LE(radial, at20 * (1.0 + 1e-12));
  EXPECT_NEAR(radial, at20, 0.01);
  // The mesh default's N = 128 is too coarse in φ for 0.5 m at 20 levels.
  EXPECT_GT(metresPerVertexAtNadir(kEarthRadiusM, 20, m, 128, 20 * m - 1), 0.5);
  // The fan under the camera is ~m/ln2 ring spacings across: about 10 m.
  EXPECT_NEAR(poleCapRadiusM(kEarthRadiusM, 20, m, 20 * m - 1), 9.96, 0.05);
}

TEST(ClipmapOrientation, MetresPerVertexHalvesPerLevelAndRejectsBadInputs) {
  // Past the first few levels sin θ ≈ θ, so one level further in halves the spacing.
  const uint32_t m = 8, numPhi = 64;
  for (uint32_t ring = 10 * m; ring < 20 * m; ++ring)
    EXPECT_NEAR(metresPerVertexAtNadir(kEarthRadiusM, 20, m, numPhi, ring - m) /
                    metresPerVertexAtNadir(kEarthRadiusM, 20, m, numPhi, ring),
                2.0, 1e-5)
        << ring;
  // Ring 0 against the pole: the whole hemisphere's radius in one radial edge.
  EXPECT_NEAR(metresPerVertexAtNadir(kEarthRadiusM, 10, m, numPhi, 0), kEarthRadiusM * kPi / 2, 1e-6);
  EXPECT_THROW(metresPerVertexAtNadir(kEarthRadiusM, 10, m, numPhi, 10 * m), Error);
  EXPECT_NO_THROW(metresPerVertexAtNadir(kEarthRadiusM, 10, m, numPhi, 10 * m - 1));
  EXPECT_THROW(metresPerVertexAtNadir(kEarthRadiusM, 10, m, 2, 5), Error);
  EXPECT_THROW(metresPerVertexAtNadir(kNan, 10, m, numPhi, 5), Error);
  EXPECT_THROW(metresPerVertexAtNadir(kEarthRadiusM, 0, m, numPhi, 0), Error);
  EXPECT_THROW(poleCapRadiusM(kEarthRadiusM, 10, m, 10 * m), Error);
}

}  // namespace
}  // namespace planet
