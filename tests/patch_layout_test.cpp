// Where the patch textures lie (engine/render/patch_layout.h): the cube faces and their gnomonic
// coordinates, and the layout of levels around a camera (finest texel size, recentring,
// layers), including every bad setting.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "render/patch_layout.h"
#include "test_support.h"

namespace planet {
namespace {

using test::errorOf;

constexpr double kEarthRadiusM = 6371000.0;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Deterministic pseudo-random doubles in [lo, hi) (mt19937 is specified bit for bit).
class Random {
 public:
  explicit Random(uint32_t seed) : engine_(seed) {}
  double uniform(double lo, double hi) { return lo + (hi - lo) * (double(engine_()) / 4294967296.0); }
  glm::dvec3 direction() {
    for (;;) {
      glm::dvec3 v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
      double length = glm::length(v);
      if (length > 0.1 && length <= 1.0) return v / length;
    }
  }

 private:
  std::mt19937 engine_;
};

int64_t floorDiv(int64_t value, int64_t step) { return value / step - (value % step != 0 && value < 0 ? 1 : 0); }

TEST(PatchLayout, CubeFacesAreOrthonormalRightHandedAndInOrder) {
  const glm::dvec3 normals[kCubeFaceCount] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int face = 0; face < kCubeFaceCount; ++face) {
    const CubeFace f = cubeFace(face);
    EXPECT_EQ(f.normal, normals[face]) << face;
    EXPECT_EQ(glm::length(f.axisA), 1.0) << face;
    EXPECT_EQ(glm::length(f.axisB), 1.0) << face;
    EXPECT_EQ(glm::dot(f.axisA, f.axisB), 0.0) << face;
    EXPECT_EQ(glm::dot(f.axisA, f.normal), 0.0) << face;
    EXPECT_EQ(glm::dot(f.axisB, f.normal), 0.0) << face;
    EXPECT_EQ(glm::cross(f.axisA, f.axisB), f.normal) << face;
  }
  EXPECT_NE(errorOf([] { cubeFace(6); }).find("6"), std::string::npos);
  EXPECT_NE(errorOf([] { cubeFace(-1); }).find("-1"), std::string::npos);
}

TEST(PatchLayout, DominantFaceAtCentresEdgesAndCorners) {
  for (int face = 0; face < kCubeFaceCount; ++face) {
    EXPECT_EQ(dominantCubeFace(cubeFace(face).normal), face);
    EXPECT_EQ(dominantCubeFace(3.5 * cubeFace(face).normal), face);  // need not be unit
  }
  // Edges: two faces tie, the lower index wins; tilted by 1e-12 toward the other, it wins.
  for (int f = 0; f < kCubeFaceCount; ++f) {
    for (int g = f + 1; g < kCubeFaceCount; ++g) {
      if (g / 2 == f / 2) continue;  // opposite faces share no edge
      const glm::dvec3 nf = cubeFace(f).normal, ng = cubeFace(g).normal;
      EXPECT_EQ(dominantCubeFace(nf + ng), f) << f << " " << g;
      EXPECT_EQ(dominantCubeFace(nf + (1.0 + 1e-12) * ng), g) << f << " " << g;
    }
  }
  // Corners: three faces tie, the x face (lowest index) wins; a nudge picks each of the three.
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 d((corner & 1) ? -1.0 : 1.0, (corner & 2) ? -1.0 : 1.0, (corner & 4) ? -1.0 : 1.0);
    const int faceX = d.x > 0 ? 0 : 1, faceY = d.y > 0 ? 2 : 3, faceZ = d.z > 0 ? 4 : 5;
    EXPECT_EQ(dominantCubeFace(d), faceX) << corner;
    EXPECT_EQ(dominantCubeFace(d + glm::dvec3(0, 1e-12 * d.y, 0)), faceY) << corner;
    EXPECT_EQ(dominantCubeFace(d + glm::dvec3(0, 0, 1e-12 * d.z)), faceZ) << corner;
  }
  EXPECT_NE(errorOf([] { dominantCubeFace(glm::dvec3(0.0)); }).find("(0, 0, 0)"), std::string::npos);
  EXPECT_NE(errorOf([] { dominantCubeFace({kNan, 0, 1}); }).find("nan"), std::string::npos);
  EXPECT_NE(errorOf([] { dominantCubeFace({1, kInf, 0}); }).find("inf"), std::string::npos);
}

TEST(PatchLayout, FaceDirectionAndCoordinatesRoundTrip) {
  Random random(7);
  for (int face = 0; face < kCubeFaceCount; ++face) {
    const CubeFace f = cubeFace(face);
    EXPECT_EQ(cubeFaceDirection(face, 0, 0), f.normal);
    EXPECT_LT(glm::length(cubeFaceDirection(face, 1, 0) - glm::normalize(f.normal + f.axisA)), 1e-15);
    for (int i = 0; i < 500; ++i) {
      const double a = random.uniform(-1, 1), b = random.uniform(-1, 1);
      const glm::dvec3 d = cubeFaceDirection(face, a, b);
      EXPECT_NEAR(glm::length(d), 1.0, 1e-15);
      EXPECT_EQ(dominantCubeFace(d), face) << a << " " << b;
      const glm::dvec2 ab = cubeFaceCoordinates(face, d);
      EXPECT_NEAR(ab.x, a, 4e-16) << face;
      EXPECT_NEAR(ab.y, b, 4e-16) << face;
      // Scaled and off-face directions: coordinates ignore length; beyond the face they still map
      // back (gnomonic coordinates cover the whole open hemisphere).
      EXPECT_NEAR(cubeFaceCoordinates(face, 7.0 * d).x, a, 4e-16);
      const glm::dvec2 far = cubeFaceCoordinates(face, cubeFaceDirection(face, 40 * a, -25 * b));
      EXPECT_NEAR(far.x, 40 * a, 1e-13);
      EXPECT_NEAR(far.y, -25 * b, 1e-13);
    }
    // The other hemisphere, and its boundary, have no coordinates on this face.
    EXPECT_NE(errorOf([&] { cubeFaceCoordinates(face, -f.normal); }).find(fmt::format("face {}", face)),
              std::string::npos);
    EXPECT_THROW(cubeFaceCoordinates(face, f.axisA), Error);
    EXPECT_THROW(cubeFaceCoordinates(face, {kNan, kNan, kNan}), Error);
  }
  EXPECT_THROW(cubeFaceDirection(6, 0, 0), Error);
  EXPECT_THROW(cubeFaceCoordinates(-1, {1, 0, 0}), Error);
}

// Every documented property of one layout.
void checkLayout(const PatchSettings& settings, double radiusM, const glm::dvec3& camera, double nadirPixelM,
                 const PatchLayout& layout) {
  SCOPED_TRACE(fmt::format("camera ({}, {}, {}), nadir pixel {} m, radius {} m", camera.x, camera.y, camera.z,
                           nadirPixelM, radiusM));
  ASSERT_EQ(layout.face, dominantCubeFace(camera));
  ASSERT_EQ(layout.resolution, settings.resolution);
  ASSERT_EQ(layout.levels.size(), settings.levelCount);
  const glm::dvec2 ab = cubeFaceCoordinates(layout.face, camera);
  const double scale = std::sqrt(1.0 + ab.x * ab.x + ab.y * ab.y);
  const double target = nadirPixelM / settings.texelsPerNadirPixel;
  auto fits = [&](int e) { return radiusM * std::ldexp(1.0, e) / scale <= target; };
  // Finest: the largest e that fits, clamped to [-60, 0].
  const int finest = layout.levels[0].exponent;
  EXPECT_GE(finest, -60);
  EXPECT_LE(finest, 0);
  if (finest > -60) {
    EXPECT_TRUE(fits(finest));
  }
  if (finest < 0) {
    EXPECT_FALSE(fits(finest + 1));
  }

  const int64_t res = settings.resolution;
  const int64_t step = res / settings.recentreDivisor;
  const double margin = (0.5 - 1.0 / settings.recentreDivisor) * double(res);
  std::vector<bool> layerUsed(settings.levelCount, false);
  for (size_t j = 0; j < layout.levels.size(); ++j) {
    const PatchLevel& level = layout.levels[j];
    EXPECT_EQ(level.exponent, finest + int(j));
    const int n = int(settings.levelCount);
    EXPECT_EQ(int(level.layer), ((level.exponent % n) + n) % n);
    EXPECT_FALSE(layerUsed[level.layer]);
    layerUsed[level.layer] = true;
    EXPECT_EQ(floorDiv(level.originA, step) * step, level.originA);
    EXPECT_EQ(floorDiv(level.originB, step) * step, level.originB);
    // The camera in texels from the level's low corner, and its distance to every edge.
    const double x = std::ldexp(ab.x, -level.exponent) - double(level.originA);
    const double y = std::ldexp(ab.y, -level.exponent) - double(level.originB);
    EXPECT_GE(std::min(x, double(res) - x), margin) << "level " << j;
    EXPECT_GE(std::min(y, double(res) - y), margin) << "level " << j;
  }
}

TEST(PatchLayout, LevelsSurroundTheCameraAtTheDocumentedTexelSize) {
  Random random(11);
  const PatchSettings settingsList[] = {PatchSettings{}, PatchSettings{64, 3, 0.5, 4}, PatchSettings{16, 16, 2.0, 2},
                                        PatchSettings{4096, 1, 1.0, 4096}};
  for (const PatchSettings& settings : settingsList) {
    for (int i = 0; i < 400; ++i) {
      const double radius = i % 2 ? kEarthRadiusM : 1737400.0;
      const glm::dvec3 camera = random.direction() * random.uniform(0.5, 3.0);
      const double nadirPixelM = std::pow(10.0, random.uniform(-4.0, 7.5));  // clamps at both ends too
      const PatchLayout layout = choosePatchLayout(settings, radius, camera, nadirPixelM);
      checkLayout(settings, radius, camera, nadirPixelM, layout);
      // Deterministic.
      const PatchLayout again = choosePatchLayout(settings, radius, camera, nadirPixelM);
      EXPECT_EQ(again.face, layout.face);
      for (size_t j = 0; j < layout.levels.size(); ++j) {
        EXPECT_EQ(again.levels[j].exponent, layout.levels[j].exponent);
        EXPECT_EQ(again.levels[j].originA, layout.levels[j].originA);
        EXPECT_EQ(again.levels[j].originB, layout.levels[j].originB);
        EXPECT_EQ(again.levels[j].layer, layout.levels[j].layer);
      }
    }
  }
  // The clamps: a pixel larger than a face gives exponent 0, a sub-atomic one -60.
  EXPECT_EQ(choosePatchLayout({}, kEarthRadiusM, {0, 0, 1}, 1e9).levels[0].exponent, 0);
  EXPECT_EQ(choosePatchLayout({}, kEarthRadiusM, {0, 0, 1}, 1e-30).levels[0].exponent, -60);
  // Exactly on the boundary the inequality holds with equality: that exponent is taken.
  PatchSettings onePerPixel;
  onePerPixel.texelsPerNadirPixel = 1.0;
  EXPECT_EQ(
      choosePatchLayout(onePerPixel, kEarthRadiusM, {0, 0, 1}, kEarthRadiusM * std::ldexp(1.0, -20)).levels[0].exponent,
      -20);
}

TEST(PatchLayout, SmallCameraMovesKeepOriginsAndOneStepMovesTheFinestLevelOneStep) {
  Random random(23);
  const PatchSettings settings;
  const int64_t step = settings.resolution / settings.recentreDivisor;
  int movesChecked = 0, stepsChecked = 0;
  for (int i = 0; i < 300; ++i) {
    const glm::dvec3 camera = random.direction();
    const PatchLayout layout = choosePatchLayout(settings, kEarthRadiusM, camera, 0.3);
    const glm::dvec2 ab = cubeFaceCoordinates(layout.face, camera);
    // The largest move (along a and b separately) that crosses no level's recentre boundary.
    double room = kInf;
    for (const PatchLevel& level : layout.levels) {
      const double texel = std::ldexp(1.0, level.exponent);
      const double half = double(settings.resolution / 2);
      for (double position : {ab.x / texel - double(level.originA), ab.y / texel - double(level.originB)}) {
        room = std::min(room, (position - half) * texel);                 // to the lower boundary
        room = std::min(room, (half + double(step) - position) * texel);  // to the upper one
      }
    }
    ASSERT_GE(room, 0.0);
    // (A camera within rounding of a boundary has no room to test.)
    const bool hasRoom = room > 1e-6 * std::ldexp(1.0, layout.levels[0].exponent);
    for (double fraction : {-0.9, -0.3, 0.4, 0.9}) {
      if (!hasRoom) break;
      const double da = fraction * room, db = -0.5 * fraction * room;
      const PatchLayout moved =
          choosePatchLayout(settings, kEarthRadiusM, cubeFaceDirection(layout.face, ab.x + da, ab.y + db), 0.3);
      ASSERT_EQ(moved.face, layout.face);
      ++movesChecked;
      for (size_t j = 0; j < layout.levels.size(); ++j) {
        if (moved.levels[j].exponent != layout.levels[j].exponent) continue;  // pixel size crossed a power of 2
        EXPECT_EQ(moved.levels[j].originA, layout.levels[j].originA) << i << " level " << j;
        EXPECT_EQ(moved.levels[j].originB, layout.levels[j].originB) << i << " level " << j;
      }
    }
    // From the centre of its finest texel, one recentre step of the finest level along a moves
    // that level by exactly one step (when the face and the exponent stay).
    const PatchLevel& finest = layout.levels[0];
    const double texel = std::ldexp(1.0, finest.exponent);
    const double a = (std::floor(ab.x / texel) + 0.5) * texel;
    const PatchLayout before = choosePatchLayout(settings, kEarthRadiusM, cubeFaceDirection(layout.face, a, ab.y), 0.3);
    const PatchLayout after =
        choosePatchLayout(settings, kEarthRadiusM, cubeFaceDirection(layout.face, a + double(step) * texel, ab.y), 0.3);
    if (after.face != before.face || after.levels[0].exponent != before.levels[0].exponent) continue;
    EXPECT_EQ(after.levels[0].originA, before.levels[0].originA + step) << i;
    EXPECT_EQ(after.levels[0].originB, before.levels[0].originB) << i;
    ++stepsChecked;
  }
  // Nearly every random camera had room to move and stayed on its face.
  EXPECT_GE(movesChecked, 4 * 280);
  EXPECT_GE(stepsChecked, 250);
}

TEST(PatchLayout, TexelCoordinatesAndSpacing) {
  PatchLevel level;
  level.exponent = -3;
  level.originA = -5;
  level.originB = 7;
  EXPECT_EQ(patchTexelCoordinates(level, 0, 0), glm::dvec2(-4.5 / 8, 7.5 / 8));
  EXPECT_EQ(patchTexelCoordinates(level, 3, 1), glm::dvec2(-1.5 / 8, 8.5 / 8));

  // The spacing is R·Δ/√(1 + a² + b²) at the centre texel; the true distances to the
  // neighbouring texels there lie between it and it / (1 + a² + b²) (the two gnomonic scales).
  const PatchSettings settings;
  const glm::dvec3 camera = glm::normalize(glm::dvec3(0.4, -0.7, 0.55));
  const PatchLayout layout = choosePatchLayout(settings, kEarthRadiusM, camera, 0.3);
  for (const PatchLevel& l : layout.levels) {
    const double centre = settings.resolution / 2;
    const glm::dvec2 c = patchTexelCoordinates(l, centre, centre);
    const double q = 1.0 + c.x * c.x + c.y * c.y;
    const double spacing = patchTexelSpacingM(layout, l, kEarthRadiusM);
    EXPECT_DOUBLE_EQ(spacing, kEarthRadiusM * std::ldexp(1.0, l.exponent) / std::sqrt(q));
    const glm::dvec3 p = cubeFaceDirection(layout.face, c.x, c.y);
    const glm::dvec2 ca = patchTexelCoordinates(l, centre + 1, centre);
    const glm::dvec2 cb = patchTexelCoordinates(l, centre, centre + 1);
    for (const glm::dvec2& n : {ca, cb}) {
      const double distance = kEarthRadiusM * glm::length(cubeFaceDirection(layout.face, n.x, n.y) - p);
      EXPECT_LE(distance, spacing * (1 + 1e-3));
      EXPECT_GE(distance, spacing / q * (1 - 1e-3));
    }
  }
}

TEST(PatchLayout, BadSettingsAndInputsNameTheValue) {
  auto settingsError = [](PatchSettings s) { return errorOf([&] { validatePatchSettings(s); }); };
  auto expectNames = [](const std::string& message, const std::string& value) {
    EXPECT_NE(message.find(value), std::string::npos) << "'" << message << "' should name " << value;
  };
  EXPECT_EQ(settingsError(PatchSettings{}), "");
  expectNames(settingsError({8, 6, 1.0, 8}), "got 8");
  expectNames(settingsError({8192, 6, 1.0, 8}), "got 8192");
  expectNames(settingsError({100, 6, 1.0, 8}), "got 100");  // not a multiple of 8
  expectNames(settingsError({512, 0, 1.0, 8}), "got 0");
  expectNames(settingsError({512, 17, 1.0, 8}), "got 17");
  expectNames(settingsError({512, 6, 0.0, 8}), "got 0");
  expectNames(settingsError({512, 6, -2.0, 8}), "got -2");
  expectNames(settingsError({512, 6, kNan, 8}), "got nan");
  expectNames(settingsError({512, 6, kInf, 8}), "got inf");
  expectNames(settingsError({512, 6, 1.0, 0}), "got 0");
  expectNames(settingsError({512, 6, 1.0, 1}), "got 1");
  expectNames(settingsError({512, 6, 1.0, 1024}), "got 1024");
  expectNames(settingsError({512, 6, 1.0, 3}), "got 512");  // 512 is no multiple of 3
  for (const std::string& message : {settingsError({8, 6, 1.0, 8}), settingsError({512, 6, kNan, 8})})
    EXPECT_EQ(message.find('\n'), std::string::npos);

  const glm::dvec3 up(0, 0, 1);
  expectNames(errorOf([&] { choosePatchLayout({8, 6, 1.0, 8}, kEarthRadiusM, up, 1.0); }), "got 8");
  expectNames(errorOf([&] { choosePatchLayout({}, 0.0, up, 1.0); }), "got 0");
  expectNames(errorOf([&] { choosePatchLayout({}, -5.0, up, 1.0); }), "got -5");
  expectNames(errorOf([&] { choosePatchLayout({}, kNan, up, 1.0); }), "got nan");
  expectNames(errorOf([&] { choosePatchLayout({}, kEarthRadiusM, up, 0.0); }), "got 0");
  expectNames(errorOf([&] { choosePatchLayout({}, kEarthRadiusM, up, kInf); }), "got inf");
  expectNames(errorOf([&] { choosePatchLayout({}, kEarthRadiusM, glm::dvec3(0.0), 1.0); }), "(0, 0, 0)");
  expectNames(errorOf([&] { choosePatchLayout({}, kEarthRadiusM, {0, kNan, 1}, 1.0); }), "nan");
}

}  // namespace
}  // namespace planet
